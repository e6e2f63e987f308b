#pragma once
// Gmsh-generated reference meshes of the paper's geometries (Section 6, Figs. 2 and 17).
// Every generator returns a validated Mesh (see mesh.hpp for conventions). The Gmsh API
// is a process-wide singleton: generators serialize their use of it internally.
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

// A single half-disk {x^2 + y^2 < R^2, y > 0} (body 0) with `arc_nodes` nodes on its arc,
// for convergence tests. Groups: "arc", "flat".
Mesh generate_half_disk(double radius, int arc_nodes);

}  // namespace contactrb::mesh
