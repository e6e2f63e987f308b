// contactrb --version, cases, usage errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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

TEST(Cli, CasesListsTheEightCasesOnePerLine) {
  const auto r = run_cli("cases");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 8u) << r.out;
  EXPECT_EQ(lines[0].rfind("hertz-a ", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("hertz-b ", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("ring-block ", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("hertz-3p ", 0), 0u) << lines[3];
  EXPECT_EQ(lines[4].rfind("hertz-3d ", 0), 0u) << lines[4];
  EXPECT_EQ(lines[5].rfind("patch-3d ", 0), 0u) << lines[5];
  EXPECT_EQ(lines[6].rfind("cattaneo ", 0), 0u) << lines[6];
  EXPECT_EQ(lines[7].rfind("cattaneo-3d ", 0), 0u) << lines[7];
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

TEST(Cli, AMistypedCommandIsNamedWithTheNearestCommand) {
  const auto r = run_cli("offlin --case hertz-b");
  EXPECT_GT(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown command 'offlin' (did you mean 'offline'?)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the commands are"), std::string::npos) << r.err;
  const auto far = run_cli("frobnicate");
  EXPECT_NE(far.err.find("unknown command 'frobnicate'"), std::string::npos) << far.err;
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

TEST(Cli, AMistypedOptionIsNamedWithTheNearestOption) {
  // The light front (online) and the full program (offline) give the same message.
  const auto online = run_cli("online --modle m.h5 --mu 0.3");
  EXPECT_GT(online.exit_code, 1);
  EXPECT_NE(online.err.find("unknown option '--modle' of `contactrb online` (did you mean '--model'?)"),
            std::string::npos)
      << online.err;
  EXPECT_EQ(online.err.find("is required"), std::string::npos) << online.err;
  const auto offline = run_cli("offline --case hertz-b --eps-pdo=1e-3 --out m.h5");
  EXPECT_NE(offline.err.find("unknown option '--eps-pdo' of `contactrb offline` (did you mean '--eps-pod'?)"),
            std::string::npos)
      << offline.err;
}

TEST(Cli, AMissingFullProgramIsADeploymentErrorWithExitCodeOne) {
  // contactrb alone, without contactrb-full beside it or in ../libexec/contactrb.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("contactrb_lonely_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path lonely = dir / "contactrb";
  std::filesystem::copy_file(CONTACTRB_CLI, lonely, std::filesystem::copy_options::overwrite_existing);
  const auto r = contactrb::test::run_shell(contactrb::test::shell_quote(lonely.string()) + " cases");
  std::filesystem::remove_all(dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("contactrb: error: cannot run"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reinstall contactrb"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}
