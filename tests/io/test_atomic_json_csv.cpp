#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "contactrb/common/error.hpp"
#include "contactrb/io/atomic_file.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/json_file.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::Error;
namespace io = contactrb::io;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

long entries(const fs::path& dir) { return std::distance(fs::directory_iterator(dir), fs::directory_iterator{}); }

}  // namespace

TEST(AtomicFile, FailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  contactrb::test::TempDir dir("atomic");
  const fs::path path = dir.path() / "result.txt";
  io::write_file_atomically(path.string(), [](std::ostream& out) { out << "first\n"; });
  EXPECT_EQ(slurp(path), "first\n");
  EXPECT_THROW(io::write_file_atomically(path.string(),
                                         [](std::ostream& out) {
                                           out << "half";
                                           throw std::runtime_error("interrupted");
                                         }),
               std::runtime_error);
  EXPECT_EQ(slurp(path), "first\n");
  EXPECT_EQ(entries(dir.path()), 1);
  io::write_file_atomically(path.string(), [](std::ostream& out) { out << "second\n"; });
  EXPECT_EQ(slurp(path), "second\n");
  EXPECT_EQ(entries(dir.path()), 1);
}

TEST(AtomicFile, MissingDirectoryIsAnErrorNamingThePath) {
  contactrb::test::TempDir dir("atomic_missing");
  const std::string path = (dir.path() / "nope" / "x.txt").string();
  try {
    io::write_file_atomically(path, [](std::ostream& out) { out << "x"; });
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::write_file_atomically("", [](std::ostream&) {}), Error);
}

TEST(JsonFile, RoundTripAndErrors) {
  contactrb::test::TempDir dir("json");
  const fs::path path = dir.path() / "solution.json";
  nlohmann::json j;
  j["case"] = "hertz-b";
  j["mu"] = 0.905;
  j["iterations"] = 12;
  j["bad"] = std::numeric_limits<double>::quiet_NaN();
  j["errors"] = {1e-3, 2.5e-7};
  io::write_json(j, path.string());
  const nlohmann::json r = io::read_json(path.string());
  EXPECT_EQ(r["case"], "hertz-b");
  EXPECT_EQ(r["mu"].get<double>(), 0.905);
  EXPECT_EQ(r["iterations"].get<int>(), 12);
  EXPECT_TRUE(r["bad"].is_null());
  EXPECT_EQ(r["errors"][1].get<double>(), 2.5e-7);

  EXPECT_THROW(io::read_json((dir.path() / "missing.json").string()), Error);
  { std::ofstream(dir.path() / "broken.json") << "{\"a\": "; }
  try {
    io::read_json((dir.path() / "broken.json").string());
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos) << e.what();
  }
}

TEST(CsvWriter, WritesHeaderRowsAndQuotesText) {
  contactrb::test::TempDir dir("csv");
  const fs::path path = dir.path() / "table.csv";
  io::CsvWriter csv({"N", "error", "note"});
  csv.add_row({10LL, 0.1, std::string("plain")}).add_row({20LL, 1.0 / 3.0, std::string("a, \"quoted\"")});
  EXPECT_EQ(csv.num_rows(), 2);
  csv.write(path.string());
  EXPECT_EQ(slurp(path), "N,error,note\n10,0.1,plain\n20,0.3333333333333333,\"a, \"\"quoted\"\"\"\n");
  EXPECT_THROW(csv.add_row({1LL}), Error);
  EXPECT_THROW(io::CsvWriter({}), Error);
}
