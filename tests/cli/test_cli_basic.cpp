// contactrb --version, cases, usage errors.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "contactrb/common/version.hpp"

using contactrb::test::run_cli;

TEST(Cli, Version) {
  const auto r = run_cli("--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(std::string("contactrb ") + contactrb::kVersion), std::string::npos) << r.out;
}

TEST(Cli, NoSubcommandPrintsHelp) {
  const auto r = run_cli("");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("cases"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mesh"), std::string::npos) << r.out;
}

TEST(Cli, CasesListsTheFourCasesOnePerLine) {
  const auto r = run_cli("cases");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  EXPECT_EQ(lines[0].rfind("hertz-a ", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("hertz-b ", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("ring-block ", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("hertz-3p ", 0), 0u) << lines[3];
}

TEST(Cli, UnknownSubcommandIsAUsageError) {
  const auto r = run_cli("frobnicate");
  EXPECT_GT(r.exit_code, 0);
  EXPECT_FALSE(r.err.empty());
}

TEST(Cli, MeshNeedsExactlyOneInput) {
  EXPECT_GT(run_cli("mesh --out /tmp/contactrb_cli_unused").exit_code, 0);
  EXPECT_GT(run_cli("mesh --case hertz-a --msh x.msh --out /tmp/contactrb_cli_unused").exit_code, 0);
  EXPECT_GT(run_cli("mesh --case hertz-a").exit_code, 0);  // --out is required
}

TEST(Cli, MeshLevelMustBeNonNegativeAndOnlyForCases) {
  const auto r = run_cli("mesh --case hertz-a --level -1 --out /tmp/contactrb_cli_unused");
  EXPECT_GT(r.exit_code, 0);
  EXPECT_NE(r.err.find("level"), std::string::npos) << r.err;
  EXPECT_GT(run_cli("mesh --msh x.msh --level 1 --out /tmp/contactrb_cli_unused").exit_code, 0);
}
