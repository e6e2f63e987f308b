// The names of every enum of the library (STYLE.md, item 11): *_from_string reads back each
// to_string, and refuses anything else with a contactrb::Error naming the accepted values; and
// the records' JSON (to_json beside each record) in the cases a file cannot show: absent
// estimates and undefined effectivities are null, a fixed N or R has no threshold.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/level_sequence_json.hpp"
#include "contactrb/cases/parameter_json.hpp"
#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/file_seal.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/fem/cholesky.hpp"
#include "contactrb/hf/hf_solution_json.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/greedy.hpp"
#include "contactrb/offline/nmf.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/offline/offline_report_json.hpp"
#include "contactrb/offline/pod.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/online/online_solution_json.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/sampling.hpp"
#include "contactrb/solve/kacanov.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"
#include "contactrb/solve/selected_inverse.hpp"
#include "contactrb/solve/sparse_lu.hpp"
#include "contactrb/study/evaluation_json.hpp"

namespace contactrb {
namespace {

// Every value of `values` reads back from its name; a name no value has is refused, and the
// message names the unknown word and every accepted one.
template <class Enum, std::size_t K, class FromString>
void expect_names_read_back(const std::array<Enum, K>& values, FromString from_string) {
  std::string names;
  for (Enum value : values) {
    const std::string name = to_string(value);
    EXPECT_NE(name, "unknown");
    EXPECT_EQ(from_string(name), value) << name;
    names += name + "|";
  }
  try {
    from_string("no-such-name");
    ADD_FAILURE() << "accepted 'no-such-name' (" << names << ")";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'no-such-name'"), std::string::npos) << what;
    for (Enum value : values) EXPECT_NE(what.find(to_string(value)), std::string::npos) << what;
  }
}

TEST(EnumNames, EveryEnumReadsBackItsNames) {
  expect_names_read_back(std::array{InputKind::Text, InputKind::Hdf5}, input_kind_from_string);
  expect_names_read_back(std::array{SealState::Valid, SealState::Absent, SealState::Mismatch}, seal_state_from_string);
  using namespace solve;
  expect_names_read_back(std::array{KacanovStatus::Converged, KacanovStatus::MaxIterations, KacanovStatus::StepFailed,
                                    KacanovStatus::NonFinite},
                         kacanov_status_from_string);
  expect_names_read_back(std::array{QPStatus::Solved, QPStatus::MaxIterations, QPStatus::Numerics, QPStatus::Unbounded,
                                    QPStatus::InvalidInput},
                         qp_status_from_string);
  expect_names_read_back(std::array{SparseLUBackend::Umfpack, SparseLUBackend::EigenSparseLU},
                         sparse_lu_backend_from_string);
  expect_names_read_back(std::array{SparseLUStatus::Success, SparseLUStatus::Singular, SparseLUStatus::InvalidInput},
                         sparse_lu_status_from_string);
  expect_names_read_back(std::array{FactorOrdering::Auto, FactorOrdering::Cholmod, FactorOrdering::NodeMetis},
                         factor_ordering_from_string);
  expect_names_read_back(std::array{SelectedInverseStatus::Success, SelectedInverseStatus::NotPositiveDefinite,
                                    SelectedInverseStatus::InvalidInput},
                         selected_inverse_status_from_string);
  expect_names_read_back(
      std::array{fem::FactorStatus::Success, fem::FactorStatus::NotPositiveDefinite, fem::FactorStatus::InvalidInput},
      fem::factor_status_from_string);
  expect_names_read_back(std::array{fem::CholeskyBackend::Automatic, fem::CholeskyBackend::Cholmod,
                                    fem::CholeskyBackend::EigenSimplicial},
                         fem::cholesky_backend_from_string);
}

TEST(EnumNames, EveryEnumOfTheMethodReadsBackItsNames) {
  using namespace contact;
  expect_names_read_back(std::array{Discretization::Collocation, Discretization::LAC, Discretization::LACSimpson},
                         discretization_from_string);
  expect_names_read_back(std::array{SearchMethod::Automatic, SearchMethod::AllPairs, SearchMethod::Tree},
                         search_method_from_string);
  expect_names_read_back(std::array{LinearizationMethod::Analytic, LinearizationMethod::FiniteDifference},
                         linearization_method_from_string);
  expect_names_read_back(std::array{hf::HFMethod::Newton, hf::HFMethod::Kacanov}, hf::hf_method_from_string);
  expect_names_read_back(std::array{cases::MeshFile::Required, cases::MeshFile::Optional}, cases::mesh_file_from_string);
  using namespace online;
  using namespace offline;
  expect_names_read_back(std::array{OnlineIteration::Automatic, OnlineIteration::Relaxed, OnlineIteration::Accelerated},
                         online_iteration_from_string);
  expect_names_read_back(std::array{InitialGuess::Interpolated, InitialGuess::Zero}, initial_guess_from_string);
  expect_names_read_back(std::array{SampleDistribution::Kind::Uniform, SampleDistribution::Kind::Normal},
                         sample_distribution_kind_from_string);
  expect_names_read_back(std::array{ProgressMode::Automatic, ProgressMode::Terminal, ProgressMode::Lines, ProgressMode::None},
                         progress_mode_from_string);
  expect_names_read_back(std::array{SnapshotRunOptions::WarmStart::Automatic, SnapshotRunOptions::WarmStart::On,
                                    SnapshotRunOptions::WarmStart::Off},
                         warm_start_from_string);
  expect_names_read_back(std::array{PODTruncation::SingularValue, PODTruncation::ProjectionError},
                         pod_truncation_from_string);
  expect_names_read_back(std::array{InnerProduct::Energy, InnerProduct::H1}, inner_product_from_string);
  expect_names_read_back(std::array{DualConeMethod::CPG, DualConeMethod::AngleGreedy, DualConeMethod::NMF},
                         dual_cone_method_from_string);
  expect_names_read_back(std::array{GreedyStatus::ToleranceReached, GreedyStatus::MaxSize, GreedyStatus::Exhausted},
                         greedy_status_from_string);
  expect_names_read_back(std::array{GreedyOfflineStatus::ToleranceReached, GreedyOfflineStatus::Budget,
                                    GreedyOfflineStatus::Stagnated},
                         greedy_offline_status_from_string);
  expect_names_read_back(std::array{NMFStatus::Converged, NMFStatus::MaxIterations}, nmf_status_from_string);
}

TEST(EnumNames, TheMessageListsTheAcceptedNames) {
  try {
    offline::dual_cone_method_from_string("cgp");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "unknown dual cone method 'cgp' (expected cpg, angle, nmf, rows or registered)");
  }
}

TEST(RecordJson, AnAbsentEstimateIsNull) {
  online::OnlineSolution s;
  s.status = solve::KacanovStatus::MaxIterations;
  s.message = "did not converge";
  s.u_hat = Eigen::VectorXd::Zero(2);
  s.lambda_hat = Eigen::VectorXd::Zero(1);
  const nlohmann::json j = online::to_json(s);
  EXPECT_TRUE(j.at("estimate").is_null());
  EXPECT_EQ(j.at("converged"), false);
  EXPECT_EQ(j.at("status"), "max_iterations");
  EXPECT_EQ(j.at("message"), "did not converge");
  EXPECT_EQ(j.at("u_hat").size(), 2u);
  s.estimate.available = true;
  s.estimate.energy = 0.5;
  EXPECT_EQ(online::to_json(s).at("estimate").at("energy"), 0.5);
  s.message.clear();
  EXPECT_FALSE(online::to_json(s).contains("message"));
}

TEST(RecordJson, APointIsANumberForOneParameterAndNamedOtherwise) {
  std::vector<cases::ParameterSpec> p(2);
  p[0].name = "delta";
  p[1].name = "R2";
  EXPECT_EQ(cases::mu_json(p, cases::Mu::Constant(1, 0.3)), 0.3);
  EXPECT_EQ(cases::mu_json(p, cases::Mu(Eigen::Vector2d(0.3, 1.1))), (nlohmann::json{{"delta", 0.3}, {"R2", 1.1}}));
}

TEST(RecordJson, UndefinedEffectivitiesAreNull) {
  study::EvaluationSummary s;  // no row: NaN effectivities
  const nlohmann::json j = study::to_json(s);
  EXPECT_TRUE(j.at("effectivity").at("min").is_null());
  EXPECT_EQ(j.at("effectivity").at("count"), 0);
  EXPECT_EQ(j.at("e_displ").at("max"), 0.0);
  study::EvaluationRow row;
  row.mu = cases::Mu::Constant(1, 0.2);
  const nlohmann::json r = study::to_json(row, {});
  EXPECT_TRUE(r.at("estimate").is_null());
  EXPECT_EQ(r.at("mu"), 0.2);
}

TEST(RecordJson, AFixedSizeHasNoThreshold) {
  offline::OfflineSettings settings;
  offline::OfflineReport report;
  report.pod_threshold = 1e-3;
  EXPECT_EQ(offline::to_json(report, settings).at("thresholds").at("pod"), 1e-3);
  EXPECT_TRUE(offline::to_json(settings).at("n").is_null());
  settings.pod_modes = 4;
  settings.dual_method = offline::DualConeMethod::NMF;
  EXPECT_TRUE(offline::to_json(report, settings).at("thresholds").at("pod").is_null());
  EXPECT_EQ(offline::to_json(settings).at("n"), 4);
  EXPECT_EQ(offline::to_json(settings).at("dual"), "nmf");
  EXPECT_EQ(offline::to_json(report, settings).at("dual").at("method"), "nmf");
}

TEST(RecordJson, TheHFSolveOfEachMethod) {
  hf::HFSolution s;
  s.method = hf::HFMethod::Kacanov;
  s.history.resize(3);
  nlohmann::json j = hf::to_json(s);
  EXPECT_EQ(j.at("increments").at("displacement").size(), 3u);
  EXPECT_FALSE(j.contains("newton_residuals"));
  s.method = hf::HFMethod::Newton;
  s.newton_history.resize(2);
  j = hf::to_json(s);
  EXPECT_EQ(j.at("newton_residuals").size(), 2u);
  EXPECT_EQ(j.at("kkt"), hf::to_json(s.kkt));
  cases::SequenceStart start;
  start.stages.push_back({1, 100, 4, true, 0.1, 0.2, 0.3});
  j = cases::to_json(start);
  EXPECT_EQ(j.at("sequence").size(), 1u);
  EXPECT_EQ(j.at("sequence")[0].at("n_dofs"), 100);
  EXPECT_DOUBLE_EQ(j.at("sequence")[0].at("time_s").get<double>(), 0.6);
}

}  // namespace
}  // namespace contactrb
