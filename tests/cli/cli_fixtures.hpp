#pragma once
// What several CLI suites set up alike: a small tmpfs (the full-disk tests) and a small hertz-a
// snapshot file with its model.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace contactrb::test {

// A tmpfs of `kib` KiB mounted on a fresh directory for the lifetime of the object, when this
// process may mount (root); `mounted()` false otherwise (the test then skips, saying why).
class SmallDisk {
 public:
  explicit SmallDisk(const std::filesystem::path& dir, long kib = 64) : dir_(dir) {
    std::filesystem::create_directories(dir_);
    if (::geteuid() != 0) return;
    mounted_ = run_shell("mount -t tmpfs -o size=" + std::to_string(kib) + "k contactrb-full-disk " +
                         shell_quote(dir_.string()))
                   .exit_code == 0;
  }
  ~SmallDisk() {
    if (mounted_) run_shell("umount " + shell_quote(dir_.string()));
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  bool mounted() const { return mounted_; }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

 private:
  std::filesystem::path dir_;
  bool mounted_ = false;
};

// Three hertz-a training values (0.15, 0.3, 0.45) at level 0 into `snapshots`, and the model of
// the default offline settings into `model` (call from SetUpTestSuite).
inline void make_small_hertz_model(const std::string& snapshots, const std::string& model) {
  const CliResult s = run_cli("snapshots --case hertz-a --values 0.15,0.3,0.45 -q --out " + shell_quote(snapshots));
  ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
  const CliResult o = run_cli("offline --snapshots " + shell_quote(snapshots) + " --out " + shell_quote(model));
  ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
}

}  // namespace contactrb::test
