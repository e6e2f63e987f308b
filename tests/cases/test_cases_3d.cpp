// The three-dimensional cases (docs/cases.md, "Three-dimensional cases"): their dimension,
// reference meshes and Dirichlet data, and the TOML key uz.
#include <gtest/gtest.h>

#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"

namespace cases = contactrb::cases;
namespace mesh = contactrb::mesh;

namespace {

std::string error_of(const auto& f) {
  try {
    f();
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Cases3d, CatalogAndSpecsAgreeOnTheDimension) {
  for (const cases::CaseInfo& info : cases::builtin_cases()) {
    EXPECT_EQ(cases::case_dimension(cases::builtin_case_spec(info.name)), info.dimension) << info.name;
  }
  EXPECT_EQ(cases::find_case("hertz-3d").dimension, 3);
  EXPECT_EQ(cases::find_case("patch-3d").dimension, 3);
  EXPECT_EQ(cases::find_case("hertz-a").dimension, 2);
}

TEST(Cases3d, Hertz3dMeshHasEveryDirichletGroupAndTheImposedDisplacement) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3d");
  const mesh::Mesh3 m = cases::reference_mesh3(spec, 0);
  for (const cases::DirichletSpec& d : spec.dirichlet) EXPECT_FALSE(m.boundary(d.group).empty()) << d.group;
  const auto bc = cases::dirichlet_at(spec, cases::Mu::Constant(1, 0.025));
  ASSERT_EQ(bc.front().group, "top");
  EXPECT_EQ(*bc.front().uz, -0.025);
  EXPECT_EQ(*bc.front().ux, 0.0);
  EXPECT_EQ(*bc[1].uz, 0.0);  // bottom clamped
  EXPECT_FALSE(bc[2].uy.has_value());  // symmetry_x: rollers, ux only
  EXPECT_THROW(cases::reference_mesh3(spec, mesh::kMaxHertz3dLevel + 1), contactrb::Error);
}

TEST(Cases3d, PatchSymmetryGroupsLieOnTheirPlanes) {
  const mesh::Mesh3 m = cases::reference_mesh3("patch-3d", 0);
  for (const auto& [group, axis] : {std::pair{"symmetry_x", 0}, std::pair{"symmetry_y", 1}}) {
    const std::vector<int> nodes = mesh::boundary_nodes(m, group);
    ASSERT_FALSE(nodes.empty()) << group;
    for (int v : nodes) EXPECT_EQ(m.nodes[static_cast<std::size_t>(v)](axis), 0.0) << group;
    // Both blocks: the face x = 0 (y = 0) of a block of side 1 and height 1/2, total area 1.
    double area = 0.0;
    for (const mesh::Face& f : m.boundary(group)) area += mesh::facet_area_normal(m, f).norm();
    EXPECT_NEAR(area, 1.0, 1e-12) << group;
  }
}

TEST(Cases3d, TwoDimensionalOperationsRefuseA3dCaseAndTheOtherWay) {
  const std::string m2 = error_of([] { cases::reference_mesh("hertz-3d", 0); });
  EXPECT_NE(m2.find("three-dimensional"), std::string::npos) << m2;
  EXPECT_NE(m2.find("hertz-3d"), std::string::npos) << m2;
  const std::string m3 = error_of([] { cases::reference_mesh3("hertz-a", 0); });
  EXPECT_NE(m3.find("two-dimensional"), std::string::npos) << m3;
}

TEST(Cases3d, TomlKeyUz) {
  const std::string text = R"(name = "uz-case"
[mesh]
generator = "GEN"
[slave]
E = 10
nu = 0.3
[master]
E = 10
nu = 0.3
[[dirichlet]]
group = "top"
uz = { b = -1.0 }
[[dirichlet]]
group = "bottom"
ux = 0.0
uy = 0.0
uz = 0.0
[parameter]
name = "d"
kind = "dirichlet-scale"
domain = [0.01, 0.03]
training = [0.01, 0.02]
)";
  const auto with_generator = [&](const std::string& generator) {
    std::string t = text;
    t.replace(t.find("GEN"), 3, generator);
    return t;
  };
  const cases::CaseSpec spec = cases::case_from_toml_string(with_generator("stacked-blocks"), "uz.toml");
  ASSERT_TRUE(spec.dirichlet[0].uz.has_value());
  EXPECT_EQ(spec.dirichlet[0].uz->b, -1.0);
  EXPECT_TRUE(cases::same_case(spec, cases::case_from_toml_string(cases::to_toml(spec), "again.toml")));
  EXPECT_EQ(cases::case_dimension(spec), 3);
  EXPECT_NO_THROW(cases::reference_mesh3(spec, 0));
  // A 3D case takes no traction and no body-scaling parameter (their data are 2D vectors).
  cases::CaseSpec pushed = spec;
  pushed.tractions.push_back({"top", true, Eigen::Vector2d::Zero(), 1.0, -1, -1});
  EXPECT_NE(error_of([&] { cases::reference_mesh3(pushed, 0); }).find("Dirichlet data only"), std::string::npos);
  cases::CaseSpec scaled = spec;
  scaled.parameters.front().kind = cases::ParameterKind::BodyScaling;
  scaled.parameters.front().body = 0;
  EXPECT_NE(error_of([&] { cases::reference_mesh3(scaled, 0); }).find("body-scaling"), std::string::npos);
  // uz on a 2D mesh: one clear error naming the group.
  const cases::CaseSpec flat = cases::case_from_toml_string(with_generator("hertz"), "uz2d.toml");
  const std::string m = error_of([&] { cases::reference_mesh(flat, 0); });
  EXPECT_NE(m.find("uz"), std::string::npos) << m;
  EXPECT_NE(m.find("two-dimensional"), std::string::npos) << m;
}
