#include "contactrb/offline/offline_builder.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "contactrb/cases/unit_box.hpp"
#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"
#include "contactrb/common/run_threads.hpp"
#include "contactrb/fem/cholesky.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/offline/angle_greedy.hpp"
#include "contactrb/offline/compression.hpp"
#include "contactrb/offline/cone_projection.hpp"
#include "contactrb/offline/cpg.hpp"
#include "contactrb/offline/eim.hpp"
#include "contactrb/offline/eim_flatten.hpp"
#include "contactrb/offline/error_estimate.hpp"
#include "contactrb/offline/geometric_term.hpp"
#include "contactrb/offline/nmf.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/model_check.hpp"
#include "contactrb/online/registered_basis.hpp"
#include "contactrb/offline/pod.hpp"
#include "contactrb/offline/registration.hpp"
#include "contactrb/offline/row_cone.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

using model::ContactSurface;
using model::EstimateData;
using model::ReducedModel;
using model::ReducedReconstruction;
using online::InitialGuess;
using online::OnlineSettings;
using online::OnlineSolution;
using online::OnlineSolver;
using online::check_model;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Selection matrix P (num_dofs x n_free): P(free_dofs[i], i) = 1, so P' A P = A_00.
Eigen::SparseMatrix<double> free_selection(int num_dofs, const std::vector<int>& free_dofs) {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(free_dofs.size());
  for (std::size_t i = 0; i < free_dofs.size(); ++i) trip.emplace_back(free_dofs[i], static_cast<int>(i), 1.0);
  Eigen::SparseMatrix<double> P(num_dofs, ix(free_dofs.size()));
  P.setFromTriplets(trip.begin(), trip.end());
  return P;
}

Eigen::VectorXd restrict_to(const Eigen::VectorXd& global, const std::vector<int>& idx) {
  Eigen::VectorXd out(ix(idx.size()));
  for (std::size_t i = 0; i < idx.size(); ++i) out(ix(i)) = global(idx[i]);
  return out;
}

// u_D(mu) on the contact DOFs: lift_c * theta^lift(mu).
Eigen::VectorXd lift_at(const Eigen::MatrixXd& lift_c, const cases::AffineThetas& th, const cases::Mu& mu) {
  if (th.lift.empty()) return Eigen::VectorXd::Zero(lift_c.rows());
  return lift_c * cases::evaluate(th.lift, mu);
}

const char* eim_status(const EIMResult& r) { return to_string(r.status); }

// Linear dependence threshold of the enrichment: a supremizer whose M-norm drops below this
// fraction of its own norm when orthogonalized against the basis adds nothing (round-off).
constexpr double kSupremizerDependence = 1e-10;
// Relative POD tolerance of the registered cone's supremizers (their span grows with P R).
constexpr double kRegisteredSupremizerPOD = 1e-3;

// The snapshot a dual generator stands for: the greedies' own pick, otherwise (NMF) the snapshot
// closest in angle in the Lambda norm.
int generator_snapshot(const DualConeResult& dual, const Eigen::MatrixXd& Lambda, const Eigen::VectorXd& w, int r) {
  if (sz(r) < dual.selected.size()) return dual.selected[sz(r)];
  const Eigen::VectorXd xi = dual.generators.col(r);
  int best = 0;
  double best_cos = -1.0;
  for (Index p = 0; p < Lambda.cols(); ++p) {
    const double nl = std::sqrt(w.dot(Lambda.col(p).cwiseAbs2())), nx = std::sqrt(w.dot(xi.cwiseAbs2()));
    if (nl <= 0.0 || nx <= 0.0) continue;
    const double c = w.dot(Lambda.col(p).cwiseProduct(xi)) / (nl * nx);
    if (c > best_cos) {
      best_cos = c;
      best = static_cast<int>(p);
    }
  }
  return best;
}

// M^-1 (K_p' xi) on the free DOFs for each column xi of `generators` (on the kept rows), K_p the
// rows of snapshot snapshot_of[column].
Eigen::MatrixXd supremizer_columns(const fem::SparseCholesky& chol, Index n_free, const io::SnapshotSet& set,
                                   const std::vector<int>& kept, const Eigen::MatrixXd& generators,
                                   const std::vector<int>& snapshot_of, const std::vector<int>& global_to_free) {
  // Blocks of right-hand sides: one supernodal solve per block (matrix products) instead of
  // one triangular pair per column, with a block's worth of extra memory.
  constexpr Index kBlock = 64;
  Eigen::MatrixXd S(n_free, generators.cols());
  for (Index r0 = 0; r0 < generators.cols(); r0 += kBlock) {
    const Index nb = std::min(kBlock, generators.cols() - r0);
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n_free, nb);
    for (Index j = 0; j < nb; ++j) {
      const io::Snapshot& snap = set.snapshots[sz(snapshot_of[sz(r0 + j)])];
      Eigen::VectorXd lambda_full = Eigen::VectorXd::Zero(snap.K.rows());
      for (std::size_t i = 0; i < kept.size(); ++i) lambda_full(kept[i]) = generators(ix(i), r0 + j);
      const Eigen::VectorXd t = snap.K.transpose() * lambda_full;  // contact DOFs
      for (Index i = 0; i < t.size(); ++i) {
        const int fi = global_to_free[sz(set.contact_dofs[sz(i)])];
        if (fi >= 0) B(fi, j) += t(i);
      }
    }
    S.middleCols(r0, nb) = chol.solve(B);
  }
  return S;
}

// Supremizer enrichment: appends M^-1 (K_r' xi_r) (free DOFs), M-orthonormalized against the
// basis (Gram-Schmidt twice), dependent ones dropped. Returns the number appended.
int enrich_with_supremizers(Eigen::MatrixXd& Theta, const Eigen::SparseMatrix<double>& M, const io::SnapshotSet& set,
                            const std::vector<int>& kept, const DualConeResult& dual, const Eigen::MatrixXd& Lambda,
                            const Eigen::VectorXd& weights, const std::vector<int>& global_to_free) {
  fem::SparseCholesky chol;
  require(chol.compute(M) == fem::FactorStatus::Success,
          "offline: the inner-product matrix is not positive definite (supremizers)");
  const Index R = dual.generators.cols();
  const Index n_free = Theta.rows();
  std::vector<int> snapshot_of;
  for (Index r = 0; r < R; ++r) snapshot_of.push_back(generator_snapshot(dual, Lambda, weights, static_cast<int>(r)));
  const Eigen::MatrixXd S = supremizer_columns(chol, n_free, set, kept, dual.generators, snapshot_of, global_to_free);
  int added = 0;
  Eigen::MatrixXd out(n_free, Theta.cols() + R);
  out.leftCols(Theta.cols()) = Theta;
  Index n = Theta.cols();
  for (Index r = 0; r < R; ++r) {
    Eigen::VectorXd v = S.col(r);
    const double norm0 = std::sqrt(std::max(0.0, v.dot(M * v)));
    if (norm0 <= 0.0) continue;
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd Mv = M * v;
      v -= out.leftCols(n) * (out.leftCols(n).transpose() * Mv);
    }
    const double norm = std::sqrt(std::max(0.0, v.dot(M * v)));
    if (norm <= kSupremizerDependence * norm0) continue;
    out.col(n++) = v / norm;
    ++added;
  }
  Theta = out.leftCols(n);
  return added;
}

// The registered cone's supremizers: M^-1 (K_p' Xi(support_p) G_k) for every training point p and
// generator k, M-orthogonalized against the basis, compressed by a POD at kRegisteredSupremizerPOD
// (relative), appended. Returns the number appended.
int enrich_with_registered_supremizers(Eigen::MatrixXd& Theta, const Eigen::SparseMatrix<double>& M,
                                       const io::SnapshotSet& set, const std::vector<int>& kept,
                                       const model::Registration& reg, const std::vector<int>& global_to_free) {
  fem::SparseCholesky chol;
  require(chol.compute(M) == fem::FactorStatus::Success,
          "offline: the inner-product matrix is not positive definite (supremizers)");
  const Index P = reg.support.cols(), R = reg.R();
  Eigen::MatrixXd generators(ix(kept.size()), P * R), Xi;
  std::vector<int> snapshot_of;
  for (Index p = 0; p < P; ++p) {
    online::registered_basis(reg, reg.support.col(p), static_cast<int>(R), Xi);
    generators.middleCols(p * R, R) = Xi;
    snapshot_of.insert(snapshot_of.end(), sz(R), static_cast<int>(p));
  }
  Eigen::MatrixXd S = supremizer_columns(chol, Theta.rows(), set, kept, generators, snapshot_of, global_to_free);
  constexpr Index kBlock = 64;  // P R columns: 465 on hertz-a, 4.4 GB a copy at level 7
  for (Index b = 0; b < S.cols(); b += kBlock) {
    auto block = S.middleCols(b, std::min(kBlock, S.cols() - b));
    for (int pass = 0; pass < 2; ++pass) block -= Theta * (Theta.transpose() * (M * block));
  }
  PODSettings ps;
  ps.tolerance = kRegisteredSupremizerPOD;
  ps.relative = true;
  const PODResult r = pod_by_correlation(S, M, ps);
  Eigen::MatrixXd out(Theta.rows(), Theta.cols() + r.N);
  out << Theta, r.basis;
  Theta = std::move(out);
  return r.N;
}

// A gap gamma below this fraction of the largest reference coordinate is round-off (M^g = 0 is
// then exact up to it).
constexpr double kGapRoundoff = 1e-12;

// --- Input checks: a library entry point, so the set may not come from read_snapshot_file, and
// every index used by the steps below (free_selection, restrict_to, the contact surface) is used
// unchecked.

void check_set_matches_case(const io::SnapshotSet& set, const cases::CaseSpec& spec) {
  require(set.dimension == 2, "offline: the snapshots are " + std::to_string(set.dimension) +
                                  "D: reduced models are built from 2D snapshots only in this build");
  require(!set.snapshots.empty(), "offline: the snapshot set is empty");
  try {
    io::check_snapshot_set(set);
  } catch (const Error& e) {
    throw Error(std::string("offline: inconsistent snapshot set: ") + e.what());
  }
  require(set.parameters.size() == spec.parameters.size(),
          "offline: the snapshots have " + std::to_string(set.parameters.size()) + " parameters, the case " +
              std::to_string(spec.parameters.size()));
  for (std::size_t k = 0; k < set.parameters.size(); ++k) {
    require(set.parameters[k].name == spec.parameters[k].name,
            "offline: parameter " + std::to_string(k + 1) + " of the snapshots is '" + set.parameters[k].name +
                "', of the case '" + spec.parameters[k].name + "'");
  }
  for (const io::Snapshot& s : set.snapshots) {
    require(s.converged, "offline: the snapshot at mu = " + cases::mu_values_text(s.mu) + " did not converge (" + s.status +
                             ": " + s.message + "); drop it or recompute it");
  }
}

// A repeated training value adds no information but one more identical column: with a zero step
// the whole set is one value, and the model answered elsewhere with converged = true and a
// contact force 45 times the HF one.
void check_distinct_training_values(const io::SnapshotSet& set) {
  std::vector<std::pair<std::vector<double>, int>> mus;
  for (std::size_t p = 0; p < set.snapshots.size(); ++p) {
    const cases::Mu& mu = set.snapshots[p].mu;
    mus.emplace_back(std::vector<double>(mu.data(), mu.data() + mu.size()), static_cast<int>(p));
  }
  std::sort(mus.begin(), mus.end());
  for (std::size_t i = 1; i < mus.size(); ++i) {
    if (mus[i].first == mus[i - 1].first) {
      // shortest round-trip digits: the value exactly as stored
      const std::string text = cases::mu_values_text(set.snapshots[sz(mus[i].second)].mu);
      throw Error("offline: the training value mu = " + text + " appears twice (snapshots " +
                  std::to_string(mus[i - 1].second) + " and " + std::to_string(mus[i].second) +
                  "): the training values must be distinct");
    }
  }
}

void check_snapshot_sizes(const io::SnapshotSet& set) {
  const int n_free = static_cast<int>(set.free_dofs.size());
  const int n_c = static_cast<int>(set.contact_dofs.size());
  const int R_hf = static_cast<int>(set.snapshots.front().lambda.size());
  for (const io::Snapshot& s : set.snapshots) {
    require(s.u0.size() == n_free && s.u.size() == set.num_dofs && s.lambda.size() == R_hf && s.K.rows() == R_hf &&
                s.K.cols() == n_c && s.g.size() == R_hf && s.weight.size() == R_hf,
            "offline: snapshot at mu = " + cases::mu_values_text(s.mu) + " has inconsistent array sizes (u0 " +
                std::to_string(s.u0.size()) + "/" + std::to_string(n_free) + ", lambda " +
                std::to_string(s.lambda.size()) + "/" + std::to_string(R_hf) + ", K " + std::to_string(s.K.rows()) +
                " x " + std::to_string(s.K.cols()) + ")");
  }
}

// --- The affine terms (49) on the reference mesh and the inner product M of the POD.
struct ReferenceTerms {
  mesh::Mesh mesh;
  cases::AffineTerms terms;
  cases::AffineThetas thetas;
  Eigen::SparseMatrix<double> free_selection;  // P: P' A P = A_00
  std::vector<Eigen::SparseMatrix<double>> A00;  // P' A_j P, j < J^a (a greedy's builds share them)
  Eigen::SparseMatrix<double> inner;           // M on the free DOFs
  Eigen::MatrixXd lift_c;                      // u_D terms on the contact DOFs, one column per term
  std::vector<int> global_to_free;             // -1 on a Dirichlet DOF
};

ReferenceTerms assemble_reference_terms(const io::SnapshotSet& set, const cases::CaseSpec& spec, InnerProduct product,
                                        OfflineReport& report) {
  const auto t0 = Clock::now();
  ReferenceTerms ref;
  // The set's own mesh when it records one (no .msh file needed), else the case's.
  ref.mesh = set.mesh.nodes.empty() ? cases::reference_mesh(spec, set.level) : set.mesh;
  require(ref.mesh.num_dofs() == set.num_dofs, "offline: the case's reference mesh has " +
                                                   std::to_string(ref.mesh.num_dofs()) + " DOFs, the snapshots " +
                                                   std::to_string(set.num_dofs));
  ref.terms = cases::assemble_affine_terms(spec, ref.mesh);
  ref.thetas = cases::theta_functions(spec);
  require(ref.terms.A.size() == ref.thetas.a.size() && ref.terms.f.size() == ref.thetas.f.size() &&
              ref.terms.lift.size() == ref.thetas.lift.size(),
          "offline: affine terms and theta functions disagree in number");
  ref.free_selection = free_selection(set.num_dofs, set.free_dofs);
  const Eigen::SparseMatrix<double>& Psel = ref.free_selection;
  for (const fem::SparseMatrix& A : ref.terms.A) ref.A00.push_back(Psel.transpose() * A * Psel);
  if (product == InnerProduct::Energy) {
    const fem::SparseMatrix A_ref =
        cases::combine(ref.terms.A, cases::evaluate(ref.thetas.a, cases::reference_mu(spec.parameters)));
    ref.inner = Psel.transpose() * A_ref * Psel;
  } else {
    ref.inner = Psel.transpose() * fem::h1_product(ref.mesh) * Psel;
  }
  const int JD = static_cast<int>(ref.terms.lift.size());
  ref.lift_c.resize(ix(set.contact_dofs.size()), JD);
  for (int k = 0; k < JD; ++k) ref.lift_c.col(k) = restrict_to(ref.terms.lift[sz(k)], set.contact_dofs);
  ref.global_to_free.assign(sz(set.num_dofs), -1);
  for (std::size_t i = 0; i < set.free_dofs.size(); ++i) ref.global_to_free[sz(set.free_dofs[i])] = static_cast<int>(i);
  report.assembly_s = seconds_since(t0);
  return ref;
}

// --- (T2) POD of the primal snapshots u_0 in the M-norm.
struct PrimalSnapshots {
  Eigen::MatrixXd U0;  // n_free x P
  PODResult pod;
};

// weight: the factor of `inner` a greedy's builds share (factored here when empty). With
// extend_basis the POD gives the singular values and N only: the basis is the extended one.
PrimalSnapshots pod_step(const io::SnapshotSet& set, const Eigen::SparseMatrix<double>& inner,
                         const OfflineSettings& settings, OfflineReport& report, std::optional<PODWeight>& weight) {
  PrimalSnapshots out;
  const int P = static_cast<int>(set.snapshots.size());
  out.U0.resize(ix(set.free_dofs.size()), P);
  for (int p = 0; p < P; ++p) out.U0.col(p) = set.snapshots[sz(p)].u0;
  PODSettings pod_settings;
  pod_settings.tolerance = settings.eps_pod;
  pod_settings.relative = settings.eps_pod_relative;
  pod_settings.max_modes = settings.pod_modes;
  pod_settings.basis = !settings.extend_basis;
  if (!weight) weight.emplace(inner);
  out.pod = pod(out.U0, *weight, pod_settings);
  const PODResult& r = out.pod;
  require(r.N >= 1, "offline: POD kept no mode (eps_pod = " + number_text(settings.eps_pod) +
                        (settings.eps_pod_relative ? " relative" : " absolute") +
                        " above every singular value, largest " +
                        number_text(r.singular_values.size() ? r.singular_values(0) : 0.0) + ")");
  report.singular_values = r.singular_values;
  report.N_pod = r.N;
  report.pod_threshold = r.threshold;
  report.pod_s = r.seconds;
  return out;
}

// --- Remark 7: the dual snapshots on the constraints active on the training set.
struct DualSnapshots {
  std::vector<int> kept;      // kept constraint rows
  Eigen::MatrixXd Lambda;     // R_kept x P, >= 0
  Eigen::VectorXd weights;    // |I_r| on the kept rows
};

DualSnapshots compression_step(const io::SnapshotSet& set, const OfflineSettings& settings, OfflineReport& report) {
  const auto t0 = Clock::now();
  const int P = static_cast<int>(set.snapshots.size());
  const int R_hf = static_cast<int>(set.snapshots.front().lambda.size());
  Eigen::MatrixXd Lambda(R_hf, P);
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(R_hf);
  for (int p = 0; p < P; ++p) {
    Lambda.col(p) = set.snapshots[sz(p)].lambda;
    weights += set.snapshots[sz(p)].weight;
  }
  weights /= static_cast<double>(P);  // |I_r| depends on mu for a mapped slave body: the mean
  CompressionSettings cs;
  cs.enabled = settings.compression;
  const Compression comp = compress_constraints(Lambda, cs);
  require(!comp.kept.empty(), "offline: no constraint is active on the training set: no dual basis to build");
  DualSnapshots out;
  out.kept = comp.kept;
  // The snapshot multipliers are >= 0 up to the QP's round-off: clip tiny negatives.
  out.Lambda = restrict_rows(Lambda, out.kept).cwiseMax(0.0);
  out.weights = restrict_rows(weights, out.kept);
  report.R_hf = R_hf;
  report.R_kept = static_cast<int>(out.kept.size());
  report.dual_s = seconds_since(t0);  // the report times the compression with the dual cone
  return out;
}

// --- (T3) The dual cone W_R^+ (Algorithm 2 for CPG) on the kept rows.
DualConeResult dual_cone_step(const DualSnapshots& dual_snapshots, const OfflineSettings& settings,
                              OfflineReport& report) {
  const auto t0 = Clock::now();
  DualConeSettings ds;
  ds.greedy.tolerance = settings.eps_du;
  ds.greedy.relative = settings.eps_du_relative;
  ds.greedy.max_size = settings.dual_size;
  ds.weights = dual_snapshots.weights;
  DualConeResult dual;
  switch (settings.dual_method) {
    case DualConeMethod::CPG: dual = build_cpg(dual_snapshots.Lambda, ds); break;
    case DualConeMethod::AngleGreedy: dual = build_angle_greedy(dual_snapshots.Lambda, ds); break;
    case DualConeMethod::NMF: dual = build_nmf_cone(dual_snapshots.Lambda, ds); break;
    case DualConeMethod::Rows:
    case DualConeMethod::Registered: dual = build_row_cone(dual_snapshots.Lambda, ds); break;
  }
  require(dual.generators.cols() >= 1, "offline: the dual cone is empty");
  report.R = static_cast<int>(dual.generators.cols());
  report.dual_errors = dual.errors;
  report.dual_relative_errors = dual.relative_errors;
  report.dual_status = to_string(dual.status);
  report.dual_condition_number = generator_condition_number(dual.generators, ds.weights);
  report.dual_s += seconds_since(t0);
  return dual;
}

// --- The primal basis Theta, the POD modes enriched with one supremizer per dual generator
// (registered cone: with the compressed supremizers of its generators at the training supports).
Eigen::MatrixXd primal_basis_step(const io::SnapshotSet& set, const ReferenceTerms& ref, const PODResult& pod_result,
                                  const DualSnapshots& dual_snapshots, const DualConeResult& dual,
                                  const model::Registration* registration, const OfflineSettings& settings,
                                  OfflineReport& report) {
  Eigen::MatrixXd Theta = pod_result.basis;
  if (settings.supremizers) {
    const auto t0 = Clock::now();
    if (registration != nullptr) {
      report.N_supremizers = enrich_with_registered_supremizers(Theta, ref.inner, set, dual_snapshots.kept,
                                                                *registration, ref.global_to_free);
    } else {
      report.N_supremizers = enrich_with_supremizers(Theta, ref.inner, set, dual_snapshots.kept, dual,
                                                     dual_snapshots.Lambda, dual_snapshots.weights, ref.global_to_free);
    }
    report.supremizer_s = seconds_since(t0);
  }
  report.N = static_cast<int>(Theta.cols());
  return Theta;
}

// --- The primal basis by extension (OfflineSettings::extend_basis), grown snapshot by snapshot.
// What a cache keeps of it: the snapshots it was grown from and the basis in growth order.
struct BasisExtension {
  std::vector<Eigen::VectorXd> u0;   // the snapshots' u_0, in set order
  std::vector<int> rows;             // the kept rows that have their supremizer, ascending
  Eigen::MatrixXd Theta;             // n_free x N, M-orthonormal, in growth order
  std::vector<char> supremizer;      // per column of Theta: a supremizer, else a snapshot's component
  std::unique_ptr<fem::SparseCholesky> chol;  // of M, for the supremizers
  // (49)'s Theta' A_j,00 Theta in growth order, for the first `projected` basis vectors.
  std::vector<Eigen::MatrixXd> A_growth;
  int projected = 0;
  void clear() {
    u0.clear();
    rows.clear();
    Theta.resize(0, 0);
    supremizer.clear();
    A_growth.clear();
    projected = 0;
  }
};

// The basis of `set` with its growth order mapped to Theta's columns, and how many of its
// leading vectors the cache held already (the estimate reuses their split columns).
struct ExtendedBasis {
  Eigen::MatrixXd Theta;   // snapshot components first, then supremizers (N_supremizers's layout)
  std::vector<int> order;  // Theta's column n is basis vector order[n] in growth order
  int reused = 0;
};

// Appends v M-orthogonalized against Theta (Gram-Schmidt twice, M-normalized), unless its M-norm
// falls below kExtensionDependence of its own. Returns whether it was appended.
bool append_orthonormal(Eigen::MatrixXd& Theta, Eigen::VectorXd v, const Eigen::SparseMatrix<double>& M) {
  const double norm0 = std::sqrt(std::max(0.0, v.dot(M * v)));
  if (norm0 <= 0.0) return false;
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::VectorXd Mv = M * v;
    v -= Theta * (Theta.transpose() * Mv);
  }
  const double norm = std::sqrt(std::max(0.0, v.dot(M * v)));
  if (norm <= kExtensionDependence * norm0) return false;
  Theta.conservativeResize(v.size(), Theta.cols() + 1);
  Theta.col(Theta.cols() - 1) = v / norm;
  return true;
}

// The supremizer of row `row` of snapshot p: M^-1 P' E_c' K_p(row, :)' (free DOFs).
Eigen::VectorXd row_supremizer(const fem::SparseCholesky& chol, const io::SnapshotSet& set, int p, int row,
                               const std::vector<int>& global_to_free) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(chol.rows());
  for (io::SnapshotRows::InnerIterator it(set.snapshots[sz(p)].K, row); it; ++it) {
    const int fi = global_to_free[sz(set.contact_dofs[sz(it.col())])];
    if (fi >= 0) b(fi) += it.value();
  }
  return chol.solve(b);
}

// The cache's basis when it was grown from the set's leading snapshots, else cleared. Returns
// the number of basis vectors kept.
int reusable_extension(const io::SnapshotSet& set, const std::vector<int>& kept, BasisExtension& ext) {
  bool same = ext.u0.size() <= set.snapshots.size();
  for (std::size_t p = 0; same && p < ext.u0.size(); ++p) {
    const Eigen::VectorXd& u0 = set.snapshots[p].u0;
    same = u0.size() == ext.u0[p].size() && (u0.array() == ext.u0[p].array()).all();
  }
  same = same && std::includes(kept.begin(), kept.end(), ext.rows.begin(), ext.rows.end());
  if (!same) ext.clear();
  return static_cast<int>(ext.Theta.cols());
}

// Grows the cache's basis by the set's snapshots it does not hold: each one's u_0, then the
// supremizers of the kept rows it is the first to activate (row_cone.hpp: the rows' snapshots).
ExtendedBasis extended_basis_step(const io::SnapshotSet& set, const ReferenceTerms& ref, const std::vector<int>& kept,
                                  const OfflineSettings& settings, BasisExtension& ext, OfflineReport& report) {
  const auto t0 = Clock::now();
  ExtendedBasis out;
  out.reused = reusable_extension(set, kept, ext);
  if (!ext.chol && settings.supremizers) {
    ext.chol = std::make_unique<fem::SparseCholesky>();
    require(ext.chol->compute(ref.inner) == fem::FactorStatus::Success,
            "offline: the inner-product matrix is not positive definite (supremizers)");
  }
  if (ext.Theta.rows() != ix(set.free_dofs.size())) ext.Theta.resize(ix(set.free_dofs.size()), 0);
  for (std::size_t p = ext.u0.size(); p < set.snapshots.size(); ++p) {
    const io::Snapshot& snap = set.snapshots[p];
    if (append_orthonormal(ext.Theta, snap.u0, ref.inner)) ext.supremizer.push_back(0);
    ext.u0.push_back(snap.u0);
    std::vector<int> first_active;
    std::set_difference(kept.begin(), kept.end(), ext.rows.begin(), ext.rows.end(), std::back_inserter(first_active));
    first_active.erase(std::remove_if(first_active.begin(), first_active.end(),
                                      [&](int r) { return !(snap.lambda(r) > 0.0); }),
                       first_active.end());
    for (int r : first_active) {
      if (settings.supremizers &&
          append_orthonormal(ext.Theta, row_supremizer(*ext.chol, set, static_cast<int>(p), r, ref.global_to_free),
                             ref.inner)) {
        ext.supremizer.push_back(1);
      }
    }
    std::vector<int> rows;
    std::set_union(ext.rows.begin(), ext.rows.end(), first_active.begin(), first_active.end(), std::back_inserter(rows));
    ext.rows = std::move(rows);
  }
  for (int pass : {0, 1}) {  // snapshot components first, supremizers last
    for (std::size_t i = 0; i < ext.supremizer.size(); ++i) {
      if (ext.supremizer[i] == pass) out.order.push_back(static_cast<int>(i));
    }
  }
  out.Theta.resize(ext.Theta.rows(), ext.Theta.cols());
  for (std::size_t n = 0; n < out.order.size(); ++n) out.Theta.col(ix(n)) = ext.Theta.col(out.order[n]);
  report.N = static_cast<int>(out.Theta.cols());
  report.N_supremizers = static_cast<int>(std::count(ext.supremizer.begin(), ext.supremizer.end(), 1));
  report.N_pod = report.N - report.N_supremizers;
  report.supremizer_s = seconds_since(t0);
  return out;
}

// --- (T1) EIM of kappa, K(u(mu)) on the kept rows and the contact DOFs, flattened.
EIMResult eim_kappa_step(const io::SnapshotSet& set, const std::vector<int>& kept, const OfflineSettings& settings,
                         OfflineReport& report) {
  const auto t0 = Clock::now();
  // The row and registered cones are solved on the exact contact rows only (ContactRows::Eim is
  // refused online), so their models carry no EIM of kappa: the flattened kept rows of every
  // training K are R_kept n_c P numbers (4.2 GB a copy on hertz-a level 7), and on the greedy's
  // steps the EIM and its estimate terms were about half of each build.
  if (solved_on_exact_rows(settings)) {
    EIMResult none;
    none.Q.resize(ix(kept.size()) * ix(set.contact_dofs.size()), 0);
    report.Mk = 0;
    report.eim_kappa_status = "not built: the cone is solved on the exact contact rows";
    report.eim_kappa_s = seconds_since(t0);
    return none;
  }
  std::vector<Eigen::MatrixXd> Ks;
  Ks.reserve(set.snapshots.size());
  for (const io::Snapshot& s : set.snapshots) Ks.push_back(restrict_rows(s.K, kept));
  EIMSettings ek;
  ek.tolerance = settings.eps_eim_k;
  ek.relative = settings.eps_eim_k_relative;
  ek.max_size = settings.eim_k_size;
  EIMResult eim_k = eim(flatten_columns(Ks), ek);
  // M^k = 0 makes D^kappa (54) zero: every online solve would fail (the primal space would not
  // see the contact). Refuse the model rather than write it.
  require(eim_k.size() >= 1, "offline: the EIM of the contact map kappa kept no function (M^k = 0: eps_eim_k = " +
                                 number_text(settings.eps_eim_k) + " is above max |kappa| = " +
                                 number_text(eim_k.errors.empty() ? 0.0 : eim_k.errors.front()) +
                                 " on the training set, or eim_k_size = 0); lower eps_eim_k");
  report.Mk = eim_k.size();
  report.eim_kappa_errors = eim_k.errors;
  report.eim_kappa_status = eim_status(eim_k);
  report.eim_kappa_threshold = eim_k.threshold;
  report.eim_kappa_s = seconds_since(t0);
  return eim_k;
}

// --- (T1) EIM of gamma = g - K u_D(mu) on the kept rows.
EIMResult eim_gamma_step(const io::SnapshotSet& set, const ReferenceTerms& ref, const std::vector<int>& kept,
                         const OfflineSettings& settings, OfflineReport& report) {
  const auto t0 = Clock::now();
  const int P = static_cast<int>(set.snapshots.size());
  Eigen::MatrixXd G(ix(kept.size()), P);
  for (int p = 0; p < P; ++p) {
    const io::Snapshot& s = set.snapshots[sz(p)];
    G.col(p) = restrict_rows(Eigen::VectorXd(s.g - s.K * lift_at(ref.lift_c, ref.thetas, s.mu)), kept);
  }
  EIMSettings eg;
  eg.tolerance = settings.eps_eim_g;
  eg.relative = settings.eps_eim_g_relative;
  eg.max_size = settings.eim_g_size;
  EIMResult eim_g = eim(G, eg);
  // M^g = 0 replaces gamma by 0: accepted only when gamma vanishes on the whole training set up
  // to the round-off of the geometry (e.g. a flat patch test, initially touching, 2e-33).
  const double gamma_max = eim_g.errors.empty() ? 0.0 : eim_g.errors.front();
  double extent = 0.0;  // largest reference coordinate
  for (const auto& x : ref.mesh.nodes) extent = std::max(extent, x.cwiseAbs().maxCoeff());
  require(eim_g.size() >= 1 || gamma_max <= kGapRoundoff * extent,
          "offline: the EIM of the gap gamma kept no function (M^g = 0: eps_eim_g = " +
              number_text(settings.eps_eim_g) + " is above max |gamma| = " + number_text(gamma_max) +
              " on the training set, or eim_g_size = 0), so the reduced gap would be 0; lower eps_eim_g");
  report.Mg = eim_g.size();
  report.eim_gamma_errors = eim_g.errors;
  report.eim_gamma_status = eim_status(eim_g);
  report.eim_gamma_threshold = eim_g.threshold;
  report.eim_gamma_s = seconds_since(t0);
  return eim_g;
}

// --- The reduced arrays. The provenance and the settings the model was built with.
void record_provenance(const io::SnapshotSet& set, const cases::CaseSpec& spec, const OfflineSettings& settings,
                       const cases::AffineThetas& thetas, ReducedModel& m) {
  m.case_name = set.case_name;
  m.case_kind = set.case_kind;
  m.case_spec = set.case_spec;
  m.level = set.level;
  m.parameters = spec.parameters;
  m.thetas = thetas;
  m.inner_product = to_string(settings.inner_product);
  m.dual_method = to_string(settings.dual_method);
  m.eps_pod = settings.eps_pod;
  m.eps_pod_relative = settings.eps_pod_relative;
  m.eps_du = settings.eps_du;
  m.eps_du_relative = settings.eps_du_relative;
  m.eps_eim_k = settings.eps_eim_k;
  m.eps_eim_k_relative = settings.eps_eim_k_relative;
  m.eps_eim_g = settings.eps_eim_g;
  m.eps_eim_g_relative = settings.eps_eim_g_relative;
  m.compression = settings.compression;
  m.kacanov_alpha = set.kacanov_alpha;
  m.kacanov_tolerance = set.kacanov_tolerance;
  m.kacanov_max_iterations = set.kacanov_max_iterations;
}

// (49)'s stiffness terms Theta' A_j,00 Theta of an extension build: the cache's terms of the
// basis vectors it held, bordered by the new vectors' rows and columns (products with the new
// columns only: the basis vectors already held are the same bits), then in Theta's layout.
std::vector<Eigen::MatrixXd> extended_stiffness_terms(const ReferenceTerms& ref, const ExtendedBasis& extension,
                                                      BasisExtension& ext) {
  const Index N = ext.Theta.cols(), Ja = ix(ref.A00.size());
  if (ext.projected > extension.reused || ix(ext.A_growth.size()) != Ja) {
    ext.A_growth.assign(sz(static_cast<int>(Ja)), Eigen::MatrixXd(0, 0));
    ext.projected = 0;
  }
  const Index old = ext.projected, fresh = N - old;
  std::vector<Eigen::MatrixXd> out;
  for (Index j = 0; j < Ja; ++j) {
    Eigen::MatrixXd& Ag = ext.A_growth[sz(static_cast<int>(j))];
    if (fresh > 0) {
      const Eigen::MatrixXd B = ext.Theta.transpose() * (ref.A00[sz(static_cast<int>(j))] * ext.Theta.rightCols(fresh));
      Ag.conservativeResize(N, N);
      Ag.rightCols(fresh) = B;
      Ag.bottomLeftCorner(fresh, old) = B.topRows(old).transpose();
      Ag.bottomRightCorner(fresh, fresh) = 0.5 * (B.bottomRows(fresh) + B.bottomRows(fresh).transpose());
    }
    Eigen::MatrixXd Ah(N, N);
    for (Index c = 0; c < N; ++c) {
      const int oc = extension.order[sz(static_cast<int>(c))];
      for (Index r = 0; r < N; ++r) Ah(r, c) = Ag(extension.order[sz(static_cast<int>(r))], oc);
    }
    out.push_back(std::move(Ah));
  }
  ext.projected = static_cast<int>(N);
  return out;
}

// (49): A_hat_j = Theta' A_j,00 Theta and f_hat_j = Theta' f_j on the free DOFs, and the lift
// terms u_D(mu) enters through (A_j u_D,k, f_j . u_D,k, u_D,l . A_j u_D,k); the stiffness terms
// given (`A_hat`, an extension build's: extended_stiffness_terms) or projected here.
void project_affine_terms(const ReferenceTerms& ref, const Eigen::MatrixXd& Theta, const std::vector<int>& free_dofs,
                          std::optional<std::vector<Eigen::MatrixXd>> A_hat, ReducedModel& m) {
  const cases::AffineTerms& terms = ref.terms;
  const int Ja = static_cast<int>(terms.A.size());
  const int Jf = static_cast<int>(terms.f.size());
  const int JD = static_cast<int>(terms.lift.size());
  if (A_hat) {
    m.A_hat = std::move(*A_hat);
  } else {
    for (int j = 0; j < Ja; ++j) {
      Eigen::MatrixXd Ah = Theta.transpose() * (ref.A00[sz(j)] * Theta);
      m.A_hat.push_back(0.5 * (Ah + Ah.transpose()));
    }
  }
  for (int j = 0; j < Jf; ++j) m.f_hat.push_back(Theta.transpose() * restrict_to(terms.f[sz(j)], free_dofs));
  for (int j = 0; j < Ja; ++j) {
    for (int k = 0; k < JD; ++k) {
      const Eigen::VectorXd Al = terms.A[sz(j)] * terms.lift[sz(k)];
      m.A_lift_hat.push_back(Theta.transpose() * restrict_to(Al, free_dofs));
      for (int l = 0; l < JD; ++l) m.lift_AA.push_back(terms.lift[sz(l)].dot(Al));
    }
  }
  for (int j = 0; j < Jf; ++j) {
    for (int k = 0; k < JD; ++k) m.lift_f.push_back(terms.f[sz(j)].dot(terms.lift[sz(k)]));
  }
}

// --- The registered cone (offline/registration.hpp): the training pressures registered on their
// supports, their CPG cone, and the data that predict the support online.
void registration_step(const io::SnapshotSet& set, const cases::CaseSpec& spec, const OfflineSettings& settings,
                       const DualSnapshots& dual_snapshots, ReducedModel& m, OfflineReport& report) {
  const auto t0 = Clock::now();
  Eigen::MatrixXd training_mu(ix(spec.parameters.size()), ix(set.snapshots.size()));
  for (std::size_t p = 0; p < set.snapshots.size(); ++p) training_mu.col(ix(p)) = set.snapshots[p].mu;
  DualConeSettings ds;
  ds.greedy.tolerance = settings.eps_du;
  ds.greedy.relative = settings.eps_du_relative;
  ds.greedy.max_size = settings.dual_size;
  RegistrationResult r = build_registration(m.surface, dual_snapshots.kept, dual_snapshots.Lambda, training_mu,
                                            spec.parameters, ds);
  m.registration = std::move(r.registration);
  // The report's dual cone is the registered one (the model's R_max stays the kept rows').
  report.R = m.registration.R();
  report.dual_errors = r.cone.errors;
  report.dual_relative_errors = r.cone.relative_errors;
  report.dual_status = to_string(r.cone.status);
  report.dual_condition_number = generator_condition_number(m.registration.generators, {});
  report.dual_s += seconds_since(t0);
}

// The contact surface: its nodes chained in ascending global index, their two DOFs in that order
// in set.contact_dofs (checked).
ContactSurface contact_surface(const io::SnapshotSet& set, const mesh::Mesh& reference) {
  std::vector<int> nodes = set.slave;
  nodes.insert(nodes.end(), set.master.begin(), set.master.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  require(2 * nodes.size() == set.contact_dofs.size(),
          "offline: " + std::to_string(set.contact_dofs.size()) + " contact DOFs for " + std::to_string(nodes.size()) +
              " contact nodes (expected both components of each)");
  std::map<int, int> local;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    require(set.contact_dofs[2 * i] == 2 * nodes[i] && set.contact_dofs[2 * i + 1] == 2 * nodes[i] + 1,
            "offline: contact_dofs are not the two components of the ascending contact nodes");
    local[nodes[i]] = static_cast<int>(i);
  }
  ContactSurface surf;
  std::map<int, int> slave_set;
  for (int s : set.slave) slave_set[s] = 1;
  for (int node : nodes) {
    surf.reference_nodes.push_back(reference.nodes[sz(node)]);
    surf.body.push_back(slave_set.count(node) ? mesh::kSlaveBody : mesh::kMasterBody);
  }
  for (int s : set.slave) surf.slave.push_back(local[s]);
  for (int s : set.master) surf.master.push_back(local[s]);
  surf.discretization = contact::discretization_from_string(set.constraint);
  surf.num_constraints = static_cast<int>(set.snapshots.front().lambda.size());
  return surf;
}

// The contact arrays: Theta on the contact DOFs, the dual cone Xi, C^kappa_j (55) and
// D^gamma = Xi' Q^gamma (B^gamma)^-1 (54), whose inverse is applied online.
void contact_arrays(const io::SnapshotSet& set, const ReferenceTerms& ref, const Eigen::MatrixXd& Theta,
                    const std::vector<int>& kept, const Eigen::MatrixXd& Xi, const EIMResult& eim_k,
                    const EIMResult& eim_g, ReducedModel& m) {
  const int n_c = static_cast<int>(set.contact_dofs.size());
  const int R_kept = static_cast<int>(kept.size());
  m.Theta_c = Eigen::MatrixXd::Zero(n_c, Theta.cols());
  for (int i = 0; i < n_c; ++i) {
    const int fi = ref.global_to_free[sz(set.contact_dofs[sz(i)])];
    if (fi >= 0) m.Theta_c.row(i) = Theta.row(fi);
  }
  m.lift_c = ref.lift_c;
  m.kept_rows = kept;
  m.Xi = Xi;
  for (int j = 0; j < eim_k.size(); ++j) {
    const auto rn = unflatten_index(eim_k.magic_points[sz(j)], n_c);
    m.kappa_row.push_back(rn.first);
    m.kappa_dof.push_back(rn.second);
    const Eigen::MatrixXd Qj = unflatten_column(eim_k.Q.col(j), R_kept, n_c);
    m.C_kappa.push_back(Xi.transpose() * (Qj * m.Theta_c));  // (55): C_j = Xi' Q_j Theta_c
  }
  m.B_kappa = eim_k.B;
  m.eim_kappa_errors = eim_k.errors;
  m.gamma_row = eim_g.magic_points;
  m.B_gamma = eim_g.B;
  m.XiQ_gamma = Xi.transpose() * eim_g.Q;
  m.eim_gamma_errors = eim_g.errors;
}

// --- The a posteriori error estimate's offline data (error_estimate.hpp).
EstimateData estimate_data_step(const io::SnapshotSet& set, const cases::CaseSpec& spec, const ReferenceTerms& ref,
                                const Eigen::MatrixXd& Theta, const ReducedModel& m,
                                const DualSnapshots& dual_snapshots, const EIMResult& eim_k, const EIMResult& eim_g,
                                EstimateBase* base, const ExtendedBasis* extension) {
  return build_estimate_data({&ref.terms, &ref.thetas, cases::reference_mu(spec.parameters), &set.free_dofs,
                              &set.contact_dofs, &Theta, &m.Theta_c, &m.Xi, &eim_k.Q, &eim_g.Q, &set,
                              &dual_snapshots.kept, &ref.lift_c, &dual_snapshots.weights, &eim_k.magic_points,
                              &eim_k.B, &eim_g.magic_points, &eim_g.B, &m.surface, base,
                              extension ? &extension->order : nullptr, extension ? extension->reused : 0});
}

// The training points and their coordinates. Theta is M-orthonormal, so Theta' M u_0 are the
// projection coefficients: the initial guess where the reduced solve below does not converge.
void training_coordinates(const Eigen::MatrixXd& Theta, const Eigen::SparseMatrix<double>& inner,
                          const PrimalSnapshots& primal, const io::SnapshotSet& set, ReducedModel& m) {
  const int P = static_cast<int>(set.snapshots.size());
  m.training_u_hat = Theta.transpose() * (inner * primal.U0);
  m.training_lambda_hat = Eigen::MatrixXd::Zero(m.R_max, P);
  m.training_mu.resize(ix(m.parameters.size()), P);
  for (int p = 0; p < P; ++p) m.training_mu.col(p) = set.snapshots[sz(p)].mu;
}

// The online initial guess (OnlineSettings::initial_guess): the reduced solutions at the training
// values, P online solves: from zero, or (`guess` Interpolated, extension builds) from the
// projection coefficients just stored, which the reduced Newton refines in a few steps (a greedy
// solves every training value again at each step, and from zero these solves cost more than the
// rest of the build on finer meshes).
void solve_at_training_values(ReducedModel& m, InitialGuess guess) {
  OnlineSolver solver(m);
  OnlineSettings cold;
  cold.initial_guess = guess;
  cold.error_estimate = false;  // only u_hat and lambda_hat are kept
  for (Index p = 0; p < m.training_mu.cols(); ++p) {
    const OnlineSolution sol = solver.solve(m.training_mu.col(p), cold);
    if (!sol.converged()) continue;
    m.training_u_hat.col(p) = sol.u_hat;
    m.training_lambda_hat.col(p).head(sol.lambda_hat.size()) = sol.lambda_hat;
  }
}

// The HF-size data that reconstruct a field from (u_hat, lambda_hat) (reconstruction.hpp).
ReducedReconstruction reconstruction_data(const io::SnapshotSet& set, const ReferenceTerms& ref,
                                          const Eigen::MatrixXd& Theta, const ReducedModel& m) {
  ReducedReconstruction rec;
  rec.num_dofs = set.num_dofs;
  rec.free_dofs = set.free_dofs;
  rec.Theta = Theta;
  rec.lift = ref.terms.lift;
  rec.thetas = ref.thetas;
  rec.kept_rows = m.kept_rows;
  rec.num_constraints = m.surface.num_constraints;
  rec.Xi = m.Xi;
  rec.registration = m.registration;
  rec.mesh = ref.mesh;
  return rec;
}

}  // namespace

namespace {
// d u_hat / d mu at a training point whose online solution is `at`: one-sided differences of the
// online solution, started from `at`, with steps of kSensitivityStep of each parameter's range
// (backward at the upper bound). Measured on hertz-3p: steps 1e-4 to 1e-2 give the same start
// quality; a parameter of zero range, or a solve that does not converge, gives a zero column.
constexpr double kSensitivityStep = 1e-3;
Eigen::MatrixXd u_sensitivity(const ReducedModel& m, OnlineSolver& solver, const cases::Mu& mu, const OnlineSolution& at) {
  const Index p = m.num_parameters();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m.N_max, p);
  OnlineSettings settings;
  settings.error_estimate = false;
  Eigen::VectorXd start(at.u_hat.size() + at.lambda_hat.size());
  start << at.u_hat, at.lambda_hat;
  settings.start = start;
  for (Index k = 0; k < p; ++k) {
    const cases::ParameterSpec& q = m.parameters[sz(static_cast<int>(k))];
    double h = kSensitivityStep * (q.max - q.min);
    if (!(h > 0.0)) continue;
    if (mu(k) + h > q.max) h = -h;
    cases::Mu shifted = mu;
    shifted(k) += h;
    const OnlineSolution s = solver.solve(shifted, settings);
    if (s.converged()) S.col(k) = (s.u_hat - at.u_hat) / h;
  }
  return S;
}
}  // namespace

namespace {
// work(solver, i) for i = 0 .. count - 1, shared out round-robin over `threads` threads, each with
// its own OnlineSolver of m.
void for_each_point(const ReducedModel& m, Index count, int threads,
                    const std::function<void(OnlineSolver&, Index)>& work) {
  const Index T = std::max<Index>(1, std::min<Index>(threads, count));
  run_threads(static_cast<std::size_t>(T), [&](std::size_t t) {
    OnlineSolver solver(m);
    for (Index i = static_cast<Index>(t); i < count; i += T) work(solver, i);
  });
}
}  // namespace

void add_training_jacobians(ReducedModel& m, int threads) {
  m.training_jacobian.resize(0, 0);
  m.training_u_sensitivity.resize(0, 0);
  // The registered cone's steps cost a thousand times more on the fine meshes it is for.
  if (m.dual_method != model::kRowCone || m.N_max > model::kMaxJacobianN || m.training_mu.cols() == 0) return;
  const Index n = m.N_max, p = m.num_parameters();
  // p = 1 starts from the linear interpolation of two training values, already first order.
  const bool sensitivities = p > 1;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n * m.training_mu.cols());
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, sensitivities ? p * m.training_mu.cols() : 0);
  for_each_point(m, m.training_mu.cols(), threads, [&](OnlineSolver& solver, Index i) {
    OnlineSettings settings;
    settings.error_estimate = false;
    // From the stored answer at the point (converged there: one step).
    Eigen::VectorXd start(n + m.R_max);
    start << m.training_u_hat.col(i), m.training_lambda_hat.col(i);
    settings.start = std::move(start);
    const OnlineSolution sol = solver.solve(m.training_mu.col(i), settings);
    if (!sol.converged()) return;
    J.middleCols(i * n, n) = solver.linearized_fixed_point_jacobian(m.training_mu.col(i), sol.u_hat, sol.lambda_hat);
    if (sensitivities) S.middleCols(i * p, p) = u_sensitivity(m, solver, m.training_mu.col(i), sol);
  });
  m.training_jacobian = std::move(J);
  m.training_u_sensitivity = std::move(S);
}

namespace {
// Farthest-first choice of `count` candidates away from `fixed` (columns, scaled coordinates).
std::vector<std::size_t> farthest_first(const Eigen::MatrixXd& fixed, const Eigen::MatrixXd& candidates, Index count) {
  Eigen::VectorXd d2 = Eigen::VectorXd::Constant(candidates.cols(), std::numeric_limits<double>::infinity());
  for (Index f = 0; f < fixed.cols(); ++f) d2 = d2.cwiseMin((candidates.colwise() - fixed.col(f)).colwise().squaredNorm().transpose());
  std::vector<std::size_t> chosen;
  while (ix(chosen.size()) < count) {
    Index best = 0;
    if (!(d2.maxCoeff(&best) > 0.0)) break;  // every candidate is a point already held
    chosen.push_back(sz(static_cast<int>(best)));
    d2 = d2.cwiseMin((candidates.colwise() - candidates.col(best)).colwise().squaredNorm().transpose());
  }
  return chosen;
}
}  // namespace

void add_preconditioner_points(ReducedModel& m, const std::vector<cases::Mu>& candidates, int total, int threads) {
  const Index held = m.training_mu.cols(), p = m.num_parameters();
  if (m.dual_method != model::kRowCone || m.N_max > model::kMaxJacobianN || total <= held || candidates.empty()) return;
  Eigen::MatrixXd C(p, ix(candidates.size()));
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    require(candidates[c].size() == p, "add_preconditioner_points: a candidate of the wrong size");
    C.col(ix(c)) = candidates[c];
  }
  const cases::UnitBox box = cases::unit_box(m.parameters);
  const std::vector<std::size_t> chosen = farthest_first(box(m.training_mu), box(C), total - held);
  std::vector<std::optional<OnlineSolution>> answers(chosen.size());
  for_each_point(m, ix(chosen.size()), threads, [&](OnlineSolver& solver, Index k) {
    OnlineSettings settings;
    settings.error_estimate = false;  // only u_hat and lambda_hat are kept
    answers[sz(static_cast<int>(k))] = solver.solve(candidates[chosen[sz(static_cast<int>(k))]], settings);
  });
  std::vector<std::pair<std::size_t, OnlineSolution>> solved;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    if (answers[k]->converged()) solved.emplace_back(chosen[k], std::move(*answers[k]));
  }
  const Index P = held + ix(solved.size());
  m.training_mu.conservativeResize(Eigen::NoChange, P);
  m.training_u_hat.conservativeResize(Eigen::NoChange, P);
  m.training_lambda_hat.conservativeResize(Eigen::NoChange, P);
  for (std::size_t k = 0; k < solved.size(); ++k) {
    const Index col = held + ix(k);
    m.training_mu.col(col) = candidates[solved[k].first];
    m.training_u_hat.col(col) = solved[k].second.u_hat;
    m.training_lambda_hat.col(col).setZero();
    m.training_lambda_hat.col(col).head(solved[k].second.lambda_hat.size()) = solved[k].second.lambda_hat;
  }
  if (!solved.empty()) {  // one block per point: add_training_jacobians
    m.training_jacobian.resize(0, 0);
    m.training_u_sensitivity.resize(0, 0);
  }
}

// What a greedy's builds share (offline_builder.hpp), valid for one case, level, discretization
// and inner product: the first build fills it, the next ones check that their set is of the same
// problem and reuse it.
struct OfflineBuildCache::Parts {
  bool matches(const io::SnapshotSet& set, const cases::CaseSpec& spec, InnerProduct product) const {
    return ref.has_value() && case_name == spec.name && level == set.level && constraint == set.constraint &&
           this->product == product && num_dofs == set.num_dofs && free_dofs == set.free_dofs &&
           contact_dofs == set.contact_dofs;
  }
  std::string case_name, constraint;
  int level = -1, num_dofs = -1;
  InnerProduct product = InnerProduct::Energy;
  std::vector<int> free_dofs, contact_dofs;
  std::optional<ReferenceTerms> ref;
  EstimateBase estimate;
  GeometricRatios geometric;
  BasisExtension basis;
  std::optional<PODWeight> pod_weight;  // of ref->inner
};

OfflineBuildCache::OfflineBuildCache() : parts_(std::make_unique<Parts>()) {}
OfflineBuildCache::~OfflineBuildCache() = default;
void OfflineBuildCache::add_geometric_ratio(const cases::Mu& mu, double eta) {
  parts_->geometric.emplace_back(mu, eta);
}

namespace {

// The reference terms of `set`: from the cache when it holds this problem's, else assembled (and
// the cache, if any, restarted on this problem).
const ReferenceTerms& cached_reference_terms(const io::SnapshotSet& set, const cases::CaseSpec& spec,
                                             InnerProduct product, OfflineReport& report,
                                             OfflineBuildCache::Parts& parts) {
  if (parts.matches(set, spec, product)) return *parts.ref;
  parts.estimate.factored = false;
  parts.estimate.columns_built = false;
  parts.estimate.pad_nodes = 0;
  parts.estimate.contact_columns.clear();
  if (parts.ref) parts.geometric.clear();  // another problem's (those given before the first build are this one's)
  parts.basis.clear();
  parts.basis.chol.reset();
  parts.pod_weight.reset();
  parts.ref = assemble_reference_terms(set, spec, product, report);
  parts.case_name = spec.name;
  parts.constraint = set.constraint;
  parts.level = set.level;
  parts.num_dofs = set.num_dofs;
  parts.product = product;
  parts.free_dofs = set.free_dofs;
  parts.contact_dofs = set.contact_dofs;
  return *parts.ref;
}

}  // namespace

bool solved_on_exact_rows(const OfflineSettings& settings) {
  return settings.dual_method == DualConeMethod::Rows || settings.dual_method == DualConeMethod::Registered;
}

const char* to_string(InnerProduct p) { return p == InnerProduct::Energy ? "energy" : "h1"; }

void check_settings(const OfflineSettings& s) {
  require(std::isfinite(s.eps_pod) && s.eps_pod >= 0.0, "offline: eps_pod must be >= 0, got " + number_text(s.eps_pod));
  require(s.pod_modes >= -1 && s.pod_modes != 0, "offline: pod_modes must be -1 (by eps_pod) or >= 1, got " +
                                                    std::to_string(s.pod_modes));
  require(std::isfinite(s.eps_du) && s.eps_du >= 0.0, "offline: eps_du must be >= 0, got " + number_text(s.eps_du));
  require(s.dual_size >= -1 && s.dual_size != 0, "offline: dual_size must be -1 or >= 1, got " +
                                                    std::to_string(s.dual_size));
  require(std::isfinite(s.eps_eim_k) && s.eps_eim_k >= 0.0, "offline: eps_eim_k must be >= 0");
  require(std::isfinite(s.eps_eim_g) && s.eps_eim_g >= 0.0, "offline: eps_eim_g must be >= 0");
  require(s.eim_k_size >= -1 && s.eim_g_size >= -1, "offline: EIM sizes must be >= -1");
  require(!s.extend_basis || (s.dual_method == DualConeMethod::Rows && s.compression),
          "offline: the primal basis by extension needs the row cone and the constraint compression");
}

// The offline stage, paper Section 5 (docs/theory.md, "POD, dual cones, EIM"): (T2) POD,
// (T3) dual cone, (T1) EIM of kappa and gamma, then the arrays (49), (54)-(55) of Algorithm 1.
OfflineResult build_reduced_model(const io::SnapshotSet& set, const cases::CaseSpec& spec,
                                  const OfflineSettings& settings, OfflineBuildCache* cache) {
  const auto t_total = Clock::now();
  check_settings(settings);
  check_set_matches_case(set, spec);
  check_distinct_training_values(set);
  check_snapshot_sizes(set);

  OfflineResult out;
  OfflineReport& rep = out.report;
  OfflineBuildCache own;
  OfflineBuildCache::Parts& parts = cache ? *cache->parts_ : *own.parts_;
  const ReferenceTerms& ref = cached_reference_terms(set, spec, settings.inner_product, rep, parts);
  const PrimalSnapshots primal = pod_step(set, ref.inner, settings, rep, parts.pod_weight);  // (T2)
  const DualSnapshots dual_snapshots = compression_step(set, settings, rep);  // Remark 7
  const DualConeResult dual = dual_cone_step(dual_snapshots, settings, rep);  // (T3)
  ReducedModel& m = out.model;
  m.surface = contact_surface(set, ref.mesh);
  if (settings.dual_method == DualConeMethod::Registered) registration_step(set, spec, settings, dual_snapshots, m, rep);
  std::optional<ExtendedBasis> extension;
  if (settings.extend_basis) extension = extended_basis_step(set, ref, dual_snapshots.kept, settings, parts.basis, rep);
  const Eigen::MatrixXd Theta =
      extension ? std::move(extension->Theta)
                : primal_basis_step(set, ref, primal.pod, dual_snapshots, dual,
                                    m.registration.empty() ? nullptr : &m.registration, settings, rep);
  const EIMResult eim_k = eim_kappa_step(set, dual_snapshots.kept, settings, rep);  // (T1)
  const EIMResult eim_g = eim_gamma_step(set, ref, dual_snapshots.kept, settings, rep);  // (T1)

  const auto t0 = Clock::now();
  record_provenance(set, spec, settings, ref.thetas, m);
  m.N_max = rep.N;
  m.N_supremizers = rep.N_supremizers;
  m.R_max = m.registration.empty() ? rep.R : rep.R_kept;
  m.Mk_max = rep.Mk;
  m.Mg_max = rep.Mg;
  m.singular_values = primal.pod.singular_values;
  project_affine_terms(ref, Theta, set.free_dofs,
                       extension ? std::optional(extended_stiffness_terms(ref, *extension, parts.basis)) : std::nullopt,
                       m);  // (49)
  contact_arrays(set, ref, Theta, dual_snapshots.kept, dual.generators, eim_k, eim_g, m);  // (54)-(55)
  m.estimate = estimate_data_step(set, spec, ref, Theta, m, dual_snapshots, eim_k, eim_g, &parts.estimate,
                                  extension ? &*extension : nullptr);
  // The row and registered cones are solved on the exact rows, whose estimate has the geometric term.
  if (solved_on_exact_rows(settings)) {
    m.estimate.geometric_ratio = max_geometric_ratio(set, spec, ref.mesh,
                                                     contact::discretization_from_string(set.constraint), &parts.geometric);
  }
  training_coordinates(Theta, ref.inner, primal, set, m);
  check_model(m);
  solve_at_training_values(m, settings.extend_basis ? InitialGuess::Interpolated : InitialGuess::Zero);
  if (settings.training_jacobians) add_training_jacobians(m);
  rep.reduction_s = seconds_since(t0);

  out.reconstruction = reconstruction_data(set, ref, Theta, m);
  rep.total_s = seconds_since(t_total);
  return out;
}

}  // namespace contactrb::offline
