#pragma once
// Error and speed-up analysis of a reduced model against the HF solver (paper Section 6.2.3:
// e_ener (64), e_displ (65), e_inter (66)). For each mu: the HF solve (problem at mu from the
// case specification the model records, the model's constraint discretization and Kacanov
// settings), the online solve (median time over repeats), the reconstruction
// u = u_D(mu) + Theta u_hat, lambda = Xi lambda_hat on the HF mesh, and the three errors.
// A speed-up is never reported without the errors of the same solve beside it.
#include <Eigen/Core>
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace contactrb::study {

struct EvaluationOptions {
  online::OnlineSizes sizes;          // -1: the model's maxima
  online::OnlineSettings online;      // of every online solve (`contactrb online`'s defaults)
  int online_repeats = 5;     // the online time is the median over this many solves (>= 1)
  int jobs = 1;               // HF solves in parallel (online timings are taken serially)
  // The HF reference: the semi-smooth Newton (KKT residual 1e-10) by default, the fastest HF solver
  // and an accurate truth; Kacanov stops at the snapshots' eps_KA (1e-3 on the increments), whose
  // error on hertz-3p is as large as the reduced model's (docs/offline-online.md, "Error estimate").
  hf::HFMethod hf_method = hf::HFMethod::Newton;
  // Grid sequencing of the HF reference solves (docs/solvers.md, "Grid sequencing"), inside their
  // timed region: coarse levels of the model's level; -1: cases::default_sequence (2 with Newton
  // on 2D level >= 4, the fastest HF path there), 0: none.
  int sequence = -1;
  offline::ProgressMode progress = offline::ProgressMode::None;
  std::ostream* progress_stream = nullptr;  // nullptr: std::cerr
  std::vector<cases::Mu> multiplier_mus;    // mu points (among the evaluated ones) whose
                                            // multipliers are kept (EvaluationRow::multipliers)
};

// Multipliers of one mu against the abscissa of their constraint row in the reference
// configuration (the slave node of the row), HF and reconstructed RB, one entry per row.
struct MultiplierProfile {
  std::vector<double> abscissa;
  std::vector<double> lambda_hf;
  std::vector<double> lambda_rb;
};

struct EvaluationRow {
  cases::Mu mu;
  bool hf_converged = false;
  std::string hf_status;       // solve::to_string(KacanovStatus) of the HF solve
  int hf_iterations = 0;
  double hf_time_s = 0.0;      // HF problem at mu (mapped mesh, data), setup (assembly, factorization,
                               // condensation) + solve, wall clock; not the reference mesh generation
  bool rb_converged = false;
  std::string rb_status;
  int rb_iterations = 0;
  double online_time_s = 0.0;  // median over the repeats
  double speedup = 0.0;        // hf_time_s / online_time_s
  double e_ener = 0.0;         // (64): 1/2 |a(u_rb,u_rb) - f(u_rb) - a(u_hf,u_hf) + f(u_hf)|, absolute
  double e_displ = 0.0;        // (65): |u_rb - u_hf|_H1 / |u_hf|_H1 on Omega(mu)
  double e_inter = 0.0;        // (66): sqrt(sum over slave nodes of min(0, gap(u_rb))^2), the
                               // pointwise normal gap g(u_rb) - k(u_rb; u_rb) of the deformed
                               // configuration (inf if the deformed master degenerates)
  // Contact pressure (ours, docs/offline-online.md), lambda_rb = Xi lambda_hat on the HF rows,
  // weights |I_r|(mu) of the HF quadrature (the L2(Gamma^c) norm of the P0 pressure):
  double e_press = 0.0;        // |lambda_rb - lambda_hf|_Lambda / |lambda_hf|_Lambda
  double e_force = 0.0;        // |F_rb - F_hf| / |F_hf|, F = sum_r |I_r| lambda_r (total contact force)
  double e_peak = 0.0;         // |max lambda_rb - max lambda_hf| / max lambda_hf (peak pressure)
  // The best the model's dual cone can do: min_{c >= 0} |Xi c - lambda_hf|_Lambda / |lambda_hf|_Lambda
  // (kept rows; the dropped rows' HF multipliers count in full). e_press >= e_press_cone always;
  // their gap is what the reduced saddle point (53) loses (docs/offline-online.md).
  double e_press_cone = 0.0;
  double force_hf = 0.0, force_rb = 0.0;
  double peak_hf = 0.0, peak_rb = 0.0;
  double energy_hf = 0.0;      // 1/2 a(u, u) - f(u), u = u_hf
  double energy_rb = 0.0;      // same for u = u_rb (so e_ener != |energy_rb - energy_hf| in general)
  MultiplierProfile multipliers;  // filled only for EvaluationOptions::multiplier_mus
  // The a posteriori estimate against the true error it estimates (docs/offline-online.md).
  double e_energy_norm = 0.0;  // |u_rb - u_hf|_A(mu) = sqrt(d' A(mu) d), d = u_rb - u_hf, absolute
  double estimate = std::numeric_limits<double>::quiet_NaN();     // OnlineSolution::estimate.energy (NaN: none)
  double effectivity = std::numeric_limits<double>::quiet_NaN();  // estimate / e_energy_norm
};

// Errors: max and mean over the rows where both solves converged; times and speed-ups: medians
// over the same rows (0 when there is none).
struct EvaluationSummary {
  int count = 0;
  int hf_failures = 0;
  int rb_failures = 0;
  double max_e_ener = 0.0, mean_e_ener = 0.0;
  double max_e_displ = 0.0, mean_e_displ = 0.0;
  double max_e_inter = 0.0, mean_e_inter = 0.0;
  double max_e_press = 0.0, mean_e_press = 0.0;
  double max_e_force = 0.0, mean_e_force = 0.0;
  double max_e_peak = 0.0, mean_e_peak = 0.0;
  double max_e_press_cone = 0.0;
  double median_hf_time_s = 0.0;
  double median_online_time_s = 0.0;
  double median_speedup = 0.0;
  // Effectivity estimate / e_energy_norm over the rows where both converged and it is defined
  // (NaN when there is none).
  int effectivity_count = 0;
  double min_effectivity = std::numeric_limits<double>::quiet_NaN();
  double median_effectivity = std::numeric_limits<double>::quiet_NaN();
  double max_effectivity = std::numeric_limits<double>::quiet_NaN();
};

struct Evaluation {
  std::vector<std::string> parameter_names;  // the model's parameters (CSV columns)
  std::string hf_solver;            // the HF reference's method, hf::to_string (the hf_solver CSV column)
  std::vector<int> hf_sequence;     // the coarse levels of its grid sequencing (empty: none)
  std::vector<EvaluationRow> rows;  // in the order of the mu values
  EvaluationSummary summary;        // errors over the rows where both solves converged
  int N = 0, R = 0, Mk = 0, Mg = 0; // the sizes used
};

// Throws contactrb::Error for an empty set, mu outside the domain, a multiplier mu that is not
// one of `mus`, invalid sizes or options, a reconstruction that does not match the model
// (sizes), or a case spec whose HF discretization does not match it. A solve that does not
// converge is not an error: see hf_converged, rb_converged and the summary's failure counts.
Evaluation evaluate_model(const contactrb::model::ReducedModel& model,
                          const contactrb::model::ReducedReconstruction& reconstruction, const cases::CaseSpec& spec,
                          const std::vector<cases::Mu>& mus, const EvaluationOptions& options = {});

// CSV (one line per row: mu (p = 1) or one column per parameter, named as the parameter (p > 1),
// hf_solver,hf_converged,hf_iterations,hf_time_s,rb_converged,rb_status,
// rb_iterations,online_time_s,speedup,e_ener,e_displ,e_inter,e_press,e_force,e_peak,e_press_cone,force_hf,force_rb,
// peak_hf,peak_rb,energy_hf,energy_rb,e_energy_norm,estimate,effectivity) and
// multiplier profile CSVs (abscissa,lambda_hf,lambda_rb), both written atomically.
void write_evaluation_csv(const Evaluation& evaluation, const std::string& path);
void write_multiplier_csv(const MultiplierProfile& profile, const std::string& path);

}  // namespace contactrb::study
