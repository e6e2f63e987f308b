// write_msh (msh_io.hpp): Gmsh ASCII format 4.1. One entity of the mesh's dimension per body
// (physical groups "body1", "body2"), one entity of one dimension less per boundary group (a
// physical group of the same name). Node tag = node index + 1; nodes are listed in index
// order, grouped by body.
#include <algorithm>
#include <fstream>
#include <limits>

#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/mesh/msh_io.hpp"

namespace contactrb::mesh {

namespace {

// A point as x y z (z = 0 in 2D).
template <int Dim>
std::ostream& write_point(std::ostream& os, const Eigen::Matrix<double, Dim, 1>& p) {
  os << p.x() << ' ' << p.y();
  if constexpr (Dim == 2) {
    return os << " 0";
  } else {
    return os << ' ' << p.z();
  }
}

template <int Dim>
struct Box {
  using Point = Eigen::Matrix<double, Dim, 1>;
  Point lo = Point::Constant(std::numeric_limits<double>::max());
  Point hi = Point::Constant(std::numeric_limits<double>::lowest());
  void add(const Point& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

template <int Dim>
std::ostream& operator<<(std::ostream& os, const Box<Dim>& b) {
  write_point<Dim>(os, b.lo) << ' ';
  return write_point<Dim>(os, b.hi);
}

template <std::size_t N>
void write_indices(std::ostream& out, std::size_t tag, const std::array<int, N>& v) {
  out << tag;
  for (int i : v) out << ' ' << i + 1;
  out << '\n';
}

template <int Dim>
void write_simplex_msh(const SimplexMesh<Dim>& mesh, const std::string& path) {
  constexpr int cell_type = Dim == 2 ? 2 : 4;   // 3-node triangle, 4-node tetrahedron
  constexpr int facet_type = Dim == 2 ? 1 : 2;  // 2-node line, 3-node triangle
  validate(mesh);
  for (const auto& [name, edges] : mesh.boundaries) {
    require(!name.empty() && name.find('"') == std::string::npos && name.find('\n') == std::string::npos,
            "write_msh: boundary group name '" + name + "' cannot be written as a Gmsh physical name");
  }
  const int bodies = mesh.num_bodies();
  std::vector<int> owner(mesh.nodes.size(), 0);
  std::vector<Box<Dim>> body_box(static_cast<std::size_t>(bodies));
  std::vector<std::vector<int>> body_nodes(static_cast<std::size_t>(bodies));
  for (int t = 0; t < mesh.num_cells(); ++t) {
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) owner[static_cast<std::size_t>(v)] = mesh.body[static_cast<std::size_t>(t)];
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
      for (const auto& [name, edges] : mesh.boundaries) out << Dim - 1 << ' ' << tag++ << " \"" << name << "\"\n";
      for (int b = 0; b < bodies; ++b) out << Dim << ' ' << b + 1 << " \"body" << b + 1 << "\"\n";
    }
    out << "$EndPhysicalNames\n";

    out << "$Entities\n" << (Dim == 2 ? "0 " : "0 0 ") << groups << ' ' << bodies << (Dim == 2 ? " 0\n" : "\n");
    {
      int tag = 1;
      for (const auto& [name, edges] : mesh.boundaries) {
        Box<Dim> box;
        for (const auto& e : edges) {
          for (int v : e.vertices()) box.add(mesh.nodes[static_cast<std::size_t>(v)]);
        }
        if (edges.empty()) box = Box<Dim>{Box<Dim>::Point::Zero(), Box<Dim>::Point::Zero()};
        out << tag << ' ' << box << " 1 " << tag << " 0\n";
        ++tag;
      }
      for (int b = 0; b < bodies; ++b) out << b + 1 << ' ' << body_box[static_cast<std::size_t>(b)] << " 1 " << b + 1 << " 0\n";
    }
    out << "$EndEntities\n";

    out << "$Nodes\n" << bodies << ' ' << mesh.num_nodes() << " 1 " << mesh.num_nodes() << '\n';
    for (int b = 0; b < bodies; ++b) {
      const auto& nodes = body_nodes[static_cast<std::size_t>(b)];
      out << Dim << ' ' << b + 1 << " 0 " << nodes.size() << '\n';
      for (int v : nodes) out << v + 1 << '\n';
      for (int v : nodes) write_point<Dim>(out, mesh.nodes[static_cast<std::size_t>(v)]) << '\n';
    }
    out << "$EndNodes\n";

    std::size_t edge_count = 0;
    for (const auto& [name, edges] : mesh.boundaries) edge_count += edges.size();
    const std::size_t elements = edge_count + mesh.cells().size();
    out << "$Elements\n" << groups + bodies << ' ' << elements << " 1 " << elements << '\n';
    std::size_t element = 1;
    {
      int tag = 1;
      for (const auto& [name, edges] : mesh.boundaries) {
        out << Dim - 1 << ' ' << tag++ << ' ' << facet_type << ' ' << edges.size() << '\n';
        for (const auto& e : edges) write_indices(out, element++, e.vertices());
      }
    }
    for (int b = 0; b < bodies; ++b) {
      const auto count = std::count(mesh.body.begin(), mesh.body.end(), b);
      out << Dim << ' ' << b + 1 << ' ' << cell_type << ' ' << count << '\n';
      for (int t = 0; t < mesh.num_cells(); ++t) {
        if (mesh.body[static_cast<std::size_t>(t)] != b) continue;
        write_indices(out, element++, mesh.cells()[static_cast<std::size_t>(t)]);
      }
    }
    out << "$EndElements\n";
  });
}

}  // namespace

void write_msh(const Mesh& mesh, const std::string& path) { write_simplex_msh(mesh, path); }

void write_msh(const Mesh3& mesh, const std::string& path) { write_simplex_msh(mesh, path); }

}  // namespace contactrb::mesh
