// Usage errors of the HF solver: one clear message each.
#include <gtest/gtest.h>

#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "hf_test_meshes.hpp"

using namespace contactrb;

namespace {
hf::ContactProblem blocks() {
  hf::ContactProblem p;
  p.mesh = test_meshes::two_blocks(1.0, 1.0, 1.0, 4, 2, 5, 2);
  p.materials = {{10.0, 0.3}, {10.0, 0.3}};
  p.dirichlet = {{"top", 0.0, -0.01}, {"bottom", 0.0, 0.0}};
  return p;
}
std::string message_of(const hf::ContactProblem& p, const hf::HFSettings& s = {}) {
  try {
    hf::HFSolver(p).solve(s);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(HFErrors, SlaveNeverFacingTheMaster) {
  hf::ContactProblem p = blocks();
  // Move the slave block far to the right: no slave node projects inside the master.
  mesh::map_body(p.mesh, mesh::kSlaveBody, Eigen::Matrix2d::Identity(), Eigen::Vector2d(5.0, 0.0));
  EXPECT_NE(message_of(p).find("faces the master"), std::string::npos) << message_of(p);
  // The same error once the analysis thread of a Newton solve has started (it is joined).
  hf::HFSettings newton;
  newton.method = hf::HFMethod::Newton;
  try {
    const hf::HFSolver solver(p, hf::setup_options_for(newton));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("faces the master"), std::string::npos) << e.what();
  }
}

TEST(HFErrors, BadSettingsAndData) {
  hf::HFSettings s;
  s.kacanov.alpha = 0.0;
  EXPECT_NE(message_of(blocks(), s).find("alpha"), std::string::npos);
  s.kacanov.alpha = 1.5;
  EXPECT_NE(message_of(blocks(), s).find("alpha"), std::string::npos);
  s = {};
  s.kacanov.tolerance = -1.0;
  EXPECT_NE(message_of(blocks(), s).find("tolerance"), std::string::npos);
  hf::ContactProblem p = blocks();
  p.materials.pop_back();
  EXPECT_NE(message_of(p).find("material"), std::string::npos);
  p = blocks();
  p.dirichlet.push_back({"nowhere", 0.0, 0.0});
  EXPECT_NE(message_of(p).find("nowhere"), std::string::npos);
  p = blocks();
  p.dirichlet = {{"top", 0.0, -0.01}};  // lower block free to float
  EXPECT_NE(message_of(p).find("body 1 (master) is not held by the Dirichlet conditions"), std::string::npos)
      << message_of(p);
}

TEST(HFErrors, NonConvergenceIsAStatusWithIterationsAndIncrements) {
  hf::HFSettings s;
  s.kacanov.max_iterations = 2;
  s.kacanov.tolerance = 1e-14;
  s.kacanov.alpha = 0.3;
  const hf::HFSolution sol = hf::HFSolver(blocks()).solve(s);
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.status, solve::KacanovStatus::MaxIterations);
  EXPECT_EQ(sol.iterations, 2);
  EXPECT_NE(sol.message.find("2 iterations"), std::string::npos) << sol.message;
  EXPECT_NE(sol.message.find("increments"), std::string::npos) << sol.message;
}

// Overflowing data at the library level (check_case_spec refuses such data before a case
// gets here; a ContactProblem built directly does not go through it). A Dirichlet value of 1e155
// makes the squared distances of the projection overflow (no segment found); at 1e154 the energy
// is infinite. Either a clear error or a flagged status, never "converged".
TEST(HFErrors, OverflowingDataEndInAnErrorOrANonFiniteStatus) {
  for (const double uy : {-1e154, -1e155, -1e200}) {
    SCOPED_TRACE(uy);
    hf::ContactProblem p = blocks();
    p.dirichlet = {{"top", 0.0, uy}, {"bottom", 0.0, 0.0}};
    try {
      const hf::HFSolution s = hf::HFSolver(p).solve({});
      EXPECT_FALSE(s.converged);
      EXPECT_NE(s.status, solve::KacanovStatus::Converged) << s.message;
      EXPECT_NE(s.message.find("finite"), std::string::npos) << s.message;
      std::printf("  uy = %g: status %s: %s\n", uy, solve::to_string(s.status), s.message.c_str());
    } catch (const Error& e) {  // a clear error is as good as a flagged status
      EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << e.what();
      std::printf("  uy = %g: error: %s\n", uy, e.what());
    }
  }
}
