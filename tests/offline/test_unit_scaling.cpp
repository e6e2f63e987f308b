// Unit-free offline tolerances: hertz-a and hertz-b written in other units (E x 1e9, as in
// SI; lengths and displacements x 1e-3) give the same sizes N, R, M^k, M^g at the default
// (relative) tolerances, the same reduced solutions (in the new units) and the same relative
// errors on the verification set as in the paper's units. The cases are TOML files (tests/data/scaling/) on the built-in hertz mesh,
// written by the test with its lengths scaled or not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/mesh/msh_io.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace contactrb;

#include "support/cpg_settings.hpp"
namespace {

const fs::path kData = fs::path(CONTACTRB_SOURCE_DIR) / "tests" / "data" / "scaling";

// The case files copied to one directory with hertz.msh (the built-in hertz mesh, as exported
// in examples/hertz-a) and hertz-mm.msh (the same, lengths x 1e-3). Both are written by
// write_msh so that they have the same node order.
class ScaledCases {
 public:
  ScaledCases() : dir_("unit_scaling") {
    mesh::Mesh m = mesh::read_msh((fs::path(CONTACTRB_SOURCE_DIR) / "examples" / "hertz-a" / "hertz-a.msh").string());
    mesh::write_msh(m, dir_.file("hertz.msh"));
    for (Eigen::Vector2d& x : m.nodes) x *= 1e-3;
    mesh::write_msh(m, dir_.file("hertz-mm.msh"));
    for (const char* c : {"hertz-a", "hertz-b"}) {
      for (const char* units : {"", "-si", "-mm"}) {
        const std::string name = std::string(c) + units + ".toml";
        fs::copy_file(kData / name, dir_.path() / name);
      }
    }
  }
  cases::CaseSpec spec(const std::string& name) const { return cases::case_from_toml_file(dir_.file(name + ".toml")); }

 private:
  test::TempDir dir_;
};

struct Study {
  contactrb::offline::OfflineResult offline;
  study::Evaluation evaluation;
  double hf_energy_scale = 0.0;  // max |energy_hf| over the verification set
};

// Training snapshots, the model of the paper's method (CPG), the evaluation on the verification set.
Study study_of(const cases::CaseSpec& spec) {
  contactrb::offline::SnapshotRequest request =
      contactrb::offline::make_snapshot_request(spec, "training", 0, std::nullopt, std::nullopt);
  contactrb::offline::SnapshotRunOptions run;
  run.jobs = 2;
  const io::SnapshotSet set = contactrb::offline::generate_snapshots(request, run);
  EXPECT_EQ(set.num_failed(), 0) << spec.name;
  Study s;
  s.offline = contactrb::offline::build_reduced_model(set, spec, test_support::cpg_settings());
  study::EvaluationOptions options;
  options.online_repeats = 1;
  options.jobs = 2;
  s.evaluation =
      study::evaluate_model(s.offline.model, s.offline.reconstruction, spec, spec.set("verification"), options);
  for (const study::EvaluationRow& r : s.evaluation.rows)
    s.hf_energy_scale = std::max(s.hf_energy_scale, std::abs(r.energy_hf));
  return s;
}

void print(const std::string& name, const Study& s) {
  const model::ReducedModel& m = s.offline.model;
  std::printf("[ %s ] N %d, R %d, Mk %d, Mg %d; max e_displ %.3e, max e_inter %.3e, max e_ener %.3e\n", name.c_str(),
              m.N_max, m.R_max, m.Mk_max, m.Mg_max, s.evaluation.summary.max_e_displ, s.evaluation.summary.max_e_inter,
              s.evaluation.summary.max_e_ener);
}

// `scaled` against `base`: same sizes, and per verification value (the i-th of each set):
//  - the same reduced solution: u_rb(scaled) = u_factor u_rb(base) and the same multiplier
//    profile lambda_rb / |lambda_rb|, to round-off (both HF solvers stop on relative
//    criteria, so the snapshots differ by round-off only);
//  - the same interpenetration (66) in units of `length` and the same energy error (64)
//    relative to the HF energy;
//  - the same relative H1 error (65) when lengths are unchanged. With lengths x 1e-3 the H1
//    norm (L2 part ~ length^2 |u|^2, gradient part ~ |u|^2) weighs its two parts differently:
//    (65) is not unit-free, whatever the model (compared above through u_rb instead).
void expect_same(const Study& base, const Study& scaled, double u_factor, double length, const std::string& what,
                 const std::vector<double>& base_mus, const std::vector<double>& scaled_mus) {
  const model::ReducedModel& a = base.offline.model;
  const model::ReducedModel& b = scaled.offline.model;
  EXPECT_EQ(b.N_max, a.N_max) << what;
  EXPECT_EQ(b.R_max, a.R_max) << what;
  EXPECT_EQ(b.Mk_max, a.Mk_max) << what;
  EXPECT_EQ(b.Mg_max, a.Mg_max) << what;
  ASSERT_EQ(scaled.evaluation.rows.size(), base.evaluation.rows.size()) << what;
  ASSERT_EQ(base_mus.size(), base.evaluation.rows.size());
  ASSERT_EQ(scaled_mus.size(), base_mus.size());
  EXPECT_EQ(scaled.evaluation.summary.rb_failures + scaled.evaluation.summary.hf_failures, 0) << what;
  online::OnlineSolver solver_a(a), solver_b(b);
  double worst_u = 0.0, worst_lambda = 0.0;
  const double rel = 1e-6;
  for (std::size_t i = 0; i < base_mus.size(); ++i) {
    const online::OnlineSolution x = solver_a.solve(base_mus[i]);
    const online::OnlineSolution y = solver_b.solve(scaled_mus[i]);
    ASSERT_TRUE(x.converged() && y.converged()) << what << ", mu = " << base_mus[i];
    const Eigen::VectorXd ux =
        u_factor * online::reconstruct_displacement(base.offline.reconstruction,
                                                    Eigen::VectorXd::Constant(1, base_mus[i]), x.u_hat);
    const Eigen::VectorXd uy = online::reconstruct_displacement(scaled.offline.reconstruction,
                                                                Eigen::VectorXd::Constant(1, scaled_mus[i]), y.u_hat);
    const Eigen::VectorXd lx = online::reconstruct_multipliers(base.offline.reconstruction,
                                                                Eigen::VectorXd::Constant(1, base_mus[i]), x.lambda_hat);
    const Eigen::VectorXd ly = online::reconstruct_multipliers(scaled.offline.reconstruction,
                                                                Eigen::VectorXd::Constant(1, scaled_mus[i]), y.lambda_hat);
    worst_u = std::max(worst_u, (uy - ux).norm() / ux.norm());
    worst_lambda = std::max(worst_lambda, (ly / ly.norm() - lx / lx.norm()).norm());

    const study::EvaluationRow& r = base.evaluation.rows[i];
    const study::EvaluationRow& t = scaled.evaluation.rows[i];
    if (length == 1.0) {
      EXPECT_NEAR(t.e_displ, r.e_displ, rel * r.e_displ) << what << ", mu = " << r.mu;
    }
    EXPECT_NEAR(t.e_inter / length, r.e_inter, rel * r.e_inter + 1e-14) << what << ", mu = " << r.mu;
    EXPECT_NEAR(t.e_ener / scaled.hf_energy_scale, r.e_ener / base.hf_energy_scale,
                rel * r.e_ener / base.hf_energy_scale + 1e-14)
        << what << ", mu = " << r.mu;
  }
  std::printf("[ %s ] max |u_rb - %g u_rb(paper units)| / |u_rb| = %.2e, multiplier profiles %.2e\n", what.c_str(),
              u_factor, worst_u, worst_lambda);
  EXPECT_LT(worst_u, 1e-9) << what;
  EXPECT_LT(worst_lambda, 1e-9) << what;
}

}  // namespace

TEST(UnitScaling, HertzAAndHertzBGiveTheSameModelInOtherUnits) {
  const ScaledCases cases;
  for (const char* c : {"hertz-a", "hertz-b"}) {
    const std::string name(c);
    const cases::CaseSpec spec = cases.spec(name);
    const cases::CaseSpec si = cases.spec(name + "-si");
    const cases::CaseSpec mm = cases.spec(name + "-mm");
    ASSERT_EQ(si.bodies[0].E, 1e9 * spec.bodies[0].E);
    const mesh::Mesh ref = cases::reference_mesh(spec);
    const mesh::Mesh ref_mm = cases::reference_mesh(mm);
    ASSERT_EQ(ref.num_nodes(), ref_mm.num_nodes());
    EXPECT_NEAR(ref_mm.nodes[7].x(), 1e-3 * ref.nodes[7].x(), 1e-18);

    const Study base = study_of(spec);
    const Study s_si = study_of(si);
    const Study s_mm = study_of(mm);
    print(name, base);
    print(name + "-si", s_si);
    print(name + "-mm", s_mm);
    // The model is a real one: truncated, and accurate on values it was not trained on.
    EXPECT_LT(base.offline.model.N_max, static_cast<int>(contactrb::cases::values_1d(spec.set("training")).size())) << name;
    EXPECT_LT(base.evaluation.summary.max_e_displ, 0.05) << name;
    const std::vector<double> mus = contactrb::cases::values_1d(spec.set("verification"));
    expect_same(base, s_si, 1.0, 1.0, name + " E x 1e9", mus, contactrb::cases::values_1d(si.set("verification")));
    expect_same(base, s_mm, 1e-3, 1e-3, name + " lengths x 1e-3", mus, contactrb::cases::values_1d(mm.set("verification")));
  }
}

// The same SI case with the former absolute defaults (eps_POD 1e-3 etc.) keeps more modes
// than in the paper's units: what the relative defaults remove.
TEST(UnitScaling, AbsoluteTolerancesDependOnTheUnits) {
  const ScaledCases cases;
  const cases::CaseSpec spec = cases.spec("hertz-a");
  const cases::CaseSpec si = cases.spec("hertz-a-si");
  contactrb::offline::SnapshotRunOptions run;
  run.jobs = 2;
  contactrb::offline::OfflineSettings absolute = test_support::cpg_settings();
  absolute.set_absolute();
  absolute.eps_pod = 1e-3;
  absolute.eps_eim_k = absolute.eps_eim_g = 1e-6;
  const auto sizes = [&](const cases::CaseSpec& c) {
    const io::SnapshotSet set = contactrb::offline::generate_snapshots(
        contactrb::offline::make_snapshot_request(c, "training", 0, std::nullopt, std::nullopt), run);
    const model::ReducedModel m = contactrb::offline::build_reduced_model(set, c, absolute).model;
    std::printf("[ %s, absolute ] N %d, R %d, Mk %d, Mg %d\n", c.name.c_str(), m.N_max, m.R_max, m.Mk_max, m.Mg_max);
    return std::vector<int>{m.N_max, m.R_max};
  };
  const std::vector<int> paper_units = sizes(spec);
  const std::vector<int> si_units = sizes(si);
  EXPECT_GT(si_units[0], paper_units[0]);  // sigma_i x sqrt(1e9) in the energy norm
  EXPECT_GT(si_units[1], paper_units[1]);  // |lambda| x 1e9
}

// The POD reaches far below the former limit of the method of snapshots (eigenvalues of
// S' M S above 1e-13 eig_1, i.e. sigma_i / sigma_1 above about 3e-7, which capped hertz-b at
// N = 11 whatever eps_POD): on the paper's 22 hertz-b training snapshots, eps_POD = 1e-9
// relative keeps more than 11 modes, each singular value kept above the threshold.
TEST(OfflinePOD, HertzBGoesBeyondElevenModesAtATightTolerance) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-b");
  contactrb::offline::SnapshotRunOptions run;
  run.jobs = 2;
  const io::SnapshotSet set = contactrb::offline::generate_snapshots(
      contactrb::offline::make_snapshot_request(spec, "training", 0, std::nullopt, std::nullopt), run);
  ASSERT_EQ(set.snapshots.size(), 22u);
  contactrb::offline::OfflineSettings s;
  s.eps_pod = 1e-9;
  const contactrb::offline::OfflineResult off = contactrb::offline::build_reduced_model(set, spec, s);
  const Eigen::VectorXd& sigma = off.report.singular_values;
  const int N = off.report.N_pod;  // the POD modes (the supremizers follow them)
  std::printf("[ hertz-b ] eps_POD 1e-9 relative: N %d, sigma_N / sigma_1 = %.2e\n", N, sigma(N - 1) / sigma(0));
  EXPECT_GT(N, 11);
  EXPECT_LT(sigma(11) / sigma(0), 3e-7);  // the 12th mode lies below the former limit
  for (int i = 0; i < N; ++i) EXPECT_GT(sigma(i), 1e-9 * sigma(0)) << i;
  if (N < sigma.size()) {
    EXPECT_LE(sigma(N), 1e-9 * sigma(0));
  }
}
