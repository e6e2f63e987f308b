#pragma once
// One case, end to end, as in the paper's Sections 6.2.3-6.3: training snapshots (and the
// case's verification set), offline stages with the three dual-cone builders (CPG,
// angle-greedy, NMF; plus the truncated NMF with R = R_CPG) and the row cone, evaluation of every model on the
// training set (Figs. 10, 13, 15, 21) and on the verification set (Fig. 22), and the offline
// histories behind Figs. 9, 11, 12, 19, 20 (POD singular values, dual cone error against R for
// the three builders at a common maximal R, EIM error against M). `contactrb report` writes the
// result as CSV files, study.json and report.md (write_study_files, study_markdown) and plots
// the figures with scripts/plot_report.py.
#include <Eigen/Core>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/study/study_configurations.hpp"

namespace contactrb::study {

// The offline tolerances of a study (absolute, as OfflineSettings) and the tolerance lists of
// the Table 3/5-style rows (R reaching eps_DU) and of the Table 4-style row (N against eps_POD).
// The defaults are `contactrb offline`'s (OfflineSettings): a user case gets the same models
// from `report` as from `offline` (the paper's eps_EIM 1e-2 / 1e-3 give M^g = 0 on user cases).
struct StudyTolerances {
  double eps_pod = offline::OfflineSettings{}.eps_pod;
  double eps_du = offline::OfflineSettings{}.eps_du;
  double eps_eim_k = offline::OfflineSettings{}.eps_eim_k;
  double eps_eim_g = offline::OfflineSettings{}.eps_eim_g;
  // true: the four tolerances are relative, as `contactrb offline`'s defaults (a case file);
  // false: absolute (the built-in cases, the paper's reading). The tables of report.md
  // (table_eps_du, table_eps_pod: the paper's Tables 3-5) are absolute either way.
  bool relative = true;
  std::vector<double> table_eps_du{1e-1, 1e-2, 5e-3, 1e-3};
  std::vector<double> table_eps_pod{1e-2, 1e-3, 1e-4, 1e-5};
};

// The tolerances used for a built-in case (the paper's where they make sense with our scalings;
// docs/cli.md, "`contactrb report`", lists them and why). Any other case name gets the defaults
// of StudyTolerances (those of `contactrb offline`); so does a case file whatever its name
// (`contactrb report --case-file` does not call this).
StudyTolerances default_study_tolerances(const std::string& case_name);

// A model whose largest e_displ (65) on the verification set (the training set when there is
// none) is above this gets a warning (stderr and report.md).
constexpr double kStudyErrorWarning = 1e-2;

struct StudySettings {
  int level = 0;                                    // mesh refinement level (0: the paper's mesh)
  std::optional<contact::Discretization> constraint;  // empty: the case's
  // The HF method of the training snapshots; empty: offline::default_snapshot_method.
  std::optional<hf::HFMethod> snapshot_method;
  // Grid sequencing of the training snapshots' cold solves (offline::set_snapshot_sequence) and of
  // the evaluations' HF reference solves (EvaluationOptions::sequence); -1: automatic.
  int sequence = -1;
  StudyTolerances tolerances;
  offline::InnerProduct inner_product = offline::InnerProduct::Energy;
  bool compression = true;
  // Parameter sets: the case's "training" set, and its "verification" set when it has one.
  // max_*: keep at most that many values, evenly spaced, both ends included (-1: all;
  // max_training >= 2; max_verification = 0: no verification). Explicit values override.
  int max_training = -1;
  int max_verification = -1;
  std::optional<std::vector<double>> training_values;
  std::optional<std::vector<double>> verification_values;
  // The dual cone histories (Figs. 9, 11, 19) run to R = min(history_max_R, P, R_kept).
  int history_max_R = 30;
  // Multiplier profiles (Figs. 8, 18) of the CPG model for this many mu (evenly spaced in the
  // verification set, else in the training set; 0: none).
  int multiplier_profiles = 3;
  // Deformed configurations (Figs. 3, 5, 17): HF solutions at this many training values (evenly
  // spaced, both ends first: 2 gives the smallest and the largest mu; 0: none).
  int deformed_configurations = 2;
  // LAC against collocation (Figs. 7, 8): HF pressures of both discretizations at this many
  // training values (evenly spaced; 0: none).
  int constraint_comparisons = 4;
  int online_repeats = 5;  // online time: median over this many solves
  int jobs = 1;            // HF solves in parallel
  offline::ProgressMode progress = offline::ProgressMode::None;
  std::ostream* progress_stream = nullptr;  // nullptr: std::cerr
};
// Throws contactrb::Error naming the first invalid setting.
void check_settings(const StudySettings& settings);

// One offline stage of the study and its evaluations.
struct StudyModel {
  std::string key;    // "cpg" | "angle" | "nmf" | "nmf-truncated" | "rows" (CSV column values)
  std::string label;  // for tables and legends, e.g. "NMF (R = R_CPG)"
  offline::OfflineSettings settings;
  offline::OfflineReport report;
  int N = 0, R = 0, Mk = 0, Mg = 0;
  double dual_error = 0.0;  // max_mu |lambda - Pi_{K_R} lambda|_Lambda on the training set at its R
  Evaluation training;
  std::optional<Evaluation> verification;
};

// Dual cone error histories on the training set (errors[R], R = 0 .. R_max; paper Figs. 9, 11
// right, 19 right). The angle-greedy has two: the true cone-projection error (of the cone it
// builds) and the linear-projection error that steers it.
struct DualHistories {
  int R_max = 0;
  std::vector<double> cpg;
  std::vector<double> angle_cone;
  std::vector<double> angle_linear;
  std::vector<double> nmf;
  double cpg_s = 0.0, angle_s = 0.0, nmf_s = 0.0;  // algorithm times (NMF: its factorizations)
};

struct StudyResult {
  std::string case_name;
  int level = 0;
  std::string constraint;
  std::string parameter_name;
  std::vector<double> training_mus;
  std::vector<double> verification_mus;  // empty: no verification set
  double training_snapshots_s = 0.0;     // wall clock of the HF snapshot runs
  double verification_snapshots_s = 0.0; // 0: not computed (the evaluations solve HF themselves)
  int num_dofs = 0;
  int R_hf = 0;    // constraint rows
  int R_kept = 0;  // after compression (Remark 7)
  StudyTolerances tolerances;
  int jobs = 1;
  Eigen::VectorXd singular_values;  // POD (Figs. 11 left, 19 left)
  DualHistories dual;
  std::vector<double> eim_kappa;  // EIM l-infinity training error against M = 0 .. (Figs. 12, 20)
  std::vector<double> eim_gamma;
  std::vector<StudyModel> models;  // cpg, angle, nmf, nmf-truncated, rows
  std::vector<MultiplierProfile> profiles;  // of the CPG model
  std::vector<double> profile_mus;
  std::string profile_set;  // "verification" | "training"
  std::vector<DeformedConfiguration> configurations;
  std::vector<ConstraintComparison> comparisons;
  double total_s = 0.0;

  const StudyModel& model(const std::string& key) const;  // throws contactrb::Error if absent
};

// Throws contactrb::Error for invalid settings, a failed training snapshot (naming mu), or any
// error of the offline or evaluation stages.
StudyResult run_study(const cases::CaseSpec& spec, const StudySettings& settings);

// At most `count` values of `values`, evenly spaced by index, first and last included
// (count < 0 or >= size: all; count = 1: the first).
std::vector<double> evenly_spaced_subset(const std::vector<double>& values, int count);
// Smallest R with history[R] <= eps, -1 when none (Tables 3, 5: R reaching eps_DU).
int size_reaching(const std::vector<double>& history, double eps);
// Number of singular values > eps (Table 4: N against eps_POD).
int pod_size(const Eigen::VectorXd& singular_values, double eps);

// Writes into `dir` (which must exist): pod_singular_values.csv, dual_cone_error.csv,
// eim_error.csv, sizes.csv, errors_training.csv, errors_verification.csv (when there is a
// verification set), multipliers.csv, dual_table.csv, pod_table.csv, the configuration files
// (write_configuration_files, when computed) and study.json (which lists them). Every file is written atomically with a header row. Returns the file names.
std::vector<std::string> write_study_files(const StudyResult& result, const std::string& dir);

// One sentence per model whose max e_displ exceeds kStudyErrorWarning (empty: none).
std::vector<std::string> study_warnings(const StudyResult& result);

// report.md: tables of sizes, errors, times and speed-ups, the offline step times and the
// Table 3/4/5-style rows; `figures` (PNG file names, relative to the report) are linked.
std::string study_markdown(const StudyResult& result, const std::vector<std::string>& figures);

}  // namespace contactrb::study
