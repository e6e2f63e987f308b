#pragma once
// An iterate (u_0, lambda) of the semi-smooth Newton solver and what the method reads at it: the
// contact maps, the residual F of the nonsmooth system, its merit |F| and the KKT report
// (docs/theory.md, "Semi-smooth Newton"). Internal to hf/semismooth_newton.cpp and its steps.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <string>

#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/hf/semismooth_newton.hpp"

namespace contactrb::hf {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

struct NewtonIterate {
  Eigen::VectorXd u0, lambda, u;
  contact::ContactMaps maps;
  RowSparse K0;           // K(u) on the free columns
  Eigen::VectorXd F1;     // A_00 u_0 - b + K_0' lambda
  Eigen::VectorXd ncp;    // min(lambda_r, c_r d_r)
  double merit = 0.0;     // |(F1, |I_r| ncp_r)|
  double stationarity = 0.0, primal = 0.0, dual = 0.0, complementarity = 0.0;  // HFKKT
  double kkt() const { return std::max({stationarity, primal, dual, complementarity}); }
};

bool finite(const NewtonIterate& x);
std::string residual_text(const NewtonIterate& x);  // "KKT residuals: stationarity ..., ..."

// Evaluates iterates of one problem: the scaling c_r of the complementarity function, once.
class NewtonEvaluator {
 public:
  NewtonEvaluator(const NewtonProblem& problem, const NewtonSettings& settings);
  const Eigen::VectorXd& c() const { return c_; }
  // Throws contactrb::Error when the geometry cannot be evaluated at u.
  NewtonIterate operator()(Eigen::VectorXd u0, Eigen::VectorXd lambda) const;

 private:
  const NewtonProblem& p_;
  const NewtonSettings& s_;
  Eigen::VectorXd c_;
};

}  // namespace contactrb::hf
