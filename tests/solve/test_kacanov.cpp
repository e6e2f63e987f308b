// Kacanov driver (solve/kacanov.hpp): the stopping test (63) on the unrelaxed step, its
// independence of the relaxation alpha, and the statuses. The linearized "step" is a known map,
// so the iteration counts follow from a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/kacanov.hpp"

using namespace contactrb::solve;
using Eigen::VectorXd;

namespace {
// A step whose linearized solution does not depend on the iterate: u_bar = u_star,
// lambda_bar = lambda_star (the fixed point is reached by relaxation only).
KacanovStep constant_step(const VectorXd& u_star, const VectorXd& lambda_star) {
  return [u_star, lambda_star](const VectorXd&, const VectorXd&, VectorXd& u_bar, VectorXd& lambda_bar, int& inner,
                               std::string&) {
    u_bar = u_star;
    lambda_bar = lambda_star;
    inner = 1;
    return true;
  };
}
}  // namespace

TEST(Kacanov, RelativeIncrementFromZeroIsInfinite) {
  EXPECT_EQ(relative_increment(VectorXd::Zero(3), VectorXd::Zero(3)), 0.0);
  EXPECT_TRUE(std::isinf(relative_increment(VectorXd::Constant(3, 1e-30), VectorXd::Zero(3))));
  EXPECT_DOUBLE_EQ(relative_increment(VectorXd::Constant(1, 3.0), VectorXd::Constant(1, 2.0)), 0.5);
}

// u* = 1, u^0 = 2, lambda* = 3, lambda^0 = 0, alpha = 1/2: u^k = 1 + 2^-k, lambda^k = 3 (1 - 2^-k).
// Unrelaxed test at step k: du = 2^-(k-1) / (1 + 2^-(k-1)), dlambda = 2^-(k-1) / (1 - 2^-(k-1))
// (infinite at k = 1). dlambda <= 1e-3 first at 2^(k-1) >= 1001, k = 11. (The relaxed
// increments, half as large, would have stopped at k = 10.)
TEST(Kacanov, StopsOnTheUnrelaxedStep) {
  KacanovSettings s;
  s.alpha = 0.5;
  s.tolerance = 1e-3;
  const KacanovResult r =
      kacanov(constant_step(VectorXd::Constant(1, 1.0), VectorXd::Constant(1, 3.0)), VectorXd::Constant(1, 2.0),
              VectorXd::Zero(1), s);
  ASSERT_EQ(r.status, KacanovStatus::Converged) << r.message;
  EXPECT_EQ(r.iterations, 11);
  ASSERT_EQ(r.history.size(), 11u);
  EXPECT_TRUE(std::isinf(r.history[0].dlambda));
  const double t = std::ldexp(1.0, -9);  // 2^-(k-1) at k = 10
  EXPECT_NEAR(r.history[9].du, t / (1.0 + t), 1e-15);
  EXPECT_NEAR(r.history[9].dlambda, t / (1.0 - t), 1e-15);
  EXPECT_GT(r.history[9].dlambda, 1e-3);
  EXPECT_DOUBLE_EQ(r.u_bar(0), 1.0);
}

// The defect this reproduces: at alpha = 1e-4 the relaxed increment of the first step is
// 1e-4 |u_bar - u^0| / |u^0| and passed (63) at once, far from the fixed point. The unrelaxed
// step is 1/2 here: the iteration must go on, and cannot reach 1e-3 in 50 steps
// (u^k - u* = (1 - 1e-4)^k).
TEST(Kacanov, SmallAlphaDoesNotMakeTheTestEasier) {
  KacanovSettings s;
  s.alpha = 1e-4;
  s.tolerance = 1e-3;
  s.max_iterations = 50;
  const KacanovResult r =
      kacanov(constant_step(VectorXd::Constant(2, 1.0), VectorXd::Constant(2, 3.0)), VectorXd::Constant(2, 2.0),
              VectorXd::Constant(2, 2.0), s);
  EXPECT_EQ(r.status, KacanovStatus::MaxIterations);
  EXPECT_EQ(r.iterations, 50);
  EXPECT_NE(r.message.find("did not converge"), std::string::npos) << r.message;
  EXPECT_GT(r.history.front().du, 0.4);
  EXPECT_GT(r.history.back().du, 0.4);
}

// With a contraction u_bar = u* + B (u - u*) (|B| = 0.5), the iteration count of the unrelaxed
// test grows as alpha falls (the relaxed map contracts by 1 - alpha/2), and the returned u_bar
// is within the tolerance's reach of u* for every alpha.
TEST(Kacanov, ContractionReachesTheFixedPointForEveryAlpha) {
  const VectorXd u_star = (VectorXd(3) << 1.0, -2.0, 0.5).finished();
  const VectorXd l_star = (VectorXd(2) << 0.25, 4.0).finished();
  const KacanovStep step = [&](const VectorXd& u, const VectorXd& l, VectorXd& u_bar, VectorXd& l_bar, int& inner,
                               std::string&) {
    u_bar = u_star + 0.5 * (u - u_star);
    l_bar = l_star + 0.5 * (l - l_star);
    inner = 1;
    return true;
  };
  int previous = 0;
  for (double alpha : {1.0, 0.3, 0.03}) {
    KacanovSettings s;
    s.alpha = alpha;
    s.tolerance = 1e-6;
    s.max_iterations = 5000;
    const KacanovResult r = kacanov(step, VectorXd::Zero(3), VectorXd::Constant(2, 1.0), s);
    ASSERT_EQ(r.status, KacanovStatus::Converged) << "alpha " << alpha << ": " << r.message;
    EXPECT_GT(r.iterations, previous) << "alpha " << alpha;
    previous = r.iterations;
    // |u_bar - u*| = 0.5 |u - u*| and |u_bar - u| = 0.5 |u - u*| <= 1e-6 |u|: |u_bar - u*| <= ~1e-6 |u*|.
    EXPECT_LE((r.u_bar - u_star).norm(), 1.1e-6 * u_star.norm()) << "alpha " << alpha;
    EXPECT_LE((r.lambda_bar - l_star).norm(), 1.1e-6 * l_star.norm()) << "alpha " << alpha;
  }
}

TEST(Kacanov, StepFailureIsAStatus) {
  const KacanovStep failing = [](const VectorXd&, const VectorXd&, VectorXd&, VectorXd&, int&, std::string& m) {
    m = "no";
    return false;
  };
  const KacanovResult r = kacanov(failing, VectorXd::Ones(2), VectorXd::Zero(1), {});
  EXPECT_EQ(r.status, KacanovStatus::StepFailed);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_NE(r.message.find("no"), std::string::npos);
}

// A documented limit (docs/solvers.md): the contact lost at the solution (lambda_bar = 0) while
// the relaxed lambda^{k-1} is not zero keeps the relative multiplier increment at exactly 1 for
// alpha < 1; alpha = 1 reaches lambda = 0 in one step and converges at the next.
TEST(Kacanov, LostContactNeedsAlphaOne) {
  const KacanovStep step = constant_step(VectorXd::Constant(1, 1.0), VectorXd::Zero(1));
  KacanovSettings s;
  s.alpha = 0.5;
  s.max_iterations = 40;
  const KacanovResult relaxed = kacanov(step, VectorXd::Constant(1, 1.0), VectorXd::Constant(1, 2.0), s);
  EXPECT_EQ(relaxed.status, KacanovStatus::MaxIterations);
  EXPECT_DOUBLE_EQ(relaxed.history.back().dlambda, 1.0);
  s.alpha = 1.0;
  const KacanovResult undamped = kacanov(step, VectorXd::Constant(1, 1.0), VectorXd::Constant(1, 2.0), s);
  EXPECT_EQ(undamped.status, KacanovStatus::Converged);
  EXPECT_EQ(undamped.iterations, 2);
}

// A NaN increment fails every comparison, and max(du = 0, NaN) is 0, so a step whose
// multipliers are NaN would pass the stopping test as "converged". Non-finite steps end with
// their own status, on the first such step.
TEST(Kacanov, NonFiniteStepIsAStatusNeverConverged) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  KacanovSettings s;
  s.alpha = 1.0;
  const KacanovResult r =
      kacanov(constant_step(VectorXd::Constant(1, 1.0), VectorXd::Constant(1, nan)), VectorXd::Constant(1, 1.0),
              VectorXd::Constant(1, 1.0), s);
  EXPECT_EQ(r.status, KacanovStatus::NonFinite);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_NE(r.message.find("not finite (multipliers)"), std::string::npos) << r.message;
  EXPECT_STREQ(to_string(r.status), "non_finite");
  const KacanovResult d = kacanov(constant_step(VectorXd::Constant(2, inf), VectorXd::Zero(1)), VectorXd::Ones(2),
                                  VectorXd::Zero(1), s);
  EXPECT_EQ(d.status, KacanovStatus::NonFinite);
  EXPECT_NE(d.message.find("not finite (displacement)"), std::string::npos) << d.message;
}
