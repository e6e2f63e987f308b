#include "contactrb/fem/quadrature.hpp"

#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::fem {
namespace {

// Adds the three permutations of the barycentric point (a, b, b) with weight w.
void add_orbit(TriangleQuadrature& rule, double a, double b, double w) {
  rule.barycentric.emplace_back(a, b, b);
  rule.barycentric.emplace_back(b, a, b);
  rule.barycentric.emplace_back(b, b, a);
  for (int k = 0; k < 3; ++k) rule.weights.push_back(w);
}

TriangleQuadrature make_rule(int degree) {
  TriangleQuadrature rule;
  rule.degree = degree;
  switch (degree) {
    case 1:
      rule.barycentric.emplace_back(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
      rule.weights.push_back(1.0);
      break;
    case 2:
      add_orbit(rule, 2.0 / 3.0, 1.0 / 6.0, 1.0 / 3.0);
      break;
    case 4:  // Dunavant (1985), 6 points
      add_orbit(rule, 0.108103018168070, 0.445948490915965, 0.223381589678011);
      add_orbit(rule, 0.816847572980459, 0.091576213509771, 0.109951743655322);
      break;
    case 5:  // Dunavant (1985), 7 points
      rule.barycentric.emplace_back(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
      rule.weights.push_back(0.225);
      add_orbit(rule, 0.059715871789770, 0.470142064105115, 0.132394152788506);
      add_orbit(rule, 0.797426985353087, 0.101286507323456, 0.125939180544827);
      break;
    default:
      break;
  }
  return rule;
}

}  // namespace

const TriangleQuadrature& triangle_quadrature(int degree) {
  require(degree >= 0 && degree <= 5,
          "triangle_quadrature: degree " + std::to_string(degree) + " not available (0..5)");
  static const TriangleQuadrature rules[] = {make_rule(1), make_rule(2), make_rule(4), make_rule(5)};
  if (degree <= 1) return rules[0];
  if (degree == 2) return rules[1];
  if (degree <= 4) return rules[2];
  return rules[3];
}

}  // namespace contactrb::fem
