// snapshots --part k/K and merge (offline/snapshot_parts.hpp): the merged file holds the same data
// as the serial file, bit for bit but the timings; a missing, a repeated or a foreign part is
// named in the error; a part is refused where a whole set is needed.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "cli/cli_runner.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_parts.hpp"
#include "support/snapshot_fixtures.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::expect_user_error;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
namespace offline = contactrb::offline;

namespace {

const std::string kValues = "--case hertz-a --values 0.2,0.25,0.3,0.35,0.4 -q";

CliResult snapshots(const std::string& extra, const std::string& out) {
  return run_cli("snapshots " + kValues + " " + extra + " --out " + shell_quote(out));
}

CliResult merge(const std::vector<std::string>& files, const std::string& out) {
  std::ostringstream args;  // (not string +=: GCC 12 warns, -Wrestrict, on " " + std::string)
  args << "merge";
  for (const std::string& f : files) args << ' ' << shell_quote(f);
  args << " --out " << shell_quote(out);
  return run_cli(args.str());
}

}  // namespace

TEST(SnapshotParts, PartOptionParsing) {
  const offline::SnapshotPart p = offline::parse_snapshot_part("2/4");
  EXPECT_EQ(p.k, 2);
  EXPECT_EQ(p.count, 4);
  for (const char* bad : {"0/4", "5/4", "2", "/4", "2/", "a/4", "2/4x", " 2/4", "-1/4", "2/-4", "1/0"}) {
    EXPECT_THROW(offline::parse_snapshot_part(bad), contactrb::Error) << bad;
  }
  EXPECT_EQ(offline::part_indices(7, {1, 3}), (std::vector<std::size_t>{0, 3, 6}));
  EXPECT_EQ(offline::part_indices(7, {3, 3}), (std::vector<std::size_t>{2, 5}));
  EXPECT_EQ(offline::part_indices(2, {3, 3}), (std::vector<std::size_t>{}));
}

TEST(SnapshotParts, TagRoundTrip) {
  const offline::PartTag tag{"my set [x]", {3, 7}, 40, 0x0123456789abcdefULL};
  const std::string text = offline::part_tag_text(tag);
  EXPECT_EQ(text, "my set [x] [part 3/7 of 40 values, 0123456789abcdef]");
  const auto back = offline::parse_part_tag(text);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->set, "my set [x]");
  EXPECT_EQ(back->part.k, 3);
  EXPECT_EQ(back->part.count, 7);
  EXPECT_EQ(back->total, 40u);
  EXPECT_EQ(back->values, 0x0123456789abcdefULL);
  for (const char* not_part : {"training", "custom", "training [part 2/4]", "t [part 2/4 of 3 values, 0123456789abcdef]",
                               "t [part 2/4 of 9 values, 0123456789ABCDEF]", "t [part 2/4 of 9 values, 01]"}) {
    EXPECT_FALSE(offline::parse_part_tag(not_part).has_value()) << not_part;
  }
}

// Parts 3/3, 1/3, 2/3 (merged in that order) against the serial file, through files and the
// command line: the same bits but the timings, and the set name of the serial file.
TEST(SnapshotParts, MergeEqualsSerial) {
  contactrb::test::TempDir dir("parts_merge");
  ASSERT_EQ(snapshots("", dir.file("serial.h5")).exit_code, 0);
  for (int k = 1; k <= 3; ++k) {
    const CliResult r = snapshots("--part " + std::to_string(k) + "/3", dir.file("p" + std::to_string(k) + ".h5"));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  const auto part2 = contactrb::io::read_snapshot_file(dir.file("p2.h5"));
  ASSERT_EQ(part2.snapshots.size(), 2u);  // values 0.25 and 0.4
  EXPECT_EQ(part2.snapshots[0].mu(0), 0.25);
  EXPECT_EQ(part2.snapshots[1].mu(0), 0.4);
  const CliResult m = merge({dir.file("p3.h5"), dir.file("p1.h5"), dir.file("p2.h5")}, dir.file("merged.h5"));
  ASSERT_EQ(m.exit_code, 0) << m.out << m.err;
  EXPECT_EQ(contactrb::test::field_value(m.out, "solves"), "5") << m.out;
  const auto serial = contactrb::io::read_snapshot_file(dir.file("serial.h5"));
  const auto merged = contactrb::io::read_snapshot_file(dir.file("merged.h5"));
  EXPECT_EQ(merged.set_name, "custom");
  contactrb::test::expect_same_data(serial, merged, false);

  // A missing part, a part given twice, a part of another run, a file that is no part.
  expect_user_error(merge({dir.file("p1.h5"), dir.file("p3.h5")}, dir.file("m2.h5")), "part 2/3 is missing");
  expect_user_error(merge({dir.file("p3.h5")}, dir.file("m2.h5")), "parts 1/3, 2/3 are missing");
  fs::copy_file(dir.file("p2.h5"), dir.file("p2-copy.h5"));
  expect_user_error(merge({dir.file("p1.h5"), dir.file("p2.h5"), dir.file("p2-copy.h5"), dir.file("p3.h5")}, dir.file("m2.h5")),
                    "part 2/3 is given twice: " + dir.file("p2.h5") + " and " + dir.file("p2-copy.h5"));
  ASSERT_EQ(run_cli("snapshots --case hertz-a --values 0.2,0.25,0.3,0.35,0.45 -q --part 2/3 --out " +
                    shell_quote(dir.file("other.h5")))
                .exit_code,
            0);
  expect_user_error(merge({dir.file("p1.h5"), dir.file("other.h5"), dir.file("p3.h5")}, dir.file("m2.h5")),
                    "are parts of different runs: their parameter values differ");
  expect_user_error(merge({dir.file("p1.h5"), dir.file("serial.h5")}, dir.file("m2.h5")),
                    dir.file("serial.h5") + " is not a part of a snapshot set");
  EXPECT_FALSE(fs::exists(dir.file("m2.h5")));
  // A model is never built from a part.
  expect_user_error(run_cli("offline --snapshots " + shell_quote(dir.file("p1.h5")) + " --out " +
                            shell_quote(dir.file("model.h5"))),
                    "is part 1/3 of a snapshot set, not a whole set");
}

TEST(SnapshotParts, MorePartsThanValuesIsRefused) {
  contactrb::test::TempDir dir("parts_too_many");
  expect_user_error(snapshots("--part 1/6", dir.file("p.h5")), "has 5 values, fewer than 6 parts");
  expect_user_error(snapshots("--part 7/6", dir.file("p.h5")), "--part '7/6': expected k/K");
}
