// Greedy sampling against POD over the whole training set (docs/offline-online.md, "Greedy
// sampling"). For each case and tolerance: the HF solves the greedy spends, the sizes, the
// per-step times, and max e_displ / e_press on the case's verification set; then the same for
// the POD over every training snapshot (the default `contactrb offline`). Prints markdown.
//
//   bench_greedy [case ...] [--tol 1e-2,1e-3] [--jobs 2] [--dense P] [--steps] [--hf-tol eps_KA]
//                [--eps-du e] [--eps-eim e] [--eps-pod e] [--dual rows|cpg|angle|nmf] [--no-compression]
//                [--no-supremizers]
// --dense P: P equispaced training points over the domain instead of the case's training set.
// The offline settings apply to the greedy's builds and to the POD (--no-compression to both).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

using namespace contactrb;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> split(const std::string& s) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  return v;
}

void row(const std::string& name, const std::string& method, int hf, const contactrb::offline::OfflineResult& r,
         const study::Evaluation& ev, double offline_s, const std::string& extra) {
  std::cout << "| " << name << " | " << method << " | " << hf << " | " << r.model.N_max << " | " << r.model.R_max << " | "
            << r.model.Mk_max << ", " << r.model.Mg_max << " | " << std::setprecision(2) << std::scientific
            << ev.summary.max_e_displ << " | " << ev.summary.max_e_press << " | " << std::defaultfloat
            << std::setprecision(3) << ev.summary.rb_failures << " | " << std::fixed << std::setprecision(1) << offline_s
            << std::defaultfloat << std::setprecision(6) << " | " << extra << " |\n"
            << std::flush;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  std::vector<double> tolerances{1e-2, 1e-3};
  int jobs = 2, dense = 0;
  bool steps = false;
  double eps_eim = contactrb::offline::OfflineSettings{}.eps_eim_k;
  double eps_pod = contactrb::offline::OfflineSettings{}.eps_pod;
  bool no_sup = false, no_compression = false;
  contactrb::offline::DualConeMethod dual = contactrb::offline::OfflineSettings{}.dual_method;
  double eps_du = contactrb::offline::OfflineSettings{}.eps_du, hf_tol = solve::KacanovSettings{}.tolerance;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--tol" && i + 1 < argc) {
      tolerances = split(argv[++i]);
    } else if (a == "--jobs" && i + 1 < argc) {
      jobs = std::atoi(argv[++i]);
    } else if (a == "--dense" && i + 1 < argc) {
      dense = std::atoi(argv[++i]);
    } else if (a == "--eps-du" && i + 1 < argc) {
      eps_du = std::atof(argv[++i]);
    } else if (a == "--hf-tol" && i + 1 < argc) {
      hf_tol = std::atof(argv[++i]);
    } else if (a == "--eps-eim" && i + 1 < argc) {
      eps_eim = std::atof(argv[++i]);
    } else if (a == "--eps-pod" && i + 1 < argc) {
      eps_pod = std::atof(argv[++i]);
    } else if (a == "--dual" && i + 1 < argc) {
      dual = contactrb::offline::dual_cone_method_from_string(argv[++i]);
    } else if (a == "--no-compression") {
      no_compression = true;
    } else if (a == "--no-supremizers") {
      no_sup = true;
    } else if (a == "--steps") {
      steps = true;
    } else {
      names.push_back(a);
    }
  }
  if (names.empty()) names = {"hertz-a", "hertz-b", "ring-block"};
  std::cout << "| case | method | HF solves | N | R | Mk, Mg | max e_displ | max e_press | rb failures | offline s | "
               "greedy status, last max estimate |\n| --- | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | --- |\n";
  for (const std::string& name : names) {
    const cases::CaseSpec spec = cases::builtin_case_spec(name);
    std::optional<std::vector<cases::Mu>> values;
    if (dense > 1) {  // one-parameter cases: P equispaced values
      const cases::ParameterSpec& q = spec.parameters.front();
      std::vector<double> v = cases::arithmetic_set(q.min, (q.max - q.min) / (dense - 1), dense);
      v.back() = q.max;
      values.emplace();
      for (double x : v) values->push_back(cases::Mu::Constant(1, x));
    }
    contactrb::offline::SnapshotRequest request =
        contactrb::offline::make_snapshot_request(spec, "training", 0, std::nullopt, values);
    request.settings.kacanov.tolerance = hf_tol;
    contactrb::offline::OfflineSettings offline;  // the defaults of `contactrb offline`
    offline.eps_du = eps_du;
    offline.eps_pod = eps_pod;
    offline.dual_method = dual;
    offline.supremizers = !no_sup;
    offline.compression = !no_compression;
    offline.eps_eim_k = offline.eps_eim_g = eps_eim;
    const std::vector<cases::Mu>& verification = spec.set("verification");
    study::EvaluationOptions eo;
    eo.jobs = jobs;
    eo.online_repeats = 1;
    for (double tol : tolerances) {
      contactrb::offline::GreedyOfflineSettings gs;
      gs.tolerance = tol;
      gs.offline = offline;
      gs.jobs = jobs;
      gs.progress = steps ? contactrb::offline::ProgressMode::Lines : contactrb::offline::ProgressMode::None;
      gs.progress_stream = &std::cout;
      const auto t0 = std::chrono::steady_clock::now();
      const contactrb::offline::GreedyOfflineResult g = contactrb::offline::run_offline_greedy(spec, request, gs);
      const double greedy_s = seconds_since(t0);
      if (steps) {  // the parts of the estimate where the greedy stopped
        online::OnlineSolver solver(g.offline.model);
        const cases::Mu& mu = g.steps.back().argmax_mu;
        const online::OnlineSolution s = solver.solve(mu);
        const auto& e = s.estimate;
        std::cout << "at argmax " << cases::mu_values_text(mu) << ": estimate " << e.energy << " residual "
                  << e.residual << " viol " << e.violation << " compl " << e.complementarity << " |lambda| "
                  << e.multiplier_norm << " eim_r " << e.eim_residual << " eim_s " << e.eim_slack << " norm "
                  << contactrb::offline::reduced_energy_norm(g.offline.model, mu, s.u_hat) << " iterations "
                  << s.iterations << "\n";
      }
      const study::Evaluation ev =
          study::evaluate_model(g.offline.model, g.offline.reconstruction, spec, verification, eo);
      double hf_s = g.start_hf_s, build_s = 0.0, sweep_s = 0.0;
      for (const contactrb::offline::GreedyStep& s : g.steps) {
        hf_s += s.hf_s;
        build_s += s.build_s;
        sweep_s += s.sweep_s;
      }
      std::ostringstream extra;
      extra << to_string(g.status) << ", " << std::setprecision(2) << std::scientific << g.steps.back().max_estimate
            << std::defaultfloat << std::setprecision(3) << "; HF " << hf_s << " s, build " << build_s << " s, sweep "
            << sweep_s << " s over " << g.steps.size() << " steps";
      std::ostringstream method;
      method << "greedy tol " << tol << " (" << request.mu.size() << " points)";
      row(name, method.str(), g.hf_solves, g.offline, ev, greedy_s, extra.str());
    }
    // POD over every training snapshot.
    const auto t0 = std::chrono::steady_clock::now();
    contactrb::offline::SnapshotRunOptions run;
    run.jobs = jobs;
    const io::SnapshotSet set = contactrb::offline::generate_snapshots(request, run);
    const contactrb::offline::OfflineResult pod = contactrb::offline::build_reduced_model(set, spec, offline);
    const double pod_s = seconds_since(t0);
    const study::Evaluation ev = study::evaluate_model(pod.model, pod.reconstruction, spec, verification, eo);
    row(name, "POD, all training (" + std::to_string(request.mu.size()) + " points)", static_cast<int>(set.snapshots.size()),
        pod, ev, pod_s, "-");
  }
  return 0;
}
