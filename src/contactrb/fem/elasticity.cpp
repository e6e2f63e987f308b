#include "contactrb/fem/elasticity.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/fem/p1_element.hpp"
#include "contactrb/fem/quadrature.hpp"
#include "contactrb/fem/sparsity.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::fem {
namespace {

P1Triangle element_of(const mesh::Mesh& mesh, int t) {
  const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
  return p1_triangle(mesh.nodes[static_cast<std::size_t>(tri[0])], mesh.nodes[static_cast<std::size_t>(tri[1])],
                     mesh.nodes[static_cast<std::size_t>(tri[2])]);
}

void check_body(const mesh::Mesh& mesh, int body, const char* who) {
  require(body >= 0 && body < mesh.num_bodies(), std::string(who) + ": body " + std::to_string(body) +
                                                     " out of range (mesh has " +
                                                     std::to_string(mesh.num_bodies()) + " bodies)");
}

void check_materials(const mesh::Mesh& mesh, const std::vector<Material>& materials, const char* who) {
  require(static_cast<int>(materials.size()) == mesh.num_bodies(),
          std::string(who) + ": " + std::to_string(materials.size()) + " materials for " +
              std::to_string(mesh.num_bodies()) + " bodies");
  for (const Material& m : materials) check_material(m);
}

// Assembles one matrix over `triangles` with kernel(P1Triangle) -> ElementMatrix.
template <class Kernel>
SparseMatrix assemble(const mesh::Mesh& mesh, const std::vector<int>& triangles, Kernel kernel) {
  const NodalSparsity pattern(mesh, triangles);
  SparseMatrix A = pattern.zero_matrix();
  for (int t : triangles) {
    pattern.add(mesh.triangles[static_cast<std::size_t>(t)], kernel(element_of(mesh, t)), A.valuePtr());
  }
  return A;
}

// Both Lame parts on one pattern, in one pass: S_div into the returned matrix, S_sym into
// `symmetric_gradient` (pattern order).
SparseMatrix assemble_lame_parts(const mesh::Mesh& mesh, const NodalSparsity& pattern,
                                 const std::vector<int>& triangles, std::vector<double>& symmetric_gradient) {
  SparseMatrix divergence = pattern.zero_matrix();
  symmetric_gradient = pattern.zero_values();
  for (int t : triangles) {
    const P1Triangle element = element_of(mesh, t);
    const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
    pattern.add(tri, element_divergence(element), divergence.valuePtr());
    pattern.add(tri, element_symmetric_gradient(element), symmetric_gradient);
  }
  return divergence;
}

}  // namespace

double Material::lame_lambda() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
double Material::lame_mu() const { return E / (2.0 * (1.0 + nu)); }

void check_material(const Material& material) {
  require(std::isfinite(material.E) && material.E > 0.0,
          "material: Young modulus E = " + number_text(material.E) + " must be finite and > 0");
  require(std::isfinite(material.nu) && material.nu > -1.0 && material.nu < 0.5,
          "material: Poisson ratio nu = " + number_text(material.nu) + " must lie in (-1, 0.5)");
}

SparseMatrix stiffness_body(const mesh::Mesh& mesh, int body, const Material& material) {
  check_body(mesh, body, "stiffness_body");
  check_material(material);
  const std::vector<int> triangles = triangles_of_body(mesh, body);
  const NodalSparsity pattern(mesh, triangles);
  std::vector<double> sym;
  SparseMatrix K = assemble_lame_parts(mesh, pattern, triangles, sym);
  // Combined entry by entry so that the result equals lambda_L * S_div + 2 mu_L * S_sym
  // to the last bit.
  const double lambda = material.lame_lambda(), two_mu = 2.0 * material.lame_mu();
  double* values = K.valuePtr();
  for (std::size_t k = 0; k < sym.size(); ++k) values[k] = lambda * values[k] + two_mu * sym[k];
  return K;
}

namespace {

// stiffness(): the pattern made on first use (nullptr given) or the caller's.
SparseMatrix stiffness_on(const mesh::Mesh& mesh, const std::vector<Material>& materials, const NodalSparsity* given) {
  check_materials(mesh, materials, "stiffness");
  // Bodies are disjoint (mesh.hpp), so every matrix entry belongs to the body of its column
  // node: one pattern and one pass serve all bodies.
  std::vector<int> node_body(static_cast<std::size_t>(mesh.num_nodes()), -1);
  bool disjoint = true;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const int b = mesh.body[static_cast<std::size_t>(t)];
    for (int v : mesh.triangles[static_cast<std::size_t>(t)]) {
      int& nb = node_body[static_cast<std::size_t>(v)];
      if (nb >= 0 && nb != b) disjoint = false;
      nb = b;
    }
  }
  if (!disjoint) {  // a node shared by two bodies: sum the bodies' matrices
    SparseMatrix K(mesh.num_dofs(), mesh.num_dofs());
    for (int b = 0; b < mesh.num_bodies(); ++b) K += stiffness_body(mesh, b, materials[static_cast<std::size_t>(b)]);
    return K;
  }
  const std::vector<int> triangles = triangles_of_body(mesh, -1);
  std::optional<NodalSparsity> own;
  if (given == nullptr) own.emplace(mesh, triangles);
  const NodalSparsity& pattern = given != nullptr ? *given : *own;
  require(pattern.num_dofs() == mesh.num_dofs(), "stiffness: the pattern has " + std::to_string(pattern.num_dofs()) +
                                                     " DOFs, the mesh " + std::to_string(mesh.num_dofs()));
  std::vector<double> symmetric_gradient;
  SparseMatrix K = assemble_lame_parts(mesh, pattern, triangles, symmetric_gradient);
  const double* sym = symmetric_gradient.data();
  double* values = K.valuePtr();
  for (int col = 0; col < K.outerSize(); ++col) {
    const int b = node_body[static_cast<std::size_t>(col / 2)];
    if (b < 0) continue;  // node in no triangle: empty column
    const Material& m = materials[static_cast<std::size_t>(b)];
    const double lambda = m.lame_lambda(), two_mu = 2.0 * m.lame_mu();
    for (int k = K.outerIndexPtr()[col]; k < K.outerIndexPtr()[col + 1]; ++k) {
      values[k] = lambda * values[k] + two_mu * sym[k];
    }
  }
  return K;
}

}  // namespace

SparseMatrix stiffness(const mesh::Mesh& mesh, const std::vector<Material>& materials) {
  return stiffness_on(mesh, materials, nullptr);
}

SparseMatrix stiffness(const mesh::Mesh& mesh, const std::vector<Material>& materials, const NodalSparsity& pattern) {
  return stiffness_on(mesh, materials, &pattern);
}

SparseMatrix divergence_part(const mesh::Mesh& mesh, int body) {
  check_body(mesh, body, "divergence_part");
  return assemble(mesh, triangles_of_body(mesh, body), element_divergence);
}

SparseMatrix symmetric_gradient_part(const mesh::Mesh& mesh, int body) {
  check_body(mesh, body, "symmetric_gradient_part");
  return assemble(mesh, triangles_of_body(mesh, body), element_symmetric_gradient);
}

Eigen::VectorXd body_load(const mesh::Mesh& mesh, int body, const Eigen::Vector2d& load) {
  check_body(mesh, body, "body_load");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (int t : triangles_of_body(mesh, body)) {
    const double share = element_of(mesh, t).area / 3.0;  // int phi_i = area / 3
    for (int v : mesh.triangles[static_cast<std::size_t>(t)]) f.segment<2>(2 * v) += share * load;
  }
  return f;
}

Eigen::VectorXd body_load(const mesh::Mesh& mesh, int body,
                          const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& load, int degree) {
  check_body(mesh, body, "body_load");
  require(static_cast<bool>(load), "body_load: empty load function");
  const TriangleQuadrature& rule = triangle_quadrature(degree);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (int t : triangles_of_body(mesh, body)) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
    const double area = element_of(mesh, t).area;
    for (std::size_t q = 0; q < rule.weights.size(); ++q) {
      const Eigen::Vector3d& l = rule.barycentric[q];
      const Eigen::Vector2d x = l(0) * mesh.nodes[static_cast<std::size_t>(tri[0])] +
                                l(1) * mesh.nodes[static_cast<std::size_t>(tri[1])] +
                                l(2) * mesh.nodes[static_cast<std::size_t>(tri[2])];
      const Eigen::Vector2d value = area * rule.weights[q] * load(x);
      for (int i = 0; i < 3; ++i) f.segment<2>(2 * tri[static_cast<std::size_t>(i)]) += l(i) * value;
    }
  }
  return f;
}

SparseMatrix mass(const mesh::Mesh& mesh) { return assemble(mesh, triangles_of_body(mesh, -1), element_mass); }

SparseMatrix vector_laplacian(const mesh::Mesh& mesh) {
  return assemble(mesh, triangles_of_body(mesh, -1), element_laplacian);
}

SparseMatrix h1_product(const mesh::Mesh& mesh) {
  return assemble(mesh, triangles_of_body(mesh, -1),
                  [](const P1Triangle& e) { return ElementMatrix(element_mass(e) + element_laplacian(e)); });
}

SparseMatrix boundary_mass(const mesh::Mesh& mesh, const std::string& group) {
  const std::vector<mesh::Edge>& edges = mesh.boundary(group);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(8 * edges.size());
  for (const mesh::Edge& e : edges) {
    if (e.a < 0 || e.a >= mesh.num_nodes() || e.b < 0 || e.b >= mesh.num_nodes()) {
      throw Error("boundary_mass: an edge of group '" + group + "' has a node index out of range");
    }
    const double length =
        (mesh.nodes[static_cast<std::size_t>(e.b)] - mesh.nodes[static_cast<std::size_t>(e.a)]).norm();
    const int ends[2] = {e.a, e.b};
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const double m = length * (i == j ? 2.0 : 1.0) / 6.0;
        for (int c = 0; c < 2; ++c) triplets.emplace_back(2 * ends[i] + c, 2 * ends[j] + c, m);
      }
    }
  }
  SparseMatrix M(mesh.num_dofs(), mesh.num_dofs());
  M.setFromTriplets(triplets.begin(), triplets.end());
  return M;
}

Eigen::Matrix3Xd element_stress(const mesh::Mesh& mesh, const std::vector<Material>& materials,
                                const Eigen::VectorXd& u) {
  check_materials(mesh, materials, "element_stress");
  require(u.size() == mesh.num_dofs(), "element_stress: displacement has " + std::to_string(u.size()) +
                                           " entries for " + std::to_string(mesh.num_dofs()) + " DOFs");
  Eigen::Matrix3Xd stress(3, mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
    Eigen::Matrix<double, 6, 1> ue;
    for (int i = 0; i < 3; ++i) ue.segment<2>(2 * i) = u.segment<2>(2 * tri[static_cast<std::size_t>(i)]);
    const Material& m = materials[static_cast<std::size_t>(mesh.body[static_cast<std::size_t>(t)])];
    stress.col(t) = plane_strain_stress(strain_operator(element_of(mesh, t)) * ue, m.lame_lambda(), m.lame_mu());
  }
  return stress;
}

}  // namespace contactrb::fem
