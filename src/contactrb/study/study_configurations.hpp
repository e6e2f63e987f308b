#pragma once
// The HF pictures of the paper's study that need no reduced model: the deformed configuration
// Omega(mu) + u(mu) (Figs. 3, 5, 17) and the contact pressure of the two constraint
// discretizations, LAC against collocation, on the same mesh (Figs. 7, 8). Each is a fresh HF
// solve at the case's settings; `contactrb report` writes them as CSV (write_configuration_files)
// and scripts/plot_report.py draws them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::study {

// Omega(mu) (the mapped mesh) and the total HF displacement at mu.
struct DeformedConfiguration {
  double mu = 0.0;
  mesh::Mesh mesh;    // Omega(mu): nodes of the mapped mesh
  Eigen::VectorXd u;  // total displacement, interleaved (u_x, u_y) per node
  bool converged = false;
  std::string status;
};

// The HF contact pressure of one constraint discretization at one mu: one value per
// constraint row (the P0 pressure on its cell I_r), at the abscissa of the row's centre node
// in the reference configuration (as the multiplier profiles, Figs. 4, 6, 18).
struct ConstraintProfile {
  std::string constraint;  // "lac" | "collocation"
  std::vector<double> abscissa;
  std::vector<double> pressure;
  std::vector<double> weight;  // |I_r|(mu)
  double contact_force = 0.0;  // sum_r lambda_r |I_r|
  double energy = 0.0;
  int iterations = 0;
  bool converged = false;
  std::string status;
};

struct ConstraintComparison {
  double mu = 0.0;
  ConstraintProfile lac;
  ConstraintProfile collocation;
};

// HF solves of a one-parameter case at each mu on `reference` (reference_mesh(spec, level)).
// Throws contactrb::Error for mu outside the domain or an invalid problem; a solve that does
// not converge is returned with converged = false and its status (the caller decides).
std::vector<DeformedConfiguration> deformed_configurations(const cases::CaseSpec& spec, const mesh::Mesh& reference,
                                                           const std::vector<double>& mus);
std::vector<ConstraintComparison> compare_constraints(const cases::CaseSpec& spec, const mesh::Mesh& reference,
                                                      const std::vector<double>& mus);

// deformed_nodes.csv (mu, node, body, x, y, ux, uy: x, y on Omega(mu)), deformed_triangles.csv
// (triangle, n0, n1, n2, body: the connectivity, common to every mu) and
// constraint_comparison.csv (mu, constraint, abscissa, pressure, weight). Empty inputs write no
// file. Returns the names written (relative to dir).
std::vector<std::string> write_configuration_files(const std::vector<DeformedConfiguration>& configurations,
                                                   const std::vector<ConstraintComparison>& comparisons,
                                                   const std::string& dir);

}  // namespace contactrb::study
