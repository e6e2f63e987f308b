// Moving contact zone: the row cone (the default of `contactrb offline`) against the paper's
// CPG cone (`--dual cpg`) and the registered cone, per case (docs/performance.md, "Moving contact zone"). For each case and method: the
// sizes, max and median e_displ / e_press / e_force, the effectivity range and median, the median
// and worst online time per query and the offline time, one CSV line each (study::evaluate_model,
// as `contactrb evaluate`), and the same as a markdown table on stdout.
//
//   build/bench/bench_moving_zone [--quick] [--hf-tol EPS] [--jobs J] [--out FILE.csv] [case ...]
//
// Cases (default: all): hertz-3p (the weak greedy of `offline --case hertz-3p --greedy` at its
// default tolerance and budget over the training set, the 200 random verification points),
// hertz-a-l4 (hertz-a at level 4, its 31 training values), hertz-a, hertz-b, ring-block (default
// offline over the training set). Methods: cpg (default online iteration), rows (default online
// iteration: accelerated, exact contact rows), rows-newton (`online --iteration newton`), the two
// rows lines on the same model; registered (`--dual registered --r 15`) on the cases built from
// their training set. Online time: per point the median of 5 solves (wall), then the
// median and the maximum over the points.
// --hf-tol: the Kacanov tolerance eps_KA of the snapshots (default: `contactrb offline`'s). The
// errors are measured against Newton HF solves (KKT residual 1e-10, study::EvaluationOptions).
// --quick (under a minute): hertz-3p greedy over the first 100 training points with a budget of
// 10 HF solves and the first 20 verification points; level 2 instead of 4.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/study/evaluation.hpp"

using namespace contactrb;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Kacanov iterations allowed with --hf-tol (the relaxed iteration gains a decade in about 50).
constexpr int kTightMaxIterations = 5000;

struct Options {
  bool quick = false;
  std::optional<double> hf_tol;
  int jobs = 2;
  std::string out = "moving_zone.csv";
  std::vector<std::string> cases;
};

// One benchmark case: the built-in case, its level, and whether the model comes from the greedy.
struct BenchCase {
  std::string label;
  std::string name;
  int level = 0;
  bool greedy = false;
};

// A reduced model and what its offline stage cost.
struct BuiltModel {
  offline::OfflineResult offline;
  int hf_solves = 0;
  double offline_s = 0.0;  // wall: HF snapshots + build (the greedy: its whole run)
};

struct Line {
  std::string case_label, method;
  int hf_solves = 0;
  double offline_s = 0.0;
  study::Evaluation evaluation;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size();
  return m % 2 == 1 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

// The median of a column over the rows where both solves converged (the summary's rows).
double converged_median(const study::Evaluation& e, double study::EvaluationRow::*field) {
  std::vector<double> v;
  for (const study::EvaluationRow& r : e.rows) {
    if (r.hf_converged && r.rb_converged) v.push_back(r.*field);
  }
  return median(v);
}

double max_online_s(const study::Evaluation& e) {
  double worst = 0.0;
  for (const study::EvaluationRow& r : e.rows) worst = std::max(worst, r.online_time_s);
  return worst;
}

// The registered cone's R (`--dual registered --r 15`).
constexpr int kRegisteredR = 15;

offline::OfflineSettings offline_settings(offline::DualConeMethod dual) {
  offline::OfflineSettings s;  // the defaults of `contactrb offline`
  s.dual_method = dual;
  if (dual == offline::DualConeMethod::Registered) s.dual_size = kRegisteredR;
  return s;
}

// The greedy of `contactrb offline --greedy` (default tolerance and budget; --quick: 10).
BuiltModel greedy_model(const cases::CaseSpec& spec, const offline::SnapshotRequest& request,
                        offline::DualConeMethod dual, const Options& opt) {
  offline::GreedyOfflineSettings gs;
  gs.offline = offline_settings(dual);
  gs.jobs = opt.jobs;
  if (opt.quick) gs.max_hf = 10;
  const auto t0 = Clock::now();
  offline::GreedyOfflineResult g = offline::run_offline_greedy(spec, request, gs);
  BuiltModel b;
  b.offline_s = seconds_since(t0);
  b.hf_solves = g.hf_solves;
  std::cerr << "  greedy " << offline::to_string(dual) << ": " << offline::to_string(g.status) << ", " << g.hf_solves
            << " HF solves, model of step " << g.model_step << ", " << b.offline_s << " s\n";
  b.offline = std::move(g.offline);
  return b;
}

// `contactrb offline` over the snapshots of the whole training set (computed once per case).
BuiltModel pod_model(const cases::CaseSpec& spec, const io::SnapshotSet& set, double snapshots_s,
                     offline::DualConeMethod dual) {
  const auto t0 = Clock::now();
  BuiltModel b;
  b.offline = offline::build_reduced_model(set, spec, offline_settings(dual));
  b.offline_s = snapshots_s + seconds_since(t0);
  b.hf_solves = static_cast<int>(set.snapshots.size());
  return b;
}

Line evaluate(const BenchCase& c, const std::string& method, const BuiltModel& b, const cases::CaseSpec& spec,
              const std::vector<cases::Mu>& verification, online::OnlineIteration iteration, const Options& opt) {
  study::EvaluationOptions eo;
  eo.jobs = opt.jobs;
  eo.online.iteration = iteration;
  const std::string label = c.level > 0 ? c.name + " level " + std::to_string(c.level) : c.name;
  Line line{label, method, b.hf_solves, b.offline_s, {}};
  line.evaluation = study::evaluate_model(b.offline.model, b.offline.reconstruction, spec, verification, eo);
  std::cerr << "  " << method << ": max e_press " << line.evaluation.summary.max_e_press << "\n";
  return line;
}

// The lines of one case: cpg, rows, rows-newton, and registered (R 15) on the one-shot cases.
std::vector<Line> run_case(const BenchCase& c, const Options& opt) {
  std::cerr << c.name << " (level " << c.level << ")\n";
  const cases::CaseSpec spec = cases::builtin_case_spec(c.name);
  std::optional<std::vector<cases::Mu>> values;
  std::vector<cases::Mu> verification = spec.set("verification");
  if (opt.quick && c.greedy) {
    const std::vector<cases::Mu>& training = spec.set("training");
    values.emplace(training.begin(), training.begin() + std::min<std::ptrdiff_t>(100, std::ssize(training)));
    verification.resize(std::min<std::size_t>(20, verification.size()));
  }
  offline::SnapshotRequest request = offline::make_snapshot_request(spec, "training", c.level, std::nullopt, values);
  if (opt.hf_tol) {
    request.settings.kacanov.tolerance = *opt.hf_tol;
    request.settings.kacanov.max_iterations = kTightMaxIterations;
  }
  std::vector<BuiltModel> models;  // cpg, rows (, registered: the non-greedy cases)
  if (c.greedy) {
    models.push_back(greedy_model(spec, request, offline::DualConeMethod::CPG, opt));
    models.push_back(greedy_model(spec, request, offline::DualConeMethod::Rows, opt));
  } else {
    offline::SnapshotRunOptions run;
    run.jobs = opt.jobs;
    const auto t0 = Clock::now();
    const io::SnapshotSet set = offline::generate_snapshots(request, run);
    const double snapshots_s = seconds_since(t0);
    models.push_back(pod_model(spec, set, snapshots_s, offline::DualConeMethod::CPG));
    models.push_back(pod_model(spec, set, snapshots_s, offline::DualConeMethod::Rows));
    models.push_back(pod_model(spec, set, snapshots_s, offline::DualConeMethod::Registered));
  }
  using online::OnlineIteration;
  std::vector<Line> lines{evaluate(c, "cpg", models[0], spec, verification, OnlineIteration::Automatic, opt),
                          evaluate(c, "rows", models[1], spec, verification, OnlineIteration::Automatic, opt),
                          evaluate(c, "rows-newton", models[1], spec, verification, OnlineIteration::Newton, opt)};
  if (models.size() > 2) {
    lines.push_back(evaluate(c, "registered", models[2], spec, verification, OnlineIteration::Automatic, opt));
  }
  return lines;
}

const std::vector<std::string> kColumns{
    "case", "method", "hf_solves", "N", "R", "Mk", "Mg", "points", "hf_failures", "rb_failures", "max_e_displ",
    "median_e_displ", "max_e_press", "median_e_press", "max_e_press_cone", "max_e_force", "median_e_force",
    "min_effectivity", "median_effectivity", "max_effectivity", "median_online_s", "max_online_s", "median_hf_s",
    "offline_s"};

std::vector<io::CsvCell> csv_row(const Line& l) {
  const study::Evaluation& e = l.evaluation;
  const study::EvaluationSummary& s = e.summary;
  using R = study::EvaluationRow;
  return {l.case_label, l.method, static_cast<long long>(l.hf_solves), static_cast<long long>(e.N),
          static_cast<long long>(e.R), static_cast<long long>(e.Mk), static_cast<long long>(e.Mg),
          static_cast<long long>(s.count), static_cast<long long>(s.hf_failures), static_cast<long long>(s.rb_failures),
          s.max_e_displ, converged_median(e, &R::e_displ), s.max_e_press, converged_median(e, &R::e_press),
          s.max_e_press_cone, s.max_e_force, converged_median(e, &R::e_force), s.min_effectivity,
          s.median_effectivity, s.max_effectivity, s.median_online_time_s, max_online_s(e), s.median_hf_time_s,
          l.offline_s};
}

void print_markdown(const std::vector<Line>& lines) {
  std::cout << "| case | method | HF solves | N, R, M^k, M^g | max (median) e_displ | max (median) e_press | "
               "max (median) e_force | effectivity min-max (median) | online median, worst | offline |\n"
               "| --- | --- | ---: | --- | --- | --- | --- | --- | --- | ---: |\n";
  using R = study::EvaluationRow;
  for (const Line& l : lines) {
    const study::Evaluation& e = l.evaluation;
    const study::EvaluationSummary& s = e.summary;
    std::ostringstream os;
    os << "| " << l.case_label << " | " << l.method << " | " << l.hf_solves << " | " << e.N << ", " << e.R << ", "
       << e.Mk << ", " << e.Mg << " | " << std::scientific << std::setprecision(1) << s.max_e_displ << " ("
       << converged_median(e, &R::e_displ) << ") | " << s.max_e_press << " (" << converged_median(e, &R::e_press)
       << ") | " << s.max_e_force << " (" << converged_median(e, &R::e_force) << ") | " << std::defaultfloat
       << std::setprecision(3) << s.min_effectivity << "-" << s.max_effectivity << " (" << s.median_effectivity
       << ") | " << std::fixed << std::setprecision(1) << 1e6 * s.median_online_time_s << " us, "
       << 1e6 * max_online_s(e) << " us | " << l.offline_s << " s |";
    if (s.rb_failures + s.hf_failures > 0) os << " failures: HF " << s.hf_failures << ", online " << s.rb_failures;
    std::cout << os.str() << "\n";
  }
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      o.quick = true;
    } else if (a == "--hf-tol" && i + 1 < argc) {
      o.hf_tol = std::atof(argv[++i]);
    } else if (a == "--jobs" && i + 1 < argc) {
      o.jobs = std::atoi(argv[++i]);
    } else if (a == "--out" && i + 1 < argc) {
      o.out = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      throw Error("unknown option '" + a + "' (usage: bench_moving_zone [--quick] [--hf-tol EPS] [--jobs J] [--out FILE] [case ...])");
    } else {
      o.cases.push_back(a);
    }
  }
  require(o.jobs >= 1, "--jobs must be >= 1");
  require(!o.hf_tol || *o.hf_tol > 0.0, "--hf-tol must be > 0");
  return o;
}

std::vector<BenchCase> bench_cases(const Options& o) {
  const std::vector<BenchCase> all{{"hertz-3p", "hertz-3p", 0, true},
                                   {"hertz-a-l4", "hertz-a", o.quick ? 2 : 4, false},
                                   {"hertz-a", "hertz-a", 0, false},
                                   {"hertz-b", "hertz-b", 0, false},
                                   {"ring-block", "ring-block", 0, false}};
  if (o.cases.empty()) return all;
  std::vector<BenchCase> chosen;
  for (const std::string& name : o.cases) {
    const auto it = std::find_if(all.begin(), all.end(), [&name](const BenchCase& c) { return c.label == name; });
    require(it != all.end(), "unknown case '" + name + "' (hertz-3p, hertz-a-l4, hertz-a, hertz-b, ring-block)");
    chosen.push_back(*it);
  }
  return chosen;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options opt = parse(argc, argv);
    io::CsvWriter csv(kColumns);
    std::vector<Line> lines;
    for (const BenchCase& c : bench_cases(opt)) {
      for (Line& l : run_case(c, opt)) {
        csv.add_row(csv_row(l));
        lines.push_back(std::move(l));
      }
      csv.write(opt.out);  // after each case: a long run keeps what it measured
    }
    print_markdown(lines);
    std::cerr << "wrote " << opt.out << "\n";
  } catch (const Error& e) {
    std::cerr << "bench_moving_zone: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
