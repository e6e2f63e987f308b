// Parallel snapshot generation: results independent of the number of threads (bitwise),
// the stored arrays consistent with each other, failures recorded and never dropped.
// hertz-a at level 0 on 4 parameter values keeps it fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "support/snapshot_fixtures.hpp"

using contactrb::Error;
using contactrb::io::Snapshot;
using contactrb::io::SnapshotSet;
using contactrb::offline::generate_snapshots;
using contactrb::offline::SnapshotRequest;
using contactrb::offline::SnapshotRunOptions;

namespace {

const std::vector<double> kValues{0.15, 0.22, 0.31, 0.45};

class SnapshotGeneration : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    request_ = std::make_unique<SnapshotRequest>(contactrb::offline::make_snapshot_request(
        contactrb::cases::builtin_case_spec("hertz-a"), "training", 0, std::nullopt, contactrb::cases::points_1d(kValues)));
    SnapshotRunOptions one;
    one.jobs = 1;
    serial_ = std::make_unique<SnapshotSet>(generate_snapshots(*request_, one));
    SnapshotRunOptions two;
    two.jobs = 2;
    parallel_ = std::make_unique<SnapshotSet>(generate_snapshots(*request_, two));
  }
  static void TearDownTestSuite() {
    request_.reset();
    serial_.reset();
    parallel_.reset();
  }
  static std::unique_ptr<SnapshotRequest> request_;
  static std::unique_ptr<SnapshotSet> serial_;
  static std::unique_ptr<SnapshotSet> parallel_;
};
std::unique_ptr<SnapshotRequest> SnapshotGeneration::request_;
std::unique_ptr<SnapshotSet> SnapshotGeneration::serial_;
std::unique_ptr<SnapshotSet> SnapshotGeneration::parallel_;

}  // namespace

TEST_F(SnapshotGeneration, OneAndTwoJobsGiveBitwiseIdenticalData) {
  ASSERT_EQ(serial_->snapshots.size(), kValues.size());
  EXPECT_EQ(serial_->num_failed(), 0);
  contactrb::test::expect_same_data(*serial_, *parallel_, /*with_timings=*/false);
}

TEST_F(SnapshotGeneration, RecordsTheCaseAndTheSet) {
  const SnapshotSet& s = *serial_;
  EXPECT_EQ(s.case_name, "hertz-a");
  EXPECT_EQ(s.case_kind, "builtin");
  EXPECT_EQ(s.case_spec, "hertz-a");
  EXPECT_EQ(s.set_name, "custom");  // explicit values
  EXPECT_EQ(s.constraint, "collocation");
  ASSERT_EQ(s.parameters.size(), 1u);
  EXPECT_DOUBLE_EQ(s.parameters[0].min, 0.15);
  EXPECT_DOUBLE_EQ(s.parameters[0].max, 0.45);
  EXPECT_EQ(s.parameters[0].kind, "dirichlet-scale");
  EXPECT_EQ(s.kacanov_alpha, 0.3);
  for (std::size_t i = 0; i < kValues.size(); ++i) EXPECT_EQ(s.snapshots[i].mu, Eigen::VectorXd::Constant(1, kValues[i]));
  EXPECT_EQ(s.slave.size(), 51u);  // the paper's mesh (Fig. 2)
}

// The arrays agree with one another: u restricted to the free DOFs is u0, lambda >= 0,
// the rows K u <= g hold to the solver's tolerance, and a pressure acts only where the
// gap closes (complementarity).
TEST_F(SnapshotGeneration, StoredArraysAreConsistent) {
  const SnapshotSet& s = *serial_;
  for (const Snapshot& snap : s.snapshots) {
    SCOPED_TRACE("mu = " + std::to_string(snap.mu(0)));
    ASSERT_TRUE(snap.converged) << snap.message;
    EXPECT_EQ(snap.status, "converged");
    EXPECT_GT(snap.iterations, 1);
    EXPECT_GT(snap.time_s, 0.0);
    EXPECT_GT(snap.cpu_time_s, 0.0);
    ASSERT_EQ(snap.u0.size(), static_cast<Eigen::Index>(s.free_dofs.size()));
    for (std::size_t k = 0; k < s.free_dofs.size(); ++k) {
      EXPECT_EQ(snap.u(s.free_dofs[k]), snap.u0(static_cast<Eigen::Index>(k)));
    }
    Eigen::VectorXd uc(static_cast<Eigen::Index>(s.contact_dofs.size()));
    for (std::size_t c = 0; c < s.contact_dofs.size(); ++c) uc(static_cast<Eigen::Index>(c)) = snap.u(s.contact_dofs[c]);
    const Eigen::VectorXd slack = snap.g - snap.K * uc;
    const double scale = snap.g.cwiseAbs().maxCoeff();
    EXPECT_GE(snap.lambda.minCoeff(), 0.0);
    EXPECT_GT(snap.lambda.maxCoeff(), 0.0);  // hertz-a is in contact over the whole domain
    EXPECT_GE(slack.minCoeff(), -1e-8 * scale);
    EXPECT_LE(snap.lambda.cwiseProduct(slack).cwiseAbs().maxCoeff(), 1e-8 * scale * snap.lambda.maxCoeff());
    EXPECT_EQ(snap.weight.size(), snap.lambda.size());
    EXPECT_GT(snap.weight.minCoeff(), 0.0);
    EXPECT_EQ(snap.gap_pointwise.size(), static_cast<Eigen::Index>(s.slave.size()));
  }
  // More imposed displacement, more contact force.
  const auto force = [](const Snapshot& x) { return x.lambda.dot(x.weight); };
  EXPECT_LT(force(s.snapshots.front()), force(s.snapshots.back()));
}

TEST_F(SnapshotGeneration, RealSetRoundTripsBitwise) {
  contactrb::test::TempDir dir("real_roundtrip");
  contactrb::io::write_snapshot_file(*parallel_, dir.file("s.h5"));
  contactrb::test::expect_same_data(*parallel_, contactrb::io::read_snapshot_file(dir.file("s.h5")),
                                    /*with_timings=*/true);
}

TEST_F(SnapshotGeneration, NonConvergedSolvesAreRecordedAsFailed) {
  SnapshotRequest r = *request_;
  r.settings.kacanov.max_iterations = 1;
  SnapshotRunOptions two;
  two.jobs = 2;
  const SnapshotSet s = generate_snapshots(r, two);
  ASSERT_EQ(s.snapshots.size(), kValues.size());
  EXPECT_EQ(s.num_failed(), static_cast<int>(kValues.size()));
  for (const Snapshot& snap : s.snapshots) {
    EXPECT_FALSE(snap.converged);
    EXPECT_EQ(snap.status, "max_iterations");
    EXPECT_FALSE(snap.message.empty());
  }
  EXPECT_EQ(s.kacanov_max_iterations, 1);
  EXPECT_EQ(contactrb::offline::summarize(s).failures, static_cast<int>(kValues.size()));
}

TEST_F(SnapshotGeneration, ExceptionsAreRecordedAsFailed) {
  SnapshotRequest r = *request_;
  const auto factory = r.make_problem;
  r.make_problem = [factory](const contactrb::cases::Mu& mu) {
    if (mu(0) == 0.22) throw Error("synthetic mesh failure at 0.22");
    return factory(mu);
  };
  SnapshotRunOptions two;
  two.jobs = 2;
  const SnapshotSet s = generate_snapshots(r, two);
  ASSERT_EQ(s.snapshots.size(), kValues.size());
  EXPECT_EQ(s.num_failed(), 1);
  const Snapshot& failed = s.snapshots[1];
  EXPECT_FALSE(failed.converged);
  EXPECT_EQ(failed.status, "exception");
  EXPECT_EQ(failed.message, "synthetic mesh failure at 0.22");
  EXPECT_EQ(failed.u.size(), 0);
  // The others are untouched: the same bits as without the failure.
  for (std::size_t i : {0u, 2u, 3u}) {
    EXPECT_TRUE(contactrb::test::same_bits(s.snapshots[i].u, serial_->snapshots[i].u));
  }
}

TEST_F(SnapshotGeneration, DifferentDiscretizationsAcrossMuAreAnError) {
  SnapshotRequest r = *request_;
  const auto factory = r.make_problem;
  r.make_problem = [factory](const contactrb::cases::Mu& mu) {
    auto p = factory(mu);
    if (mu(0) > 0.3) p.discretization = contactrb::contact::Discretization::LAC;
    return p;
  };
  EXPECT_THROW(generate_snapshots(r), Error);
}

TEST_F(SnapshotGeneration, ProgressLinesOnePerValue) {
  SnapshotRequest r = *request_;
  r.settings.kacanov.max_iterations = 2;  // fast; failures are reported too
  std::ostringstream out;
  SnapshotRunOptions opt;
  opt.jobs = 2;
  opt.progress = contactrb::offline::ProgressMode::Lines;
  opt.progress_stream = &out;
  (void)generate_snapshots(r, opt);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), static_cast<long>(kValues.size())) << text;
  EXPECT_NE(text.find("snapshot 4/4"), std::string::npos) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos);
}

TEST(SnapshotRequestErrors, BadArgumentsThrow) {
  const auto spec = contactrb::cases::builtin_case_spec("hertz-a");
  SnapshotRequest r;
  r.mu = contactrb::cases::points_1d({0.2});
  EXPECT_THROW(generate_snapshots(r), Error);  // no factory
  r.make_problem = [](const contactrb::cases::Mu&) { return contactrb::hf::ContactProblem{}; };
  SnapshotRunOptions zero;
  zero.jobs = 0;
  EXPECT_THROW(generate_snapshots(r, zero), Error);
  r.mu.clear();
  EXPECT_THROW(generate_snapshots(r), Error);
  EXPECT_THROW(contactrb::offline::make_snapshot_request(spec, "no-such-set"), Error);
  EXPECT_THROW(
      contactrb::offline::make_snapshot_request(spec, "training", 0, std::nullopt, contactrb::cases::points_1d({0.9})),
      Error);
}

// A TOML case is stored as its TOML text, which reads back to the same specification.
TEST(SnapshotRequestCase, TomlCaseIsStoredAsItsText) {
  const std::string file = std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-patch/case.toml";
  const auto spec = contactrb::cases::case_from_toml_file(file);
  const SnapshotRequest r = contactrb::offline::make_snapshot_request(spec, "training");
  EXPECT_EQ(r.case_kind, "toml");
  EXPECT_EQ(r.set_name, "training");
  EXPECT_EQ(r.mu, spec.set("training"));
  EXPECT_TRUE(contactrb::cases::same_case(contactrb::cases::case_from_toml_string(r.case_spec, "stored"), spec));
  // A built-in case is stored by name.
  const SnapshotRequest b =
      contactrb::offline::make_snapshot_request(contactrb::cases::builtin_case_spec("hertz-b"), "verification");
  EXPECT_EQ(b.case_kind, "builtin");
  EXPECT_EQ(b.case_spec, "hertz-b");
  EXPECT_EQ(b.mu.size(), 21u);  // midpoints of the 22 training values
}

// A 3D case by the same path: patch-3d's snapshots record dimension 3 and the tetrahedral
// reference mesh, do not depend on the thread count, hold u with 3 components per node and the
// patch test's uniform pressure E mu (E = 10, docs/cases.md "patch-3d"); the offline builder
// refuses them with a message naming the dimension.
TEST(SnapshotGeneration3d, PatchSnapshotsAreThreeDimensionalAndRefusedByTheBuilder) {
  const contactrb::cases::CaseSpec spec = contactrb::cases::builtin_case_spec("patch-3d");
  const SnapshotRequest request = contactrb::offline::make_snapshot_request(
      spec, "training", 0, std::nullopt, contactrb::cases::points_1d({0.01, 0.03}));
  EXPECT_EQ(request.dimension, 3);
  SnapshotRunOptions two;
  two.jobs = 2;
  const SnapshotSet s = generate_snapshots(request, {});
  contactrb::test::expect_same_data(s, generate_snapshots(request, two), /*with_timings=*/false);
  EXPECT_EQ(s.dimension, 3);
  EXPECT_TRUE(s.mesh.nodes.empty());
  ASSERT_FALSE(s.mesh3.nodes.empty());
  EXPECT_EQ(s.num_dofs, 3 * s.mesh3.num_nodes());
  EXPECT_EQ(s.contact_dofs.size() % 3, 0u);
  for (const Snapshot& snap : s.snapshots) {
    ASSERT_TRUE(snap.converged) << snap.message;
    EXPECT_EQ(snap.u.size(), s.num_dofs);
    const double p = 10.0 * snap.mu(0);
    EXPECT_LT((snap.lambda.array() - p).abs().maxCoeff(), 1e-10 * p);
  }
  try {
    contactrb::offline::build_reduced_model(s, spec, {});
    ADD_FAILURE() << "3D snapshots were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the snapshots are 3D"), std::string::npos) << e.what();
  }
}
