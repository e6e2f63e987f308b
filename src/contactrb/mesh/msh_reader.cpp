// read_msh (msh_io.hpp): own parser of the Gmsh ASCII format 4.1 (Gmsh reference manual,
// section "MSH file format").
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/mesh/msh_io.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::mesh {

namespace {

// Gmsh element type codes and their node counts.
constexpr int kLine2 = 1;
constexpr int kTriangle3 = 2;
constexpr int kPoint = 15;
// A triangle is degenerate when |area| <= kZeroAreaTolerance * (longest edge)^2, the test
// of mesh::validate().
constexpr double kZeroAreaTolerance = 1e-12;

std::string element_type_name(int type) {
  switch (type) {
    case 3: return "4-node quadrangle";
    case 4: return "4-node tetrahedron";
    case 5: return "8-node hexahedron";
    case 6: return "6-node prism";
    case 7: return "5-node pyramid";
    case 8: return "3-node line";
    case 9: return "6-node triangle";
    case 10: return "9-node quadrangle";
    case 16: return "8-node quadrangle";
    default: return "type " + std::to_string(type);
  }
}

// Whitespace-separated tokens with line numbers; "quoted strings" are one token.
class Tokens {
 public:
  Tokens(std::string text, std::string path) : text_(std::move(text)), path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error("mesh file '" + path_ + "', line " + std::to_string(line_) + ": " + problem);
  }

  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }

  std::string next(const std::string& what) {
    skip_space();
    if (pos_ >= text_.size()) fail("unexpected end of file while reading " + what);
    const std::size_t start = pos_;
    if (text_[pos_] == '"') {
      const std::size_t close = text_.find('"', pos_ + 1);
      if (close == std::string::npos) fail("unterminated quoted string while reading " + what);
      pos_ = close + 1;
      return text_.substr(start + 1, close - start - 1);
    }
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  long long integer(const std::string& what) {
    const std::string t = next(what);
    try {
      std::size_t used = 0;
      const long long v = std::stoll(t, &used);
      if (used == t.size()) return v;
    } catch (const std::exception&) {  // reported below
    }
    fail("expected an integer (" + what + "), found '" + t + "'");
  }

  int count(const std::string& what) {
    const long long v = integer(what);
    if (v < 0 || v > 1'000'000'000) fail("invalid " + what + " " + std::to_string(v));
    return static_cast<int>(v);
  }

  double real(const std::string& what) {
    const std::string t = next(what);
    try {
      std::size_t used = 0;
      const double v = std::stod(t, &used);
      if (used == t.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {  // reported below
    }
    fail("expected a number (" + what + "), found '" + t + "'");
  }

  void expect(const std::string& token) {
    const std::string t = next(token);
    if (t != token) fail("expected '" + token + "', found '" + t + "'");
  }

 private:
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::string text_;
  std::string path_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

struct Element {
  long long tag;
  int type;
  int entity_dim;
  int entity_tag;
  std::vector<long long> nodes;
};

struct MshContent {
  std::map<std::pair<int, int>, std::string> physical_names;        // (dim, tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> entity_physicals;  // (dim, entity) -> tags
  std::vector<long long> node_tags;                                  // file order
  std::unordered_map<long long, Eigen::Vector3d> node_coords;
  std::unordered_map<long long, int> node_entity_dim;
  std::vector<Element> elements;
};

void read_format(Tokens& in, const std::string& path) {
  const std::string version = in.next("format version");
  const std::string file_type = in.next("file type");
  in.next("data size");
  if (version.rfind("2", 0) == 0) {
    throw Error("mesh file '" + path + "' uses the legacy Gmsh format version " + version +
                "; only ASCII format 4.1 is supported (re-export with gmsh -save -format msh41, "
                "or Mesh.MshFileVersion = 4.1)");
  }
  if (version != "4.1") {
    throw Error("mesh file '" + path + "' uses Gmsh format version " + version +
                "; only ASCII format 4.1 is supported (re-export with Mesh.MshFileVersion = 4.1)");
  }
  if (file_type != "0") {
    throw Error("mesh file '" + path + "' is a binary Gmsh file; only ASCII format 4.1 is supported "
                "(re-export with Mesh.Binary = 0)");
  }
  in.expect("$EndMeshFormat");
}

void read_physical_names(Tokens& in, MshContent& c) {
  const int n = in.count("number of physical names");
  for (int k = 0; k < n; ++k) {
    const int dim = static_cast<int>(in.integer("physical group dimension"));
    const int tag = static_cast<int>(in.integer("physical group tag"));
    c.physical_names[{dim, tag}] = in.next("physical group name");
  }
  in.expect("$EndPhysicalNames");
}

void read_entities(Tokens& in, MshContent& c) {
  std::array<int, 4> counts{};
  for (int& n : counts) n = in.count("number of entities");
  for (int dim = 0; dim < 4; ++dim) {
    for (int k = 0; k < counts[static_cast<std::size_t>(dim)]; ++k) {
      const int tag = static_cast<int>(in.integer("entity tag"));
      const int box = dim == 0 ? 3 : 6;  // a point has X Y Z, other entities a bounding box
      for (int b = 0; b < box; ++b) in.real("entity coordinates");
      auto& phys = c.entity_physicals[{dim, tag}];
      const int np = in.count("number of physical tags");
      for (int p = 0; p < np; ++p) phys.push_back(static_cast<int>(in.integer("physical tag")));
      if (dim > 0) {
        const int nb = in.count("number of bounding entities");
        for (int b = 0; b < nb; ++b) in.integer("bounding entity tag");
      }
    }
  }
  in.expect("$EndEntities");
}

void read_nodes(Tokens& in, MshContent& c) {
  const int blocks = in.count("number of node blocks");
  in.count("number of nodes");
  in.integer("minimum node tag");
  in.integer("maximum node tag");
  for (int b = 0; b < blocks; ++b) {
    const int dim = static_cast<int>(in.integer("node block entity dimension"));
    in.integer("node block entity tag");
    const bool parametric = in.integer("node block parametric flag") != 0;
    const int n = in.count("number of nodes in block");
    const std::size_t first = c.node_tags.size();
    for (int k = 0; k < n; ++k) {
      const long long tag = in.integer("node tag");
      if (c.node_entity_dim.count(tag) != 0) in.fail("node tag " + std::to_string(tag) + " is defined twice");
      c.node_tags.push_back(tag);
      c.node_entity_dim[tag] = dim;
    }
    for (int k = 0; k < n; ++k) {
      Eigen::Vector3d x;
      for (int d = 0; d < 3; ++d) x[d] = in.real("node coordinate");
      if (parametric) {
        for (int d = 0; d < dim; ++d) in.real("node parametric coordinate");
      }
      c.node_coords[c.node_tags[first + static_cast<std::size_t>(k)]] = x;
    }
  }
  in.expect("$EndNodes");
}

void read_elements(Tokens& in, MshContent& c) {
  const int blocks = in.count("number of element blocks");
  in.count("number of elements");
  in.integer("minimum element tag");
  in.integer("maximum element tag");
  for (int b = 0; b < blocks; ++b) {
    const int dim = static_cast<int>(in.integer("element block entity dimension"));
    const int entity = static_cast<int>(in.integer("element block entity tag"));
    const int type = static_cast<int>(in.integer("element type"));
    const int n = in.count("number of elements in block");
    int nodes = 0;
    switch (type) {
      case kPoint: nodes = 1; break;
      case kLine2: nodes = 2; break;
      case kTriangle3: nodes = 3; break;
      default:
        in.fail("element " + element_type_name(type) +
                " is not supported (contactrb reads 3-node triangles, 2-node lines and points)");
    }
    for (int k = 0; k < n; ++k) {
      Element e{in.integer("element tag"), type, dim, entity, {}};
      for (int v = 0; v < nodes; ++v) e.nodes.push_back(in.integer("element node tag"));
      c.elements.push_back(std::move(e));
    }
  }
  in.expect("$EndElements");
}

MshContent parse(const std::string& path) {
  // A regular file below the size limit: /dev/zero or a FIFO would be read without end.
  Tokens in(read_text_input(path, "mesh file"), path);
  if (in.at_end() || in.next("header") != "$MeshFormat") {
    throw Error("mesh file '" + path + "' is not a Gmsh mesh (it does not start with $MeshFormat)");
  }
  read_format(in, path);
  MshContent c;
  bool have_nodes = false;
  bool have_elements = false;
  while (!in.at_end()) {
    const std::string section = in.next("section name");
    if (section.empty() || section[0] != '$') in.fail("expected a section such as $Nodes, found '" + section + "'");
    const std::string name = section.substr(1);
    if (name == "PhysicalNames") {
      read_physical_names(in, c);
    } else if (name == "Entities") {
      read_entities(in, c);
    } else if (name == "Nodes") {
      read_nodes(in, c);
      have_nodes = true;
    } else if (name == "Elements") {
      read_elements(in, c);
      have_elements = true;
    } else {  // sections we do not need ($Comments, $Periodic, $NodeData, ...)
      while (in.next("end of section $" + name) != "$End" + name) {
      }
    }
  }
  if (!have_nodes || !have_elements) {
    throw Error("mesh file '" + path + "' has no " + std::string(have_nodes ? "$Elements" : "$Nodes") + " section");
  }
  return c;
}

std::string list_groups(const MshContent& c) {
  if (c.physical_names.empty()) return "none";
  std::string s;
  for (const auto& [key, name] : c.physical_names) {
    if (!s.empty()) s += ", ";
    s += "'" + name + "' (" + std::to_string(key.first) + "D)";
  }
  return s;
}

int find_group(const MshContent& c, const std::string& path, int dim, const std::string& name,
               const std::string& role) {
  for (const auto& [key, n] : c.physical_names) {
    if (key.first == dim && n == name) return key.second;
  }
  throw Error("mesh file '" + path + "' has no " + std::to_string(dim) + "D physical group '" + name + "' (" +
              role + "); groups present: " + list_groups(c));
}

double triangle_area(const std::array<Eigen::Vector2d, 3>& p, double& longest2) {
  longest2 = 0.0;
  for (std::size_t k = 0; k < 3; ++k) longest2 = std::max(longest2, (p[k] - p[(k + 1) % 3]).squaredNorm());
  return 0.5 * ((p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[2].x() - p[0].x()) * (p[1].y() - p[0].y()));
}

// The physical groups of an element's entity (none: an empty list).
const std::vector<int>& element_physicals(const MshContent& c, const Element& e) {
  static const std::vector<int> none;
  auto it = c.entity_physicals.find({e.entity_dim, e.entity_tag});
  return it == c.entity_physicals.end() ? none : it->second;
}

// The mesh nodes: the nodes of the triangles, in the order of the $Nodes section, on one plane
// z = const. Returns node tag -> mesh node.
std::unordered_map<long long, int> read_nodes(const MshContent& c, const std::string& where, Mesh& mesh) {
  std::unordered_map<long long, int> index;
  std::set<long long> used;
  for (const Element& e : c.elements) {
    if (e.type != kTriangle3) continue;
    for (long long v : e.nodes) {
      if (c.node_coords.count(v) == 0) {
        throw Error(where + "element " + std::to_string(e.tag) + " references undefined node " + std::to_string(v));
      }
      used.insert(v);
    }
  }
  for (long long tag : c.node_tags) {
    if (used.count(tag) != 0) {
      index[tag] = mesh.num_nodes();
      const Eigen::Vector3d& x = c.node_coords.at(tag);
      mesh.nodes.emplace_back(x.x(), x.y());
    } else if (c.node_entity_dim.at(tag) >= 2) {
      // Nodes of surfaces (or volumes) must belong to a triangle; nodes of geometry points
      // and curves that no triangle uses (e.g. Gmsh's point nodes) are dropped.
      throw Error(where + "node " + std::to_string(tag) + " (on a " + std::to_string(c.node_entity_dim.at(tag)) +
                  "D entity) is not referenced by any triangle (unreferenced node)");
    }
  }
  const double z0 = c.node_coords.empty() ? 0.0 : c.node_coords.begin()->second.z();
  for (const auto& [tag, x] : c.node_coords) {
    if (used.count(tag) != 0 && std::abs(x.z() - z0) > 1e-12 * (1.0 + std::abs(x.x()) + std::abs(x.y()))) {
      throw Error(where + "node " + std::to_string(tag) + " is off the plane z = " + number_text(z0) +
                  " (a 2D mesh is required)");
    }
  }
  return index;
}

// The body of a triangle: the one body group among its physicals (throws for none or both).
int triangle_body(const MshContent& c, const Element& e, const std::vector<int>& body_tag, const MshGroups& groups,
                  const std::string& where) {
  int body = -1;
  for (int p : element_physicals(c, e)) {
    for (std::size_t b = 0; b < body_tag.size(); ++b) {
      if (e.entity_dim == 2 && p == body_tag[b]) {
        if (body != -1 && body != static_cast<int>(b)) {
          throw Error(where + "triangle " + std::to_string(e.tag) + " belongs to both body groups");
        }
        body = static_cast<int>(b);
      }
    }
  }
  if (body == -1) {
    std::string names;
    for (const std::string& n : groups.body_groups) names += (names.empty() ? "'" : " or '") + n + "'";
    throw Error(where + "triangle " + std::to_string(e.tag) + " (surface " + std::to_string(e.entity_tag) +
                ") is in no body group " + names);
  }
  return body;
}

// The triangles and their bodies (disjoint: no node shared). Returns their element tags.
std::vector<long long> read_triangles(const MshContent& c, const std::vector<int>& body_tag, const MshGroups& groups,
                                      const std::unordered_map<long long, int>& index, const std::string& where,
                                      Mesh& mesh) {
  std::unordered_map<long long, int> node_owner;  // node tag -> body
  std::vector<long long> triangle_tags;
  for (const Element& e : c.elements) {
    if (e.type != kTriangle3) continue;
    const int body = triangle_body(c, e, body_tag, groups, where);
    std::array<int, 3> tri{};
    for (std::size_t k = 0; k < 3; ++k) {
      tri[k] = index.at(e.nodes[k]);
      auto [it, inserted] = node_owner.emplace(e.nodes[k], body);
      if (!inserted && it->second != body) {
        throw Error(where + "node " + std::to_string(e.nodes[k]) + " is shared by both bodies (bodies must be disjoint)");
      }
    }
    mesh.triangles.push_back(tri);
    mesh.body.push_back(body);
    triangle_tags.push_back(e.tag);
  }
  if (mesh.triangles.empty()) throw Error(where + "contains no triangles");
  return triangle_tags;
}

// Zero-area triangles, then orientation per body (all clockwise: flip; mixed: error).
void orient_triangles(const std::vector<long long>& triangle_tags, const MshGroups& groups, const std::string& where,
                      Mesh& mesh) {
  const std::size_t bodies = groups.body_groups.size();
  std::vector<int> clockwise(bodies, 0);
  std::vector<int> counter(bodies, 0);
  std::vector<long long> first_clockwise(bodies, -1);
  std::vector<long long> first_counter(bodies, -1);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
    std::array<Eigen::Vector2d, 3> p;
    for (std::size_t k = 0; k < 3; ++k) p[k] = mesh.nodes[static_cast<std::size_t>(tri[k])];
    double longest2 = 0.0;
    const double area = triangle_area(p, longest2);
    const long long tag = triangle_tags[static_cast<std::size_t>(t)];
    if (std::abs(area) <= kZeroAreaTolerance * longest2) {
      throw Error(where + "triangle " + std::to_string(tag) + " has zero area (degenerate triangle)");
    }
    const auto b = static_cast<std::size_t>(mesh.body[static_cast<std::size_t>(t)]);
    if (area < 0) {
      if (clockwise[b]++ == 0) first_clockwise[b] = tag;
    } else {
      if (counter[b]++ == 0) first_counter[b] = tag;
    }
  }
  for (std::size_t b = 0; b < bodies; ++b) {
    if (clockwise[b] > 0 && counter[b] > 0) {
      const bool minority_cw = clockwise[b] <= counter[b];
      throw Error(where + "body '" + groups.body_groups[b] + "' has inverted triangles: " +
                  std::to_string(clockwise[b]) + " clockwise and " + std::to_string(counter[b]) +
                  " counter-clockwise (mixed orientation; e.g. triangle " +
                  std::to_string(minority_cw ? first_clockwise[b] : first_counter[b]) + ")");
    }
    if (clockwise[b] > 0) {  // a consistently mirrored body: reorient
      for (int t = 0; t < mesh.num_triangles(); ++t) {
        if (mesh.body[static_cast<std::size_t>(t)] == static_cast<int>(b)) {
          std::swap(mesh.triangles[static_cast<std::size_t>(t)][1], mesh.triangles[static_cast<std::size_t>(t)][2]);
        }
      }
    }
  }
}

// Boundary groups: every named 1D physical group; edges oriented with the body on the left.
void read_boundaries(const MshContent& c, const std::unordered_map<long long, int>& index, const std::string& where,
                     Mesh& mesh) {
  std::map<std::pair<int, int>, int> directed;  // counter-clockwise triangle edge -> count
  for (const auto& tri : mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k) ++directed[{tri[k], tri[(k + 1) % 3]}];
  }
  for (const auto& [key, name] : c.physical_names) {
    if (key.first == 1) mesh.boundaries[name];  // present even if empty
  }
  for (const Element& e : c.elements) {
    if (e.type != kLine2) continue;
    for (int p : element_physicals(c, e)) {
      auto name = c.physical_names.find({1, p});
      if (e.entity_dim != 1 || name == c.physical_names.end()) continue;
      const std::string edge_name = "boundary group '" + name->second + "' line " + std::to_string(e.tag) +
                                    " (nodes " + std::to_string(e.nodes[0]) + ", " + std::to_string(e.nodes[1]) + ")";
      auto ia = index.find(e.nodes[0]);
      auto ib = index.find(e.nodes[1]);
      if (ia == index.end() || ib == index.end()) throw Error(where + edge_name + " is not an edge of any triangle");
      const int a = ia->second;
      const int b = ib->second;
      const int forward = directed.count({a, b}) ? directed.at({a, b}) : 0;
      const int backward = directed.count({b, a}) ? directed.at({b, a}) : 0;
      if (forward + backward == 0) throw Error(where + edge_name + " is not an edge of any triangle");
      if (forward + backward > 1) throw Error(where + edge_name + " is an interior edge, not on the boundary");
      mesh.boundaries[name->second].push_back(forward ? Edge{a, b} : Edge{b, a});
    }
  }
}

}  // namespace

Mesh read_msh(const std::string& path, const MshGroups& groups) {
  require(groups.body_groups.size() == 1 || groups.body_groups.size() == 2,
          "read_msh: body_groups must name 1 or 2 physical groups (got " +
              std::to_string(groups.body_groups.size()) + ")");
  const MshContent c = parse(path);
  const std::string where = "mesh file '" + path + "': ";
  std::vector<int> body_tag;
  for (std::size_t b = 0; b < groups.body_groups.size(); ++b) {
    body_tag.push_back(find_group(c, path, 2, groups.body_groups[b], b == 0 ? "the slave body" : "the master body"));
  }
  for (const std::string& name : groups.required_boundaries) find_group(c, path, 1, name, "a required boundary");

  Mesh mesh;
  const std::unordered_map<long long, int> index = read_nodes(c, where, mesh);
  const std::vector<long long> triangle_tags = read_triangles(c, body_tag, groups, index, where, mesh);
  orient_triangles(triangle_tags, groups, where, mesh);
  read_boundaries(c, index, where, mesh);
  try {
    validate(mesh);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  return mesh;
}

}  // namespace contactrb::mesh
