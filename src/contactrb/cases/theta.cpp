#include "contactrb/cases/theta.hpp"

#include <cmath>

#include "contactrb/common/error.hpp"

namespace contactrb::cases {

double ThetaMonomial::operator()(const Eigen::VectorXd& mu) const {
  double x = coefficient;
  for (const ThetaFactor& f : factors) {
    const double r = mu(f.parameter) / f.scale;
    double y = 1.0;
    for (int i = 0; i < std::abs(f.power); ++i) y *= r;
    x *= f.power < 0 ? 1.0 / y : y;
  }
  return x;
}

Eigen::VectorXd evaluate(const std::vector<ThetaMonomial>& thetas, const Eigen::VectorXd& mu) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(thetas.size()));
  for (std::size_t j = 0; j < thetas.size(); ++j) v(static_cast<Eigen::Index>(j)) = thetas[j](mu);
  return v;
}

void check_thetas(const AffineThetas& thetas, int num_parameters, const std::string& what) {
  for (const auto* list : {&thetas.a, &thetas.f, &thetas.lift}) {
    for (const ThetaMonomial& t : *list) {
      require(std::isfinite(t.coefficient) && t.coefficient != 0.0, what + ": a theta coefficient is zero or not finite");
      for (const ThetaFactor& f : t.factors) {
        require(f.parameter >= 0 && f.parameter < num_parameters,
                what + ": a theta factor names parameter " + std::to_string(f.parameter) + " of " +
                    std::to_string(num_parameters));
        require(std::isfinite(f.scale) && f.scale != 0.0, what + ": a theta factor has a zero or non-finite scale");
        require(std::abs(f.power) <= 8, what + ": a theta factor has power " + std::to_string(f.power));
      }
    }
  }
}

}  // namespace contactrb::cases
