// Contact-pressure accuracy of the reduced model (docs/validation.md, "Pressure and supremizers") on the three paper cases
// at the default OfflineSettings but eps_pod 3e-5 and the dual cone named, their training sets and verification sets (HF settings of the
// snapshots: the paper's alpha = 0.3, eps_KA = 1e-3).
//
// The independent reference for "how good can the pressure be": e_press_cone, the best
// approximation of the HF pressure in the model's own dual cone (a non-negative least-squares
// problem). The reduced multiplier lies in that cone, so e_press >= e_press_cone always.
//  - Without supremizers the reduced saddle point is not inf-sup stable (R > N on hertz-a:
//    Q = D A_hat^-1 D' is singular) and e_press is far above the cone's best (0.30 on hertz-a).
//  - With them (the default) e_press stays within a small factor of the cone's best, and
//    hertz-b and ring-block reach 1e-2 on the pressure and 1e-3 on the force. hertz-a does not
//    where the cone itself cannot (a slave node enters the contact between two training values:
//    e_press_cone = 2.2e-2 at mu = 0.175), see docs/offline-online.md.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace {

using contactrb::study::Evaluation;
using contactrb::offline::OfflineResult;
using contactrb::offline::OfflineSettings;

const contactrb::io::SnapshotSet& training(const std::string& name) {
  static std::map<std::string, std::unique_ptr<contactrb::io::SnapshotSet>> cache;
  auto& slot = cache[name];
  if (!slot) {
    contactrb::offline::SnapshotRunOptions options;
    options.jobs = 2;
    slot = std::make_unique<contactrb::io::SnapshotSet>(contactrb::offline::generate_snapshots(
        contactrb::offline::make_snapshot_request(contactrb::cases::builtin_case_spec(name), "training"), options));
  }
  return *slot;
}

Evaluation evaluate(const std::string& name, bool supremizers,
                    contactrb::offline::DualConeMethod dual = contactrb::offline::DualConeMethod::CPG) {
  const auto spec = contactrb::cases::builtin_case_spec(name);
  OfflineSettings s;
  s.supremizers = supremizers;
  s.dual_method = dual;
  s.eps_pod = 3e-5;  // the figures below are at this POD tolerance (N 5 on ring-block)
  const OfflineResult off = contactrb::offline::build_reduced_model(training(name), spec, s);
  contactrb::study::EvaluationOptions o;
  o.jobs = 2;
  o.online_repeats = 1;
  const Evaluation e =
      contactrb::study::evaluate_model(off.model, off.reconstruction, spec, spec.set("verification"), o);
  EXPECT_EQ(e.summary.hf_failures + e.summary.rb_failures, 0);
  std::printf("[ %s %s supremizers %s ] N %d R %d Mk %d Mg %d: max e_press %.3e (cone's best %.3e), e_force %.3e, "
              "e_peak %.3e, e_displ %.3e\n",
              name.c_str(), contactrb::offline::to_string(dual), supremizers ? "on" : "off", e.N, e.R, e.Mk, e.Mg, e.summary.max_e_press,
              e.summary.max_e_press_cone, e.summary.max_e_force, e.summary.max_e_peak, e.summary.max_e_displ);
  for (const auto& r : e.rows) EXPECT_GE(r.e_press, r.e_press_cone * (1.0 - 1e-9)) << "mu = " << r.mu;
  return e;
}

// With supremizers the reduced pressure is near the best the cone holds: within 30% of it, up to
// an absolute floor set by the Kacanov stopping test (63) of the HF reference and of the online
// solve, eps_KA = 1e-3 each on the unrelaxed step (measured: e_press 3.1e-3 against a cone's best
// of 6.9e-4 on hertz-b; 1.1e-3 against 9.8e-4 with HF snapshots at eps_KA = 1e-8).
void expect_near_cone_best(const Evaluation& e) {
  constexpr double kKacanovFloor = 4e-3;  // a stopping test on the increment leaves a few eps_KA of error
  for (const auto& r : e.rows) {
    EXPECT_LE(r.e_press, 1.3 * r.e_press_cone + kKacanovFloor)
        << "mu = " << r.mu << ": e_press " << r.e_press << ", cone's best " << r.e_press_cone;
  }
}

TEST(PressureAccuracy, HertzBMeetsTheTargetOnlyWithSupremizers) {
  const Evaluation on = evaluate("hertz-b", true);
  EXPECT_LE(on.summary.max_e_press, 1e-2);
  EXPECT_LE(on.summary.max_e_force, 1e-3);
  expect_near_cone_best(on);
  const Evaluation off = evaluate("hertz-b", false);
  EXPECT_GT(off.summary.max_e_force, 1e-3);  // measured 3.3e-3 (on: 6.0e-5)
  EXPECT_GT(off.summary.max_e_press, 1.5 * on.summary.max_e_press);  // measured 6.8e-3 against 3.1e-3
}

TEST(PressureAccuracy, RingBlockMeetsTheTargetOnlyWithSupremizers) {
  const Evaluation on = evaluate("ring-block", true);
  EXPECT_LE(on.summary.max_e_press, 1e-2);
  EXPECT_LE(on.summary.max_e_force, 1e-3);
  expect_near_cone_best(on);
  const Evaluation off = evaluate("ring-block", false);
  EXPECT_GT(off.summary.max_e_press, 1e-2);  // measured 4.4e-2: R = 8 generators, N = 5 POD modes
  EXPECT_GT(off.summary.max_e_press, 10.0 * off.summary.max_e_press_cone);
}

TEST(PressureAccuracy, HertzAIsAtTheConesBestWithSupremizers) {
  const Evaluation on = evaluate("hertz-a", true);
  expect_near_cone_best(on);
  // Where the cone holds the pressure to 5e-3, so does the reduced model to 1e-2.
  for (const auto& r : on.rows) {
    if (r.e_press_cone <= 5e-3) {
      EXPECT_LE(r.e_press, 1e-2) << "mu = " << r.mu;
    }
  }
  const Evaluation off = evaluate("hertz-a", false);
  EXPECT_GT(off.summary.max_e_press, 0.1);  // measured 0.30 (R 14 > N 10: lambda_hat not determined)
  EXPECT_GT(off.summary.max_e_press, 5.0 * off.summary.max_e_press_cone);
}

// The row cone holds every non-negative pressure on the rows active in training, and the online
// stage evaluates those HF rows exactly (ContactRows::Automatic): the pressure error is no longer
// the cone's but follows the displacement's, where the CPG cone stops at its best (2.2e-2 on
// hertz-a). Measured at the default offline tolerances: hertz-a e_press 5.3e-4 (CPG 2.6e-2), hertz-b
// 4.3e-4.
TEST(PressureAccuracy, RowConeFollowsTheMovingContactZoneOnHertzAAndB) {
  for (const char* name : {"hertz-a", "hertz-b"}) {
    const Evaluation rows = evaluate(name, true, contactrb::offline::DualConeMethod::Rows);
    EXPECT_LE(rows.summary.max_e_press, 2e-3) << name;
    EXPECT_LE(rows.summary.max_e_displ, 1e-3) << name;
    EXPECT_LE(rows.summary.max_e_press_cone, 1e-12) << name;  // every HF pressure lies in the cone
    // The estimate from the exact rows has no square-root floor and, with its geometric term, is
    // an upper bound: measured effectivities 2.32-2.68 on hertz-a and 2.38-2.63 on hertz-b against
    // Newton references (docs/offline-online.md, "Error estimate").
    EXPECT_GE(rows.summary.min_effectivity, 1.0) << name;
    EXPECT_LE(rows.summary.max_effectivity, 10.0) << name;
    EXPECT_LE(rows.summary.median_effectivity, 5.0) << name;
  }
}

}  // namespace
