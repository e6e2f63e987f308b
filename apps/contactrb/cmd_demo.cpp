// `contactrb demo`: the whole method on the paper's test case (b) (hertz-b, parametrized lower
// radius) in one command (docs/cli.md, "`contactrb demo`"): HF snapshots on the training set, the
// offline stage with CPG, the online stage on the verification set against the HF solver, and
// a table like the paper's (N, R, M^k, M^g, errors, HF time, online time, speed-up against the
// Newton HF solver, study::EvaluationOptions::hf_method).
// Writes DIR/model.h5 (io/reduced_model_file.hpp) and DIR/evaluation.csv (study/evaluation.hpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace contactrb::app {

namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  std::string out = "out/demo";
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool quiet = false;
};

// Offline tolerances of the demo (absolute; docs/cli.md, "`contactrb demo`"): the errors come
// down to the level of the Kacanov tolerance of the HF snapshots (eps_KA = 1e-3).
offline::OfflineSettings demo_settings() {
  offline::OfflineSettings s;
  s.set_absolute();
  s.eps_pod = 1e-5;    // N = 11 of 22 (the numerical rank; paper Table 4 at 1e-5: 20)
  s.eps_du = 1e-3;     // R = 10 (paper Table 5: CPG R = 13 at 1e-3)
  s.eps_eim_k = 1e-4;  // the paper's 1e-2 / 1e-3 keep M^g = 1: e_displ 2.8%
  s.eps_eim_g = 1e-5;
  s.dual_method = offline::DualConeMethod::CPG;
  return s;
}

std::string fmt(const char* f, int v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

int run_demo(const DemoOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); };
  require(opt.jobs >= 1, "--jobs must be >= 1 (got " + std::to_string(opt.jobs) + ")");
  ensure_output_directory(opt.out);
  const std::string model_path = (fs::path(opt.out) / "model.h5").string();
  const std::string csv_path = (fs::path(opt.out) / "evaluation.csv").string();
  check_output_file(model_path);
  check_file_roles({}, {{"model.h5 in --out", model_path}, {"evaluation.csv in --out", csv_path}});
  const offline::ProgressMode progress = opt.quiet ? offline::ProgressMode::None : offline::ProgressMode::Automatic;
  const auto step = [&](const std::string& text) {
    if (!opt.quiet) std::cerr << "demo: " << text << std::endl;
  };

  const auto t_start = Clock::now();
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-b");
  const std::vector<cases::Mu>& verification = spec.set("verification");
  step("case hertz-b (" + spec.parameters.front().name + "), " + std::to_string(spec.set("training").size()) +
       " training values, " + std::to_string(verification.size()) + " verification values, " +
       std::to_string(opt.jobs) + " job(s)");

  step("[1/3] HF snapshots on the training set");
  auto t0 = Clock::now();
  offline::SnapshotRunOptions run;
  run.jobs = opt.jobs;
  run.progress = progress;
  const io::SnapshotSet set = offline::generate_snapshots(offline::make_snapshot_request(spec, "training"), run);
  const double snapshots_s = seconds(t0);
  for (const io::Snapshot& s : set.snapshots) {
    require(s.converged, "demo: the HF solve at mu = " + cases::mu_values_text(s.mu) + " failed (" + s.status + ": " +
                             s.message + ")");
  }

  step("[2/3] offline stage: POD, CPG dual cone, EIM of kappa and gamma");
  t0 = Clock::now();
  const offline::OfflineSettings settings = demo_settings();
  const offline::OfflineResult off = offline::build_reduced_model(set, spec, settings);
  const double offline_s = seconds(t0);
  // Held to the end: the files of one demo run are never mixed with those of another.
  const OutputLock lock(opt.out);
  io::write_reduced_model_file(off.model, off.reconstruction, model_path);

  step("[3/3] online stage on the verification set against the HF solver");
  t0 = Clock::now();
  study::EvaluationOptions eo;
  eo.jobs = opt.jobs;
  eo.progress = progress;
  const study::Evaluation ev = study::evaluate_model(off.model, off.reconstruction, spec, verification, eo);
  const double evaluation_s = seconds(t0);
  study::write_evaluation_csv(ev, csv_path);
  const study::EvaluationSummary& su = ev.summary;

  std::cout << "contactrb demo: case hertz-b, " << set.snapshots.size() << " training snapshots ("
            << fmt("%.2f", snapshots_s) << " s), offline " << fmt("%.2f", offline_s) << " s, "
            << verification.size() << " verification values (" << fmt("%.2f", evaluation_s) << " s), total "
            << fmt("%.1f", seconds(t_start)) << " s, " << opt.jobs << " job(s)\n"
            << "tolerances: eps_POD " << settings.eps_pod << ", eps_DU " << settings.eps_du << ", eps_EIM^k "
            << settings.eps_eim_k << ", eps_EIM^g " << settings.eps_eim_g << " (absolute, CPG)\n\n"
            << "|  N |  R | M^k | M^g | max e_displ | max e_inter | max e_ener | max e_press | max e_force | "
               "median HF time (" << ev.hf_solver << ") | median online time | speed-up |\n"
            << "| -: | -: | --: | --: | ----------: | ----------: | ---------: | ----------: | ----------: | "
               "----------------------: | -----------------: | -------: |\n"
            << "| " << fmt("%2d", ev.N) << " | " << fmt("%2d", ev.R) << " | " << fmt("%3d", ev.Mk) << " | "
            << fmt("%3d", ev.Mg) << " | " << fmt("%11.2e", su.max_e_displ) << " | " << fmt("%11.2e", su.max_e_inter)
            << " | " << fmt("%10.2e", su.max_e_ener) << " | " << fmt("%11.2e", su.max_e_press) << " | "
            << fmt("%11.2e", su.max_e_force) << " | " << fmt("%20.2f ms", su.median_hf_time_s * 1e3)
            << " | " << fmt("%15.3f ms", su.median_online_time_s * 1e3) << " | " << fmt("%8.0f", su.median_speedup)
            << " |\n\n";
  if (su.hf_failures + su.rb_failures > 0) {
    std::cout << "failures: " << su.hf_failures << " HF, " << su.rb_failures
              << " online (errors over the values where both converged; see evaluation.csv)\n";
  }
  std::cout << "e_displ: relative H1 error (65); e_inter: interpenetration (66); e_ener: energy error (64);\n"
            << "e_press: relative L2 error of the contact pressure; e_force: relative error of the contact force;\n"
            << "speed-up: median over mu of HF time / online time (HF: the " << ev.hf_solver
            << " solver, setup and solve; online: median of " << eo.online_repeats << " solves)\n"
            << "wrote " << model_path << "\nwrote " << csv_path << "\n";
  return su.hf_failures + su.rb_failures > 0 ? 3 : 0;
}

}  // namespace

Command add_demo_command(CLI::App& app) {
  auto opt = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand(
      "demo", "hertz-b end to end: HF snapshots, offline (CPG), online on the verification set, a paper-style table");
  sub->add_option("--out", opt->out, "Output directory (model.h5, evaluation.csv)")->capture_default_str();
  sub->add_option("--jobs,-j", opt->jobs, "Worker threads for the HF solves (default: the cores)")
      ->capture_default_str();
  sub->add_flag("--quiet,-q", opt->quiet, "No progress report on stderr");
  return {sub, [opt] { return run_demo(*opt); }};
}

}  // namespace contactrb::app
