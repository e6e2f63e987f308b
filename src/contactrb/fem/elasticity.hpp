#pragma once
// P1 plane-strain linear elasticity on triangles (paper Section 3.1).
// sigma = lambda_L tr(eps) I + 2 mu_L eps, lambda_L = E nu / ((1 + nu)(1 - 2 nu)),
// mu_L = E / (2 (1 + nu)). The paper's (16) prints (1 + 2 nu): a typo (DESIGN.md).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <string>
#include <vector>

#include "contactrb/fem/sparsity.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, num_dofs x num_dofs

struct Material {
  double E = 1.0;
  double nu = 0.3;
  double lame_lambda() const;  // plane strain
  double lame_mu() const;
};
// Throws contactrb::Error unless E > 0 and -1 < nu < 0.5 (finite).
void check_material(const Material& material);

// Stiffness a(v, w) = int sigma(v) : eps(w) over the triangles of one body only.
SparseMatrix stiffness_body(const mesh::Mesh& mesh, int body, const Material& material);
// Sum over bodies with materials[body].
SparseMatrix stiffness(const mesh::Mesh& mesh, const std::vector<Material>& materials);
// The same on a pattern built beforehand: NodalSparsity(mesh, triangles_of_body(mesh, -1)) (the
// caller shares it, e.g. hf::HFSolver with the ordering of A_00 on another thread).
SparseMatrix stiffness(const mesh::Mesh& mesh, const std::vector<Material>& materials, const NodalSparsity& pattern);
// The two Lame parts of one body's stiffness: a = lambda_L * S_div + 2 mu_L * S_sym with
// S_div(v, w) = int div v div w and S_sym(v, w) = int eps(v) : eps(w).
SparseMatrix divergence_part(const mesh::Mesh& mesh, int body);
SparseMatrix symmetric_gradient_part(const mesh::Mesh& mesh, int body);

// Load vector of a constant body force `load` on one body: int load . w.
Eigen::VectorXd body_load(const mesh::Mesh& mesh, int body, const Eigen::Vector2d& load);
// Load vector of a variable body force: int load(x) . w, with the triangle quadrature
// exact for polynomials of total degree `degree` (quadrature.hpp; the default 4 makes
// load . phi exact for loads of degree <= 3).
Eigen::VectorXd body_load(const mesh::Mesh& mesh, int body,
                          const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& load, int degree = 4);

// Vector L2 mass int v . w, vector Laplacian int grad v : grad w, and the H1 inner
// product (their sum), over the whole mesh.
SparseMatrix mass(const mesh::Mesh& mesh);
SparseMatrix vector_laplacian(const mesh::Mesh& mesh);
SparseMatrix h1_product(const mesh::Mesh& mesh);
// Vector L2 mass on a boundary group: int_Gamma v . w.
SparseMatrix boundary_mass(const mesh::Mesh& mesh, const std::string& group);

// Stress (constant per P1 triangle) of a displacement field: (sxx, syy, sxy) per triangle.
Eigen::Matrix3Xd element_stress(const mesh::Mesh& mesh, const std::vector<Material>& materials,
                                const Eigen::VectorXd& u);

}  // namespace contactrb::fem
