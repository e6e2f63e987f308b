#include "contactrb/fem/quadrature.hpp"

#include <array>
#include <cmath>
#include <functional>
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

double factorial(int n) {
  double f = 1.0;
  for (int k = 2; k <= n; ++k) f *= k;
  return f;
}

// Calls visit(beta) for every beta in N^4 with |beta| = total.
void for_each_composition(int total, const std::function<void(const std::array<int, 4>&)>& visit) {
  for (int a = 0; a <= total; ++a)
    for (int b = 0; a + b <= total; ++b)
      for (int c = 0; a + b + c <= total; ++c) visit({a, b, c, total - a - b - c});
}

// Grundmann-Moeller rule of degree d = 2 s + 1 on the tetrahedron (n = 3): for i = 0..s, the
// points (2 beta + 1) / (d + n - 2 i), |beta| = s - i, with weight
// (-1)^i 2^(-2s) (d + n - 2i)^d / (i! (d + n - i)!) times n! (weights normalized to sum 1).
TetrahedronQuadrature grundmann_moeller(int s) {
  constexpr int n = 3;
  const int d = 2 * s + 1;
  TetrahedronQuadrature rule;
  rule.degree = d;
  for (int i = 0; i <= s; ++i) {
    const double denominator = d + n - 2 * i;
    const double w = (i % 2 == 0 ? 1.0 : -1.0) * std::pow(2.0, -2 * s) * std::pow(denominator, d) /
                     (factorial(i) * factorial(d + n - i)) * factorial(n);
    for_each_composition(s - i, [&](const std::array<int, 4>& beta) {
      Eigen::Vector4d l;
      for (int k = 0; k < 4; ++k) l(k) = (2 * beta[static_cast<std::size_t>(k)] + 1) / denominator;
      rule.barycentric.push_back(l);
      rule.weights.push_back(w);
    });
  }
  return rule;
}

}  // namespace

const TetrahedronQuadrature& tetrahedron_quadrature(int degree) {
  require(degree >= 0 && degree <= 7,
          "tetrahedron_quadrature: degree " + std::to_string(degree) + " not available (0..7)");
  static const TetrahedronQuadrature rules[] = {grundmann_moeller(0), grundmann_moeller(1), grundmann_moeller(2),
                                                grundmann_moeller(3)};
  return rules[degree / 2];  // degree 2 s or 2 s + 1: the rule of degree 2 s + 1
}

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
