// Physically degenerate and overflowing case data: check_case_spec refuses
// them with a message naming the datum, exactly at the documented limits (docs/cases.md), and
// parameter sets must be strictly increasing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/common/error.hpp"

using contactrb::cases::builtin_case_spec;
using contactrb::cases::CaseSpec;

namespace {
std::string error_of(const CaseSpec& c) {
  try {
    contactrb::cases::check_case_spec(c);
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(DegenerateData, PoissonRatioNearOneHalf) {
  CaseSpec c = builtin_case_spec("hertz-a");
  c.bodies[1].nu = 0.5 - 2e-6;  // nearly incompressible but still resolved: accepted
  EXPECT_EQ(error_of(c), "");
  c.bodies[1].nu = 0.5 - 0.5e-6;
  EXPECT_NE(error_of(c).find("body 2: Poisson's ratio nu = 0.4999995 is within 1e-6 of 0.5"), std::string::npos)
      << error_of(c);
  c.bodies[1].nu = std::nextafter(0.5, 0.0);
  EXPECT_NE(error_of(c).find("nu = 0.49999999999999994 is within 1e-6"), std::string::npos) << error_of(c);
}

TEST(DegenerateData, StiffnessRatio) {
  CaseSpec c = builtin_case_spec("ring-block");  // E = 15 and 1
  c.bodies[0].E = 1e12;
  EXPECT_EQ(error_of(c), "");  // exactly the limit
  c.bodies[0].E = 1.01e12;
  EXPECT_NE(error_of(c).find("(1.01e+12, 1) differ by a factor 1.01e+12 above 1e12"), std::string::npos)
      << error_of(c);
  c.bodies[0].E = 1.0;
  c.bodies[1].E = 1e-13;  // the other way round
  EXPECT_NE(error_of(c).find("above 1e12"), std::string::npos) << error_of(c);
}

TEST(DegenerateData, MagnitudesThatOverflow) {
  CaseSpec c = builtin_case_spec("hertz-a");  // uy = -mu/2 on top, mu in [0.15, 0.45]
  c.dirichlet[0].uy->b = -1e50 / 0.45;
  EXPECT_EQ(error_of(c), "");
  c.dirichlet[0].uy->b = -1e51;  // 4.5e50 at mu = 0.45
  EXPECT_NE(error_of(c).find("Dirichlet data on 'top' reaches magnitude 4.5e+50 on the parameter domain"),
            std::string::npos)
      << error_of(c);
  c = builtin_case_spec("hertz-a");
  c.dirichlet[0].uy->a = 1e300;  // a + b mu with a huge constant part
  EXPECT_NE(error_of(c).find("reaches magnitude 1e+300"), std::string::npos) << error_of(c);
  c = builtin_case_spec("hertz-a");
  c.bodies[0].load = Eigen::Vector2d(0.0, -2e50);
  EXPECT_NE(error_of(c).find("body 1: body load of magnitude 2e+50 is above 1e50"), std::string::npos) << error_of(c);
  c = builtin_case_spec("hertz-a");
  c.bodies[0].E = 1e51;
  c.bodies[1].E = 1e51;
  EXPECT_NE(error_of(c).find("Young's modulus E = 1e+51 is above 1e50"), std::string::npos) << error_of(c);
}

TEST(DegenerateData, ParameterSetsMustIncrease) {
  CaseSpec c = builtin_case_spec("hertz-a");
  c.sets[0].points[5] = c.sets[0].points[4];
  EXPECT_NE(error_of(c).find("the values of parameter set 'training'"), std::string::npos) << error_of(c);
  EXPECT_NE(error_of(c).find("must be strictly increasing, but value 6 (0.19) is not above value 5 (0.19)"),
            std::string::npos)
      << error_of(c);
  EXPECT_NO_THROW(contactrb::cases::check_increasing({0.1, 0.2, 0.3}, "x"));
  EXPECT_THROW(contactrb::cases::check_increasing({0.3, 0.2}, "x"), contactrb::Error);
  EXPECT_NO_THROW(contactrb::cases::check_increasing({}, "x"));
}
