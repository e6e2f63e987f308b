// `contactrb offline`: the offline stage from a snapshot file (docs/user-guide.md, "offline"):
// POD, compression, dual cone, EIM of kappa and gamma, the reduced arrays. Writes the reduced
// model (HDF5, io/reduced_model_file.hpp) and, in the same directory, offline.json (the
// histories of each step and their times). `--case NAME` (snapshots and offline in one run)
// is not implemented: run `contactrb snapshots` first.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/json_file.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/rb/offline_builder.hpp"
#include "contactrb/rb/reduced_model.hpp"

namespace contactrb::app {

namespace {

struct OfflineOptions {
  std::string snapshots;
  double eps_pod = rb::OfflineSettings{}.eps_pod;
  int n = -1;
  std::string inner_product = "energy";
  std::string dual = "cpg";
  double eps_du = rb::OfflineSettings{}.eps_du;
  int r = -1;
  double eps_eim_k = rb::OfflineSettings{}.eps_eim_k;
  double eps_eim_g = rb::OfflineSettings{}.eps_eim_g;
  bool no_compression = false;
  std::string out;
};

std::string report_path(const std::string& model_path) {
  const std::filesystem::path dir = std::filesystem::path(model_path).parent_path();
  return (dir / "offline.json").string();
}

rb::OfflineSettings settings_from(const OfflineOptions& opt) {
  rb::OfflineSettings s;
  s.eps_pod = opt.eps_pod;
  s.pod_modes = opt.n;
  if (opt.inner_product == "energy") {
    s.inner_product = rb::InnerProduct::Energy;
  } else if (opt.inner_product == "h1") {
    s.inner_product = rb::InnerProduct::H1;
  } else {
    throw Error("--inner-product must be 'energy' or 'h1', got '" + opt.inner_product + "'");
  }
  if (opt.dual == "cpg") {
    s.dual_method = rb::DualConeMethod::CPG;
  } else if (opt.dual == "angle") {
    s.dual_method = rb::DualConeMethod::AngleGreedy;
  } else if (opt.dual == "nmf") {
    s.dual_method = rb::DualConeMethod::NMF;
  } else {
    throw Error("--dual must be 'cpg', 'angle' or 'nmf', got '" + opt.dual + "'");
  }
  require(opt.n == -1 || opt.n >= 1, "--n must be >= 1 (got " + std::to_string(opt.n) + ")");
  require(opt.r == -1 || opt.r >= 1, "--r must be >= 1 (got " + std::to_string(opt.r) + ")");
  require(opt.eps_pod >= 0.0, "--eps-pod must be >= 0");
  require(opt.eps_du >= 0.0, "--eps-du must be >= 0");
  require(opt.eps_eim_k >= 0.0, "--eps-eim-k must be >= 0");
  require(opt.eps_eim_g >= 0.0, "--eps-eim-g must be >= 0");
  s.eps_du = opt.eps_du;
  s.dual_size = opt.r;
  s.eps_eim_k = opt.eps_eim_k;
  s.eps_eim_g = opt.eps_eim_g;
  s.compression = !opt.no_compression;
  rb::check_settings(s);
  return s;
}

cases::CaseSpec spec_of(const io::SnapshotSet& set, const std::string& path) {
  if (set.case_kind == "builtin") return cases::builtin_case_spec(set.case_spec);
  require(set.case_kind == "toml", "snapshot file '" + path + "' has an unknown case kind '" + set.case_kind + "'");
  return cases::case_from_toml_string(set.case_spec, path);
}

nlohmann::json to_json(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

int run_offline(const OfflineOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  const rb::OfflineSettings settings = settings_from(opt);
  check_output_file(opt.out);
  const std::string json_path = report_path(opt.out);

  const auto t0 = Clock::now();
  const io::SnapshotSet set = io::read_snapshot_file(opt.snapshots);
  const cases::CaseSpec spec = spec_of(set, opt.snapshots);
  const auto t1 = Clock::now();
  const rb::OfflineResult result = rb::build_reduced_model(set, spec, settings);
  const auto t2 = Clock::now();
  io::write_reduced_model_file(result.model, opt.out);
  const auto t3 = Clock::now();
  const rb::OfflineReport& rep = result.report;
  const rb::ReducedModel& m = result.model;

  nlohmann::json j;
  j["snapshots"] = opt.snapshots;
  j["model"] = opt.out;
  j["case"] = set.case_name;
  j["case_kind"] = set.case_kind;
  j["level"] = set.level;
  j["constraint"] = set.constraint;
  j["parameter"] = {{"name", set.parameter_name}, {"min", set.parameter_min}, {"max", set.parameter_max}};
  nlohmann::json mus = nlohmann::json::array();
  for (const auto& s : set.snapshots) mus.push_back(s.mu);
  j["training"] = {{"set", set.set_name}, {"values", mus}, {"count", set.snapshots.size()}};
  j["snapshot_kacanov"] = {{"alpha", set.kacanov_alpha},
                           {"tolerance", set.kacanov_tolerance},
                           {"max_iterations", set.kacanov_max_iterations}};
  j["settings"] = {{"eps_pod", settings.eps_pod},
                   {"n", settings.pod_modes >= 1 ? nlohmann::json(settings.pod_modes) : nlohmann::json(nullptr)},
                   {"inner_product", rb::to_string(settings.inner_product)},
                   {"dual", opt.dual},
                   {"eps_du", settings.eps_du},
                   {"r", settings.dual_size >= 1 ? nlohmann::json(settings.dual_size) : nlohmann::json(nullptr)},
                   {"eps_eim_k", settings.eps_eim_k},
                   {"eps_eim_g", settings.eps_eim_g},
                   {"compression", settings.compression}};
  j["sizes"] = {{"N", m.N_max}, {"R", m.R_max}, {"Mk", m.Mk_max}, {"Mg", m.Mg_max}};
  j["pod"] = {{"singular_values", to_json(rep.singular_values)}, {"N", rep.N}};
  j["compression"] = {{"enabled", settings.compression},
                      {"constraints", rep.R_hf},
                      {"kept", rep.R_kept},
                      {"dropped", rep.R_hf - rep.R_kept}};
  j["dual"] = {{"method", opt.dual},
               {"R", rep.R},
               {"errors", rep.dual_errors},
               {"relative_errors", rep.dual_relative_errors},
               {"status", rep.dual_status},
               {"condition_number", rep.dual_condition_number}};
  j["eim_kappa"] = {{"M", rep.Mk}, {"errors", rep.eim_kappa_errors}, {"status", rep.eim_kappa_status}};
  j["eim_gamma"] = {{"M", rep.Mg}, {"errors", rep.eim_gamma_errors}, {"status", rep.eim_gamma_status}};
  j["model_doubles"] = rb::model_doubles(m);
  j["times_s"] = {{"read", seconds(t0, t1)},        {"assembly", rep.assembly_s},   {"pod", rep.pod_s},
                  {"dual", rep.dual_s},             {"eim_kappa", rep.eim_kappa_s}, {"eim_gamma", rep.eim_gamma_s},
                  {"reduction", rep.reduction_s},   {"build", rep.total_s},         {"write", seconds(t2, t3)},
                  {"total", seconds(t0, Clock::now())}};
  io::write_json(j, json_path);

  const auto last = [](const std::vector<double>& v) { return v.empty() ? 0.0 : v.back(); };
  std::cout << "case " << set.case_name << ", " << set.snapshots.size() << " snapshots (set " << set.set_name << "), "
            << set.constraint << "\n"
            << "sizes: N " << m.N_max << ", R " << m.R_max << ", Mk " << m.Mk_max << ", Mg " << m.Mg_max << "\n"
            << "pod: " << rb::to_string(settings.inner_product) << " product, N " << rep.N << " of "
            << rep.singular_values.size() << " (eps_pod " << settings.eps_pod << ")\n"
            << "compression: " << rep.R_kept << " of " << rep.R_hf << " constraints kept"
            << (settings.compression ? "" : " (off)") << "\n"
            << "dual: " << opt.dual << ", R " << rep.R << ", error " << last(rep.dual_errors) << " (eps_du "
            << settings.eps_du << ", " << rep.dual_status << ")\n"
            << "eim kappa: Mk " << rep.Mk << ", error " << last(rep.eim_kappa_errors) << " (" << rep.eim_kappa_status
            << ")\n"
            << "eim gamma: Mg " << rep.Mg << ", error " << last(rep.eim_gamma_errors) << " (" << rep.eim_gamma_status
            << ")\n"
            << std::fixed << std::setprecision(3) << "time: " << seconds(t0, Clock::now()) << " s (pod " << rep.pod_s
            << ", dual " << rep.dual_s << ", eim " << rep.eim_kappa_s + rep.eim_gamma_s << ", other "
            << rep.total_s - rep.pod_s - rep.dual_s - rep.eim_kappa_s - rep.eim_gamma_s << ", io "
            << seconds(t0, t1) + seconds(t2, t3) << ")\n"
            << std::defaultfloat << "wrote " << opt.out << "\nwrote " << json_path << "\n";
  return 0;
}

}  // namespace

Command add_offline_command(CLI::App& app) {
  auto opt = std::make_shared<OfflineOptions>();
  CLI::App* sub = app.add_subcommand(
      "offline",
      "Offline stage: a reduced model (HDF5) and offline.json from a snapshot file (`contactrb snapshots` first; "
      "--case is not supported)");
  sub->add_option("--snapshots", opt->snapshots, "Snapshot file written by `contactrb snapshots`")->required();
  CLI::Option* eps_pod =
      sub->add_option("--eps-pod", opt->eps_pod, "POD: absolute threshold on the singular values")->capture_default_str();
  CLI::Option* n = sub->add_option("--n", opt->n, "POD: a fixed N instead of --eps-pod (capped at the rank)");
  eps_pod->excludes(n);
  sub->add_option("--inner-product", opt->inner_product, "POD inner product: energy | h1")->capture_default_str();
  sub->add_option("--dual", opt->dual, "Dual cone: cpg | angle | nmf")->capture_default_str();
  sub->add_option("--eps-du", opt->eps_du, "Dual cone: absolute tolerance eps_DU (L2(Gamma^c) norm)")
      ->capture_default_str();
  sub->add_option("--r", opt->r, "Dual cone: a fixed R (NMF rank, or a greedy size limit)");
  sub->add_option("--eps-eim-k", opt->eps_eim_k, "EIM of the contact map kappa: ell-infinity tolerance")
      ->capture_default_str();
  sub->add_option("--eps-eim-g", opt->eps_eim_g, "EIM of the gap gamma: ell-infinity tolerance")->capture_default_str();
  sub->add_flag("--no-compression", opt->no_compression, "Keep the constraints never active on the training set");
  sub->add_option("--out", opt->out, "Output model file (HDF5); offline.json goes to the same directory")
      ->required();
  return {sub, [opt] { return run_offline(*opt); }};
}

}  // namespace contactrb::app
