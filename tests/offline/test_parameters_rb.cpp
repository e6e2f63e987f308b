// Reduced models of several parameters (docs/cases.md): hertz-3p with R2 and E2 frozen (domains of
// one point) over hertz-a's training values is hertz-a, reduced: the same online answers to the
// solver tolerance. And the model file keeps every parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "support/temp_dir.hpp"

using namespace contactrb;

namespace {

// hertz-3p with R2 = 1 and E2 = 15 frozen, its sets hertz-a's (delta, 1, 15).
cases::CaseSpec frozen_hertz_3p() {
  cases::CaseSpec c = cases::builtin_case_spec("hertz-3p");
  c.parameters[1].min = c.parameters[1].max = 1.0;
  c.parameters[2].min = c.parameters[2].max = 15.0;
  const cases::CaseSpec a = cases::builtin_case_spec("hertz-a");
  c.sets.clear();
  for (const cases::ParameterSet& s : a.sets) {
    cases::ParameterSet t{s.name, {}};
    for (const cases::Mu& mu : s.points) t.points.push_back(Eigen::Vector3d(mu(0), 1.0, 15.0));
    c.sets.push_back(t);
  }
  c.origin = "test";
  return c;
}

offline::OfflineResult build(const cases::CaseSpec& spec) {
  offline::SnapshotRunOptions run;
  run.jobs = 2;
  const io::SnapshotSet set = offline::generate_snapshots(offline::make_snapshot_request(spec, "training"), run);
  return offline::build_reduced_model(set, spec);
}

}  // namespace

TEST(ParametersRb, FrozenParametersGiveTheOneParameterModel) {
  const cases::CaseSpec three = frozen_hertz_3p();
  const offline::OfflineResult m3 = build(three);
  const offline::OfflineResult m1 = build(cases::builtin_case_spec("hertz-a"));
  EXPECT_EQ(m3.model.N_max, m1.model.N_max);
  EXPECT_EQ(m3.model.R_max, m1.model.R_max);
  EXPECT_EQ(m3.model.J_a(), 2);  // one stiffness term per body (E2 is a parameter)
  EXPECT_EQ(m1.model.J_a(), 1);
  online::OnlineSolver s3(m3.model), s1(m1.model);
  online::OnlineSettings zero;  // the same path for both: the paper's start u_hat = 0
  zero.initial_guess = online::InitialGuess::Zero;
  for (const cases::Mu& mu : three.set("verification")) {
    const online::OnlineSolution a = s3.solve(mu, zero);
    const online::OnlineSolution b = s1.solve(mu(0), zero);
    ASSERT_TRUE(a.converged() && b.converged()) << mu(0);
    // Same snapshots to round-off, same bases, same start: the two reduced iterations agree far
    // below the Kacanov tolerance (1e-3) they stop at.
    EXPECT_NEAR(a.energy, b.energy, 1e-8 * std::abs(b.energy)) << mu(0);
    EXPECT_NEAR(a.contact_force, b.contact_force, 1e-8 * std::abs(b.contact_force)) << mu(0);
    EXPECT_EQ(a.iterations, b.iterations) << mu(0);
    // The default start differs (p = 1: linear between the two nearest training values; p = 3: the
    // nearest training point), so the iterations stop at different points within the tolerance.
    const online::OnlineSolution c = s3.solve(mu);
    const online::OnlineSolution d = s1.solve(mu(0));
    ASSERT_TRUE(c.converged() && d.converged()) << mu(0);
    EXPECT_NEAR(c.energy, d.energy, 1e-3 * std::abs(d.energy)) << mu(0);
    EXPECT_NEAR(c.contact_force, d.contact_force, 1e-3 * std::abs(d.contact_force)) << mu(0);
  }
}

TEST(ParametersRb, ModelFileKeepsEveryParameter) {
  const cases::CaseSpec three = frozen_hertz_3p();
  const offline::OfflineResult m3 = build(three);
  contactrb::test::TempDir dir("params_rb_file");
  const std::string path = (dir.path() / "m.h5").string();
  io::write_reduced_model_file(m3.model, m3.reconstruction, path);
  const model::ReducedModel back = io::read_reduced_model_file(path);
  ASSERT_EQ(back.num_parameters(), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(back.parameters[static_cast<std::size_t>(k)].name, three.parameters[static_cast<std::size_t>(k)].name);
    EXPECT_EQ(back.parameters[static_cast<std::size_t>(k)].kind, three.parameters[static_cast<std::size_t>(k)].kind);
  }
  EXPECT_EQ(back.training_mu.rows(), 3);
  EXPECT_EQ(back.training_mu.cols(), 31);
  ASSERT_EQ(back.thetas.a.size(), m3.model.thetas.a.size());
  const Eigen::Vector3d mu(0.31, 1.0, 15.0);
  EXPECT_EQ(cases::evaluate(back.thetas.a, mu), cases::evaluate(m3.model.thetas.a, mu));
  online::OnlineSolver a(back), b(m3.model);
  EXPECT_EQ(a.solve(mu).energy, b.solve(mu).energy);
}
