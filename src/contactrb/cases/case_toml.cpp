#include "contactrb/cases/case_toml.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <toml++/toml.h>

#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/cases/parameter_set_toml.hpp"
#include "contactrb/cases/parameter_sets.hpp"

namespace contactrb::cases {

namespace {

namespace fs = std::filesystem;

// Relative distance (to the largest bound) within which a value of a generated parameter
// set {start, step, count} is moved onto the domain bound it overshoots by round-off.
constexpr double kSetSnapTolerance = 1e-12;

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date/time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// Shortest round-trip text of a double, for messages (nan and inf as such).
std::string shortest(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// Reads one TOML document into a CaseSpec; every message names the file, the line (when
// toml++ knows it) and the dotted key.
class Reader {
 public:
  Reader(std::string origin, fs::path base_dir, MeshFile mesh_file)
      : origin_(std::move(origin)), base_dir_(std::move(base_dir)), mesh_file_(mesh_file) {}

  // friction null: a file with friction keys is refused (only `solve` handles friction);
  // otherwise they are read into *friction (has_friction false when the file has none).
  CaseSpec read(const toml::table& root, FrictionFileSpec* friction = nullptr) const;

 private:
  // The sections of a case file, in the order they are read (docs/cases.md).
  void read_header(const toml::table& root, CaseSpec& c) const;
  void read_mesh(const toml::table& root, CaseSpec& c) const;
  void read_body(const toml::table& root, const char* role, int index, CaseSpec& c) const;
  void read_parameters(const toml::table& root, CaseSpec& c) const;
  void read_parameter_array(const toml::array& arr, CaseSpec& c) const;
  void read_single_parameter(const toml::table& root, const toml::table& par, CaseSpec& c) const;
  ParameterSpec read_parameter(const toml::table& par, const std::string& path, bool with_sets) const;
  void read_parameter_body(const toml::table& par, const std::string& path, ParameterSpec& p) const;
  void read_dirichlet(const toml::table& root, CaseSpec& c, const std::string& prefix = "") const;
  void read_tractions(const toml::table& root, CaseSpec& c, const std::string& prefix = "") const;
  void read_friction(const toml::table& root, const CaseSpec& c, FrictionFileSpec& f) const;
  bool read_coefficient_parameter(const toml::table& t, const CaseSpec& c, FrictionFileSpec& f) const;
  void read_load_steps(const toml::node& steps, const CaseSpec& c, FrictionFileSpec& f) const;
  FrictionFileSpec::Step read_load_step(const toml::table& t, const std::string& path, const CaseSpec& c) const;
  TractionSpec read_traction(const toml::table& t, const std::string& path, const CaseSpec& c) const;
  void read_sets(const toml::table& root, CaseSpec& c) const;

  // Values: each checks the TOML type and names the key when it is wrong.
  AffineValue affine(const toml::node& n, const std::string& key, const std::vector<ParameterSpec>& params) const;
  int default_affine_parameter(const toml::table& t, const std::string& key,
                               const std::vector<ParameterSpec>& params) const;
  std::vector<double> parameter_set(const toml::node& n, const std::string& key) const;
  std::vector<double> parameter_set_array(const toml::node& n, const std::string& key) const;
  std::vector<double> parameter_set_range(const toml::table& t, const std::string& key) const;
  int body_index(const toml::node& n, const std::string& key) const;
  double number(const toml::node& n, const std::string& key) const;
  std::string string(const toml::node& n, const std::string& key) const;
  long long integer(const toml::node& n, const std::string& key) const;
  const toml::table& table(const toml::node& n, const std::string& key) const;
  std::vector<double> numbers(const toml::node& n, const std::string& key, int size = -1) const;
  Eigen::Vector2d vector2(const toml::node& n, const std::string& key) const;

  // Keys and messages.
  [[noreturn]] void fail(const toml::node* n, const std::string& what) const;
  [[noreturn]] void wrong_type(const toml::node& n, const std::string& key, const std::string& expected) const;
  void check_keys(const toml::table& t, const std::string& path, std::initializer_list<const char*> allowed) const;
  const toml::node& required(const toml::table& t, const std::string& path, const char* key) const;
  static std::string join(const std::string& path, const std::string& key);
  static std::string names(const std::vector<ParameterSpec>& params);
  static void snap_to_domain(std::vector<double>& values, double min, double max);

  std::string origin_;
  fs::path base_dir_;
  MeshFile mesh_file_;
};

// --- Keys and messages.

void Reader::fail(const toml::node* n, const std::string& what) const {
  std::ostringstream os;
  os << origin_;
  if (n != nullptr && n->source().begin.line > 0) os << ":" << n->source().begin.line;
  os << ": " << what;
  throw Error(os.str());
}

void Reader::wrong_type(const toml::node& n, const std::string& key, const std::string& expected) const {
  fail(&n, "key '" + key + "' must be " + expected + ", got " + type_name(n));
}

std::string Reader::join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

void Reader::check_keys(const toml::table& t, const std::string& path, std::initializer_list<const char*> allowed) const {
  for (auto&& [k, v] : t) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || k.str() == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      fail(&v, "unknown key '" + join(path, std::string(k.str())) + "' (allowed" +
                   (path.empty() ? std::string() : " in [" + path + "]") + ": " + list + ")");
    }
  }
}

const toml::node& Reader::required(const toml::table& t, const std::string& path, const char* key) const {
  const toml::node* n = t.get(key);
  if (n == nullptr) {
    fail(path.empty() ? nullptr : &t, "missing key '" + join(path, key) + "'" +
                                          (path.empty() ? std::string() : " in [" + path + "]"));
  }
  return *n;
}

std::string Reader::names(const std::vector<ParameterSpec>& params) {
  std::string s;
  for (const ParameterSpec& p : params) s += (s.empty() ? " (parameters: " : ", ") + p.name;
  return s.empty() ? s : s + ")";
}

// --- Values.

double Reader::number(const toml::node& n, const std::string& key) const {
  if (const auto* f = n.as_floating_point()) return f->get();
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  wrong_type(n, key, "a number");
}

std::string Reader::string(const toml::node& n, const std::string& key) const {
  if (const auto* s = n.as_string()) return s->get();
  wrong_type(n, key, "a string");
}

long long Reader::integer(const toml::node& n, const std::string& key) const {
  if (const auto* i = n.as_integer()) return i->get();
  wrong_type(n, key, "an integer");
}

const toml::table& Reader::table(const toml::node& n, const std::string& key) const {
  if (const auto* t = n.as_table()) return *t;
  wrong_type(n, key, "a table");
}

std::vector<double> Reader::numbers(const toml::node& n, const std::string& key, int size) const {
  const std::string expected = size < 0 ? "an array of numbers" : "an array of " + std::to_string(size) + " numbers";
  const auto* a = n.as_array();
  if (a == nullptr) wrong_type(n, key, expected);
  std::vector<double> v;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    if (!e.is_number()) fail(&e, "key '" + key + "' must be " + expected + ", element " + std::to_string(i + 1) +
                                     " is " + type_name(e));
    v.push_back(number(e, key));
  }
  if (size >= 0 && static_cast<int>(v.size()) != size) {
    fail(&n, "key '" + key + "' must be " + expected + ", got " + std::to_string(v.size()));
  }
  return v;
}

Eigen::Vector2d Reader::vector2(const toml::node& n, const std::string& key) const {
  const std::vector<double> v = numbers(n, key, 2);
  return {v[0], v[1]};
}

// "slave" -> 0, "master" -> 1.
int Reader::body_index(const toml::node& n, const std::string& key) const {
  const std::string bs = string(n, key);
  if (bs != "slave" && bs != "master") fail(&n, "key '" + key + "' must be slave or master, got '" + bs + "'");
  return bs == "slave" ? 0 : 1;
}

// A Dirichlet value: a number (constant) or an inline table {a, b} (a + b mu).
// The parameter a value names ({a, b, parameter = "name"}, any kind); without the key, see
// default_affine_parameter.
AffineValue Reader::affine(const toml::node& n, const std::string& key, const std::vector<ParameterSpec>& params) const {
  if (n.is_number()) return {number(n, key), 0.0, 0};
  const auto* t = n.as_table();
  if (t == nullptr) wrong_type(n, key, "a number or a table {a = ..., b = ...} (a + b mu)");
  check_keys(*t, key, {"a", "b", "parameter"});
  AffineValue v;
  if (const toml::node* a = t->get("a")) v.a = number(*a, key + ".a");
  v.b = number(required(*t, key, "b"), key + ".b");
  if (const toml::node* pn = t->get("parameter")) {
    const std::string name = string(*pn, key + ".parameter");
    v.parameter = parameter_index(params, name);
    if (v.parameter < 0) fail(pn, "key '" + key + ".parameter' names an unknown parameter '" + name + "'" + names(params));
    return v;
  }
  v.parameter = default_affine_parameter(*t, key, params);
  return v;
}

// The parameter of an a + b mu value without 'parameter': the case's only dirichlet-scale
// parameter, or the only parameter of a one-parameter case (e.g. a value scaled with a radius).
int Reader::default_affine_parameter(const toml::table& t, const std::string& key,
                                     const std::vector<ParameterSpec>& params) const {
  int found = -1;
  for (std::size_t k = 0; k < params.size(); ++k) {
    if (params[k].kind != ParameterKind::DirichletScale) continue;
    if (found >= 0) fail(&t, "key '" + key + "' depends on mu but the case has several dirichlet-scale parameters: "
                                 "name one with 'parameter = \"...\"'");
    found = static_cast<int>(k);
  }
  if (found < 0 && params.size() == 1) found = 0;
  if (found < 0) {
    fail(&t, "key '" + key + "' is a + b mu but the case has no dirichlet-scale parameter: name the parameter "
             "with 'parameter = \"...\"'");
  }
  return found;
}

// A parameter set: an array of numbers or {start, step, count}.
// The values must be strictly increasing (a repeated value, e.g. from step = 0, gave a model
// that answered far from the HF solution with converged = true).
std::vector<double> Reader::parameter_set(const toml::node& n, const std::string& key) const {
  if (n.is_array()) return parameter_set_array(n, key);
  const auto* t = n.as_table();
  if (t == nullptr) wrong_type(n, key, "an array of numbers or a table {start, step, count}");
  return parameter_set_range(*t, key);
}

std::vector<double> Reader::parameter_set_array(const toml::node& n, const std::string& key) const {
  std::vector<double> v = numbers(n, key);
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (!(v[i] > v[i - 1])) {
      fail(n.as_array()->get(i), "key '" + key + "' must be strictly increasing, but element " +
                                     std::to_string(i + 1) + " (" + shortest(v[i]) + ") is not above element " +
                                     std::to_string(i) + " (" + shortest(v[i - 1]) + ")");
    }
  }
  return v;
}

std::vector<double> Reader::parameter_set_range(const toml::table& t, const std::string& key) const {
  check_keys(t, key, {"start", "step", "count"});
  const double start = number(required(t, key, "start"), key + ".start");
  const toml::node& step_node = required(t, key, "step");
  const double step = number(step_node, key + ".step");
  const toml::node& c = required(t, key, "count");
  const long long count = integer(c, key + ".count");
  if (count < 1 || count > 1000000) fail(&c, "key '" + key + ".count' must be in [1, 1000000]");
  if (count > 1 && !(step > 0.0)) {
    fail(&step_node, "key '" + key + ".step' must be > 0 (the values must be strictly increasing), got " +
                         shortest(step));
  }
  std::vector<double> v = arithmetic_set(start, step, static_cast<int>(count));
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (!(v[i] > v[i - 1])) {  // a step below the spacing of doubles at start
      fail(&step_node, "key '" + key + ".step' = " + shortest(step) + " is too small for start = " +
                           shortest(start) + ": values " + std::to_string(i) + " and " + std::to_string(i + 1) +
                           " are equal");
    }
  }
  return v;
}

// A generated value within round-off of the domain (0.15 + 6 * 0.05 = 0.45000000000000007)
// is moved onto the bound, so that {start, step, count} can end exactly at the domain's end.
void Reader::snap_to_domain(std::vector<double>& values, double min, double max) {
  const double tol = kSetSnapTolerance * std::max(std::abs(min), std::abs(max));
  for (double& v : values) {
    if (v > max && v <= max + tol) v = max;
    if (v < min && v >= min - tol) v = min;
  }
}

// --- Sections.

CaseSpec Reader::read(const toml::table& root, FrictionFileSpec* friction) const {
  CaseSpec c;
  c.origin = origin_;
  check_keys(root, "",
             {"name", "description", "constraint", "mesh", "slave", "master", "dirichlet", "traction", "parameter", "sets",
              "friction", "load_steps"});
  for (const char* key : {"friction", "load_steps"}) {
    if (friction == nullptr && root.get(key) != nullptr) {
      fail(root.get(key), "the case is frictional (key '" + std::string(key) +
                              "'): only `contactrb solve` handles friction (docs/cases.md, \"Frictional cases\")");
    }
  }
  read_header(root, c);
  read_mesh(root, c);
  read_body(root, "slave", 0, c);
  read_body(root, "master", 1, c);
  read_parameters(root, c);
  read_dirichlet(root, c);  // after the parameters: a value a + b mu names one
  read_tractions(root, c);
  read_sets(root, c);
  try {
    check_case_spec(c);
  } catch (const Error& e) {
    fail(nullptr, e.what());
  }
  if (root.get("friction") == nullptr) {
    for (const ParameterSpec& p : c.parameters) {
      if (p.kind == ParameterKind::FrictionCoefficient) {
        fail(nullptr, "parameter '" + p.name + "' of kind friction-coefficient needs a [friction] table with law = "
                      "coulomb (docs/cases.md, \"Frictional case files\")");
      }
    }
  }
  if (friction != nullptr) read_friction(root, c, *friction);
  return c;
}

// name, description, constraint.
void Reader::read_header(const toml::table& root, CaseSpec& c) const {
  c.name = string(required(root, "", "name"), "name");
  if (const toml::node* d = root.get("description")) c.description = string(*d, "description");
  if (const toml::node* d = root.get("constraint")) {
    const std::string s = string(*d, "constraint");
    try {
      c.constraint = contact::discretization_from_string(s);
    } catch (const Error&) {
      fail(d, "key 'constraint' must be collocation, lac or lac-simpson, got '" + s + "'");
    }
  }
}

// [mesh]: exactly one of a generator and a .msh file (relative to the case file).
void Reader::read_mesh(const toml::table& root, CaseSpec& c) const {
  const toml::node& mesh_node = required(root, "", "mesh");
  const toml::table& mesh = table(mesh_node, "mesh");
  check_keys(mesh, "mesh", {"file", "generator"});
  const toml::node* file = mesh.get("file");
  const toml::node* generator = mesh.get("generator");
  if ((file == nullptr) == (generator == nullptr)) {
    fail(&mesh_node, "[mesh] needs exactly one of the keys 'mesh.file' and 'mesh.generator'");
  }
  if (generator != nullptr) {
    c.mesh.generator = string(*generator, "mesh.generator");
    if (c.mesh.generator != "hertz" && c.mesh.generator != "ring-block" && c.mesh.generator != "hertz-3d" &&
        c.mesh.generator != "stacked-blocks") {
      fail(generator, "key 'mesh.generator' must be hertz, ring-block, hertz-3d or stacked-blocks, got '" +
                          c.mesh.generator + "'");
    }
    return;
  }
  const std::string f = string(*file, "mesh.file");
  if (f.empty()) fail(file, "key 'mesh.file' is empty");
  fs::path p(f);
  if (p.is_relative()) p = base_dir_ / p;
  p = p.lexically_normal();
  if (mesh_file_ == MeshFile::Required) {
    try {
      check_input_file(p.string(), "mesh file", InputKind::Text);  // missing, a directory, a device, too large
    } catch (const Error& e) {
      fail(file, std::string("key 'mesh.file': ") + e.what());
    }
  }
  c.mesh.msh_file = p.string();
}

// [slave] or [master]: the material, the load, the .msh groups.
void Reader::read_body(const toml::table& root, const char* role, int index, CaseSpec& c) const {
  const std::string path = role;
  const toml::table& t = table(required(root, "", role), path);
  check_keys(t, path, {"body", "boundary", "E", "nu", "load"});
  BodySpec& b = c.bodies[static_cast<std::size_t>(index)];
  b.E = number(required(t, path, "E"), path + ".E");
  b.nu = number(required(t, path, "nu"), path + ".nu");
  if (const toml::node* l = t.get("load")) b.load = vector2(*l, path + ".load");
  std::string& boundary = index == 0 ? c.mesh.slave_group : c.mesh.master_group;
  for (const char* key : {"body", "boundary"}) {
    const toml::node* n = t.get(key);
    if (n == nullptr) continue;
    if (c.mesh.msh_file.empty()) {
      fail(n, "key '" + path + "." + key + "' names a group of a .msh file: not allowed with mesh.generator");
    }
    const std::string value = string(*n, path + "." + key);
    if (value.empty()) fail(n, "key '" + path + "." + key + "' is empty");
    (std::string(key) == "body" ? c.mesh.body_groups[static_cast<std::size_t>(index)] : boundary) = value;
  }
}

// [parameter] (one parameter, with its training and verification values) or [[parameter]]
// (p parameters; their sets in [sets]).
void Reader::read_parameters(const toml::table& root, CaseSpec& c) const {
  const toml::node& par_node = required(root, "", "parameter");
  if (const auto* arr = par_node.as_array()) {
    if (!arr->is_array_of_tables() || arr->empty()) {
      wrong_type(par_node, "parameter", "a table ([parameter]) or an array of tables ([[parameter]])");
    }
    read_parameter_array(*arr, c);
    return;
  }
  read_single_parameter(root, table(par_node, "parameter"), c);
}

void Reader::read_parameter_array(const toml::array& arr, CaseSpec& c) const {
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const toml::table& t = *arr.get(i)->as_table();
    c.parameters.push_back(read_parameter(t, "parameter[" + std::to_string(i + 1) + "]", false));
    for (std::size_t j = 0; j + 1 < c.parameters.size(); ++j) {
      if (c.parameters[j].name == c.parameters.back().name) {
        fail(&t, "parameter '" + c.parameters.back().name + "' is defined twice (parameter[" + std::to_string(j + 1) +
                     "] and parameter[" + std::to_string(i + 1) + "])");
      }
    }
  }
}

// [parameter] with its sets: training (required unless [sets] gives them) and verification
// (the midpoints of the training values by default).
void Reader::read_single_parameter(const toml::table& root, const toml::table& par, CaseSpec& c) const {
  c.parameters.push_back(read_parameter(par, "parameter", true));
  const ParameterSpec& p = c.parameters.back();
  const toml::node* training = par.get("training");
  if (training == nullptr) {
    if (root.get("sets") != nullptr) return;  // the sets are in [sets]
    required(par, "parameter", "training");
  }
  std::vector<double> values = parameter_set(*training, "parameter.training");
  if (training->is_table()) snap_to_domain(values, p.min, p.max);
  c.sets.push_back({"training", points_1d(values)});
  if (const toml::node* v = par.get("verification")) {
    std::vector<double> w = parameter_set(*v, "parameter.verification");
    if (v->is_table()) snap_to_domain(w, p.min, p.max);
    c.sets.push_back({"verification", points_1d(w)});
  } else {
    c.sets.push_back({"verification", points_1d(midpoints(values))});
  }
}

ParameterSpec Reader::read_parameter(const toml::table& par, const std::string& path, bool with_sets) const {
  if (with_sets) {
    check_keys(par, path, {"name", "kind", "domain", "reference", "units", "body", "center", "training", "verification"});
  } else {
    check_keys(par, path, {"name", "kind", "domain", "reference", "units", "body", "center"});
  }
  ParameterSpec p;
  p.name = string(required(par, path, "name"), path + ".name");
  if (const toml::node* u = par.get("units")) p.units = string(*u, path + ".units");
  const toml::node& kind = required(par, path, "kind");
  const std::string kind_name = string(kind, path + ".kind");
  try {
    p.kind = parameter_kind_from_string(kind_name);
  } catch (const Error&) {
    fail(&kind, "key '" + path + ".kind' must be dirichlet-scale, body-scaling, young-modulus, traction, "
                "body-force or friction-coefficient, got '" + kind_name + "'");
  }
  const toml::node& domain_node = required(par, path, "domain");
  const std::vector<double> domain = numbers(domain_node, path + ".domain", 2);
  p.min = domain[0];
  p.max = domain[1];
  if (!(p.min <= p.max)) {
    fail(&domain_node, "key '" + path + ".domain' = [" + shortest(p.min) + ", " + shortest(p.max) +
                           "] is not an interval (min > max)");
  }
  read_parameter_body(par, path, p);
  return p;
}

// body (the kinds that act on one body), center and reference (body-scaling; the reference
// defaults to the domain's minimum for the other kinds).
void Reader::read_parameter_body(const toml::table& par, const std::string& path, ParameterSpec& p) const {
  const toml::node* body = par.get("body");
  const toml::node* center = par.get("center");
  const toml::node* reference = par.get("reference");
  if (has_body(p.kind)) {
    p.body = body_index(required(par, path, "body"), path + ".body");
  } else if (body != nullptr) {
    fail(body, "key '" + path + ".body' needs kind = \"body-scaling\", \"young-modulus\" or \"body-force\"");
  }
  if (p.kind == ParameterKind::BodyScaling) {
    p.center = vector2(required(par, path, "center"), path + ".center");
    p.reference = number(required(par, path, "reference"), path + ".reference");
  } else {
    if (center != nullptr) fail(center, "key '" + path + ".center' needs kind = \"body-scaling\"");
    p.reference = reference != nullptr ? number(*reference, path + ".reference") : p.min;
  }
}

// [[dirichlet]]: a group and ux, uy and/or uz (uz: 3D meshes, checked by reference_mesh).
void Reader::read_dirichlet(const toml::table& root, CaseSpec& c, const std::string& prefix) const {
  const toml::node* d = root.get("dirichlet");
  if (d == nullptr) return;
  const auto* arr = d->as_array();
  if (arr == nullptr || !arr->is_array_of_tables()) {
    wrong_type(*d, prefix + "dirichlet", "an array of tables ([[" + prefix + "dirichlet]])");
  }
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table& t = *arr->get(i)->as_table();
    const std::string path = prefix + "dirichlet[" + std::to_string(i + 1) + "]";
    check_keys(t, path, {"group", "ux", "uy", "uz"});
    DirichletSpec ds;
    ds.group = string(required(t, path, "group"), path + ".group");
    if (const toml::node* v = t.get("ux")) ds.ux = affine(*v, path + ".ux", c.parameters);
    if (const toml::node* v = t.get("uy")) ds.uy = affine(*v, path + ".uy", c.parameters);
    if (const toml::node* v = t.get("uz")) ds.uz = affine(*v, path + ".uz", c.parameters);
    if (!ds.ux && !ds.uy && !ds.uz) {
      fail(&t, "[[dirichlet]] on group '" + ds.group + "' needs 'ux', 'uy' or 'uz' (" + path + ")");
    }
    c.dirichlet.push_back(std::move(ds));
  }
}

// [[traction]] entries (after the parameters: one may name a parameter of kind traction).
void Reader::read_tractions(const toml::table& root, CaseSpec& c, const std::string& prefix) const {
  const toml::node* d = root.get("traction");
  if (d == nullptr) return;
  const auto* arr = d->as_array();
  if (arr == nullptr || !arr->is_array_of_tables()) {
    wrong_type(*d, prefix + "traction", "an array of tables ([[" + prefix + "traction]])");
  }
  for (std::size_t i = 0; i < arr->size(); ++i) {
    c.tractions.push_back(
        read_traction(*arr->get(i)->as_table(), prefix + "traction[" + std::to_string(i + 1) + "]", c));
  }
}

// [friction] and [[load_steps]] (docs/cases.md, "Frictional case files"): both or neither.
void Reader::read_friction(const toml::table& root, const CaseSpec& c, FrictionFileSpec& f) const {
  const toml::node* fn = root.get("friction");
  const toml::node* sn = root.get("load_steps");
  if (fn == nullptr && sn == nullptr) return;
  if (fn == nullptr) fail(sn, "[[load_steps]] needs a [friction] table (law and coefficient or threshold)");
  if (sn == nullptr) fail(fn, "[friction] needs [[load_steps]] (at least one load step)");
  f.has_friction = true;
  const toml::table& t = table(*fn, "friction");
  check_keys(t, "friction", {"law", "coefficient", "threshold"});
  f.law = string(required(t, "friction", "law"), "friction.law");
  if (f.law != "coulomb" && f.law != "tresca") {
    fail(t.get("law"), "key 'friction.law' must be coulomb or tresca, got '" + f.law + "'");
  }
  const char* value_key = f.law == "coulomb" ? "coefficient" : "threshold";
  const char* other_key = f.law == "coulomb" ? "threshold" : "coefficient";
  if (const toml::node* other = t.get(other_key)) {
    fail(other, "key 'friction." + std::string(other_key) + "' does not apply to law = " + f.law + " (it takes '" +
                    value_key + "')");
  }
  if (c.constraint != contact::Discretization::Collocation) {
    fail(fn, "a frictional case needs constraint = collocation (got " + std::string(contact::to_string(c.constraint)) +
                 ")");
  }
  if (!read_coefficient_parameter(t, c, f)) {
    const toml::node& vn = required(t, "friction", value_key);
    const double v = number(vn, "friction." + std::string(value_key));
    if (!std::isfinite(v) || v < 0.0) {
      std::ostringstream got;
      got << v;
      fail(&vn, "key 'friction." + std::string(value_key) + "' must be a finite number >= 0, got " + got.str());
    }
    (f.law == "coulomb" ? f.coefficient : f.threshold) = v;
  }
  read_load_steps(*sn, c, f);
}

// A friction-coefficient parameter (at most one, Coulomb only, a domain in [0, inf)) gives f in
// place of friction.coefficient; false when the case has none.
bool Reader::read_coefficient_parameter(const toml::table& t, const CaseSpec& c, FrictionFileSpec& f) const {
  for (std::size_t k = 0; k < c.parameters.size(); ++k) {
    const ParameterSpec& p = c.parameters[k];
    if (p.kind != ParameterKind::FrictionCoefficient) continue;
    if (f.coefficient_parameter >= 0) fail(nullptr, "two parameters of kind friction-coefficient (at most one)");
    if (f.law != "coulomb") fail(t.get("law"), "parameter '" + p.name + "' of kind friction-coefficient needs law = coulomb");
    if (const toml::node* v = t.get("coefficient")) {
      fail(v, "key 'friction.coefficient' and parameter '" + p.name + "' (friction-coefficient) both give f: keep one");
    }
    if (!(p.min >= 0.0)) fail(nullptr, "parameter '" + p.name + "' of kind friction-coefficient needs a domain in [0, inf)");
    f.coefficient_parameter = static_cast<int>(k);
  }
  return f.coefficient_parameter >= 0;
}

void Reader::read_load_steps(const toml::node& steps, const CaseSpec& c, FrictionFileSpec& f) const {
  const toml::node* sn = &steps;  // for the messages
  const auto* arr = sn->as_array();
  if (arr != nullptr && arr->empty()) fail(sn, "key 'load_steps' has no step (at least one [[load_steps]])");
  if (arr == nullptr || !arr->is_array_of_tables()) wrong_type(*sn, "load_steps", "an array of tables ([[load_steps]])");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    f.steps.push_back(read_load_step(*arr->get(i)->as_table(), "load_steps[" + std::to_string(i + 1) + "]", c));
  }
}

// One load step: its [[load_steps.dirichlet]] (the same groups and components as [[dirichlet]],
// other values) and optional [[load_steps.traction]] loads.
FrictionFileSpec::Step Reader::read_load_step(const toml::table& t, const std::string& path, const CaseSpec& c) const {
  check_keys(t, path, {"dirichlet", "traction"});
  CaseSpec step;
  step.parameters = c.parameters;
  read_dirichlet(t, step, path + ".");
  read_tractions(t, step, path + ".");
  auto components = [](const DirichletSpec& d) {
    return std::to_string(d.ux.has_value()) + std::to_string(d.uy.has_value()) + std::to_string(d.uz.has_value());
  };
  bool same = step.dirichlet.size() == c.dirichlet.size();
  for (std::size_t k = 0; same && k < c.dirichlet.size(); ++k) {
    same = step.dirichlet[k].group == c.dirichlet[k].group && components(step.dirichlet[k]) == components(c.dirichlet[k]);
  }
  if (!same) {
    fail(&t, "[[" + path + ".dirichlet]] must prescribe the components of [[dirichlet]], group by group in the same "
                 "order (only the values change from step to step)");
  }
  return {std::move(step.dirichlet), std::move(step.tractions)};
}

TractionSpec Reader::read_traction(const toml::table& t, const std::string& path, const CaseSpec& c) const {
  check_keys(t, path, {"group", "pressure", "vector", "parameter", "body"});
  TractionSpec tr;
  tr.group = string(required(t, path, "group"), path + ".group");
  if (tr.group.empty()) fail(&t, "key '" + path + ".group' is empty");
  const toml::node* pressure = t.get("pressure");
  const toml::node* vector = t.get("vector");
  if ((pressure == nullptr) == (vector == nullptr)) {
    fail(&t, "[[traction]] on group '" + tr.group + "' needs exactly one of 'pressure' and 'vector' (" + path + ")");
  }
  tr.is_pressure = pressure != nullptr;
  if (pressure != nullptr) tr.pressure = number(*pressure, path + ".pressure");
  if (vector != nullptr) tr.vector = vector2(*vector, path + ".vector");
  if (const toml::node* b = t.get("body")) tr.body = body_index(*b, path + ".body");
  if (const toml::node* pn = t.get("parameter")) {
    const std::string name = string(*pn, path + ".parameter");
    tr.parameter = parameter_index(c.parameters, name);
    if (tr.parameter < 0) fail(pn, "key '" + path + ".parameter' names an unknown parameter '" + name + "'" + names(c.parameters));
    if (c.parameters[static_cast<std::size_t>(tr.parameter)].kind != ParameterKind::Traction) {
      fail(pn, "key '" + path + ".parameter' names parameter '" + name + "' of kind " +
                   to_string(c.parameters[static_cast<std::size_t>(tr.parameter)].kind) +
                   " (a traction load is scaled by a parameter of kind traction)");
    }
  }
  return tr;
}

// [sets] (after the parameters: the sets are checked against their domains), unless
// parameter.training gave the sets.
void Reader::read_sets(const toml::table& root, CaseSpec& c) const {
  const toml::node* sets_node = root.get("sets");
  if (sets_node == nullptr) {
    if (c.sets.empty()) fail(nullptr, "missing table [sets] with the parameter sets (at least 'training')");
    return;
  }
  if (!c.sets.empty()) fail(sets_node, "[sets] and the key 'parameter.training' both give sets: keep one");
  const toml::table& sets = table(*sets_node, "sets");
  ParameterBox box;
  box.min.resize(c.num_parameters());
  box.max.resize(c.num_parameters());
  for (int k = 0; k < c.num_parameters(); ++k) {
    box.names.push_back(c.parameters[static_cast<std::size_t>(k)].name);
    box.min(k) = c.parameters[static_cast<std::size_t>(k)].min;
    box.max(k) = c.parameters[static_cast<std::size_t>(k)].max;
  }
  for (auto&& [k, v] : sets) {
    const std::string name(k.str());
    c.sets.push_back({name, parameter_set_from_toml(v, box, base_dir_, "sets." + name, origin_)});
  }
  if (!c.has_set("training")) fail(sets_node, "[sets] has no 'training' set");
}

// TOML text of a double: shortest round-trip form, always a float literal.
std::string number_text(double x) {
  require(std::isfinite(x), "to_toml: non-finite value");
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string quoted(const std::string& s) {
  std::ostringstream os;
  os << '"';
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      os << '\\' << ch;
    } else if (u < 0x20 || u == 0x7f) {
      static const char* hex = "0123456789ABCDEF";
      os << "\\u00" << hex[u >> 4] << hex[u & 15];
    } else {
      os << ch;
    }
  }
  os << '"';
  return os.str();
}

std::string affine_text(const AffineValue& v, const std::vector<ParameterSpec>& params) {
  if (v.b == 0.0) return number_text(v.a);
  return "{ a = " + number_text(v.a) + ", b = " + number_text(v.b) +
         ", parameter = " + quoted(params[static_cast<std::size_t>(v.parameter)].name) + " }";
}

bool same_value(const std::optional<AffineValue>& a, const std::optional<AffineValue>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->a == b->a && a->b == b->b && (a->b == 0.0 || a->parameter == b->parameter));
}

}  // namespace

namespace {

CaseSpec read_case_text(const std::string& text, const std::string& origin, MeshFile mesh_file,
                        FrictionFileSpec* friction) {
  fs::path base = fs::path(origin).parent_path();
  if (base.empty()) base = fs::current_path();
  // Absolute, so that the resolved mesh.file (recorded by to_toml in snapshot and model
  // files) names the same file from any working directory.
  base = fs::absolute(base);
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << origin << ":" << e.source().begin.line << ":" << e.source().begin.column << ": TOML syntax error: "
       << e.description();
    throw Error(os.str());
  }
  return Reader(origin, base, mesh_file).read(root, friction);
}

}  // namespace

CaseSpec case_from_toml_string(const std::string& text, const std::string& origin, MeshFile mesh_file) {
  return read_case_text(text, origin, mesh_file, nullptr);
}

CaseSpec case_from_toml_file(const std::string& path) {
  return case_from_toml_string(read_text_input(path, "case file"), path);
}

std::optional<FrictionalCaseFile> frictional_case_from_toml_file(const std::string& path) {
  FrictionalCaseFile file;
  file.spec = read_case_text(read_text_input(path, "case file"), path, MeshFile::Required, &file.friction);
  if (!file.friction.has_friction) return std::nullopt;
  return file;
}

std::string to_toml(const CaseSpec& c) {
  check_case_spec(c);
  std::ostringstream os;
  os << "# contactrb case (docs/cases.md)\n";
  os << "name = " << quoted(c.name) << "\n";
  if (!c.description.empty()) os << "description = " << quoted(c.description) << "\n";
  os << "constraint = " << quoted(contact::to_string(c.constraint)) << "\n\n";
  os << "[mesh]\n";
  if (!c.mesh.generator.empty()) {
    os << "generator = " << quoted(c.mesh.generator) << "\n";
  } else {
    os << "file = " << quoted(c.mesh.msh_file) << "\n";
  }
  for (int i = 0; i < 2; ++i) {
    const BodySpec& b = c.bodies[static_cast<std::size_t>(i)];
    os << "\n[" << (i == 0 ? "slave" : "master") << "]\n";
    if (c.mesh.generator.empty()) {
      os << "body = " << quoted(c.mesh.body_groups[static_cast<std::size_t>(i)]) << "\n";
      os << "boundary = " << quoted(i == 0 ? c.mesh.slave_group : c.mesh.master_group) << "\n";
    }
    os << "E = " << number_text(b.E) << "\nnu = " << number_text(b.nu) << "\n";
    if (!b.load.isZero(0.0)) os << "load = [" << number_text(b.load.x()) << ", " << number_text(b.load.y()) << "]\n";
  }
  for (const DirichletSpec& d : c.dirichlet) {
    os << "\n[[dirichlet]]\ngroup = " << quoted(d.group) << "\n";
    if (d.ux) os << "ux = " << affine_text(*d.ux, c.parameters) << "\n";
    if (d.uy) os << "uy = " << affine_text(*d.uy, c.parameters) << "\n";
    if (d.uz) os << "uz = " << affine_text(*d.uz, c.parameters) << "\n";
  }
  for (const TractionSpec& t : c.tractions) {
    os << "\n[[traction]]\ngroup = " << quoted(t.group) << "\n";
    if (t.is_pressure) {
      os << "pressure = " << number_text(t.pressure) << "\n";
    } else {
      os << "vector = [" << number_text(t.vector.x()) << ", " << number_text(t.vector.y()) << "]\n";
    }
    if (t.body >= 0) os << "body = " << quoted(t.body == 0 ? "slave" : "master") << "\n";
    if (t.parameter >= 0) os << "parameter = " << quoted(c.parameters[static_cast<std::size_t>(t.parameter)].name) << "\n";
  }
  for (const ParameterSpec& p : c.parameters) {
    os << "\n[[parameter]]\nname = " << quoted(p.name) << "\nkind = " << quoted(to_string(p.kind)) << "\n"
       << "domain = [" << number_text(p.min) << ", " << number_text(p.max) << "]\n"
       << "reference = " << number_text(p.reference) << "\n";
    if (!p.units.empty()) os << "units = " << quoted(p.units) << "\n";
    if (has_body(p.kind)) os << "body = " << quoted(p.body == 0 ? "slave" : "master") << "\n";
    if (p.kind == ParameterKind::BodyScaling) {
      os << "center = [" << number_text(p.center.x()) << ", " << number_text(p.center.y()) << "]\n";
    }
  }
  os << "\n[sets]\n";
  for (const ParameterSet& set : c.sets) {
    os << quoted(set.name) << " = { points = [";
    for (std::size_t i = 0; i < set.points.size(); ++i) {
      os << (i ? ", " : "") << "[";
      for (Eigen::Index k = 0; k < set.points[i].size(); ++k) os << (k ? ", " : "") << number_text(set.points[i](k));
      os << "]";
    }
    os << "] }\n";
  }
  return os.str();
}

bool same_case(const CaseSpec& a, const CaseSpec& b) {
  if (a.name != b.name || a.description != b.description || a.constraint != b.constraint) return false;
  if (a.mesh.generator != b.mesh.generator || a.mesh.msh_file != b.mesh.msh_file ||
      a.mesh.body_groups != b.mesh.body_groups || a.mesh.slave_group != b.mesh.slave_group ||
      a.mesh.master_group != b.mesh.master_group) {
    return false;
  }
  for (std::size_t i = 0; i < 2; ++i) {
    if (a.bodies[i].E != b.bodies[i].E || a.bodies[i].nu != b.bodies[i].nu || a.bodies[i].load != b.bodies[i].load) {
      return false;
    }
  }
  if (a.dirichlet.size() != b.dirichlet.size()) return false;
  for (std::size_t i = 0; i < a.dirichlet.size(); ++i) {
    const DirichletSpec& x = a.dirichlet[i];
    const DirichletSpec& y = b.dirichlet[i];
    if (x.group != y.group || !same_value(x.ux, y.ux) || !same_value(x.uy, y.uy) || !same_value(x.uz, y.uz)) {
      return false;
    }
  }
  if (a.tractions.size() != b.tractions.size()) return false;
  for (std::size_t i = 0; i < a.tractions.size(); ++i) {
    const TractionSpec& x = a.tractions[i];
    const TractionSpec& y = b.tractions[i];
    if (x.group != y.group || x.is_pressure != y.is_pressure || x.vector != y.vector || x.pressure != y.pressure ||
        x.parameter != y.parameter || x.body != y.body) {
      return false;
    }
  }
  if (a.parameters.size() != b.parameters.size()) return false;
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    const ParameterSpec& p = a.parameters[i];
    const ParameterSpec& q = b.parameters[i];
    if (p.name != q.name || p.units != q.units || p.kind != q.kind || p.min != q.min || p.max != q.max ||
        p.reference != q.reference) {
      return false;
    }
    if (has_body(p.kind) && p.body != q.body) return false;
    if (p.kind == ParameterKind::BodyScaling && p.center != q.center) return false;
  }
  // Sets by name (a TOML table has no order).
  if (a.sets.size() != b.sets.size()) return false;
  for (const ParameterSet& s : a.sets) {
    if (!b.has_set(s.name)) return false;
    const std::vector<Mu>& t = b.set(s.name);
    if (s.points.size() != t.size()) return false;
    for (std::size_t j = 0; j < t.size(); ++j) {
      if (s.points[j].size() != t[j].size() || s.points[j] != t[j]) return false;
    }
  }
  return true;
}

}  // namespace contactrb::cases
