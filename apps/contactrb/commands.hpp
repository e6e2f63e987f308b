#pragma once
// One subcommand per file (cmd_<name>.cpp). Each add_*_command registers its subcommand
// and options on the top-level app and returns the Command that main() runs when that
// subcommand was given. Commands print their results on stdout and throw
// contactrb::Error for anything the user can fix; main() turns that into one line
// "contactrb: error: ..." on stderr and exit code 1.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::model {
struct ReducedModel;
}  // namespace contactrb::model

namespace contactrb::cases {
struct CaseSpec;
}  // namespace contactrb::cases

namespace contactrb::io {
struct SnapshotSet;
}  // namespace contactrb::io

namespace contactrb::online {
struct OnlineSizes;
struct OnlineSolution;
enum class OnlineIteration;
}  // namespace contactrb::online

namespace contactrb::app {

struct Command {
  CLI::App* subcommand = nullptr;
  std::function<int()> run;  // returns the process exit code
};

Command add_cases_command(CLI::App& app);
Command add_mesh_command(CLI::App& app);
Command add_solve_command(CLI::App& app);
Command add_snapshots_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_offline_command(CLI::App& app);
// A file a command reads or writes, with the words that name it in a message
// ("--snapshots", "offline.json next to --out").
struct FileRole {
  std::string role;
  std::string path;
};

// What `online --out` needs: the reconstruction data and the case's HF mesh Omega(mu)
// (online_fields.cpp; the mesh generation and FE code, so only contactrb-full has it).
class OnlineFields {
 public:
  virtual ~OnlineFields() = default;
  // The files of one solution into `dir` (which exists); their paths as the JSON's "files".
  virtual nlohmann::json write(const contactrb::model::ReducedModel& model, const cases::Mu& mu,
                               const online::OnlineSolution& s, const std::string& dir) const = 0;
};
struct OnlineFieldHooks {
  // The outputs of one directory of --out, for check_file_roles.
  std::vector<FileRole> (*roles)(const std::string& dir, const std::string& where) = nullptr;
  // Everything --out needs, read before any solve (everything that can fail first).
  std::unique_ptr<OnlineFields> (*read)(const contactrb::model::ReducedModel& model,
                                        const std::string& model_path) = nullptr;
};
// online_fields.cpp (contactrb-full).
const OnlineFieldHooks* online_field_hooks();

// `fields` null: --out is refused as an internal error (the front hands it to contactrb-full).
Command add_online_command(CLI::App& app, const OnlineFieldHooks* fields);
Command add_sample_command(CLI::App& app);
Command add_evaluate_command(CLI::App& app);
Command add_report_command(CLI::App& app);
Command add_demo_command(CLI::App& app);

// `contactrb solve` on a frictional case (cmd_solve_friction.cpp): the options as given.
struct FrictionalSolveRequest {
  std::string case_name;   // a frictional built-in case, or empty with case_file
  std::string case_file;   // a case file with friction keys
  std::string mu_text;     // --mu: the built-in's friction coefficient f, a case file's parameter point
  std::string constraint;  // --constraint (empty or collocation)
  std::optional<std::string> solver;  // --solver (absent or newton)
  int level = 0;
  int sequence = -1;               // --sequence (-1 or 0: none; grid sequencing has no friction)
  int newton_max_iterations = 50;  // --newton-max-iterations: per load step
  std::string out_dir;
};
// Exit code 0, or 3 when the load path fails (solution.json says how).
int run_frictional_solve(const FrictionalSolveRequest& request);

// The case of --case (a built-in name) or --case-file (a TOML file) for `command`, which solves
// 2D cases only: throws contactrb::Error in one line naming the command, the case and its
// dimension for a 3D case (case_input.cpp; contactrb-full only).
cases::CaseSpec read_case_2d(const std::string& case_name, const std::string& case_file, const std::string& command);
// The same for a command that solves both dimensions.
cases::CaseSpec read_case(const std::string& case_name, const std::string& case_file);
// A snapshot file read by `command`, which builds 2D models only: throws contactrb::Error in
// one line naming the command, the file and its dimension for 3D snapshots.
void require_2d_snapshots(const io::SnapshotSet& set, const std::string& path, const std::string& command);

// Creates `dir` (and its parents) if missing; throws contactrb::Error naming it when that
// fails or when it exists and is not a directory.
void ensure_output_directory(const std::string& dir);

// `path` names an output FILE whose directory exists and is writable (checked before long
// work starts); throws contactrb::Error naming --out otherwise.
void check_output_file(const std::string& path);

// Output safety before any work starts (docs/file-formats.md, "Output files"): throws
// contactrb::Error naming both roles when an output is the same file as an input (it would be
// destroyed) or as another output of the command (one would overwrite the other), and when an
// output path is a symbolic link, device, FIFO or directory. Paths that do not exist yet are
// compared after resolving "..", "." and the links of their existing part.
void check_file_roles(const std::vector<FileRole>& inputs, const std::vector<FileRole>& outputs);

// One parameter point per line (online --batch, evaluate --set FILE): p numbers separated by
// blanks or commas, or name=value pairs separated by commas, or a JSON object
// {"name": value, ...}; with optional surrounding blanks. Throws contactrb::Error saying what
// is wrong (a wrong count, an unknown or missing name, not a number). The one-value form is
// parse_mu_line(line) (p = 1).
cases::Mu parse_mu_line(const std::string& line, const std::vector<cases::ParameterSpec>& parameters);
double parse_mu_line(const std::string& line);

// The text of a parameter option (--mu): for p = 1 a finite number; for any p, p numbers
// separated by commas ("0.3,1.05,20") or name=value pairs ("displacement=0.3,radius=1.05").
// Each number is finite, not empty (CLI11 turns an empty value into 0) and not an underflow
// ('1e-400' is 0 to strtod). Throws contactrb::Error naming `flag`.
cases::Mu parse_mu_option(const std::string& text, const std::string& flag,
                          const std::vector<cases::ParameterSpec>& parameters);
double parse_mu_option(const std::string& text, const std::string& flag);

// The value of an option naming an enum, read by the library's *_from_string (e.g.
// offline::inner_product_from_string); its error is prefixed by the option ("--dual: unknown ...").
template <class FromString>
auto option_enum(const char* option, const std::string& value, FromString from_string) {
  try {
    return from_string(value);
  } catch (const Error& e) {
    throw Error(std::string(option) + ": " + e.what());
  }
}

// The comma-separated items of a list of parameter values (--values): each as
// parse_mu_option, strictly increasing (a repeated value is refused). Throws contactrb::Error
// naming `flag` and the position.
std::vector<double> parse_values_option(const std::vector<std::string>& items, const std::string& flag);
// The same as points of a one-parameter case (nullopt when `items` is empty); throws
// contactrb::Error naming `flag` for a case of p > 1 parameters (their points come from a named
// set: --set).
std::optional<std::vector<cases::Mu>> parse_values_points(const std::vector<std::string>& items, const std::string& flag,
                                                           const std::vector<cases::ParameterSpec>& parameters);

// --n, --r, --mk, --mg as given (absent: the model's maximum).
struct SizeFlags {
  std::optional<int> n, r, mk, mg;
};

// online_sizes.cpp: the given sizes checked (N >= 1, R, Mk, Mg >= 0; a negative value is
// refused whatever it is), then as OnlineSizes (-1: the model's maximum), and against the
// maxima stored in the model read from `path`. Throw contactrb::Error naming the flag.
online::OnlineSizes checked_size_flags(const SizeFlags& flags);
void check_sizes_against(const online::OnlineSizes& sizes, const contactrb::model::ReducedModel& model,
                         const std::string& path);
// --iteration of `online` and `evaluate`, read by online_iteration_from_string; newton only for a
// row-cone model (it needs the exact contact rows). Throws contactrb::Error naming the flag.
online::OnlineIteration checked_iteration_flag(const std::string& value, const contactrb::model::ReducedModel& model);

}  // namespace contactrb::app
