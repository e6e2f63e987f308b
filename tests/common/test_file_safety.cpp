// common/printable, common/input_file, common/output_file: escaping of echoed input, the
// input checks (regular file, size limit), same-file detection, outputs that never replace a
// link or device, stale temporary files, and the output lock.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <sstream>
#include <string>
#include <thread>

#include "support/file_bytes.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/common/printable.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::read_bytes;
using contactrb::test::write_bytes;
using contactrb::Error;

namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) { ::setenv(name, value, 1); }
  ~ScopedEnv() { ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

TEST(Printable, EscapesControlCharactersAndInvalidUtf8KeepsTheRest) {
  using contactrb::printable;
  EXPECT_EQ(printable("plain text, 0.3 /tmp/a b"), "plain text, 0.3 /tmp/a b");
  EXPECT_EQ(printable("a\x1b[2Jb"), "a\\x1b[2Jb");
  EXPECT_EQ(printable(std::string("nul\0end", 7)), "nul\\x00end");
  EXPECT_EQ(printable("tab\tdel\x7f"), "tab\\x09del\\x7f");
  EXPECT_EQ(printable("two\nlines"), "two\nlines");
  EXPECT_EQ(contactrb::printable_line("two\nlines\r"), "two\\x0alines\\x0d");
  // Valid UTF-8 is kept (an accented path), invalid bytes and C1 controls are escaped.
  EXPECT_EQ(printable("caf\xc3\xa9"), "caf\xc3\xa9");
  EXPECT_EQ(printable("\xe2\x82\xac 1"), "\xe2\x82\xac 1");
  EXPECT_EQ(printable("\xff" "0.3"), "\\xff0.3");
  EXPECT_EQ(printable("\xc3"), "\\xc3");              // truncated sequence
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");     // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xc2\x9b" "2J"), "\\xc2\\x9b2J");   // C1 CSI
}

TEST(InputFile, RegularFilesBelowTheLimitOnly) {
  const contactrb::test::TempDir dir("input_file");
  using contactrb::InputKind;
  EXPECT_NE(error_of([&] { contactrb::check_input_file(dir.file("none"), "mesh file", InputKind::Text); })
                .find("mesh file '" + dir.file("none") + "' does not exist"),
            std::string::npos);
  EXPECT_NE(error_of([&] { contactrb::check_input_file(dir.path().string(), "batch file", InputKind::Text); })
                .find("is a directory"),
            std::string::npos);
  EXPECT_NE(error_of([&] { contactrb::check_input_file("/dev/zero", "mesh file", InputKind::Text); })
                .find("not a regular file"),
            std::string::npos);
  const fs::path fifo = dir.path() / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of([&] { contactrb::check_input_file(fifo.string(), "batch file", InputKind::Text); })
                .find("not a regular file"),
            std::string::npos);
  // A link to a regular file is an ordinary input.
  write_bytes(dir.path() / "a.txt", "0.3\n");
  fs::create_symlink(dir.path() / "a.txt", dir.path() / "link.txt");
  EXPECT_EQ(contactrb::read_text_input(dir.file("link.txt"), "batch file"), "0.3\n");

  write_bytes(dir.path() / "big.txt", std::string(1024 * 1024 + 1, 'x'));
  {
    const ScopedEnv limit(contactrb::kTextInputLimitVariable, "1");
    EXPECT_EQ(contactrb::input_size_limit(InputKind::Text), 1024u * 1024u);
    const std::string e = error_of([&] { contactrb::read_text_input(dir.file("big.txt"), "mesh file"); });
    EXPECT_NE(e.find("above the input limit of 1.0 MiB"), std::string::npos) << e;
    EXPECT_NE(e.find("CONTACTRB_MAX_TEXT_INPUT_MB"), std::string::npos) << e;
    // The HDF5 limit is its own.
    EXPECT_EQ(contactrb::input_size_limit(InputKind::Hdf5), contactrb::kDefaultHdf5InputLimitMiB * 1024 * 1024);
  }
  {
    const ScopedEnv limit(contactrb::kTextInputLimitVariable, "2");
    EXPECT_EQ(contactrb::read_text_input(dir.file("big.txt"), "mesh file").size(), 1024u * 1024u + 1);
  }
  for (const char* bad : {"0", "-1", "1.5", "x", " 5", "99999999999999"}) {
    const ScopedEnv limit(contactrb::kTextInputLimitVariable, bad);
    EXPECT_NE(error_of([] { contactrb::input_size_limit(InputKind::Text); }).find("positive whole number"),
              std::string::npos)
        << bad;
  }
}

TEST(OutputFile, SameFileThroughSpellingsLinksAndPathsNotYetThere) {
  const contactrb::test::TempDir dir("same_file");
  const fs::path a = dir.path() / "a.h5";
  write_bytes(a, "x");
  fs::create_directory(dir.path() / "sub");
  EXPECT_TRUE(contactrb::same_file(a, dir.path() / "sub" / ".." / "a.h5"));
  fs::create_hard_link(a, dir.path() / "hard.h5");
  EXPECT_TRUE(contactrb::same_file(a, dir.path() / "hard.h5"));
  fs::create_symlink(a, dir.path() / "soft.h5");
  EXPECT_TRUE(contactrb::same_file(a, dir.path() / "soft.h5"));
  EXPECT_FALSE(contactrb::same_file(a, dir.path() / "b.h5"));
  // Neither exists yet: compared as resolved paths.
  EXPECT_TRUE(contactrb::same_file(dir.path() / "new" / "offline.json", dir.path() / "new" / "." / "offline.json"));
  EXPECT_FALSE(contactrb::same_file(dir.path() / "new" / "model.h5", dir.path() / "new" / "offline.json"));
  // A relative path against the absolute one.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  EXPECT_TRUE(contactrb::same_file("x/../not_yet.h5", dir.path() / "not_yet.h5"));
  fs::current_path(cwd);
}

TEST(OutputFile, NeverWritesThroughALinkOrIntoADevice) {
  const contactrb::test::TempDir dir("atomic_special");
  const fs::path target = dir.path() / "precious.txt";
  write_bytes(target, "keep");
  fs::create_symlink(target, dir.path() / "link.txt");
  const auto write = [](const fs::path& p) {
    contactrb::write_file_atomically(p.string(), [](std::ostream& out) { out << "new"; });
  };
  EXPECT_NE(error_of([&] { write(dir.path() / "link.txt"); }).find("symbolic link"), std::string::npos);
  EXPECT_TRUE(fs::is_symlink(dir.path() / "link.txt"));
  EXPECT_EQ(read_bytes(target), "keep");
  const fs::path fifo = dir.path() / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of([&] { write(fifo); }).find("not a regular file"), std::string::npos);
  EXPECT_EQ(fs::symlink_status(fifo).type(), fs::file_type::fifo);
  // A regular file is replaced, and no temporary file stays behind.
  write(target);
  EXPECT_EQ(read_bytes(target), "new");
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) entries += e.path().filename().string().find("tmp") == std::string::npos ? 0 : 1;
  EXPECT_EQ(entries, 0);
}

TEST(OutputFile, StaleTemporariesOfDeadProcessesOnly) {
  const contactrb::test::TempDir dir("stale_tmp");
  const fs::path target = dir.path() / "model.h5";
  const fs::path dead = dir.path() / "model.h5.contactrb-tmp.999999999.3";
  const fs::path live = dir.path() / ("model.h5.contactrb-tmp." + std::to_string(::getppid()) + ".0");
  const fs::path other = dir.path() / "other.h5.contactrb-tmp.999999999.0";
  const fs::path foreign = dir.path() / "model.h5.contactrb-tmp.notapid.0";
  for (const fs::path& p : {dead, live, other, foreign}) write_bytes(p, "partial");
  contactrb::remove_stale_temporaries(target);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));     // a running process may still be writing it
  EXPECT_TRUE(fs::exists(other));    // another target's: cleaned when that target is written
  EXPECT_TRUE(fs::exists(foreign));  // not our name form
  const std::string tmp = contactrb::temporary_path(target).string();
  EXPECT_EQ(tmp.rfind(target.string() + ".contactrb-tmp." + std::to_string(::getpid()) + ".", 0), 0u) << tmp;
}

// A set whose last target became a directory while it was written (another program): no file
// of it is renamed (the first target keeps its earlier content), and every temporary is removed.
TEST(OutputFile, SetWithOneBadTargetRenamesNothing) {
  const contactrb::test::TempDir dir("set_bad_target");
  const fs::path first = dir.path() / "a.txt";
  const fs::path last = dir.path() / "b.txt";
  write_bytes(first, "earlier");
  const auto write = [](const fs::path& p) {
    contactrb::write_file_atomically(p.string(), [](std::ostream& out) { out << "new"; });
  };
  const std::string e = error_of([&] {
    contactrb::OutputSet outputs;
    write(first);
    write(last);
    fs::create_directory(last);
    outputs.commit();
  });
  EXPECT_NE(e.find("b.txt' is a directory"), std::string::npos) << e;
  EXPECT_EQ(read_bytes(first), "earlier");
  EXPECT_TRUE(fs::is_directory(last));
  int files = 0;
  for (const auto& f : fs::directory_iterator(dir.path())) {
    ++files;
    EXPECT_EQ(f.path().filename().string().find("contactrb-tmp"), std::string::npos) << f.path();
  }
  EXPECT_EQ(files, 2);
}

// A staging directory is created next to its target, removed with its content at the end; one of
// a dead process is removed by the next one of the same target.
TEST(OutputFile, StagingDirectoryIsRemovedWithItsContent) {
  const contactrb::test::TempDir dir("staging");
  const fs::path target = dir.path() / "report";
  const fs::path dead = dir.path() / "report.contactrb-tmp.999999999.1";
  fs::create_directories(dead / "sub");
  write_bytes(dead / "sub" / "x.csv", "partial");
  fs::path seen;
  {
    const contactrb::StagingDirectory staging(target);
    seen = staging.path();
    EXPECT_TRUE(fs::is_directory(seen));
    EXPECT_EQ(seen.parent_path(), dir.path());
    EXPECT_FALSE(fs::exists(dead));
    write_bytes(seen / "left.csv", "left over");
  }
  EXPECT_FALSE(fs::exists(seen));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(OutputFile, LockIsExclusiveAndWaitsAtMostItsLimit) {
  const contactrb::test::TempDir dir("lock");
  auto held = std::make_unique<contactrb::OutputLock>(dir.path());
  // flock locks belong to the open file description: a second lock in the same process
  // contends like another process would.
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = error_of([&] { contactrb::OutputLock second(dir.path(), 0.2); });
  EXPECT_NE(e.find("being written by another contactrb run"), std::string::npos) << e;
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.2);
  // Released: taken at once; a holder released while another waits lets it through.
  auto waiter = std::async(std::launch::async, [&] { contactrb::OutputLock third(dir.path(), 10.0); return true; });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  held.reset();
  EXPECT_TRUE(waiter.get());
  EXPECT_NE(error_of([&] { contactrb::OutputLock missing(dir.path() / "none"); }).find("cannot open output directory"),
            std::string::npos);
}

}  // namespace
