// write_msh (msh_io.hpp): Gmsh ASCII format 4.1. One surface entity per body (physical
// groups "body1", "body2"), one curve entity per boundary group (a 1D physical group of the
// same name). Node tag = node index + 1; nodes are listed in index order, grouped by body.
#include <algorithm>
#include <fstream>
#include <limits>

#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/mesh/msh_io.hpp"

namespace contactrb::mesh {

namespace {

struct Box {
  Eigen::Vector2d lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Eigen::Vector2d hi{std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  void add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

std::ostream& operator<<(std::ostream& os, const Box& b) {
  return os << b.lo.x() << ' ' << b.lo.y() << " 0 " << b.hi.x() << ' ' << b.hi.y() << " 0";
}

}  // namespace

void write_msh(const Mesh& mesh, const std::string& path) {
  validate(mesh);
  for (const auto& [name, edges] : mesh.boundaries) {
    require(!name.empty() && name.find('"') == std::string::npos && name.find('\n') == std::string::npos,
            "write_msh: boundary group name '" + name + "' cannot be written as a Gmsh physical name");
  }
  const int bodies = mesh.num_bodies();
  std::vector<int> owner(mesh.nodes.size(), 0);
  std::vector<Box> body_box(static_cast<std::size_t>(bodies));
  std::vector<std::vector<int>> body_nodes(static_cast<std::size_t>(bodies));
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int v : mesh.triangles[static_cast<std::size_t>(t)]) owner[static_cast<std::size_t>(v)] = mesh.body[static_cast<std::size_t>(t)];
  }
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const auto b = static_cast<std::size_t>(owner[static_cast<std::size_t>(v)]);
    body_nodes[b].push_back(v);
    body_box[b].add(mesh.nodes[static_cast<std::size_t>(v)]);
  }

  // Atomic (temporary file + rename): an interrupted write never leaves half a mesh, and a
  // link or device at `path` is refused (common/output_file.hpp).
  write_file_atomically(path, [&](std::ostream& out) {
    out.precision(std::numeric_limits<double>::max_digits10);
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

    const int groups = static_cast<int>(mesh.boundaries.size());
    out << "$PhysicalNames\n" << bodies + groups << '\n';
    {
      int tag = 1;
      for (const auto& [name, edges] : mesh.boundaries) out << "1 " << tag++ << " \"" << name << "\"\n";
      for (int b = 0; b < bodies; ++b) out << "2 " << b + 1 << " \"body" << b + 1 << "\"\n";
    }
    out << "$EndPhysicalNames\n";

    out << "$Entities\n0 " << groups << ' ' << bodies << " 0\n";
    {
      int tag = 1;
      for (const auto& [name, edges] : mesh.boundaries) {
        Box box;
        for (const Edge& e : edges) {
          box.add(mesh.nodes[static_cast<std::size_t>(e.a)]);
          box.add(mesh.nodes[static_cast<std::size_t>(e.b)]);
        }
        if (edges.empty()) box = Box{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
        out << tag << ' ' << box << " 1 " << tag << " 0\n";
        ++tag;
      }
      for (int b = 0; b < bodies; ++b) out << b + 1 << ' ' << body_box[static_cast<std::size_t>(b)] << " 1 " << b + 1 << " 0\n";
    }
    out << "$EndEntities\n";

    out << "$Nodes\n" << bodies << ' ' << mesh.num_nodes() << " 1 " << mesh.num_nodes() << '\n';
    for (int b = 0; b < bodies; ++b) {
      const auto& nodes = body_nodes[static_cast<std::size_t>(b)];
      out << "2 " << b + 1 << " 0 " << nodes.size() << '\n';
      for (int v : nodes) out << v + 1 << '\n';
      for (int v : nodes) {
        const auto& p = mesh.nodes[static_cast<std::size_t>(v)];
        out << p.x() << ' ' << p.y() << " 0\n";
      }
    }
    out << "$EndNodes\n";

    std::size_t edge_count = 0;
    for (const auto& [name, edges] : mesh.boundaries) edge_count += edges.size();
    const std::size_t elements = edge_count + mesh.triangles.size();
    out << "$Elements\n" << groups + bodies << ' ' << elements << " 1 " << elements << '\n';
    std::size_t element = 1;
    {
      int tag = 1;
      for (const auto& [name, edges] : mesh.boundaries) {
        out << "1 " << tag++ << " 1 " << edges.size() << '\n';
        for (const Edge& e : edges) out << element++ << ' ' << e.a + 1 << ' ' << e.b + 1 << '\n';
      }
    }
    for (int b = 0; b < bodies; ++b) {
      const auto count = std::count(mesh.body.begin(), mesh.body.end(), b);
      out << "2 " << b + 1 << " 2 " << count << '\n';
      for (int t = 0; t < mesh.num_triangles(); ++t) {
        if (mesh.body[static_cast<std::size_t>(t)] != b) continue;
        const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
        out << element++ << ' ' << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << '\n';
      }
    }
    out << "$EndElements\n";
  });
}

}  // namespace contactrb::mesh
