#pragma once
// Transfer of an HF solution from one mesh of a geometry to another (grid sequencing, docs/solvers.md
// "Grid sequencing"): the built-in levels are separate Gmsh meshes (not nested: only the slave
// arc nodes of levels >= 2 are), so each fine node is located in a coarse triangle (2D) or
// tetrahedron (3D) of its own body and the P1 displacement is interpolated there; the contact
// pressures are interpolated along the slave boundary (2D: its arc length; 3D: its triangles). The result is an initial guess only (HFInitialGuess), never an answer.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::hf {

// Point location in the cells of one body of a mesh (triangles in 2D, tetrahedra in 3D), about
// O(log n) per query on graded meshes too (docs/solvers.md, "Grid sequencing"): a point is
// located by a bounding-volume tree over the body's cells; a point outside the body by a
// bounding-volume tree over the body's boundary facets (edges in 2D, triangles in 3D): its
// nearest facet's cell is the nearest cell. Never all pairs.
template <int Dim>
class SimplexLocator {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;
  using Barycentric = Eigen::Matrix<double, Dim + 1, 1>;
  // Throws contactrb::Error when the body has no cell.
  SimplexLocator(const mesh::SimplexMesh<Dim>& mesh, int body);
  ~SimplexLocator();
  SimplexLocator(SimplexLocator&&) noexcept;
  SimplexLocator& operator=(SimplexLocator&&) noexcept;
  struct Location {
    int cell = -1;
    Barycentric barycentric = Barycentric::Zero();  // of the point in `cell` (some < 0 outside)
    double distance = 0.0;  // from the point to the cell (0 inside)
  };
  // The cell containing x (the lowest-numbered one, to round-off: coordinates above -1e-12), or,
  // for a point outside the body (a fine boundary node beyond a coarse chord or facet of a curved
  // boundary), the cell of the nearest boundary facet (the lowest-numbered facet among equally
  // near ones), which is a nearest cell; its barycentric coordinates then extrapolate linearly
  // (docs/solvers.md, "Grid sequencing").
  Location locate(const Point& x) const;

 private:
  struct Search;  // the two trees (level_transfer.cpp)
  const mesh::SimplexMesh<Dim>* mesh_ = nullptr;
  std::unique_ptr<const Search> search_;
};
using TriangleLocator = SimplexLocator<2>;
using TetrahedronLocator = SimplexLocator<3>;
extern template class SimplexLocator<2>;
extern template class SimplexLocator<3>;

// The P1 field u_coarse (Dim per node, mesh.hpp numbering) at the nodes of `fine`: each fine
// node is located in the coarse cells of its own body (the body of a cell that uses it) and
// interpolated barycentrically (extrapolated from the nearest cell outside the coarse body).
// Exact for a field linear on each body. Throws contactrb::Error on sizes that do not match or
// a fine body absent from the coarse mesh.
template <int Dim>
Eigen::VectorXd transfer_displacement(const mesh::SimplexMesh<Dim>& coarse, const Eigen::VectorXd& u_coarse,
                                      const mesh::SimplexMesh<Dim>& fine);
extern template Eigen::VectorXd transfer_displacement(const mesh::Mesh&, const Eigen::VectorXd&, const mesh::Mesh&);
extern template Eigen::VectorXd transfer_displacement(const mesh::Mesh3&, const Eigen::VectorXd&, const mesh::Mesh3&);

// Contact pressures (one per constraint row) from the coarse rows to the fine ones: piecewise
// linear in the normalized arc length along the slave chain, each row at the centroid of its
// quadrature weights W (the mean arc length of its slave nodes, weighted), constant beyond the
// first and last coarse rows. Exact for a pressure linear in the arc length between those rows.
Eigen::VectorXd transfer_pressure(const mesh::Mesh& coarse, const contact::ContactPair& coarse_pair,
                                  const contact::ContactQuadrature& coarse_quadrature,
                                  const Eigen::VectorXd& lambda_coarse, const mesh::Mesh& fine,
                                  const contact::ContactPair& fine_pair,
                                  const contact::ContactQuadrature& fine_quadrature);

// 3D: one row per slave node (its center node). The coarse pressure is the P1 field of the
// coarse rows' values on the coarse slave triangles; each fine row takes its value at the
// closest point of its node on that surface (a bounding-volume tree over the coarse slave
// triangles). Exact for a pressure linear on the coarse slave surface.
Eigen::VectorXd transfer_pressure(const mesh::Mesh3& coarse, const contact::ContactPair3& coarse_pair,
                                  const contact::ContactQuadrature& coarse_quadrature,
                                  const Eigen::VectorXd& lambda_coarse, const mesh::Mesh3& fine,
                                  const contact::ContactPair3& fine_pair,
                                  const contact::ContactQuadrature& fine_quadrature);

// Normalized arc length (0 at slave.front(), 1 at slave.back()) of each constraint row's centroid.
std::vector<double> row_arc_positions(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                                      const contact::ContactQuadrature& quadrature);

}  // namespace contactrb::hf
