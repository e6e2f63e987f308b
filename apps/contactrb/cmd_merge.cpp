// `contactrb merge`: the parts written by `snapshots --part k/K` joined into the one snapshot
// file of the whole set (docs/parallel.md). The parts are checked (each file's checksum by the
// reader; one run; each part once; none missing) before anything is written. Failed solves
// recorded in the parts are reported as `snapshots` reports them (exit 3 unless
// --allow-failures).
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/offline/snapshot_parts.hpp"

namespace contactrb::app {

namespace {

constexpr int kExitSolveFailed = 3;  // as `contactrb snapshots`

struct MergeOptions {
  std::vector<std::string> parts;
  bool allow_failures = false;
  std::string out;
};

int run_merge(const MergeOptions& opt) {
  check_output_file(opt.out);
  std::vector<FileRole> inputs;
  for (const std::string& p : opt.parts) inputs.push_back({"the part", p});
  check_file_roles(inputs, {{"--out", opt.out}});

  std::vector<offline::PartFile> parts;
  for (const std::string& p : opt.parts) parts.push_back({p, io::read_snapshot_file(p)});
  const io::SnapshotSet set = offline::merge_snapshot_parts(parts);
  {
    const OutputLock lock(std::filesystem::path(opt.out).parent_path());
    io::write_snapshot_file(set, opt.out);
  }
  const offline::SnapshotSummary s = offline::summarize(set);
  std::cout << "case " << set.case_name << ", set " << set.set_name << ": " << parts.size() << " parts, "
            << set.snapshots.size() << " values\n"
            << "solves: " << s.solves << "\n"
            << "failures: " << s.failures << "\n"
            << "wrote " << opt.out << "\n";
  if (s.failures > 0) {
    std::ostringstream os;
    os << s.failures << " of " << s.solves << " solves failed (recorded in " << opt.out << "):";
    for (const io::Snapshot& snap : set.snapshots) {
      if (!snap.converged) os << "\n  mu = " << cases::mu_values_text(snap.mu) << ": " << snap.status << ": " << snap.message;
    }
    std::cerr << "contactrb: " << (opt.allow_failures ? "warning: " : "error: ") << os.str() << "\n";
    return opt.allow_failures ? 0 : kExitSolveFailed;
  }
  return 0;
}

}  // namespace

Command add_merge_command(CLI::App& app) {
  auto opt = std::make_shared<MergeOptions>();
  CLI::App* sub = app.add_subcommand("merge", "Join the parts of `snapshots --part k/K` into one snapshot file");
  sub->add_option("parts", opt->parts, "The part files (any order)")->required();
  sub->add_flag("--allow-failures", opt->allow_failures, "Exit 0 even when some solves failed (they are recorded)");
  sub->add_option("--out", opt->out, "Output HDF5 file (written atomically)")->required();
  return {sub, [opt] { return run_merge(*opt); }};
}

}  // namespace contactrb::app
