// Evaluation of a reduced model against the HF solver (paper (64)-(66)):
// an untruncated hertz-a model reproduces the HF solutions at its training values to solver
// tolerance; a truncated model has larger errors, and its e_ener and e_displ agree with values
// computed here from independently assembled A(mu), f(mu), the H1 product and the training
// snapshots; the reconstruction data round-trip through the model file bit for bit, stay out
// of read_reduced_model_file, and a missing or damaged group gives a clear error.
#include <gtest/gtest.h>

#include "support/temp_dir.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "contactrb/common/file_seal.hpp"
#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "support/cpg_settings.hpp"

namespace {

using contactrb::study::Evaluation;
using contactrb::study::EvaluationOptions;
using contactrb::offline::OfflineResult;
using contactrb::offline::OfflineSettings;

const std::vector<double> kTraining{0.15, 0.25, 0.35, 0.45};
const std::vector<contactrb::cases::Mu> kTrainingPoints = contactrb::cases::points_1d(kTraining);
contactrb::cases::Mu one(double mu) { return contactrb::cases::Mu::Constant(1, mu); }
std::vector<contactrb::cases::Mu> points(std::initializer_list<double> v) { return contactrb::cases::points_1d(v); }

const contactrb::cases::CaseSpec& spec() {
  static const contactrb::cases::CaseSpec s = contactrb::cases::builtin_case_spec("hertz-a");
  return s;
}

// Tight Kacanov settings (alpha 1, eps 1e-10): recorded in the model, used by both sides.
const contactrb::io::SnapshotSet& snapshots() {
  static std::unique_ptr<contactrb::io::SnapshotSet> set;
  if (!set) {
    contactrb::offline::SnapshotRequest r =
        contactrb::offline::make_snapshot_request(spec(), "training", 0, std::nullopt, kTrainingPoints);
    r.settings.kacanov = contactrb::solve::KacanovSettings{1.0, 1e-10, 500};
    contactrb::offline::SnapshotRunOptions options;
    options.jobs = 2;
    set = std::make_unique<contactrb::io::SnapshotSet>(contactrb::offline::generate_snapshots(r, options));
  }
  return *set;
}

const OfflineResult& model(bool truncated) {
  static std::unique_ptr<OfflineResult> full, small;
  auto& slot = truncated ? small : full;
  if (!slot) {
    OfflineSettings s = test_support::cpg_settings();
    if (truncated) {
      s.supremizers = false;  // N = 1: the independent computation below uses the single POD mode
      s.pod_modes = 1;
      s.dual_size = 1;
      s.eim_k_size = 1;
      s.eim_g_size = 1;
    } else {
      s.pod_modes = 100;  // capped at the rank: N = P
      s.eps_du = 0.0;
      s.eps_eim_k = 0.0;
      s.eps_eim_g = 0.0;
    }
    slot = std::make_unique<OfflineResult>(contactrb::offline::build_reduced_model(snapshots(), spec(), s));
  }
  return *slot;
}

EvaluationOptions options() {
  EvaluationOptions o;
  o.jobs = 2;
  o.online_repeats = 2;
  return o;
}

TEST(Evaluation, UntruncatedModelHasSolverToleranceErrorsAtTrainingValues) {
  ASSERT_EQ(snapshots().num_failed(), 0);
  const OfflineResult& off = model(false);
  EvaluationOptions o = options();
  o.multiplier_mus = points({0.35});
  const Evaluation e = contactrb::study::evaluate_model(off.model, off.reconstruction, spec(), kTrainingPoints, o);
  ASSERT_EQ(e.rows.size(), kTraining.size());
  EXPECT_EQ(e.N - off.model.N_supremizers, static_cast<int>(kTraining.size()));
  EXPECT_EQ(e.R, off.model.R_max);
  for (std::size_t i = 0; i < e.rows.size(); ++i) {
    const auto& r = e.rows[i];
    SCOPED_TRACE("mu = " + std::to_string(r.mu(0)));
    EXPECT_DOUBLE_EQ(r.mu(0), kTraining[i]);
    EXPECT_TRUE(r.hf_converged);
    EXPECT_TRUE(r.rb_converged) << r.rb_status;
    EXPECT_LT(r.e_displ, 1e-6);
    EXPECT_LT(r.e_ener, 1e-8 * std::abs(r.energy_hf));
    EXPECT_LT(r.e_inter, 1e-8);
    EXPECT_GT(r.hf_time_s, 0.0);
    EXPECT_GT(r.online_time_s, 0.0);
    EXPECT_NEAR(r.speedup, r.hf_time_s / r.online_time_s, 1e-12 * r.speedup);
    EXPECT_EQ(r.multipliers.abscissa.empty(), r.mu(0) != 0.35);
  }
  // The profile at 0.35: one entry per constraint row, RB against HF.
  const auto& p = e.rows[2].multipliers;
  ASSERT_EQ(p.abscissa.size(), static_cast<std::size_t>(off.reconstruction.num_constraints));
  const Eigen::VectorXd& lambda = snapshots().snapshots[2].lambda;
  double diff = 0.0;
  for (std::size_t k = 0; k < p.abscissa.size(); ++k) {
    EXPECT_NEAR(p.lambda_hf[k], lambda(static_cast<Eigen::Index>(k)), 1e-9 * lambda.norm());
    diff = std::max(diff, std::abs(p.lambda_rb[k] - p.lambda_hf[k]));
  }
  EXPECT_LT(diff, 1e-6 * lambda.cwiseAbs().maxCoeff());
  EXPECT_TRUE(std::is_sorted(p.abscissa.begin(), p.abscissa.end()) ||
              std::is_sorted(p.abscissa.rbegin(), p.abscissa.rend()));
  EXPECT_EQ(e.summary.count, 4);
  EXPECT_EQ(e.summary.hf_failures + e.summary.rb_failures, 0);
  EXPECT_LT(e.summary.max_e_displ, 1e-6);
  std::printf("[ untruncated ] N=%d R=%d Mk=%d Mg=%d: max e_ener %.3e, e_displ %.3e, e_inter %.3e\n", e.N, e.R, e.Mk,
              e.Mg, e.summary.max_e_ener, e.summary.max_e_displ, e.summary.max_e_inter);
}

TEST(Evaluation, TruncatedModelErrorsMatchIndependentComputation) {
  const OfflineResult& off = model(true);
  const Evaluation e =
      contactrb::study::evaluate_model(off.model, off.reconstruction, spec(), kTrainingPoints, options());
  ASSERT_EQ(e.N, 1);
  // Independent A(mu), f(mu) (affine terms), H1 product and HF solutions (the training snapshots).
  const auto reference = contactrb::cases::reference_mesh(spec(), 0);
  const auto terms = contactrb::cases::assemble_affine_terms(spec(), reference);
  const auto th = contactrb::cases::theta_functions(spec());
  contactrb::online::OnlineSolver solver(off.model);
  double worst = 0.0;
  std::vector<double> effectivities;
  for (std::size_t i = 0; i < kTraining.size(); ++i) {
    const double mu = kTraining[i];
    SCOPED_TRACE("mu = " + std::to_string(mu));
    const auto& r = e.rows[i];
    ASSERT_TRUE(r.hf_converged);
    const Eigen::VectorXd& uh = snapshots().snapshots[i].u;
    const auto sol = solver.solve(mu);
    const Eigen::VectorXd u = contactrb::online::reconstruct_displacement(off.reconstruction, one(mu), sol.u_hat);
    const auto A = contactrb::cases::combine(terms.A, contactrb::cases::evaluate(th.a, one(mu)));
    const Eigen::VectorXd f =
        contactrb::cases::combine(terms.f, contactrb::cases::evaluate(th.f, one(mu)), reference.num_dofs());
    const double e_ener = 0.5 * std::abs(u.dot(A * u) - f.dot(u) - uh.dot(A * uh) + f.dot(uh));
    EXPECT_NEAR(r.e_ener, e_ener, 1e-9 * e_ener);
    EXPECT_NEAR(r.energy_hf, 0.5 * uh.dot(A * uh) - f.dot(uh), 1e-9 * std::abs(r.energy_hf));
    const auto H1 = contactrb::fem::h1_product(contactrb::cases::mapped_mesh(spec(), reference, mu));
    const Eigen::VectorXd d = u - uh;
    const double e_displ = std::sqrt(d.dot(H1 * d) / uh.dot(H1 * uh));
    EXPECT_NEAR(r.e_displ, e_displ, 1e-8 * e_displ);
    EXPECT_GT(r.e_displ, 1e-4);  // one mode cannot represent four Hertz solutions
    // Pressure measures from the snapshot's multipliers and weights |I_r| (same HF solve).
    const auto& snap = snapshots().snapshots[i];
    const Eigen::VectorXd lr = contactrb::online::reconstruct_multipliers(off.reconstruction, one(mu), sol.lambda_hat);
    const Eigen::VectorXd& lh = snap.lambda;
    const Eigen::VectorXd& w = snap.weight;
    const double e_press = std::sqrt(w.dot((lr - lh).cwiseAbs2()) / w.dot(lh.cwiseAbs2()));
    EXPECT_NEAR(r.e_press, e_press, 1e-8 * e_press);
    EXPECT_NEAR(r.force_hf, w.dot(lh), 1e-9 * w.dot(lh));
    EXPECT_NEAR(r.e_force, std::abs(w.dot(lr) - w.dot(lh)) / w.dot(lh), 1e-8);
    EXPECT_NEAR(r.e_peak, std::abs(lr.maxCoeff() - lh.maxCoeff()) / lh.maxCoeff(), 1e-8);
    // One generator xi (on the kept rows): the cone's best is max(0, <xi, l>_w / <xi, xi>_w) xi.
    Eigen::VectorXd xi = Eigen::VectorXd::Zero(lh.size());
    for (std::size_t k = 0; k < off.reconstruction.kept_rows.size(); ++k) {
      xi(off.reconstruction.kept_rows[k]) = off.reconstruction.Xi(static_cast<Eigen::Index>(k), 0);
    }
    const double c = std::max(0.0, w.dot(xi.cwiseProduct(lh)) / w.dot(xi.cwiseAbs2()));
    const double best = std::sqrt(w.dot((c * xi - lh).cwiseAbs2()) / w.dot(lh.cwiseAbs2()));
    // Absolute floor: where the snapshot lies on the generator (best = 0 exactly here for the
    // snapshot the generator came from) the two computations differ by round-off (8e-11 seen).
    EXPECT_NEAR(r.e_press_cone, best, 1e-8 * best + 1e-9);
    EXPECT_GE(r.e_press, r.e_press_cone * (1.0 - 1e-12));
    // The a posteriori estimate's columns: the energy-norm error, the online estimate, their ratio.
    const double e_A = std::sqrt(d.dot(A * d));
    EXPECT_NEAR(r.e_energy_norm, e_A, 1e-9 * e_A);
    ASSERT_TRUE(sol.estimate.available);
    EXPECT_EQ(r.estimate, sol.estimate.energy);
    EXPECT_NEAR(r.effectivity, sol.estimate.energy / e_A, 1e-8 * r.effectivity);
    effectivities.push_back(r.effectivity);
    std::printf("  mu %.2f: online %s (%d iterations), e_ener %.3e, e_displ %.3e, e_inter %.3e\n", mu,
                r.rb_status.c_str(), r.rb_iterations, r.e_ener, r.e_displ, r.e_inter);
    worst = std::max(worst, r.e_displ);
  }
  EXPECT_NEAR(e.summary.max_e_displ, worst, 1e-15);
  std::sort(effectivities.begin(), effectivities.end());
  ASSERT_EQ(e.summary.effectivity_count, 4);
  EXPECT_EQ(e.summary.min_effectivity, effectivities.front());
  EXPECT_EQ(e.summary.max_effectivity, effectivities.back());
  EXPECT_DOUBLE_EQ(e.summary.median_effectivity, 0.5 * (effectivities[1] + effectivities[2]));
  EXPECT_GE(e.summary.min_effectivity, 0.5);
  // Fewer modes than the model holds: the errors grow back towards the truncated ones.
  const OfflineResult& full = model(false);
  EvaluationOptions o = options();
  o.sizes.N = 1;
  o.sizes.R = 1;
  const Evaluation sub = contactrb::study::evaluate_model(full.model, full.reconstruction, spec(), kTrainingPoints, o);
  EXPECT_EQ(sub.N, 1);
  EXPECT_GT(sub.summary.max_e_displ, 1e-4);
  std::printf("[ truncated ] N=%d R=%d Mk=%d Mg=%d: max e_ener %.3e, e_displ %.3e, e_inter %.3e\n", e.N, e.R, e.Mk,
              e.Mg, e.summary.max_e_ener, e.summary.max_e_displ, e.summary.max_e_inter);
}

std::vector<char> bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  return "";
}

TEST(Evaluation, ReconstructionRoundTripsThroughTheModelFile) {
  contactrb::test::TempDir dir("evaluation_reconstruction");
  const OfflineResult& off = model(false);
  const contactrb::model::ReducedReconstruction& rec = off.reconstruction;
  const std::string with = dir.file("with.h5");
  const std::string without = dir.file("without.h5");
  contactrb::io::write_reduced_model_file(off.model, rec, with);
  contactrb::io::write_reduced_model_file(off.model, without);

  EXPECT_TRUE(contactrb::io::has_reconstruction(with));
  EXPECT_FALSE(contactrb::io::has_reconstruction(without));
  const auto back = contactrb::io::read_reconstruction(with);
  EXPECT_EQ(back.num_dofs, rec.num_dofs);
  EXPECT_EQ(back.free_dofs, rec.free_dofs);
  EXPECT_EQ(back.Theta, rec.Theta);
  ASSERT_EQ(back.lift.size(), rec.lift.size());
  for (std::size_t k = 0; k < rec.lift.size(); ++k) EXPECT_EQ(back.lift[k], rec.lift[k]);
  ASSERT_EQ(back.thetas.lift.size(), rec.thetas.lift.size());
  for (std::size_t k = 0; k < rec.thetas.lift.size(); ++k) {
    EXPECT_EQ(back.thetas.lift[k].coefficient, rec.thetas.lift[k].coefficient);
    ASSERT_EQ(back.thetas.lift[k].factors.size(), rec.thetas.lift[k].factors.size());
    for (std::size_t f = 0; f < rec.thetas.lift[k].factors.size(); ++f) {
      EXPECT_EQ(back.thetas.lift[k].factors[f].parameter, rec.thetas.lift[k].factors[f].parameter);
      EXPECT_EQ(back.thetas.lift[k].factors[f].scale, rec.thetas.lift[k].factors[f].scale);
      EXPECT_EQ(back.thetas.lift[k].factors[f].power, rec.thetas.lift[k].factors[f].power);
    }
  }
  EXPECT_EQ(back.thetas.a.size(), rec.thetas.a.size());
  EXPECT_EQ(back.kept_rows, rec.kept_rows);
  EXPECT_EQ(back.num_constraints, rec.num_constraints);
  EXPECT_EQ(back.Xi, rec.Xi);
  EXPECT_NO_THROW(contactrb::online::check_reconstruction(off.model, back));
  // Same reconstructed fields from the file's data as from memory.
  contactrb::online::OnlineSolver solver(off.model);
  const auto sol = solver.solve(0.3);
  EXPECT_EQ(contactrb::online::reconstruct_displacement(back, one(0.3), sol.u_hat),
            contactrb::online::reconstruct_displacement(rec, one(0.3), sol.u_hat));
  EXPECT_EQ(contactrb::online::reconstruct_multipliers(back, one(0.3), sol.lambda_hat),
            contactrb::online::reconstruct_multipliers(rec, one(0.3), sol.lambda_hat));

  // The model part reads the same from both files (the group is not loaded).
  const auto m1 = contactrb::io::read_reduced_model_file(with);
  const auto m2 = contactrb::io::read_reduced_model_file(without);
  EXPECT_EQ(m1.A_hat.front(), m2.A_hat.front());
  EXPECT_EQ(m1.Xi, off.model.Xi);

  // Absent: a clear error naming the file.
  const std::string absent = error_of([&] { (void)contactrb::io::read_reconstruction(without); });
  EXPECT_NE(absent.find("no reconstruction data"), std::string::npos) << absent;
  EXPECT_NE(absent.find(without), std::string::npos) << absent;
  // Another model's data.
  EXPECT_NE(error_of([&] { contactrb::online::check_reconstruction(model(true).model, back); }).find("does not match"),
            std::string::npos);

  // Damaged: change one double found only once in the file (an entry of the HF-size basis).
  std::vector<char> data = bytes(with);
  bool changed = false;
  for (Eigen::Index i = 0; i < rec.Theta.size() && !changed; ++i) {
    const double v = rec.Theta.data()[i];
    if (v == 0.0) continue;
    char pattern[sizeof(double)];
    std::memcpy(pattern, &v, sizeof v);
    auto it = std::search(data.begin(), data.end(), pattern, pattern + sizeof pattern);
    if (it == data.end() || std::search(it + 1, data.end(), pattern, pattern + sizeof pattern) != data.end()) continue;
    const double w = v * (1.0 + 1e-12);
    std::memcpy(&*it, &w, sizeof w);
    changed = true;
  }
  ASSERT_TRUE(changed);
  const std::string damaged = dir.file("damaged.h5");
  {
    std::ofstream out(damaged, std::ios::binary);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
  }
  // The whole file's seal refuses it at once; resealed (a crafted file), the group's own
  // checksum still finds the change and the model part still reads.
  EXPECT_NE(error_of([&] { (void)contactrb::io::read_reconstruction(damaged); }).find("checksum mismatch"),
            std::string::npos);
  contactrb::seal_file(damaged);
  const std::string msg = error_of([&] { (void)contactrb::io::read_reconstruction(damaged); });
  EXPECT_NE(msg.find("reconstruction checksum mismatch"), std::string::npos) << msg;
  EXPECT_NO_THROW((void)contactrb::io::read_reduced_model_file(damaged));  // the online part is intact
  std::printf("  %s\n  %s\n", absent.c_str(), msg.c_str());
}

TEST(Evaluation, InvalidRequestsAreRefused) {
  const OfflineResult& off = model(false);
  const auto& m = off.model;
  const auto& rec = off.reconstruction;
  EXPECT_NE(
      error_of([&] { (void)contactrb::study::evaluate_model(m, rec, spec(), {}, options()); }).find("no parameter"),
      std::string::npos);
  EXPECT_NE(error_of([&] {
              (void)contactrb::study::evaluate_model(m, rec, spec(), points({0.9}), options());
            }).find("outside the domain"),
            std::string::npos);
  EvaluationOptions o = options();
  o.multiplier_mus = points({0.2});
  EXPECT_NE(
      error_of([&] { (void)contactrb::study::evaluate_model(m, rec, spec(), points({0.3}), o); }).find("mu = 0.2"),
      std::string::npos);
  // Without a stored mesh the case's mesh at the recorded level is used: here it differs from
  // the one the model was built on.
  ASSERT_FALSE(rec.mesh.nodes.empty());  // the builder stores the snapshots' mesh
  contactrb::model::ReducedModel finer = m;
  finer.level = 1;
  contactrb::model::ReducedReconstruction no_mesh = rec;
  no_mesh.mesh = {};
  const std::string mismatch =
      error_of([&] { (void)contactrb::study::evaluate_model(finer, no_mesh, spec(), points({0.3}), options()); });
  EXPECT_NE(mismatch.find("reconstruction data"), std::string::npos) << mismatch;
  // A stored mesh of another size is refused the same way.
  contactrb::model::ReducedReconstruction other_mesh = rec;
  other_mesh.mesh = contactrb::cases::reference_mesh(spec(), 1);
  const std::string other =
      error_of([&] { (void)contactrb::study::evaluate_model(m, other_mesh, spec(), points({0.3}), options()); });
  EXPECT_NE(other.find("reconstruction data"), std::string::npos) << other;
}

}  // namespace
