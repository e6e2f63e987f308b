#include "contactrb/fem/elasticity.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/fem/p1_element.hpp"
#include "contactrb/fem/quadrature.hpp"
#include "contactrb/fem/sparsity.hpp"

namespace contactrb::fem {
namespace {

template <int Dim>
P1Simplex<Dim> element_of(const mesh::SimplexMesh<Dim>& mesh, int t) {
  const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
  std::array<Vector<Dim>, Dim + 1> p;
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = mesh.nodes[static_cast<std::size_t>(cell[k])];
  return p1_simplex<Dim>(p);
}

template <int Dim>
void check_body(const mesh::SimplexMesh<Dim>& mesh, int body, const char* who) {
  require(body >= 0 && body < mesh.num_bodies(), std::string(who) + ": body " + std::to_string(body) +
                                                     " out of range (mesh has " +
                                                     std::to_string(mesh.num_bodies()) + " bodies)");
}

template <int Dim>
void check_materials(const mesh::SimplexMesh<Dim>& mesh, const std::vector<Material>& materials, const char* who) {
  require(static_cast<int>(materials.size()) == mesh.num_bodies(),
          std::string(who) + ": " + std::to_string(materials.size()) + " materials for " +
              std::to_string(mesh.num_bodies()) + " bodies");
  for (const Material& m : materials) check_material(m);
}

// Assembles one matrix over `cells` with kernel(P1Simplex) -> SimplexElementMatrix.
template <int Dim, class Kernel>
SparseMatrix assemble(const mesh::SimplexMesh<Dim>& mesh, const std::vector<int>& cells, Kernel kernel) {
  const SimplexSparsity<Dim> pattern(mesh, cells);
  SparseMatrix A = pattern.zero_matrix();
  for (int t : cells) {
    pattern.add(mesh.cells()[static_cast<std::size_t>(t)], kernel(element_of(mesh, t)), A.valuePtr());
  }
  return A;
}

// Both Lame parts on one pattern, in one pass: S_div into the returned matrix, S_sym into
// `symmetric_gradient` (pattern order).
template <int Dim>
SparseMatrix assemble_lame_parts(const mesh::SimplexMesh<Dim>& mesh, const SimplexSparsity<Dim>& pattern,
                                 const std::vector<int>& cells, std::vector<double>& symmetric_gradient) {
  SparseMatrix divergence = pattern.zero_matrix();
  symmetric_gradient = pattern.zero_values();
  for (int t : cells) {
    const P1Simplex<Dim> element = element_of(mesh, t);
    const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
    pattern.add(cell, element_divergence(element), divergence.valuePtr());
    pattern.add(cell, element_symmetric_gradient(element), symmetric_gradient);
  }
  return divergence;
}

// The body of each node (-1: in no cell); false when a node is in cells of two bodies.
template <int Dim>
bool node_bodies(const mesh::SimplexMesh<Dim>& mesh, std::vector<int>& node_body) {
  node_body.assign(static_cast<std::size_t>(mesh.num_nodes()), -1);
  bool disjoint = true;
  for (int t = 0; t < mesh.num_cells(); ++t) {
    const int b = mesh.body[static_cast<std::size_t>(t)];
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) {
      int& nb = node_body[static_cast<std::size_t>(v)];
      if (nb >= 0 && nb != b) disjoint = false;
      nb = b;
    }
  }
  return disjoint;
}

// stiffness(): the pattern made on first use (nullptr given) or the caller's.
template <int Dim>
SparseMatrix stiffness_on(const mesh::SimplexMesh<Dim>& mesh, const std::vector<Material>& materials,
                          const SimplexSparsity<Dim>* given) {
  check_materials(mesh, materials, "stiffness");
  // Bodies are disjoint (mesh.hpp), so every matrix entry belongs to the body of its column
  // node: one pattern and one pass serve all bodies.
  std::vector<int> node_body;
  if (!node_bodies(mesh, node_body)) {  // a node shared by two bodies: sum the bodies' matrices
    SparseMatrix K(mesh.num_dofs(), mesh.num_dofs());
    for (int b = 0; b < mesh.num_bodies(); ++b) K += stiffness_body(mesh, b, materials[static_cast<std::size_t>(b)]);
    return K;
  }
  const std::vector<int> cells = cells_of_body(mesh, -1);
  std::optional<SimplexSparsity<Dim>> own;
  if (given == nullptr) own.emplace(mesh, cells);
  const SimplexSparsity<Dim>& pattern = given != nullptr ? *given : *own;
  require(pattern.num_dofs() == mesh.num_dofs(), "stiffness: the pattern has " + std::to_string(pattern.num_dofs()) +
                                                     " DOFs, the mesh " + std::to_string(mesh.num_dofs()));
  std::vector<double> symmetric_gradient;
  SparseMatrix K = assemble_lame_parts(mesh, pattern, cells, symmetric_gradient);
  const double* sym = symmetric_gradient.data();
  double* values = K.valuePtr();
  for (int col = 0; col < K.outerSize(); ++col) {
    const int b = node_body[static_cast<std::size_t>(col / Dim)];
    if (b < 0) continue;  // node in no cell: empty column
    const Material& m = materials[static_cast<std::size_t>(b)];
    const double lambda = m.lame_lambda(), two_mu = 2.0 * m.lame_mu();
    for (int k = K.outerIndexPtr()[col]; k < K.outerIndexPtr()[col + 1]; ++k) {
      values[k] = lambda * values[k] + two_mu * sym[k];
    }
  }
  return K;
}

// Length of an edge (2D), area of a triangle (3D).
template <int Dim>
double facet_measure(const mesh::SimplexMesh<Dim>& mesh, const typename mesh::SimplexMesh<Dim>::Facet& facet) {
  if constexpr (Dim == 2) {
    return (mesh.nodes[static_cast<std::size_t>(facet.b)] - mesh.nodes[static_cast<std::size_t>(facet.a)]).norm();
  } else {
    return mesh::facet_area_normal(mesh, facet).norm();
  }
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

template <int Dim>
SparseMatrix stiffness_body(const mesh::SimplexMesh<Dim>& mesh, int body, const Material& material) {
  check_body(mesh, body, "stiffness_body");
  check_material(material);
  const std::vector<int> cells = cells_of_body(mesh, body);
  const SimplexSparsity<Dim> pattern(mesh, cells);
  std::vector<double> sym;
  SparseMatrix K = assemble_lame_parts(mesh, pattern, cells, sym);
  // Combined entry by entry so that the result equals lambda_L * S_div + 2 mu_L * S_sym
  // to the last bit.
  const double lambda = material.lame_lambda(), two_mu = 2.0 * material.lame_mu();
  double* values = K.valuePtr();
  for (std::size_t k = 0; k < sym.size(); ++k) values[k] = lambda * values[k] + two_mu * sym[k];
  return K;
}

template <int Dim>
SparseMatrix stiffness(const mesh::SimplexMesh<Dim>& mesh, const std::vector<Material>& materials) {
  return stiffness_on<Dim>(mesh, materials, nullptr);
}

template <int Dim>
SparseMatrix stiffness(const mesh::SimplexMesh<Dim>& mesh, const std::vector<Material>& materials,
                       const std::type_identity_t<SimplexSparsity<Dim>>& pattern) {
  return stiffness_on<Dim>(mesh, materials, &pattern);
}

template <int Dim>
SparseMatrix divergence_part(const mesh::SimplexMesh<Dim>& mesh, int body) {
  check_body(mesh, body, "divergence_part");
  return assemble(mesh, cells_of_body(mesh, body), element_divergence<Dim>);
}

template <int Dim>
SparseMatrix symmetric_gradient_part(const mesh::SimplexMesh<Dim>& mesh, int body) {
  check_body(mesh, body, "symmetric_gradient_part");
  return assemble(mesh, cells_of_body(mesh, body), element_symmetric_gradient<Dim>);
}

template <int Dim>
Eigen::VectorXd body_load(const mesh::SimplexMesh<Dim>& mesh, int body, const std::type_identity_t<Vector<Dim>>& load) {
  check_body(mesh, body, "body_load");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (int t : cells_of_body(mesh, body)) {
    const double share = element_of(mesh, t).measure() / (Dim + 1);  // int phi_i = measure / (Dim + 1)
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) f.template segment<Dim>(Dim * v) += share * load;
  }
  return f;
}

template <int Dim>
Eigen::VectorXd body_load(const mesh::SimplexMesh<Dim>& mesh, int body,
                          const std::type_identity_t<VectorField<Dim>>& load, int degree) {
  check_body(mesh, body, "body_load");
  require(static_cast<bool>(load), "body_load: empty load function");
  const SimplexQuadrature<Dim>& rule = simplex_quadrature<Dim>(degree);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (int t : cells_of_body(mesh, body)) {
    const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
    const double measure = element_of(mesh, t).measure();
    for (std::size_t q = 0; q < rule.weights.size(); ++q) {
      const auto& l = rule.barycentric[q];
      Vector<Dim> x = l(0) * mesh.nodes[static_cast<std::size_t>(cell[0])];
      for (int i = 1; i < Dim + 1; ++i) x += l(i) * mesh.nodes[static_cast<std::size_t>(cell[static_cast<std::size_t>(i)])];
      const Vector<Dim> value = measure * rule.weights[q] * load(x);
      for (int i = 0; i < Dim + 1; ++i) f.template segment<Dim>(Dim * cell[static_cast<std::size_t>(i)]) += l(i) * value;
    }
  }
  return f;
}

template <int Dim>
SparseMatrix mass(const mesh::SimplexMesh<Dim>& mesh) {
  return assemble(mesh, cells_of_body(mesh, -1), element_mass<Dim>);
}

template <int Dim>
SparseMatrix vector_laplacian(const mesh::SimplexMesh<Dim>& mesh) {
  return assemble(mesh, cells_of_body(mesh, -1), element_laplacian<Dim>);
}

template <int Dim>
SparseMatrix h1_product(const mesh::SimplexMesh<Dim>& mesh) {
  return assemble(mesh, cells_of_body(mesh, -1), [](const P1Simplex<Dim>& e) {
    return SimplexElementMatrix<Dim>(element_mass(e) + element_laplacian(e));
  });
}

template <int Dim>
SparseMatrix boundary_mass(const mesh::SimplexMesh<Dim>& mesh, const std::string& group) {
  const auto& facets = mesh.boundary(group);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(Dim * Dim * Dim) * facets.size());
  // int_F phi_i phi_j = |F| (1 + delta_ij) / (Dim (Dim + 1)) on a facet of Dim nodes.
  constexpr double denominator = Dim * (Dim + 1);
  for (const auto& facet : facets) {
    const auto ends = facet.vertices();
    for (int v : ends) {
      if (v < 0 || v >= mesh.num_nodes()) {
        throw Error("boundary_mass: a " + std::string(mesh::SimplexNames<Dim>::facet) + " of group '" + group +
                    "' has a node index out of range");
      }
    }
    const double measure = facet_measure(mesh, facet);
    for (std::size_t i = 0; i < ends.size(); ++i) {
      for (std::size_t j = 0; j < ends.size(); ++j) {
        const double m = measure * (i == j ? 2.0 : 1.0) / denominator;
        for (int c = 0; c < Dim; ++c) triplets.emplace_back(Dim * ends[i] + c, Dim * ends[j] + c, m);
      }
    }
  }
  SparseMatrix M(mesh.num_dofs(), mesh.num_dofs());
  M.setFromTriplets(triplets.begin(), triplets.end());
  return M;
}

template <int Dim>
Eigen::Matrix<double, kVoigtSize<Dim>, Eigen::Dynamic> element_stress(const mesh::SimplexMesh<Dim>& mesh,
                                                                      const std::vector<Material>& materials,
                                                                      const Eigen::VectorXd& u) {
  check_materials(mesh, materials, "element_stress");
  require(u.size() == mesh.num_dofs(), "element_stress: displacement has " + std::to_string(u.size()) +
                                           " entries for " + std::to_string(mesh.num_dofs()) + " DOFs");
  Eigen::Matrix<double, kVoigtSize<Dim>, Eigen::Dynamic> stress(kVoigtSize<Dim>, mesh.num_cells());
  for (int t = 0; t < mesh.num_cells(); ++t) {
    const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
    Eigen::Matrix<double, Dim*(Dim + 1), 1> ue;
    for (int i = 0; i < Dim + 1; ++i) {
      ue.template segment<Dim>(Dim * i) = u.template segment<Dim>(Dim * cell[static_cast<std::size_t>(i)]);
    }
    const Material& m = materials[static_cast<std::size_t>(mesh.body[static_cast<std::size_t>(t)])];
    stress.col(t) = hooke_stress<Dim>(strain_operator(element_of(mesh, t)) * ue, m.lame_lambda(), m.lame_mu());
  }
  return stress;
}

#define CONTACTRB_ELASTICITY_INSTANTIATE(D)                                                                      \
  template SparseMatrix stiffness_body<D>(const mesh::SimplexMesh<D>&, int, const Material&);                   \
  template SparseMatrix stiffness<D>(const mesh::SimplexMesh<D>&, const std::vector<Material>&);                \
  template SparseMatrix stiffness<D>(const mesh::SimplexMesh<D>&, const std::vector<Material>&,                 \
                                     const std::type_identity_t<SimplexSparsity<D>>&);                          \
  template SparseMatrix divergence_part<D>(const mesh::SimplexMesh<D>&, int);                                   \
  template SparseMatrix symmetric_gradient_part<D>(const mesh::SimplexMesh<D>&, int);                           \
  template Eigen::VectorXd body_load<D>(const mesh::SimplexMesh<D>&, int, const std::type_identity_t<Vector<D>>&); \
  template Eigen::VectorXd body_load<D>(const mesh::SimplexMesh<D>&, int,                                       \
                                        const std::type_identity_t<VectorField<D>>&, int);                      \
  template SparseMatrix mass<D>(const mesh::SimplexMesh<D>&);                                                   \
  template SparseMatrix vector_laplacian<D>(const mesh::SimplexMesh<D>&);                                       \
  template SparseMatrix h1_product<D>(const mesh::SimplexMesh<D>&);                                             \
  template SparseMatrix boundary_mass<D>(const mesh::SimplexMesh<D>&, const std::string&);                      \
  template Eigen::Matrix<double, kVoigtSize<D>, Eigen::Dynamic> element_stress<D>(                             \
      const mesh::SimplexMesh<D>&, const std::vector<Material>&, const Eigen::VectorXd&);
CONTACTRB_ELASTICITY_INSTANTIATE(2)
CONTACTRB_ELASTICITY_INSTANTIATE(3)
#undef CONTACTRB_ELASTICITY_INSTANTIATE

}  // namespace contactrb::fem
