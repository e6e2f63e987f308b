#include "contactrb/hf/newton_iterate.hpp"

#include <cmath>
#include <sstream>
#include <vector>

namespace contactrb::hf {

std::string residual_text(double stationarity, double primal, double dual, double complementarity) {
  std::ostringstream os;
  os << "KKT residuals: stationarity " << stationarity << ", primal " << primal << ", dual " << dual
     << ", complementarity " << complementarity;
  return os.str();
}

template <int Dim>
NewtonEvaluator<Dim>::NewtonEvaluator(const BasicNewtonProblem<Dim>& p, const NewtonSettings& s) : p_(p), s_(s) {
  const Eigen::SparseMatrix<double>& A = *p.A00;
  const int R = static_cast<int>(p.quadrature->weight.size());
  // c_r = (stiffness at the slave nodes of I_r) / |I_r|^2: lambda_r and c_r d_r are then
  // both pressures (a slave node pushed by delta carries A_ss delta = lambda_r |I_r|, with
  // d_r = |I_r| delta), so the active-set test does not depend on units.
  const Eigen::VectorXd diag = A.diagonal();
  const double mean_diag = diag.size() > 0 ? diag.cwiseAbs().mean() : 1.0;
  std::vector<int> global_to_free(static_cast<std::size_t>(p.dofs->num_dofs()), -1);
  for (int i = 0; i < p.dofs->num_free(); ++i) global_to_free[static_cast<std::size_t>(p.dofs->free_dofs()[static_cast<std::size_t>(i)])] = i;
  c_.resize(R);
  for (int r = 0; r < R; ++r) {
    double sum = 0.0;
    int count = 0;
    for (RowSparse::InnerIterator it(p.quadrature->W, r); it; ++it) {
      const int node = p.pair->slave[static_cast<std::size_t>(it.col())];
      for (int c = 0; c < Dim; ++c) {
        const int fi = global_to_free[static_cast<std::size_t>(Dim * node + c)];
        if (fi >= 0) {
          sum += std::abs(diag(fi));
          ++count;
        }
      }
    }
    const double w = p.quadrature->weight(r);
    c_(r) = (count > 0 ? sum / count : mean_diag) / (w * w);
  }
}

template <int Dim>
NewtonIterate<Dim> NewtonEvaluator<Dim>::operator()(Eigen::VectorXd u0, Eigen::VectorXd lambda) const {
  NewtonIterate<Dim> st;
  st.u0 = std::move(u0);
  st.lambda = std::move(lambda);
  st.u = p_.dofs->lift() + p_.dofs->extend(st.u0);
  st.maps = contact::evaluate_contact_maps(*p_.mesh, *p_.pair, *p_.quadrature, st.u, s_.linearization.projection);
  st.K0 = p_.dofs->restrict_columns(st.maps.rows.K);
  const Eigen::VectorXd Ktl = st.K0.transpose() * st.lambda;
  st.F1 = *p_.A00 * st.u0 - *p_.b + Ktl;
  const Eigen::VectorXd& d = st.maps.d;
  st.ncp = st.lambda.cwiseMin(c_.cwiseProduct(d));
  st.merit = std::sqrt(st.F1.squaredNorm() + st.ncp.cwiseProduct(p_.quadrature->weight).squaredNorm());
  // The report of hf_solver.hpp (HFKKT), at the geometry of u itself.
  const double force_scale = std::max({p_.b->norm(), Ktl.norm(), 1e-300});
  st.stationarity = st.F1.norm() / force_scale;
  const Eigen::VectorXd g_lift = st.maps.rows.g - st.maps.rows.K * p_.dofs->lift();
  const double row_scale = st.K0.rows() > 0 ? (st.K0.cwiseAbs() * st.u0.cwiseAbs()).maxCoeff() : 0.0;
  const double gap_scale = std::max({g_lift.size() > 0 ? g_lift.cwiseAbs().maxCoeff() : 0.0, row_scale, 1e-300});
  st.lambda_scale = multiplier_scale(*p_.A00, *p_.b, st.u0, st.lambda, p_.quadrature->weight);
  if (d.size() > 0) {
    st.primal = std::max(0.0, -d.minCoeff()) / gap_scale;
    st.dual = st.lambda_scale.relative(std::max(0.0, -st.lambda.minCoeff()));
    st.complementarity = st.lambda.cwiseProduct(d).cwiseAbs().maxCoeff() / (st.lambda_scale.value() * gap_scale);
  }
  return st;
}

template class NewtonEvaluator<2>;
template class NewtonEvaluator<3>;

}  // namespace contactrb::hf
