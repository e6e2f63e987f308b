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
constexpr int kTetrahedron4 = 4;
constexpr int kPoint = 15;
// A cell is degenerate when |measure| <= kZeroAreaTolerance * (longest edge)^Dim, the test
// of mesh::validate().
constexpr double kZeroAreaTolerance = 1e-12;

std::string element_type_name(int type) {
  switch (type) {
    case 3: return "4-node quadrangle";
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
      case kTetrahedron4: nodes = 4; break;
      default:
        in.fail("element " + element_type_name(type) +
                " is not supported (contactrb reads 4-node tetrahedra, 3-node triangles, 2-node lines and points)");
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

// The physical groups of an element's entity (none: an empty list).
const std::vector<int>& element_physicals(const MshContent& c, const Element& e) {
  static const std::vector<int> none;
  auto it = c.entity_physicals.find({e.entity_dim, e.entity_tag});
  return it == c.entity_physicals.end() ? none : it->second;
}

// Gmsh element types of the cells and boundary facets of a Dim-dimensional mesh, and the words
// of the messages.
template <int Dim>
struct MshSimplex;
template <>
struct MshSimplex<2> {
  static constexpr int cell_type = kTriangle3;
  static constexpr int facet_type = kLine2;
  static constexpr const char* cells = "triangles";
  static constexpr const char* facet_element = "line";
  static constexpr const char* facet_of = "an edge of any triangle";
  static constexpr const char* interior = "an interior edge";
  static constexpr const char* entity = "surface";
  static constexpr const char* negative = "clockwise";
  static constexpr const char* positive = "counter-clockwise";
};
template <>
struct MshSimplex<3> {
  static constexpr int cell_type = kTetrahedron4;
  static constexpr int facet_type = kTriangle3;
  static constexpr const char* cells = "tetrahedra";
  static constexpr const char* facet_element = "triangle";
  static constexpr const char* facet_of = "a face of any tetrahedron";
  static constexpr const char* interior = "an interior face";
  static constexpr const char* entity = "volume";
  static constexpr const char* negative = "negative-volume";
  static constexpr const char* positive = "positive-volume";
};

// A 2D mesh holds no tetrahedra: a 3D file is refused with one message.
void refuse_cells_of_other_dimension(const MshContent& c, int dim, const std::string& where) {
  for (const Element& e : c.elements) {
    if (dim == 2 && e.type == kTetrahedron4) {
      throw Error(where + "element " + std::to_string(e.tag) +
                  " is a 4-node tetrahedron: this is a 3D mesh, and a 2D mesh (3-node triangles) is expected here");
    }
  }
}

// The mesh nodes: the nodes of the cells, in the order of the $Nodes section (2D: on one plane
// z = const). Returns node tag -> mesh node.
template <int Dim>
std::unordered_map<long long, int> read_nodes(const MshContent& c, const std::string& where, SimplexMesh<Dim>& mesh) {
  using Words = MshSimplex<Dim>;
  std::unordered_map<long long, int> index;
  std::set<long long> used;
  for (const Element& e : c.elements) {
    if (e.type != Words::cell_type) continue;
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
      mesh.nodes.push_back(c.node_coords.at(tag).template head<Dim>());
    } else if (c.node_entity_dim.at(tag) >= Dim) {
      // Nodes inside the bodies' entities must belong to a cell; nodes of lower-dimensional
      // entities that no cell uses (e.g. Gmsh's point nodes) are dropped.
      throw Error(where + "node " + std::to_string(tag) + " (on a " + std::to_string(c.node_entity_dim.at(tag)) +
                  "D entity) is not referenced by any " + SimplexNames<Dim>::cell + " (unreferenced node)");
    }
  }
  if constexpr (Dim == 2) {
    const double z0 = c.node_coords.empty() ? 0.0 : c.node_coords.begin()->second.z();
    for (const auto& [tag, x] : c.node_coords) {
      if (used.count(tag) != 0 && std::abs(x.z() - z0) > 1e-12 * (1.0 + std::abs(x.x()) + std::abs(x.y()))) {
        throw Error(where + "node " + std::to_string(tag) + " is off the plane z = " + number_text(z0) +
                    " (a 2D mesh is required)");
      }
    }
  }
  return index;
}

// The body of a cell: the one body group among its physicals (throws for none or both).
template <int Dim>
int cell_body(const MshContent& c, const Element& e, const std::vector<int>& body_tag, const MshGroups& groups,
              const std::string& where) {
  const std::string cell = SimplexNames<Dim>::cell;
  int body = -1;
  for (int p : element_physicals(c, e)) {
    for (std::size_t b = 0; b < body_tag.size(); ++b) {
      if (e.entity_dim == Dim && p == body_tag[b]) {
        if (body != -1 && body != static_cast<int>(b)) {
          throw Error(where + cell + " " + std::to_string(e.tag) + " belongs to both body groups");
        }
        body = static_cast<int>(b);
      }
    }
  }
  if (body == -1) {
    std::string names;
    for (const std::string& n : groups.body_groups) names += (names.empty() ? "'" : " or '") + n + "'";
    throw Error(where + cell + " " + std::to_string(e.tag) + " (" + MshSimplex<Dim>::entity + " " +
                std::to_string(e.entity_tag) + ") is in no body group " + names);
  }
  return body;
}

// The cells and their bodies (disjoint: no node shared). Returns their element tags.
template <int Dim>
std::vector<long long> read_cells(const MshContent& c, const std::vector<int>& body_tag, const MshGroups& groups,
                                  const std::unordered_map<long long, int>& index, const std::string& where,
                                  SimplexMesh<Dim>& mesh) {
  std::unordered_map<long long, int> node_owner;  // node tag -> body
  std::vector<long long> cell_tags;
  for (const Element& e : c.elements) {
    if (e.type != MshSimplex<Dim>::cell_type) continue;
    const int body = cell_body<Dim>(c, e, body_tag, groups, where);
    typename SimplexMesh<Dim>::Cell cell{};
    for (std::size_t k = 0; k < cell.size(); ++k) {
      cell[k] = index.at(e.nodes[k]);
      auto [it, inserted] = node_owner.emplace(e.nodes[k], body);
      if (!inserted && it->second != body) {
        throw Error(where + "node " + std::to_string(e.nodes[k]) + " is shared by both bodies (bodies must be disjoint)");
      }
    }
    mesh.cells().push_back(cell);
    mesh.body.push_back(body);
    cell_tags.push_back(e.tag);
  }
  if (mesh.cells().empty()) throw Error(where + "contains no " + MshSimplex<Dim>::cells);
  return cell_tags;
}

// Longest squared edge of cell `cell`, the scale of the zero-measure test.
template <int Dim>
double longest_edge2(const SimplexMesh<Dim>& mesh, const typename SimplexMesh<Dim>::Cell& cell) {
  double longest2 = 0.0;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    for (std::size_t j = i + 1; j < cell.size(); ++j) {
      longest2 = std::max(longest2, (mesh.nodes[static_cast<std::size_t>(cell[i])] -
                                     mesh.nodes[static_cast<std::size_t>(cell[j])]).squaredNorm());
    }
  }
  return longest2;
}

// Zero-measure cells, then orientation per body (all negative: flip; mixed: error).
template <int Dim>
void orient_cells(const std::vector<long long>& cell_tags, const MshGroups& groups, const std::string& where,
                  SimplexMesh<Dim>& mesh) {
  using Words = MshSimplex<Dim>;
  const std::size_t bodies = groups.body_groups.size();
  std::vector<int> negative(bodies, 0);
  std::vector<int> positive(bodies, 0);
  std::vector<long long> first_negative(bodies, -1);
  std::vector<long long> first_positive(bodies, -1);
  for (int t = 0; t < mesh.num_cells(); ++t) {
    const double longest2 = longest_edge2(mesh, mesh.cells()[static_cast<std::size_t>(t)]);
    const double scale = Dim == 2 ? longest2 : longest2 * std::sqrt(longest2);
    const double measure = signed_volume(mesh, t);
    const long long tag = cell_tags[static_cast<std::size_t>(t)];
    if (std::abs(measure) <= kZeroAreaTolerance * scale) {
      throw Error(where + SimplexNames<Dim>::cell + " " + std::to_string(tag) + " has zero " +
                  SimplexNames<Dim>::measure + " (degenerate " + SimplexNames<Dim>::cell + ")");
    }
    const auto b = static_cast<std::size_t>(mesh.body[static_cast<std::size_t>(t)]);
    if (measure < 0) {
      if (negative[b]++ == 0) first_negative[b] = tag;
    } else {
      if (positive[b]++ == 0) first_positive[b] = tag;
    }
  }
  for (std::size_t b = 0; b < bodies; ++b) {
    if (negative[b] > 0 && positive[b] > 0) {
      const bool minority_negative = negative[b] <= positive[b];
      throw Error(where + "body '" + groups.body_groups[b] + "' has inverted " + Words::cells + ": " +
                  std::to_string(negative[b]) + " " + Words::negative + " and " + std::to_string(positive[b]) + " " +
                  Words::positive + " (mixed orientation; e.g. " + SimplexNames<Dim>::cell + " " +
                  std::to_string(minority_negative ? first_negative[b] : first_positive[b]) + ")");
    }
    if (negative[b] > 0) {  // a consistently mirrored body: reorient
      for (int t = 0; t < mesh.num_cells(); ++t) {
        if (mesh.body[static_cast<std::size_t>(t)] == static_cast<int>(b)) {
          std::swap(mesh.cells()[static_cast<std::size_t>(t)][1], mesh.cells()[static_cast<std::size_t>(t)][2]);
        }
      }
    }
  }
}

// Facets of the cells by their sorted node set: how many cells hold each, and its outward
// orientation (mesh.hpp) in the last of them.
template <int Dim>
std::map<std::array<int, Dim>, std::pair<int, std::array<int, Dim>>> cell_facets(const SimplexMesh<Dim>& mesh) {
  std::map<std::array<int, Dim>, std::pair<int, std::array<int, Dim>>> facets;
  for (const auto& cell : mesh.cells()) {
    for (const auto& local : kCellFacets<Dim>) {
      std::array<int, Dim> f{};
      for (std::size_t k = 0; k < f.size(); ++k) f[k] = cell[static_cast<std::size_t>(local[k])];
      std::array<int, Dim> key = f;
      std::sort(key.begin(), key.end());
      auto& entry = facets[key];
      ++entry.first;
      entry.second = f;
    }
  }
  return facets;
}

// Boundary groups: every named (Dim-1)-dimensional physical group; facets oriented with the
// outward normal of their body (2D: the body on the left).
template <int Dim>
void read_boundaries(const MshContent& c, const std::unordered_map<long long, int>& index, const std::string& where,
                     SimplexMesh<Dim>& mesh) {
  using Words = MshSimplex<Dim>;
  const auto facets = cell_facets(mesh);
  for (const auto& [key, name] : c.physical_names) {
    if (key.first == Dim - 1) mesh.boundaries[name];  // present even if empty
  }
  for (const Element& e : c.elements) {
    if (e.type != Words::facet_type) continue;
    for (int p : element_physicals(c, e)) {
      auto name = c.physical_names.find({Dim - 1, p});
      if (e.entity_dim != Dim - 1 || name == c.physical_names.end()) continue;
      std::string facet_name = "boundary group '" + name->second + "' " + Words::facet_element + " " +
                               std::to_string(e.tag) + " (nodes ";
      for (std::size_t k = 0; k < e.nodes.size(); ++k) facet_name += (k ? ", " : "") + std::to_string(e.nodes[k]);
      facet_name += ")";
      std::array<int, Dim> f{};
      for (std::size_t k = 0; k < f.size(); ++k) {
        auto it = index.find(e.nodes[k]);
        if (it == index.end()) throw Error(where + facet_name + " is not " + Words::facet_of);
        f[k] = it->second;
      }
      std::array<int, Dim> sorted = f;
      std::sort(sorted.begin(), sorted.end());
      auto found = facets.find(sorted);
      if (found == facets.end()) throw Error(where + facet_name + " is not " + Words::facet_of);
      if (found->second.first > 1) throw Error(where + facet_name + " is " + Words::interior + ", not on the boundary");
      if (oriented_key<Dim>(f) != oriented_key<Dim>(found->second.second)) std::swap(f[Dim - 2], f[Dim - 1]);
      if constexpr (Dim == 2) {
        mesh.boundaries[name->second].push_back(Edge{f[0], f[1]});
      } else {
        mesh.boundaries[name->second].push_back(Face{f[0], f[1], f[2]});
      }
    }
  }
}

template <int Dim>
SimplexMesh<Dim> read_simplex_msh(const std::string& path, const MshGroups& groups) {
  require(groups.body_groups.size() == 1 || groups.body_groups.size() == 2,
          "read_msh: body_groups must name 1 or 2 physical groups (got " +
              std::to_string(groups.body_groups.size()) + ")");
  const MshContent c = parse(path);
  const std::string where = "mesh file '" + path + "': ";
  refuse_cells_of_other_dimension(c, Dim, where);
  std::vector<int> body_tag;
  for (std::size_t b = 0; b < groups.body_groups.size(); ++b) {
    body_tag.push_back(find_group(c, path, Dim, groups.body_groups[b], b == 0 ? "the slave body" : "the master body"));
  }
  for (const std::string& name : groups.required_boundaries) find_group(c, path, Dim - 1, name, "a required boundary");

  SimplexMesh<Dim> mesh;
  const std::unordered_map<long long, int> index = read_nodes(c, where, mesh);
  const std::vector<long long> cell_tags = read_cells(c, body_tag, groups, index, where, mesh);
  orient_cells(cell_tags, groups, where, mesh);
  read_boundaries(c, index, where, mesh);
  try {
    validate(mesh);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  return mesh;
}

}  // namespace

Mesh read_msh(const std::string& path, const MshGroups& groups) { return read_simplex_msh<2>(path, groups); }

Mesh3 read_msh3(const std::string& path, const MshGroups& groups) { return read_simplex_msh<3>(path, groups); }

int msh_dimension(const std::string& path) {
  const MshContent c = parse(path);
  for (const Element& e : c.elements) {
    if (e.type == kTetrahedron4) return 3;
  }
  return 2;
}

}  // namespace contactrb::mesh
