// `contactrb online`: reduced solves (paper Algorithm 1) from a model file written by
// `contactrb offline` (docs/cli.md, "`contactrb online`"). One --mu: one JSON object on stdout.
// --batch FILE (or - for stdin): one mu per line, one JSON line per input line, in order; a bad
// line (not a number, outside the domain) is answered by {"line": k, "error": "..."} and the
// others are still answered; --format csv|npy gives one compact row per line instead
// (io/batch_table.hpp). The model is loaded and the solver set up once. This file is part of
// both executables; --out's code (online_fields.cpp) only of contactrb-full (front_main.cpp).
// --out DIR: also the reconstructed solution on the HF mesh Omega(mu), from the model file's
// reconstruction data (study/solution_fields.hpp): with --mu DIR/solution.vtu,
// DIR/solution_deformed.vtu, DIR/contact.vtu, DIR/multipliers.csv; with --batch the same in
// DIR/NNNNNN/ for answered line NNNNNN, and DIR/solutions.pvd, DIR/solutions_deformed.pvd,
// DIR/contact.pvd, ParaView time series over the lines. Paths are listed in the JSON ("files").
// Exit codes: 0 all answered and converged; 1 a user error (or, in batch mode, some bad line);
// 3 some solve did not converge (and, in batch mode, no bad line).
#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "batch_lines.hpp"
#include "commands.hpp"
#include "mpi_world.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/printable.hpp"
#include "contactrb/io/pvd_writer.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solution_json.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/io/batch_table.hpp"

namespace contactrb::app {

namespace {

constexpr int kExitNotConverged = 3;

struct OnlineOptions {
  std::string model;
  std::optional<std::string> mu;  // as given: parse_mu_option (CLI11 reads '' as 0)
  std::string batch;
  SizeFlags sizes;  // --n, --r, --mk, --mg
  std::optional<double> alpha;
  std::optional<double> tolerance;
  std::string start = "interpolated";  // --start: the initial guess of the reduced iteration
  std::string iteration = "automatic";  // --iteration: the reduced iteration
  std::string out;  // --out DIR: reconstructed fields
  std::string format = "json";  // --format: of the --batch answers (json | csv | npy)
  int jobs = 1;                 // --batch: threads (batch_lines.hpp)
};

// --out's code (online_fields.cpp); null in the light front, which hands --out to contactrb-full.
const OnlineFieldHooks* field_hooks_ = nullptr;

const OnlineFieldHooks& require_field_hooks() {
  if (field_hooks_ == nullptr) throw std::logic_error("online --out reached the light executable (front_main.cpp)");
  return *field_hooks_;
}

// The ParaView collections of `online --batch --out DIR`, next to the line directories.
constexpr std::array<const char*, 3> kBatchCollections = {"solutions.pvd", "solutions_deformed.pvd", "contact.pvd"};

// Line k's directory name: six digits, zero-padded (wider from line 10^6 on), so that the
// names sort as the lines.
std::string line_directory(int k) {
  std::string digits = std::to_string(k);
  return std::string(digits.size() < 6 ? 6 - digits.size() : 0, '0') + digits;
}

// Batch lines are bytes: no line can hold a parameter value beyond this length, and a longer
// one (/dev/zero through a pipe has no newline at all) must not be buffered without bound.
constexpr std::size_t kMaxBatchLineBytes = 4096;

// Reads the next line (without its '\n') into `line`, at most kMaxBatchLineBytes of it; the
// rest of a longer line is consumed and `too_long` set. False at the end of the input.
bool read_batch_line(std::streambuf& in, std::string& line, bool& too_long) {
  line.clear();
  too_long = false;
  int c = in.sbumpc();
  if (c == std::char_traits<char>::eof()) return false;
  for (; c != std::char_traits<char>::eof() && c != '\n'; c = in.sbumpc()) {
    if (line.size() < kMaxBatchLineBytes) {
      line += static_cast<char>(c);
    } else {
      too_long = true;
    }
  }
  return true;
}

// DIR/solutions.pvd, DIR/solutions_deformed.pvd, DIR/contact.pvd over the lines with files.
// Time step: mu for one parameter when the values are distinct (ParaView orders the steps by
// it), otherwise the line number (the point is in each file's field data).
void write_batch_collections(const std::string& out, std::size_t num_parameters,
                             const std::vector<std::pair<int, cases::Mu>>& written) {
  bool by_mu = num_parameters == 1;
  std::vector<double> values;
  for (const auto& [k, mu] : written) values.push_back(mu(0));
  std::sort(values.begin(), values.end());
  if (std::adjacent_find(values.begin(), values.end()) != values.end()) by_mu = false;
  const std::array<const char*, 3> files = {"solution.vtu", "solution_deformed.vtu", "contact.vtu"};
  for (std::size_t c = 0; c < kBatchCollections.size(); ++c) {
    std::vector<io::PvdDataSet> datasets;
    for (const auto& [k, mu] : written) {
      datasets.push_back({by_mu ? mu(0) : static_cast<double>(k), line_directory(k) + "/" + files[c]});
    }
    io::write_pvd((std::filesystem::path(out) / kBatchCollections[c]).string(), datasets);
  }
}

// The numbers of one answer, for --format csv|npy (the JSON line's, nothing else).
io::BatchRow batch_row(int k, const cases::Mu& mu, const online::OnlineSolution& s) {
  io::BatchRow row;
  row.line = k;
  row.answered = true;
  row.mu = mu;
  row.status = static_cast<int>(s.status);
  row.status_name = solve::to_string(s.status);
  row.iterations = s.iterations;
  row.energy = s.energy;
  row.contact_force = s.contact_force;
  row.has_estimate = s.estimate.available;
  row.estimate = s.estimate.energy;
  return row;
}

int run_batch(const OnlineOptions& opt, const contactrb::model::ReducedModel& model, const online::OnlineSizes& sizes,
              const online::OnlineSettings& settings, const OnlineFields* fields, MpiWorld* world = nullptr) {
  const std::vector<cases::ParameterSpec>& parameters = model.parameters;
  const bool root = world == nullptr || world->rank() == 0;
  std::ifstream file;
  std::istream* in = &std::cin;
  if (opt.batch != "-" && root) {
    // A regular file below the size limit: a directory would answer nothing and exit 0, a
    // device such as /dev/urandom would be answered forever.
    check_input_file(opt.batch, "batch file", InputKind::Text);
    file.open(opt.batch, std::ios::binary);
    require(file.good(), "cannot open batch file '" + printable(opt.batch) + "'");
    in = &file;
  }
  // Under mpirun: every rank has read the model, rank 0 opened the batch (batch_lines.hpp).
  if (world != nullptr && !world->agree(true)) {
    if (root) throw Error("an MPI rank could not start the run (its error is above)");
    return 1;
  }
  const bool json = opt.format == "json";
  const bool npy = opt.format == "npy";
  if (opt.format == "csv" && root) {
    std::vector<std::string> names;
    for (const cases::ParameterSpec& q : parameters) names.push_back(q.name);
    io::CsvBatchWriter header(std::cout, names);  // the header line; the rows are the answers' text
  }
  // npy: each answer is its row's bytes, collected in order (the row count is in the file's
  // header) and written at the end.
  std::ostringstream npy_rows;
  std::mutex written_mutex;
  std::vector<std::pair<int, cases::Mu>> written;  // --out: the lines with files, and their mu
  // On opt.jobs threads, in input order (batch_lines.hpp).
  const auto answer = [&](online::OnlineSolver& solver, int k, const std::string& line, bool too_long) {
    nlohmann::json j;
    io::BatchRow row;
    row.line = k;
    LineAnswer a;
    try {
      require(!too_long, "line longer than " + std::to_string(kMaxBatchLineBytes) + " bytes (expected " +
                             (parameters.size() == 1 ? std::string("one number") : "one parameter point") + ")");
      const cases::Mu mu = parse_mu_line(line, parameters);
      const online::OnlineSolution s = solver.solve(mu, settings);
      if (json) {
        j = {{"line", k}};
        j.update(online::answer_json(parameters, mu, solver, s));
      } else {
        row = batch_row(k, mu, s);
      }
      if (fields != nullptr) {
        const std::string dir = (std::filesystem::path(opt.out) / line_directory(k)).string();
        check_file_roles({{"--model", opt.model}, {"--batch", opt.batch == "-" ? "" : opt.batch}},
                         field_hooks_->roles(dir, "--out"));
        ensure_output_directory(dir);
        nlohmann::json files = fields->write(model, mu, s, dir);
        if (json) j["files"] = std::move(files);
        const std::lock_guard<std::mutex> lock(written_mutex);
        written.emplace_back(k, mu);
      }
      a.not_converged = !s.converged();
    } catch (const Error& e) {
      // The message may quote the line's bytes: escaped, so that the JSON line is valid UTF-8.
      if (json) {
        j = {{"line", k}, {"error", printable_line(e.what())}};
      } else {
        row = io::BatchRow{};
        row.line = k;
        a.message = "contactrb: error: batch line " + std::to_string(k) + ": " + printable_line(e.what()) + "\n";
      }
      a.bad = true;
    }
    if (json) {
      // replace: a non-UTF-8 byte that got through anyway becomes U+FFFD, never an exception.
      a.text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      a.text += '\n';
    } else if (npy) {
      io::append_npy_batch_row(a.text, row, parameters.size());
    } else {
      io::append_csv_batch_row(a.text, row, parameters.size());
    }
    return a;
  };
  const BatchCounts counts = answer_batch_lines(
      model, sizes, opt.jobs,
      [&](std::string& line, bool& too_long) { return read_batch_line(*in->rdbuf(), line, too_long); }, answer,
      npy ? npy_rows : std::cout, world);
  if (!root) return 0;  // rank 0 prints and reports
  if (npy) io::write_npy_batch(std::cout, io::npy_batch_columns(parameters.size()), npy_rows.str());
  std::cout.flush();
  const int k = counts.lines, bad = counts.bad, not_converged = counts.not_converged;
  std::sort(written.begin(), written.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (fields != nullptr) write_batch_collections(opt.out, parameters.size(), written);
  if (bad > 0) {
    std::cerr << "contactrb: error: " << bad << " of " << k << " batch lines could not be answered\n";
    return 1;
  }
  if (not_converged > 0) {
    std::cerr << "contactrb: error: " << not_converged << " of " << k << " online solves did not converge\n";
    return kExitNotConverged;
  }
  return 0;
}

int run_online(const OnlineOptions& opt) {
  const bool single = opt.mu.has_value();  // --mu, else --batch
  const std::unique_ptr<MpiWorld> world = MpiWorld::start_if_launched();
  require(!world || (!single && opt.out.empty()), "under mpirun, online answers --batch without --out only");
  require(!world || opt.format != "npy", "under mpirun, online --batch writes JSON or CSV lines (--format npy: run "
                                         "without mpirun, with --jobs)");
  require(!single || opt.format == "json",
          "--format " + opt.format + " is for --batch (--mu prints one JSON object)");
  // A plain number is checked before the model is read (its errors come first, as for p = 1).
  if (single && opt.mu->find_first_of("=,") == std::string::npos) (void)parse_mu_option(*opt.mu, "--mu");
  const online::OnlineSizes sizes = checked_size_flags(opt.sizes);
  const contactrb::model::ReducedModel model = io::read_reduced_model_file(opt.model);
  check_sizes_against(sizes, model, opt.model);
  online::OnlineSettings settings;
  settings.initial_guess = option_enum("--start", opt.start, online::initial_guess_from_string);
  settings.iteration = checked_iteration_flag(opt.iteration, model);
  if (opt.alpha || opt.tolerance) {
    solve::KacanovSettings k{model.kacanov_alpha, model.kacanov_tolerance, model.kacanov_max_iterations};
    if (opt.alpha) k.alpha = *opt.alpha;
    if (opt.tolerance) k.tolerance = *opt.tolerance;
    solve::check_settings(k);
    settings.kacanov = k;
  }
  if (!single) {
    require(!opt.batch.empty(), "--batch needs a file name, or - for stdin");
    if (opt.out.empty()) return run_batch(opt, model, sizes, settings, nullptr, world.get());
    const OnlineFieldHooks& hooks = require_field_hooks();
    std::vector<FileRole> outputs;
    for (const char* c : kBatchCollections) {
      outputs.push_back({std::string(c) + " in --out", (std::filesystem::path(opt.out) / c).string()});
    }
    check_file_roles({{"--model", opt.model}, {"--batch", opt.batch == "-" ? "" : opt.batch}}, outputs);
    ensure_output_directory(opt.out);
    const std::unique_ptr<OnlineFields> fields = hooks.read(model, opt.model);
    // One run's files, never mixed with another's: the lock is held until the collections are written.
    const OutputLock lock(opt.out);
    return run_batch(opt, model, sizes, settings, fields.get());
  }
  const cases::Mu mu = parse_mu_option(*opt.mu, "--mu", model.parameters);
  online::OnlineSolver solver(model, sizes);

  // --out: everything that can fail (reconstruction data, the case, its mesh) before the solve.
  std::unique_ptr<OnlineFields> fields;
  if (!opt.out.empty()) {
    const OnlineFieldHooks& hooks = require_field_hooks();
    check_file_roles({{"--model", opt.model}}, hooks.roles(opt.out, "--out"));
    ensure_output_directory(opt.out);
    fields = hooks.read(model, opt.model);
  }

  const online::OnlineSolution s = solver.solve(mu, settings);
  nlohmann::json j = online::answer_json(model.parameters, mu, solver, s);
  if (fields) {
    const OutputLock lock(opt.out);  // the four files of one run, never mixed with another's
    j["files"] = fields->write(model, mu, s, opt.out);
  }
  std::cout << j.dump() << "\n";
  if (!s.converged()) {
    std::cerr << "contactrb: error: " << s.message << "\n";
    return kExitNotConverged;
  }
  return 0;
}

}  // namespace

Command add_online_command(CLI::App& app, const OnlineFieldHooks* fields) {
  field_hooks_ = fields;
  auto opt = std::make_shared<OnlineOptions>();
  CLI::App* sub = app.add_subcommand("online", "Reduced solves from a model file (one --mu, or --batch for many)");
  sub->add_option("--model", opt->model, "Reduced model file written by `contactrb offline`")->required();
  CLI::Option_group* what = sub->add_option_group("query", "Parameter values (exactly one)");
  what->add_option("--mu", opt->mu,
                   "One parameter point inside the model's domain: a number (one parameter), p numbers "
                   "separated by commas, or name=value pairs separated by commas");
  what->add_option("--batch", opt->batch,
                   "File with one parameter point per line (p numbers separated by blanks or commas, name=value "
                   "pairs, or a JSON object), or - for stdin");
  what->require_option(1);
  sub->add_option("--n", opt->sizes.n, "Primal size N (default: the model's N_max)");
  sub->add_option("--r", opt->sizes.r, "Dual size R (default: R_max)");
  sub->add_option("--mk", opt->sizes.mk, "EIM size of kappa (default: Mk_max)");
  sub->add_option("--mg", opt->sizes.mg, "EIM size of gamma (default: Mg_max)");
  sub->add_option("--alpha", opt->alpha, "Kacanov relaxation in (0, 1] (default: the snapshots')");
  sub->add_option("--tol", opt->tolerance, "Kacanov tolerance eps_KA, > 0 (default: the snapshots')");
  sub->add_option("--iteration", opt->iteration,
                  "Reduced iteration: automatic | relaxed (the paper's) | accelerated | newton (row-cone models: "
                  "the exact contact rows)")
      ->capture_default_str();
  sub->add_option("--start", opt->start,
                  "Initial guess: interpolated (the reduced solutions at the training values, linear in mu) | "
                  "zero (the paper's)")
      ->capture_default_str();
  sub->add_option("--out", opt->out,
                  "Directory for the reconstructed solution on the HF mesh (solution.vtu, solution_deformed.vtu, "
                  "contact.vtu, multipliers.csv); with --batch one subdirectory NNNNNN per line and the ParaView "
                  "collections solutions.pvd, solutions_deformed.pvd, contact.pvd");
  sub->add_option("--jobs,-j", opt->jobs,
                  "With --batch: threads, one solver each (answers in input order; 0: every hardware thread)")
      ->capture_default_str();
  sub->add_option("--format", opt->format,
                  "Output of --batch: json (one JSON line per input line) | csv (a header, then one row per line: "
                  "line, mu, status, iterations, energy, contact_force, estimate) | npy (the same numbers as a "
                  "NumPy float64 array on stdout, status as its code, -1 for a bad line)")
      ->check(CLI::IsMember({"json", "csv", "npy"}))
      ->capture_default_str();
  return {sub, [opt] { return run_online(*opt); }};
}

}  // namespace contactrb::app
