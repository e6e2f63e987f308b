#pragma once
// Internal to contactrb_mesh (not installed, not for other modules): a scoped use of the
// Gmsh API, which is a process-wide singleton, and the few geometry/mesh helpers the
// built-in geometries need.
#include <Eigen/Core>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh::detail {

// Locks the process-wide Gmsh mutex, initializes Gmsh silently (General.Terminal = 0) with
// deterministic settings (2D: Frontal-Delaunay, one thread, order-1 triangles, sizes from
// the background field only) and a fresh model; finalizes on destruction.
class GmshSession {
 public:
  explicit GmshSession(const std::string& model_name);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;
};

// Graded size field: h = size_min where dist <= dist_min, growing linearly to size_max at
// dist = dist_max. `distance` is a Gmsh MathEval expression in x, y (and z in 3D).
struct SizeRamp {
  std::string distance;
  double size_min = 0.0;
  double size_max = 0.0;
  double dist_max = 1.0;
  double dist_min = 0.0;
};

// Built-in (geo) kernel helpers; call inside a GmshSession.
int add_point(const Eigen::Vector2d& p);
// Arc of the circle (center, radius) from angle theta0 to theta1 (radians, either
// direction, |theta1 - theta0| <= 2 pi) with exactly `nodes` equally spaced nodes
// (endpoints included). Split into pieces shorter than pi as Gmsh requires; returns the
// curve tags in order. start/end are the endpoint tags (created by the caller).
std::vector<int> add_arc(int start, int end, const Eigen::Vector2d& center, double radius,
                         double theta0, double theta1, int nodes);
// Straight segment; nodes > 0 makes it transfinite with that many nodes and geometric
// progression `ratio` (segment length ratio from start to end), nodes == 0 leaves its
// sizes to the background field.
int add_segment(int start, int end, int nodes = 0, double ratio = 1.0);
int add_plane_surface(const std::vector<int>& loop_curves);

// Synchronizes, sets the background field min over `ramps` and meshes in 2D.
void mesh_2d(const std::vector<SizeRamp>& ramps);

// Synchronizes the OpenCASCADE model, sets the background field min over `ramps` and meshes
// in 3D (Delaunay, one thread).
void mesh_3d_occ(const std::vector<SizeRamp>& ramps);

// Converts the current Gmsh mesh (one code for both dimensions): entities of the mesh's
// dimension (surfaces in 2D, volumes in 3D) -> bodies, named sets of entities of one dimension
// less -> boundary groups (facets oriented with the outward normal of their body, mesh.hpp).
// Cells are made positive.
Mesh extract_mesh(const std::map<int, int>& surface_body, const std::map<std::string, std::vector<int>>& groups);
Mesh3 extract_mesh3(const std::map<int, int>& volume_body, const std::map<std::string, std::vector<int>>& groups);

// Call from a catch block inside a GmshSession: rethrows contactrb::Error unchanged and
// anything else (Gmsh API failures) as contactrb::Error("<what>: <Gmsh's last error>").
[[noreturn]] void rethrow_as_error(const std::string& what);

// Geometric progression ratio r such that `segments` segments of total length `length`
// start with a segment of length `first` (r = 1 when first * segments == length).
double progression_ratio(double length, int segments, double first);

}  // namespace contactrb::mesh::detail
