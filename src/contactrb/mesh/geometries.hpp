#pragma once
// Gmsh-generated reference meshes of the paper's geometries (Section 6, Figs. 2 and 17) and of
// the three-dimensional Hertz sphere problem. Every generator returns a validated mesh (see
// mesh.hpp for conventions). The Gmsh API is a process-wide singleton: generators serialize
// their use of it internally.
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh {

// Two half-disks of Hertz (paper Fig. 2). Upper half-disk Omega_1 (slave, body 0): center
// (0, gap/2 + R1), flat edge on top, arc below. Lower half-disk Omega_2 (master, body 1):
// center (0, -gap/2 - R2), flat edge at the bottom, arc above. The arcs are 'gap' apart on
// the vertical axis.
// Boundary groups: "slave" (upper arc), "master" (lower arc), "top" (upper flat edge),
// "bottom" (lower flat edge).
struct HertzGeometry {
  double R1 = 1.0;
  double R2 = 1.0;
  double gap = 0.1;
  int slave_arc_nodes = 51;  // nodes on the slave arc (paper: 51 for the 675-node mesh)
  // When true and R1 == R2, body 1 is the mirror image of body 0 (matching meshes).
  bool mirror = true;
};
Mesh generate_hertz(const HertzGeometry& geometry);

// Slave-arc node counts of the refinement levels: 0 -> 51 (paper's 675-node mesh),
// 1 -> 61 (about 802 nodes, Table 1), 2 -> 121 (about 1682 nodes, Table 2), k > 2 ->
// 120 * 2^(k-2) + 1. Throws contactrb::Error for k < 0.
int hertz_arc_nodes_for_level(int level);

// A half-ring over a rectangular block (paper Section 6.3, Fig. 17; dimensions chosen in
// docs/meshes.md). Half-ring Omega_1 (slave, body 0): lower half of the annulus with outer
// radius R_out and inner radius R_in, centered at (0, gap + R_out). Block Omega_2 (master,
// body 1): [-W/2, W/2] x [-H, 0].
// Boundary groups: "slave" (outer arc of the ring), "master" (top edge of the block),
// "ring_ends" (the two horizontal end faces of the ring), "block_bottom".
struct RingBlockGeometry {
  double R_out = 1.0;
  double thickness = 0.2;
  double gap = 0.0;
  double block_width = 3.0;
  double block_height = 1.0;
  int slave_arc_nodes = 121;
  int master_edge_nodes = 91;
};
Mesh generate_ring_block(const RingBlockGeometry& geometry);

// The Hertz sphere problem in 3D as a quarter model: the part x >= 0, y >= 0 of a hemisphere
// pressed on a block, with the symmetry planes x = 0 and y = 0 (docs/cases.md, "hertz-3d").
// Hemisphere Omega_1 (slave, body 0): the lower half of the ball of radius R centred at
// (0, 0, gap/2 + R), flat face on top. Block Omega_2 (master, body 1):
// [0, W]^2 x [-gap/2 - H, -gap/2]. The curved surface and the block's top face are gap apart at
// the origin (the first contact point). Tetrahedra of size fine_size within fine_radius of it,
// growing linearly to coarse_size at coarse_radius (OpenCASCADE kernel, Delaunay, one thread:
// the same mesh on every run).
// Boundary groups: "slave" (the curved surface below z = gap/2 + cap_height R), "sphere_free"
// (the rest of the curved surface), "top" (the hemisphere's flat face), "master" (the block's
// top face), "bottom" (the block's bottom face), "master_sides" (the block's faces x = W and
// y = W), "symmetry_x" (the faces on x = 0 of both bodies), "symmetry_y" (on y = 0).
struct Hertz3dGeometry {
  double R = 1.0;
  double gap = 0.0;
  double block_width = 1.0;
  double block_height = 1.0;
  double cap_height = 0.25;
  double fine_size = 0.04;
  double fine_radius = 0.2;
  double coarse_size = 0.2;
  double coarse_radius = 0.6;
};
Mesh3 generate_hertz_3d(const Hertz3dGeometry& geometry);

// The finest hertz-3d level: level 4 has about 4e5 nodes, each level about 7 times more.
inline constexpr int kMaxHertz3dLevel = 5;
// The contact-zone size of refinement level k: 0.04 / 2^k (radius 1). Throws contactrb::Error
// for k outside [0, kMaxHertz3dLevel].
double hertz_3d_fine_size_for_level(int level);

// A single half-disk {x^2 + y^2 < R^2, y > 0} (body 0) with `arc_nodes` nodes on its arc,
// for convergence tests. Groups: "arc", "flat".
Mesh generate_half_disk(double radius, int arc_nodes);

}  // namespace contactrb::mesh
