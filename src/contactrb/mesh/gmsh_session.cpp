#include "contactrb/mesh/gmsh_session.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <unordered_map>

#include "contactrb/common/error.hpp"

namespace contactrb::mesh::detail {

namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

// Gmsh element type codes (Gmsh reference manual, "MSH file format").
constexpr int kGmshLine2 = 1;
constexpr int kGmshTriangle3 = 2;
constexpr int kGmshTetrahedron4 = 4;

}  // namespace

GmshSession::GmshSession(const std::string& model_name) : lock_(gmsh_mutex()) {
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 0);
  gmsh::option::setNumber("General.NumThreads", 1);
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: deterministic
  gmsh::option::setNumber("Mesh.ElementOrder", 1);
  gmsh::option::setNumber("Mesh.RecombineAll", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::model::add(model_name);
}

GmshSession::~GmshSession() {
  try {
    gmsh::finalize();
  } catch (...) {  // NOLINT: a destructor must not throw
  }
}

int add_point(const Eigen::Vector2d& p) { return gmsh::model::geo::addPoint(p.x(), p.y(), 0.0); }

std::vector<int> add_arc(int start, int end, const Eigen::Vector2d& center, double radius,
                         double theta0, double theta1, int nodes) {
  require(nodes >= 3, "arc needs at least 3 nodes (got " + std::to_string(nodes) + ")");
  const int segments = nodes - 1;
  const double span = std::abs(theta1 - theta0);
  // Pieces strictly shorter than pi (Gmsh's circle arcs), cut at node positions.
  int pieces = static_cast<int>(std::ceil(span / (0.75 * std::numbers::pi)));
  pieces = std::clamp(pieces, 1, segments);
  const int c = add_point(center);
  std::vector<int> curves;
  int previous_point = start;
  int previous_cut = 0;
  for (int k = 1; k <= pieces; ++k) {
    const int cut = (k == pieces) ? segments : (k * segments + pieces / 2) / pieces;
    int point = end;
    if (k < pieces) {
      const double theta = theta0 + (theta1 - theta0) * cut / segments;
      point = add_point(center + radius * Eigen::Vector2d(std::cos(theta), std::sin(theta)));
    }
    const int curve = gmsh::model::geo::addCircleArc(previous_point, c, point);
    gmsh::model::geo::mesh::setTransfiniteCurve(curve, cut - previous_cut + 1);
    curves.push_back(curve);
    previous_point = point;
    previous_cut = cut;
  }
  return curves;
}

int add_segment(int start, int end, int nodes, double ratio) {
  const int curve = gmsh::model::geo::addLine(start, end);
  if (nodes > 0) gmsh::model::geo::mesh::setTransfiniteCurve(curve, nodes, "Progression", ratio);
  return curve;
}

int add_plane_surface(const std::vector<int>& loop_curves) {
  const int loop = gmsh::model::geo::addCurveLoop(loop_curves);
  return gmsh::model::geo::addPlaneSurface({loop});
}

namespace {

// The background size field: the minimum over `ramps` of their thresholds.
void set_background_field(const std::vector<SizeRamp>& ramps) {
  std::vector<double> thresholds;
  for (const SizeRamp& r : ramps) {
    const int d = gmsh::model::mesh::field::add("MathEval");
    gmsh::model::mesh::field::setString(d, "F", r.distance);
    const int t = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(t, "InField", d);
    gmsh::model::mesh::field::setNumber(t, "SizeMin", r.size_min);
    gmsh::model::mesh::field::setNumber(t, "SizeMax", r.size_max);
    gmsh::model::mesh::field::setNumber(t, "DistMin", r.dist_min);
    gmsh::model::mesh::field::setNumber(t, "DistMax", r.dist_max);
    thresholds.push_back(t);
  }
  const int background = gmsh::model::mesh::field::add("Min");
  gmsh::model::mesh::field::setNumbers(background, "FieldsList", thresholds);
  gmsh::model::mesh::field::setAsBackgroundMesh(background);
}

}  // namespace

void mesh_2d(const std::vector<SizeRamp>& ramps) {
  gmsh::model::geo::synchronize();
  set_background_field(ramps);
  gmsh::model::mesh::generate(2);
}

void mesh_3d_occ(const std::vector<SizeRamp>& ramps) {
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay: deterministic on one thread
  set_background_field(ramps);
  gmsh::model::mesh::generate(3);
}

namespace {

// The Gmsh element type of the cells and of the boundary facets of a Dim-dimensional mesh.
template <int Dim>
constexpr int kGmshCell = Dim == 2 ? kGmshTriangle3 : kGmshTetrahedron4;
template <int Dim>
constexpr int kGmshFacet = Dim == 2 ? kGmshLine2 : kGmshTriangle3;

// The node tags of the elements of entity (dim, tag), checked to be of `type`.
std::vector<std::size_t> element_nodes(int dim, int tag, int type) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags;
  std::vector<std::vector<std::size_t>> node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, tag);
  std::vector<std::size_t> nodes;
  for (std::size_t k = 0; k < types.size(); ++k) {
    require(types[k] == type, "gmsh produced element type " + std::to_string(types[k]) + " in dimension " +
                                  std::to_string(dim) + " (expected type " + std::to_string(type) + ")");
    nodes.insert(nodes.end(), node_tags[k].begin(), node_tags[k].end());
  }
  return nodes;
}

template <int Dim>
SimplexMesh<Dim> extract_simplex_mesh(const std::map<int, int>& entity_body,
                                      const std::map<std::string, std::vector<int>>& groups) {
  std::vector<std::size_t> tags;
  std::vector<double> coords;
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> position;  // gmsh tag -> index in tags
  for (std::size_t k = 0; k < tags.size(); ++k) position.emplace(tags[k], k);

  SimplexMesh<Dim> mesh;
  std::unordered_map<std::size_t, int> index;  // gmsh tag -> mesh node
  auto node = [&](std::size_t tag) {
    auto [it, inserted] = index.emplace(tag, mesh.num_nodes());
    if (inserted) {
      const std::size_t k = position.at(tag);
      typename SimplexMesh<Dim>::Point p;
      for (int c = 0; c < Dim; ++c) p(c) = coords[3 * k + static_cast<std::size_t>(c)];
      mesh.nodes.push_back(p);
    }
    return it->second;
  };

  constexpr std::size_t kCellNodes = Dim + 1;
  for (const auto& [entity, body] : entity_body) {
    const std::vector<std::size_t> nt = element_nodes(Dim, entity, kGmshCell<Dim>);
    for (std::size_t e = 0; e + kCellNodes <= nt.size(); e += kCellNodes) {
      typename SimplexMesh<Dim>::Cell cell{};
      for (std::size_t v = 0; v < kCellNodes; ++v) cell[v] = node(nt[e + v]);
      mesh.cells().push_back(cell);
      mesh.body.push_back(body);
      if (signed_volume(mesh, mesh.num_cells() - 1) < 0.0) std::swap(mesh.cells().back()[1], mesh.cells().back()[2]);
    }
  }

  std::set<std::array<int, Dim>> outward;  // the cells' facets, oriented with their outward normal
  for (const auto& cell : mesh.cells()) {
    for (const auto& local : kCellFacets<Dim>) {
      std::array<int, Dim> f{};
      for (std::size_t k = 0; k < Dim; ++k) f[k] = cell[static_cast<std::size_t>(local[k])];
      outward.insert(oriented_key<Dim>(f));
    }
  }
  for (const auto& [name, entities] : groups) {
    auto& facets = mesh.boundaries[name];
    for (int entity : entities) {
      const std::vector<std::size_t> nt = element_nodes(Dim - 1, entity, kGmshFacet<Dim>);
      for (std::size_t e = 0; e + Dim <= nt.size(); e += Dim) {
        std::array<int, Dim> f{};
        for (std::size_t v = 0; v < Dim; ++v) f[v] = index.at(nt[e + v]);
        if (outward.count(oriented_key<Dim>(f)) == 0) std::swap(f[Dim - 2], f[Dim - 1]);
        if constexpr (Dim == 2) {
          facets.push_back(Edge{f[0], f[1]});
        } else {
          facets.push_back(Face{f[0], f[1], f[2]});
        }
      }
    }
  }
  return mesh;
}

}  // namespace

Mesh extract_mesh(const std::map<int, int>& surface_body, const std::map<std::string, std::vector<int>>& groups) {
  return extract_simplex_mesh<2>(surface_body, groups);
}

Mesh3 extract_mesh3(const std::map<int, int>& volume_body, const std::map<std::string, std::vector<int>>& groups) {
  return extract_simplex_mesh<3>(volume_body, groups);
}

void rethrow_as_error(const std::string& what) {
  try {
    throw;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(what + ": " + e.what());
  } catch (...) {
    std::string last;
    try {
      gmsh::logger::getLastError(last);
    } catch (...) {  // NOLINT: keep the generic message below
    }
    throw Error(what + ": Gmsh failed" + (last.empty() ? std::string() : " (" + last + ")"));
  }
}

double progression_ratio(double length, int segments, double first) {
  require(segments >= 1 && length > 0.0 && first > 0.0, "progression_ratio: invalid arguments");
  auto total = [&](double r) {
    return std::abs(r - 1.0) < 1e-12 ? first * segments : first * (std::pow(r, segments) - 1.0) / (r - 1.0);
  };
  double lo = 1e-3;
  double hi = 1e3;
  for (int it = 0; it < 200; ++it) {  // bisection: total(r) is increasing in r
    const double mid = std::sqrt(lo * hi);
    (total(mid) < length ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace contactrb::mesh::detail
