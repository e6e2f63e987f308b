#include "contactrb/cases/case_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <sstream>

#include "contactrb/cases/catalog.hpp"
#include "contactrb/cases/parameter_sets.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/msh_io.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::cases {

namespace {

const char* const kBuiltin = "built-in";

// Paper Section 6.2: E = 15, nu = 0.35 for both half-disks.
constexpr double kHertzE = 15.0;
constexpr double kHertzNu = 0.35;
// Ring-on-block (Section 6.3): the ring is 15 times stiffer than the block (docs/cases.md).
constexpr double kRingE = 15.0;
constexpr double kBlockE = 1.0;
constexpr double kRingBlockNu = 0.3;
// Downward displacement of the ring's end faces (docs/cases.md: the paper's 50 m do not
// fit a ring of radius 1). 0.1 gave the same active set at mu = 1 and 1.13 (10 rows);
// 0.2 (the ring thickness) gives 18 and 16 rows (Fig. 18: the zone varies with mu).
constexpr double kRingPush = 0.2;
// hertz-3d: the moduli of hertz-a, nu = 0.3 (docs/cases.md); patch-3d: the 2D patch example's.
constexpr double kHertz3dNu = 0.3;
constexpr double kPatchE = 10.0;
constexpr double kPatchNu = 0.3;

AffineValue constant(double a) { return {a, 0.0, 0}; }

// A one-parameter case's sets: training values and the verification values.
std::vector<ParameterSet> sets_1d(const std::vector<double>& training, const std::vector<double>& verification) {
  return {{"training", points_1d(training)}, {"verification", points_1d(verification)}};
}

// Physically degenerate data (docs/cases.md, "Limits"). Plane strain lambda_L =
// E nu / ((1 + nu)(1 - 2 nu)) grows like 1/(1 - 2 nu): at nu = 0.5 - 1e-6 lambda_L / mu_L is
// already 3e5 and P1 elements lock; at 0.49999999999999994 (one ulp below 0.5) the solve
// "converged" to an energy 26 times off.
constexpr double kIncompressibleMargin = 1e-6;
// Beyond this ratio of the two Young's moduli the stiffness matrix has a condition number whose
// product with the double round-off (1e-16) is no longer small.
constexpr double kMaxStiffnessRatio = 1e12;
// Largest magnitude of E, a body load and a Dirichlet value over the parameter domain: the
// energy multiplies E by squared displacements and the projection squares distances, which
// overflow double precision from about 1e154 on (the projection then indexed segment -1).
// 1e50 leaves room for any unit system and mesh size.
constexpr double kMaxDataMagnitude = 1e50;

std::string shortest(double x) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
}

CaseSpec hertz_a() {
  CaseSpec c;
  c.name = "hertz-a";
  c.description = "two half-disks R1 = R2 = 1, gap 0.1, imposed displacement mu in [0.15, 0.45], collocation";
  c.mesh.generator = "hertz";
  c.bodies = {BodySpec{kHertzE, kHertzNu, Eigen::Vector2d::Zero()}, BodySpec{kHertzE, kHertzNu, Eigen::Vector2d::Zero()}};
  // Section 6.2.1 (a): u = (0, -mu/2) on the upper flat edge, (0, mu/2) on the lower one.
  c.dirichlet = {{"top", constant(0.0), AffineValue{0.0, -0.5}}, {"bottom", constant(0.0), AffineValue{0.0, 0.5}}};
  c.constraint = contact::Discretization::Collocation;
  ParameterSpec& p = c.parameters.emplace_back();
  p.name = "imposed displacement";
  p.kind = ParameterKind::DirichletScale;
  p.min = 0.15;
  p.max = 0.45;
  p.reference = 0.3;
  const std::vector<double> training = arithmetic_set(0.15, 0.01, 31);  // 0.15 + 0.01 i, i = 0..30
  c.sets = sets_1d(training, midpoints(training));
  return c;
}

CaseSpec hertz_b() {
  CaseSpec c;
  c.name = "hertz-b";
  c.description = "two half-disks, lower radius R2 = mu in [0.9, 1.12], non-matching meshes, collocation";
  c.mesh.generator = "hertz";
  c.bodies = {BodySpec{kHertzE, kHertzNu, Eigen::Vector2d::Zero()}, BodySpec{kHertzE, kHertzNu, Eigen::Vector2d::Zero()}};
  c.dirichlet = {{"top", constant(0.0), constant(-0.2)}, {"bottom", constant(0.0), constant(0.2)}};
  c.constraint = contact::Discretization::Collocation;
  ParameterSpec& p = c.parameters.emplace_back();
  p.name = "lower radius R2";
  p.kind = ParameterKind::BodyScaling;
  p.min = 0.9;
  p.max = 1.12;
  // R2 = mu: the reference mesh has R2 = 1; body 2 is scaled by mu about the top of its
  // arc (0, -gap/2), so the gap on the vertical axis stays 0.1.
  const mesh::HertzGeometry g;
  p.reference = g.R2;
  p.body = mesh::kMasterBody;
  p.center = Eigen::Vector2d(0.0, -0.5 * g.gap);
  // The paper writes i = 0..22 but also P = 22 solves and P = [0.9, 1.12]; i = 22 gives
  // 1.125, outside P. We keep the 22 points inside P (docs/cases.md).
  const std::vector<double> training = arithmetic_set(0.905, 0.01, 22);
  c.sets = sets_1d(training, midpoints(training));
  return c;
}

// A three-parameter Hertz case (docs/cases.md, "hertz-3p"): hertz-a's imposed displacement,
// hertz-b's lower radius, and the lower body's Young's modulus. Its sets are generated (the
// paper's cases list theirs): a Latin hypercube for the greedy, a tensor grid for POD, random
// verification points.
CaseSpec hertz_3p() {
  CaseSpec c;
  c.name = "hertz-3p";
  c.description = "two half-disks: imposed displacement delta x lower radius R2 x lower modulus E2, collocation";
  c.mesh.generator = "hertz";
  c.bodies = {BodySpec{kHertzE, kHertzNu, Eigen::Vector2d::Zero()}, BodySpec{kHertzE, kHertzNu, Eigen::Vector2d::Zero()}};
  c.dirichlet = {{"top", constant(0.0), AffineValue{0.0, -0.5, 0}}, {"bottom", constant(0.0), AffineValue{0.0, 0.5, 0}}};
  c.constraint = contact::Discretization::Collocation;
  ParameterSpec delta, radius, modulus;  // pushed at the end (a reference into the vector would dangle)
  delta.name = "delta";
  delta.kind = ParameterKind::DirichletScale;
  delta.min = 0.15;
  delta.max = 0.45;
  delta.reference = 0.3;
  const mesh::HertzGeometry g;
  radius.name = "R2";
  radius.kind = ParameterKind::BodyScaling;
  radius.min = 0.9;
  radius.max = 1.12;
  radius.reference = g.R2;
  radius.body = mesh::kMasterBody;
  radius.center = Eigen::Vector2d(0.0, -0.5 * g.gap);
  modulus.name = "E2";
  modulus.kind = ParameterKind::YoungModulus;
  modulus.body = mesh::kMasterBody;
  modulus.min = 0.5 * kHertzE;
  modulus.max = 2.0 * kHertzE;
  modulus.reference = kHertzE;
  c.parameters = {delta, radius, modulus};
  ParameterBox box;
  box.names = {delta.name, radius.name, modulus.name};
  box.min = Eigen::Vector3d(delta.min, radius.min, modulus.min);
  box.max = Eigen::Vector3d(delta.max, radius.max, modulus.max);
  c.sets = {{"training", latin_hypercube(box, 1000, 1)},
            {"grid", tensor_grid({uniform_axis(delta.min, delta.max, 7), uniform_axis(radius.min, radius.max, 5),
                                  uniform_axis(modulus.min, modulus.max, 5)})},
            {"verification", uniform_random(box, 200, 2)}};
  return c;
}

CaseSpec ring_block() {
  CaseSpec c;
  c.name = "ring-block";
  c.description = "half-ring of radius mu in [0.95, 1.15] pressed on a softer block, LAC";
  c.mesh.generator = "ring-block";
  c.bodies = {BodySpec{kRingE, kRingBlockNu, Eigen::Vector2d::Zero()},
              BodySpec{kBlockE, kRingBlockNu, Eigen::Vector2d::Zero()}};
  c.dirichlet = {{"ring_ends", constant(0.0), constant(-kRingPush)},
                 {"block_bottom", constant(0.0), constant(0.0)}};
  c.constraint = contact::Discretization::LAC;
  ParameterSpec& p = c.parameters.emplace_back();
  p.name = "ring radius R1";
  p.kind = ParameterKind::BodyScaling;
  p.min = 0.95;
  p.max = 1.15;
  // R1 = mu: the ring (outer radius 1 in the reference mesh) scaled about its lowest
  // point (0, gap), which stays on the block.
  const mesh::RingBlockGeometry g;
  p.reference = g.R_out;
  p.body = mesh::kSlaveBody;
  p.center = Eigen::Vector2d(0.0, g.gap);
  // The paper's verification set is 0.9575 + 0.02 i, i = 0..10, but i = 10 gives 1.1575,
  // outside P = [0.95, 1.15]; we keep the 10 points inside P (docs/cases.md).
  c.sets = sets_1d(arithmetic_set(0.95, 0.01, 21), arithmetic_set(0.9575, 0.02, 10));
  return c;
}

// The Hertz sphere problem, quarter model (docs/cases.md, "hertz-3d"): the hemisphere's flat top
// pushed down by mu, the block's bottom clamped, rollers on the symmetry planes.
CaseSpec hertz_3d() {
  CaseSpec c;
  c.name = "hertz-3d";
  c.description = "quarter of a hemisphere R = 1 pressed on a block, imposed displacement mu in [0.01, 0.03]";
  c.mesh.generator = "hertz-3d";
  c.bodies = {BodySpec{kHertzE, kHertz3dNu, Eigen::Vector2d::Zero()},
              BodySpec{kHertzE, kHertz3dNu, Eigen::Vector2d::Zero()}};
  c.dirichlet = {{"top", constant(0.0), constant(0.0), AffineValue{0.0, -1.0, 0}},
                 {"bottom", constant(0.0), constant(0.0), constant(0.0)},
                 {"symmetry_x", constant(0.0), std::nullopt, std::nullopt},
                 {"symmetry_y", std::nullopt, constant(0.0), std::nullopt}};
  c.constraint = contact::Discretization::Collocation;
  ParameterSpec& p = c.parameters.emplace_back();
  p.name = "imposed displacement";
  p.kind = ParameterKind::DirichletScale;
  p.min = 0.01;
  p.max = 0.03;
  p.reference = 0.02;
  const std::vector<double> training = arithmetic_set(0.01, 0.002, 11);  // 0.01 + 0.002 i, i = 0..10
  c.sets = sets_1d(training, midpoints(training));
  return c;
}

// The 3D patch test (docs/cases.md, "patch-3d"): two unit-square blocks of height 1/2 with
// non-matching meshes, the top pushed down by mu, the bottom held vertically, rollers on the
// planes x = 0 and y = 0: uniaxial stress, uniform pressure E mu.
CaseSpec patch_3d() {
  CaseSpec c;
  c.name = "patch-3d";
  c.description = "two stacked blocks, non-matching meshes, uniform compression mu in [0.01, 0.03], LAC";
  c.mesh.generator = "stacked-blocks";
  c.bodies = {BodySpec{kPatchE, kPatchNu, Eigen::Vector2d::Zero()}, BodySpec{kPatchE, kPatchNu, Eigen::Vector2d::Zero()}};
  c.dirichlet = {{"top", std::nullopt, std::nullopt, AffineValue{0.0, -1.0, 0}},
                 {"bottom", std::nullopt, std::nullopt, constant(0.0)},
                 {"symmetry_x", constant(0.0), std::nullopt, std::nullopt},
                 {"symmetry_y", std::nullopt, constant(0.0), std::nullopt}};
  c.constraint = contact::Discretization::LAC;
  ParameterSpec& p = c.parameters.emplace_back();
  p.name = "imposed displacement";
  p.kind = ParameterKind::DirichletScale;
  p.min = 0.01;
  p.max = 0.03;
  p.reference = 0.02;
  const std::vector<double> training = arithmetic_set(0.01, 0.005, 5);  // 0.01 + 0.005 i, i = 0..4
  c.sets = sets_1d(training, midpoints(training));
  return c;
}

}  // namespace

namespace {

[[noreturn]] void fail_case(const std::string& what, const std::string& where) {
  throw Error(what + " (" + where + ")");
}

void check_mesh_spec(const MeshSpec& m, const std::string& where) {
  const bool gen = !m.generator.empty();
  const bool msh = !m.msh_file.empty();
  if (gen == msh) fail_case("the mesh needs exactly one of a generator or a .msh file", where);
  if (gen && m.generator != "hertz" && m.generator != "ring-block" && m.generator != "hertz-3d" &&
      m.generator != "stacked-blocks") {
    fail_case("unknown mesh generator '" + m.generator + "' (expected hertz, ring-block, hertz-3d or stacked-blocks)",
              where);
  }
  for (const std::string& g : m.body_groups) {
    if (g.empty()) fail_case("empty body group name", where);
  }
  if (m.body_groups[0] == m.body_groups[1]) fail_case("the two bodies have the same group '" + m.body_groups[0] + "'", where);
  if (m.slave_group.empty() || m.master_group.empty()) fail_case("empty contact group name", where);
  if (m.slave_group == m.master_group) fail_case("slave and master are the same group '" + m.slave_group + "'", where);
}

void check_body(const BodySpec& b, const std::string& body, const std::string& where) {
  if (!(std::isfinite(b.E) && b.E > 0.0)) {
    fail_case(body + ": Young's modulus E must be > 0 (got " + number_text(b.E) + ")", where);
  }
  if (!(std::isfinite(b.nu) && b.nu > -1.0 && b.nu < 0.5)) {
    fail_case(body + ": Poisson's ratio nu must be in (-1, 0.5) (got " + number_text(b.nu) + ")", where);
  }
  if (b.nu > 0.5 - kIncompressibleMargin) {
    fail_case(body + ": Poisson's ratio nu = " + shortest(b.nu) +
                  " is within 1e-6 of 0.5: a nearly incompressible material, for which the plane-strain Lame "
                  "coefficient lambda_L blows up and P1 elements lock (use nu <= 0.499999)",
              where);
  }
  if (b.E > kMaxDataMagnitude) {
    fail_case(body + ": Young's modulus E = " + shortest(b.E) + " is above 1e50 (products with it would overflow "
                     "double precision: change the units)",
              where);
  }
  if (!b.load.allFinite()) fail_case(body + ": body load is not finite", where);
  if (b.load.cwiseAbs().maxCoeff() > kMaxDataMagnitude) {
    fail_case(body + ": body load of magnitude " + shortest(b.load.cwiseAbs().maxCoeff()) +
                  " is above 1e50 (products with it would overflow double precision: change the units)",
              where);
  }
}

void check_bodies(const CaseSpec& c, const std::string& where) {
  for (std::size_t i = 0; i < c.bodies.size(); ++i) check_body(c.bodies[i], "body " + std::to_string(i + 1), where);
  const double ratio = std::max(c.bodies[0].E, c.bodies[1].E) / std::min(c.bodies[0].E, c.bodies[1].E);
  if (ratio > kMaxStiffnessRatio) {
    fail_case("the Young's moduli of the two bodies (" + shortest(c.bodies[0].E) + ", " + shortest(c.bodies[1].E) +
                  ") differ by a factor " + shortest(ratio) +
                  " above 1e12: the stiffness matrix is too ill-conditioned for double precision",
              where);
  }
}

// One Dirichlet value a + b mu; marks the parameter it depends on as used.
void check_dirichlet_value(const CaseSpec& c, const std::string& group, const AffineValue& v, std::vector<bool>& used,
                           const std::string& where) {
  const int p = c.num_parameters();
  if (!(std::isfinite(v.a) && std::isfinite(v.b))) fail_case("Dirichlet data on '" + group + "' is not finite", where);
  double largest = std::abs(v.a);
  if (v.b != 0.0) {
    if (v.parameter < 0 || v.parameter >= p) {
      fail_case("Dirichlet data on '" + group + "' depends on parameter " + std::to_string(v.parameter) +
                    ", but the case has " + std::to_string(p),
                where);
    }
    const ParameterSpec& k = c.parameters[static_cast<std::size_t>(v.parameter)];
    used[static_cast<std::size_t>(v.parameter)] = true;
    // a + b mu is affine: its largest magnitude over the domain is at an end.
    largest = std::max(std::abs(v.a + v.b * k.min), std::abs(v.a + v.b * k.max));
  }
  if (!(largest <= kMaxDataMagnitude)) {
    fail_case("Dirichlet data on '" + group + "' reaches magnitude " + shortest(largest) +
                  " on the parameter domain, above 1e50 (energies and distances would overflow double precision: "
                  "change the units)",
              where);
  }
}

void check_dirichlet(const CaseSpec& c, std::vector<bool>& used, const std::string& where) {
  for (const DirichletSpec& d : c.dirichlet) {
    if (d.group.empty()) fail_case("a Dirichlet condition has no group", where);
    if (!d.ux && !d.uy && !d.uz) fail_case("Dirichlet condition on '" + d.group + "' prescribes no component", where);
    for (const auto& v : {d.ux, d.uy, d.uz}) {
      if (v) check_dirichlet_value(c, d.group, *v, used, where);
    }
  }
}

// One traction; marks the parameter that scales it as used.
void check_traction(const CaseSpec& c, const TractionSpec& t, std::vector<bool>& used, const std::string& where) {
  if (t.group.empty()) fail_case("a traction has no group", where);
  const std::string on = "traction on '" + t.group + "'";
  const double size = t.is_pressure ? std::abs(t.pressure) : t.vector.cwiseAbs().maxCoeff();
  if (!std::isfinite(size)) fail_case(on + ": the load is not finite", where);
  if (!(size <= kMaxDataMagnitude)) fail_case(on + ": load above 1e50 (change the units)", where);
  if (t.body < -1 || t.body > 1) fail_case(on + ": body must be slave or master", where);
  if (t.parameter >= c.num_parameters() || t.parameter < -1) fail_case(on + ": parameter index out of range", where);
  if (t.parameter >= 0) {
    const ParameterSpec& k = c.parameters[static_cast<std::size_t>(t.parameter)];
    if (k.kind != ParameterKind::Traction) {
      fail_case(on + " is scaled by parameter '" + k.name + "' of kind " + to_string(k.kind) +
                    " (a traction load needs a traction parameter)",
                where);
    }
    used[static_cast<std::size_t>(t.parameter)] = true;
    const double scaled = size * std::max(std::abs(k.min), std::abs(k.max));
    if (!(scaled <= kMaxDataMagnitude)) {
      fail_case(on + ": the load scaled by '" + k.name + "' reaches " + shortest(scaled) +
                    " on the parameter domain, above 1e50 (change the units)",
                where);
    }
  }
  if (t.body != -1) return;
  for (const ParameterSpec& k : c.parameters) {
    if (k.kind == ParameterKind::BodyScaling) {
      fail_case(on + ": give its body (slave or master): the case has a body-scaling parameter, and the load of a "
                     "scaled body's boundary scales with it",
                where);
    }
  }
}

// Every dirichlet-scale and traction parameter scales some data; a body-force one, a load.
void check_parameters_used(const CaseSpec& c, const std::vector<bool>& used, const std::string& where) {
  for (int k = 0; k < c.num_parameters(); ++k) {
    const ParameterSpec& q = c.parameters[static_cast<std::size_t>(k)];
    if (q.kind == ParameterKind::DirichletScale && !used[static_cast<std::size_t>(k)]) {
      fail_case("parameter '" + q.name + "' of kind 'dirichlet-scale' but no Dirichlet value depends on it (give one "
                "as {a, b}: a + b mu)",
                where);
    }
    if (q.kind == ParameterKind::Traction && !used[static_cast<std::size_t>(k)]) {
      fail_case("parameter '" + q.name + "' of kind 'traction' but no [[traction]] names it", where);
    }
    if (q.kind == ParameterKind::BodyForce && c.bodies[static_cast<std::size_t>(q.body)].load.isZero(0.0)) {
      fail_case("parameter '" + q.name + "' of kind 'body-force' on a body without load (give the body a load vector)",
                where);
    }
    if (q.kind == ParameterKind::BodyForce) {
      const double scaled = c.bodies[static_cast<std::size_t>(q.body)].load.cwiseAbs().maxCoeff() *
                            std::max(std::abs(q.min), std::abs(q.max));
      if (!(scaled <= kMaxDataMagnitude)) {
        fail_case("the body load scaled by '" + q.name + "' reaches " + shortest(scaled) +
                      " on the parameter domain, above 1e50 (change the units)",
                  where);
      }
    }
  }
}

void check_sets(const CaseSpec& c, const std::string& where) {
  std::set<std::string> set_names;
  for (const ParameterSet& s : c.sets) {
    if (s.name.empty()) fail_case("a parameter set has no name", where);
    if (!set_names.insert(s.name).second) fail_case("parameter set '" + s.name + "' is defined twice", where);
    check_points(c.parameters, s.points, "parameter set '" + s.name + "' (" + where + ")");
  }
}

}  // namespace

void check_case_spec(const CaseSpec& c) {
  const std::string where = c.origin.empty() ? "case '" + c.name + "'" : "case '" + c.name + "' from " + c.origin;
  if (c.name.empty()) fail_case("the case has no name", where);
  check_mesh_spec(c.mesh, where);
  check_bodies(c, where);
  check_parameter_list(c.parameters, where);
  std::vector<bool> used(static_cast<std::size_t>(c.num_parameters()), false);  // parameters that scale some data
  check_dirichlet(c, used, where);
  for (const TractionSpec& t : c.tractions) check_traction(c, t, used, where);
  check_parameters_used(c, used, where);
  check_sets(c, where);
}

int case_dimension(const CaseSpec& spec) {
  const std::string& g = spec.mesh.generator;
  if (!g.empty()) return g == "hertz-3d" || g == "stacked-blocks" ? 3 : 2;
  return mesh::msh_dimension(spec.mesh.msh_file);
}

bool has_affine_dirichlet(const CaseSpec& spec) { return !dirichlet_parameters(spec).empty(); }

std::vector<int> dirichlet_parameters(const CaseSpec& spec) {
  std::set<int> k;
  for (const DirichletSpec& d : spec.dirichlet) {
    for (const auto& v : {d.ux, d.uy, d.uz}) {
      if (v && v->b != 0.0) k.insert(v->parameter);
    }
  }
  return {k.begin(), k.end()};
}

bool CaseSpec::has_set(const std::string& set_name) const {
  for (const ParameterSet& s : sets) {
    if (s.name == set_name) return true;
  }
  return false;
}

const std::vector<Mu>& CaseSpec::set(const std::string& set_name) const {
  for (const ParameterSet& s : sets) {
    if (s.name == set_name) return s.points;
  }
  std::string list;
  for (const ParameterSet& s : sets) list += " " + s.name;
  throw Error(context() + " has no parameter set '" + set_name + "' (sets:" + list + ")");
}

std::string CaseSpec::context() const {
  return "case '" + name + "'" + (origin.empty() ? std::string() : " from " + origin);
}

void CaseSpec::check_mu(const Mu& mu) const { cases::check_mu(parameters, mu, context()); }

int CaseSpec::parameter_of_body(ParameterKind kind, int body) const {
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    if (parameters[k].kind == kind && parameters[k].body == body) return static_cast<int>(k);
  }
  return -1;
}

CaseSpec builtin_case_spec(const std::string& name) {
  find_case(name);  // throws naming the unknown case
  CaseSpec c = name == "hertz-a"    ? hertz_a()
               : name == "hertz-b"  ? hertz_b()
               : name == "hertz-3p" ? hertz_3p()
               : name == "hertz-3d" ? hertz_3d()
               : name == "patch-3d" ? patch_3d()
                                    : ring_block();
  c.origin = kBuiltin;
  return c;
}

}  // namespace contactrb::cases
