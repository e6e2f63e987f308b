#pragma once
// The scalar parameter mu of a case: its name, its kind (how it enters the problem), its
// domain P = [min, max], the value at which the reference mesh is Omega(mu), and named
// discrete sets (paper Section 6: training sets P^tr; our verification sets).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace contactrb::cases {

// How mu enters the problem (docs/cases.md).
//  DirichletScale: only the Dirichlet data depend on mu (values a + b mu); the geometry,
//    A and f do not (paper case (a)).
//  BodyScaling: one body is scaled uniformly by s(mu) = mu / reference about a fixed
//    point c, h(mu)(x) = s (x - c) + c (paper cases (b) and (c)).
enum class ParameterKind { DirichletScale, BodyScaling };
const char* to_string(ParameterKind kind);                  // "dirichlet-scale" | "body-scaling"
ParameterKind parameter_kind_from_string(const std::string& name);  // throws contactrb::Error

struct ParameterSet {
  std::string name;  // "training", "verification", ...
  std::vector<double> values;
};

struct ParameterSpec {
  std::string name;  // physical meaning, e.g. "lower radius R2"
  ParameterKind kind = ParameterKind::DirichletScale;
  double min = 0.0;
  double max = 0.0;
  double reference = 0.0;  // mu of the reference configuration Omega = Omega(reference)
  int body = 1;            // BodyScaling: the scaled body (0 slave, 1 master)
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // BodyScaling: the fixed point c
  std::vector<ParameterSet> sets;

  // Scale factor of the scaled body: mu / reference (BodyScaling), 1 otherwise.
  double scale(double mu) const;
  bool has_set(const std::string& set_name) const;
  // Throws contactrb::Error naming the set and listing the sets present.
  const std::vector<double>& set(const std::string& set_name) const;
  // Throws contactrb::Error for a NaN or a value outside [min, max], naming the parameter,
  // the domain and `context` (e.g. "case 'hertz-a'").
  void check(double mu, const std::string& context) const;
};

// Throws contactrb::Error naming the first inconsistency: empty domain, non-finite bounds,
// reference outside the domain (or <= 0 for BodyScaling), a set value outside the
// domain, a set that is not strictly increasing, an empty or duplicated set name, a scaled
// body other than 0 or 1.
void check_parameter_spec(const ParameterSpec& spec, const std::string& context);

// Throws contactrb::Error naming `context` and the first position where `values` does not
// strictly increase (a repeated value: a training set of one repeated value gave a model that
// answered far from the HF solution with converged = true).
void check_increasing(const std::vector<double>& values, const std::string& context);

// {start + step i, i = 0..count-1}, each value computed as start + i * step (no drift).
std::vector<double> arithmetic_set(double start, double step, int count);
// The midpoints of consecutive values of an increasing set (size - 1 values).
std::vector<double> midpoints(const std::vector<double>& values);

}  // namespace contactrb::cases
