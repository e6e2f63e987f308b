#pragma once
// Transfer of an HF solution from one mesh of a geometry to another (grid sequencing, docs/solvers.md
// "Grid sequencing"): the built-in levels are separate Gmsh meshes (not nested: only the slave
// arc nodes of levels >= 2 are), so each fine node is located in a coarse triangle of its own body
// and the P1 displacement is interpolated there; the contact pressures are interpolated along the
// slave boundary. The result is an initial guess only (HFInitialGuess), never an answer.
#include <Eigen/Core>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::hf {

// Point location in the triangles of one body of a mesh: a bucket grid over the body's bounding
// box (about one triangle per cell), triangles registered in every cell their bounding box meets.
class TriangleLocator {
 public:
  TriangleLocator(const mesh::Mesh& mesh, int body);
  struct Location {
    int triangle = -1;
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // of the point in `triangle` (may be < 0 outside)
    double distance = 0.0;  // from the point to the triangle (0 inside)
  };
  // The triangle containing x, or, for a point outside the body (a fine boundary node beyond a
  // coarse chord of a curved boundary), the nearest triangle; its barycentric coordinates then
  // extrapolate linearly. Throws contactrb::Error when the body has no triangle.
  Location locate(const Eigen::Vector2d& x) const;

 private:
  const mesh::Mesh* mesh_ = nullptr;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_;      // CSR over cells
  std::vector<int> triangles_;
  void cell_of(const Eigen::Vector2d& x, int& i, int& j) const;
};

// The P1 field u_coarse (2 per node, mesh.hpp numbering) at the nodes of `fine`: each fine node
// is located in the coarse triangles of its own body (the body of a triangle that uses it).
// Exact for a field linear on each body. Throws contactrb::Error on sizes that do not match or
// a fine body absent from the coarse mesh.
Eigen::VectorXd transfer_displacement(const mesh::Mesh& coarse, const Eigen::VectorXd& u_coarse,
                                      const mesh::Mesh& fine);

// Contact pressures (one per constraint row) from the coarse rows to the fine ones: piecewise
// linear in the normalized arc length along the slave chain, each row at the centroid of its
// quadrature weights W (the mean arc length of its slave nodes, weighted), constant beyond the
// first and last coarse rows. Exact for a pressure linear in the arc length between those rows.
Eigen::VectorXd transfer_pressure(const mesh::Mesh& coarse, const contact::ContactPair& coarse_pair,
                                  const contact::ContactQuadrature& coarse_quadrature,
                                  const Eigen::VectorXd& lambda_coarse, const mesh::Mesh& fine,
                                  const contact::ContactPair& fine_pair,
                                  const contact::ContactQuadrature& fine_quadrature);

// Normalized arc length (0 at slave.front(), 1 at slave.back()) of each constraint row's centroid.
std::vector<double> row_arc_positions(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                                      const contact::ContactQuadrature& quadrature);

}  // namespace contactrb::hf
