#pragma once
// The parameters mu = (mu_1, ..., mu_p) of a case: each one's name, kind (how it enters the
// problem), domain [min, max], units and reference value; and the named discrete sets of
// points in the box P = prod [min_k, max_k] (paper Section 6: training sets P^tr; our
// verification sets). The paper shows p = 1; its Sections 2, 4 and 5 hold for any P.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace contactrb::cases {

// One value per parameter, in the order of CaseSpec::parameters.
using Mu = Eigen::VectorXd;

// How a parameter enters the problem (docs/cases.md, "Parameters"). Every kind but
// BodyScaling is affine in the parameter (a product of monomials with the others: theta.hpp);
// BodyScaling moves a body, so the gap and the contact map depend on mu (the EIM path).
//  DirichletScale: Dirichlet values a + b mu_k (the values that name this parameter).
//  BodyScaling: one body scaled uniformly by s = mu_k / reference about a fixed point c,
//    h(mu)(x) = s (x - c) + c (paper cases (b) and (c)). At most one per body.
//  YoungModulus: E of one body is mu_k (A = sum_bodies E_i A_i^{E=1}). At most one per body.
//  Traction: the magnitude of the [[traction]] loads that name this parameter (their
//    vector or pressure times mu_k).
//  BodyForce: the body load of one body is its `load` vector times mu_k. At most one per body.
//  FrictionCoefficient: Coulomb's f of a frictional case (docs/cases.md, "Frictional cases"); it
//    enters the friction law, not the affine terms: frictionless cases refuse it. At most one.
enum class ParameterKind { DirichletScale, BodyScaling, YoungModulus, Traction, BodyForce, FrictionCoefficient };
// "dirichlet-scale" | "body-scaling" | "young-modulus" | "traction" | "body-force" | "friction-coefficient"
const char* to_string(ParameterKind kind);
ParameterKind parameter_kind_from_string(const std::string& name);  // throws contactrb::Error
// True for the kinds that concern one body (BodyScaling, YoungModulus, BodyForce).
bool has_body(ParameterKind kind);

struct ParameterSpec {
  // Its name, used on the command line (--mu name=value), in CSV headers and in messages:
  // not empty, without ',', '=', '"' or control characters, unique in a case.
  std::string name;
  std::string units;  // free text ("mm", "MPa", ""), recorded in files
  ParameterKind kind = ParameterKind::DirichletScale;
  double min = 0.0;
  double max = 0.0;
  // The value of the reference configuration: Omega = Omega(reference) for BodyScaling; the
  // point of the energy inner product A(mu_ref) for every kind.
  double reference = 0.0;
  int body = 1;  // BodyScaling, YoungModulus, BodyForce: the body (0 slave, 1 master)
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // BodyScaling: the fixed point c

  // Scale factor of the scaled body: value / reference (BodyScaling), 1 otherwise.
  double scale(double value) const;
  // Throws contactrb::Error for a NaN or a value outside [min, max], naming the parameter,
  // the domain and `context` (e.g. "case 'hertz-a'").
  void check(double value, const std::string& context) const;
};

// A named set of points of P (training, verification, ...), each of size p.
struct ParameterSet {
  std::string name;
  std::vector<Mu> points;
};

// Throws contactrb::Error naming the first inconsistency of one parameter: empty or invalid
// name, a domain that is not an interval, a reference outside the domain (or <= 0 for
// BodyScaling), a body other than 0 or 1, a non-finite center.
void check_parameter_spec(const ParameterSpec& spec, const std::string& context);

// Throws contactrb::Error naming `context` and the first inconsistency of a list: no
// parameter, two with the same name, two BodyScaling (or YoungModulus, or BodyForce) on the
// same body.
void check_parameter_list(const std::vector<ParameterSpec>& parameters, const std::string& context);

// Throws contactrb::Error for mu of the wrong size, or a value that fails its check.
void check_mu(const std::vector<ParameterSpec>& parameters, const Mu& mu, const std::string& context);

// Throws contactrb::Error naming `context` and the first point of the wrong size or outside
// the box, the first repeated point, or an empty set; for p = 1 the values must also be
// strictly increasing (a training set of one repeated value gave a model that answered far
// from the HF solution with converged = true).
void check_points(const std::vector<ParameterSpec>& parameters, const std::vector<Mu>& points,
                  const std::string& context);

// The reference point (reference of each parameter).
Mu reference_mu(const std::vector<ParameterSpec>& parameters);
// Index of the parameter called `name`, -1 if none.
int parameter_index(const std::vector<ParameterSpec>& parameters, const std::string& name);

// "name = value, name = value" with the shortest round-trip digits (messages, tables).
std::string mu_text(const std::vector<ParameterSpec>& parameters, const Mu& mu);
// "0.3" for p = 1, "(0.3, 1.2)" otherwise.
std::string mu_values_text(const Mu& mu);
// mu_values_text with six significant digits (common/number_text.hpp): progress lines.
std::string mu_short_text(const Mu& mu);

// Throws contactrb::Error naming `context` and the first position where `values` does not
// strictly increase.
void check_increasing(const std::vector<double>& values, const std::string& context);

// {start + step i, i = 0..count-1}, each value computed as start + i * step (no drift).
std::vector<double> arithmetic_set(double start, double step, int count);
// The midpoints of consecutive values of an increasing set (size - 1 values).
std::vector<double> midpoints(const std::vector<double>& values);
// One-parameter points from values, and back (throws unless every point has size 1).
std::vector<Mu> points_1d(const std::vector<double>& values);
std::vector<double> values_1d(const std::vector<Mu>& points);

}  // namespace contactrb::cases
