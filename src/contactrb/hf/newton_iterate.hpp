#pragma once
// An iterate (u_0, lambda) of the semi-smooth Newton solver and what the method reads at it: the
// contact maps, the residual F of the nonsmooth system, its merit |F| and the KKT report
// (docs/theory.md, "Semi-smooth Newton"). Internal to hf/semismooth_newton.cpp and its steps.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>

#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/hf/multiplier_scale.hpp"
#include "contactrb/hf/semismooth_newton.hpp"

namespace contactrb::hf {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

template <int Dim>
struct NewtonIterate {
  Eigen::VectorXd u0, lambda, u;
  contact::ContactMapsOf<Dim> maps;
  RowSparse K0;           // K(u) on the free columns
  Eigen::VectorXd F1;     // A_00 u_0 - b + K_0' lambda
  Eigen::VectorXd ncp;    // min(lambda_r, c_r d_r)
  double merit = 0.0;     // |(F1, |I_r| ncp_r)|
  MultiplierScale lambda_scale;  // of the dual and complementarity residuals
  double stationarity = 0.0, primal = 0.0, dual = 0.0, complementarity = 0.0;  // HFKKT
  double kkt() const { return std::max({stationarity, primal, dual, complementarity}); }
};

template <int Dim>
bool finite(const NewtonIterate<Dim>& x) {
  return x.u0.allFinite() && x.lambda.allFinite() && std::isfinite(x.merit);
}
// "KKT residuals: stationarity ..., ..."
std::string residual_text(double stationarity, double primal, double dual, double complementarity);
template <int Dim>
std::string residual_text(const NewtonIterate<Dim>& x) {
  return residual_text(x.stationarity, x.primal, x.dual, x.complementarity);
}

// Evaluates iterates of one problem: the scaling c_r of the complementarity function, once.
template <int Dim>
class NewtonEvaluator {
 public:
  NewtonEvaluator(const BasicNewtonProblem<Dim>& problem, const NewtonSettings& settings);
  const Eigen::VectorXd& c() const { return c_; }
  // Throws contactrb::Error when the geometry cannot be evaluated at u.
  NewtonIterate<Dim> operator()(Eigen::VectorXd u0, Eigen::VectorXd lambda) const;

 private:
  const BasicNewtonProblem<Dim>& p_;
  const NewtonSettings& s_;
  Eigen::VectorXd c_;
};

extern template class NewtonEvaluator<2>;
extern template class NewtonEvaluator<3>;

}  // namespace contactrb::hf
