#pragma once
// P1 linear elasticity on simplices: plane strain on triangles (paper Section 3.1) and 3D
// elasticity on tetrahedra, one code for both (Dim = 2, 3).
// sigma = lambda_L tr(eps) I + 2 mu_L eps, lambda_L = E nu / ((1 + nu)(1 - 2 nu)),
// mu_L = E / (2 (1 + nu)): the 3D Lame constants, which plane strain uses unchanged. The
// paper's (16) prints (1 + 2 nu): a typo (DESIGN.md).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "contactrb/fem/p1_element.hpp"
#include "contactrb/fem/sparsity.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, num_dofs x num_dofs

struct Material {
  double E = 1.0;
  double nu = 0.3;
  double lame_lambda() const;  // 3D, hence also plane strain
  double lame_mu() const;
};
// Throws contactrb::Error unless E > 0 and -1 < nu < 0.5 (finite).
void check_material(const Material& material);

template <int Dim>
using Vector = Eigen::Matrix<double, Dim, 1>;
// A point-dependent load (body force density) of a Dim-dimensional mesh.
template <int Dim>
using VectorField = std::function<Vector<Dim>(const Vector<Dim>&)>;

// Stiffness a(v, w) = int sigma(v) : eps(w) over the cells of one body only.
template <int Dim>
SparseMatrix stiffness_body(const mesh::SimplexMesh<Dim>& mesh, int body, const Material& material);
// Sum over bodies with materials[body].
template <int Dim>
SparseMatrix stiffness(const mesh::SimplexMesh<Dim>& mesh, const std::vector<Material>& materials);
// The same on a pattern built beforehand: SimplexSparsity(mesh, cells_of_body(mesh, -1)) (the
// caller shares it, e.g. hf::HFSolver with the ordering of A_00 on another thread).
template <int Dim>
SparseMatrix stiffness(const mesh::SimplexMesh<Dim>& mesh, const std::vector<Material>& materials,
                       const std::type_identity_t<SimplexSparsity<Dim>>& pattern);
// The two Lame parts of one body's stiffness: a = lambda_L * S_div + 2 mu_L * S_sym with
// S_div(v, w) = int div v div w and S_sym(v, w) = int eps(v) : eps(w).
template <int Dim>
SparseMatrix divergence_part(const mesh::SimplexMesh<Dim>& mesh, int body);
template <int Dim>
SparseMatrix symmetric_gradient_part(const mesh::SimplexMesh<Dim>& mesh, int body);

// Load vector of a constant body force `load` on one body: int load . w.
template <int Dim>
Eigen::VectorXd body_load(const mesh::SimplexMesh<Dim>& mesh, int body, const std::type_identity_t<Vector<Dim>>& load);
// Load vector of a variable body force: int load(x) . w, with the simplex quadrature exact
// for polynomials of total degree `degree` (quadrature.hpp; the default 4 makes load . phi
// exact for loads of degree <= 3).
template <int Dim>
Eigen::VectorXd body_load(const mesh::SimplexMesh<Dim>& mesh, int body,
                          const std::type_identity_t<VectorField<Dim>>& load, int degree = 4);

// Vector L2 mass int v . w, vector Laplacian int grad v : grad w, and the H1 inner
// product (their sum), over the whole mesh.
template <int Dim>
SparseMatrix mass(const mesh::SimplexMesh<Dim>& mesh);
template <int Dim>
SparseMatrix vector_laplacian(const mesh::SimplexMesh<Dim>& mesh);
template <int Dim>
SparseMatrix h1_product(const mesh::SimplexMesh<Dim>& mesh);
// Vector L2 mass on a boundary group: int_Gamma v . w.
template <int Dim>
SparseMatrix boundary_mass(const mesh::SimplexMesh<Dim>& mesh, const std::string& group);

// Stress (constant per P1 cell) of a displacement field: one Voigt column per cell
// (p1_element.hpp: (sxx, syy, sxy) in 2D, (sxx, syy, szz, sxy, syz, sxz) in 3D).
template <int Dim>
Eigen::Matrix<double, kVoigtSize<Dim>, Eigen::Dynamic> element_stress(const mesh::SimplexMesh<Dim>& mesh,
                                                                      const std::vector<Material>& materials,
                                                                      const Eigen::VectorXd& u);

}  // namespace contactrb::fem
