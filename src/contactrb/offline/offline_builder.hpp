#pragma once
// The offline stage (Construction, in rbOOmit's terms): from a snapshot set and its case
// specification to a ReducedModel (paper Section 5: (T1) EIM of gamma and kappa, (T2) POD,
// (T3) dual cone; then the reduced arrays (49), (54)-(55)). Reassembles what it needs (the
// reference mesh, the affine terms) from the CaseSpec; the result holds nothing of HF size
// except contact-surface rows. The HF-size data needed to reconstruct fields are returned
// apart (ReducedReconstruction), for tests, VTU output and error indicators.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::offline {

enum class InnerProduct { Energy, H1 };
const char* to_string(InnerProduct p);  // "energy" | "h1"
InnerProduct inner_product_from_string(const std::string& name);  // throws contactrb::Error

// Every tolerance is relative by default, so that a case gives the same sizes whatever its
// units (docs/cli.md, "`contactrb offline`"); *_relative = false makes one absolute.
struct OfflineSettings {
  // POD (T2): eps_POD on the singular values: relative, keep sigma_i / sigma_1 > eps_pod;
  // absolute, keep sigma_i > eps_pod (in the units of the M-norm of u_0). A fixed N (>= 1)
  // when pod_modes >= 0 (capped at the numerical rank).
  // 3e-5 relative keeps the N of the former default (1e-3 absolute, sigma_1 = 33 and 35) on
  // hertz-a and hertz-b (docs/cli.md, "`contactrb offline`").
  double eps_pod = 1e-6;
  bool eps_pod_relative = true;
  int pod_modes = -1;
  InnerProduct inner_product = InnerProduct::Energy;  // energy: A(reference mu) on the free DOFs
  // Dual cone (T3): eps_DU on the L2(Gamma^c) error (58): relative, each mu's error divided by
  // |lambda(mu)|_Lambda; absolute, the error itself. dual_size >= 0 fixes R.
  DualConeMethod dual_method = DualConeMethod::Rows;
  double eps_du = 1e-3;
  bool eps_du_relative = true;
  int dual_size = -1;
  // EIM (T1): ell-infinity tolerances: relative, to the largest |entry| of the function over
  // the training set (max_mu |kappa(mu)|_inf, max_mu |gamma(mu)|_inf); absolute, the error
  // itself. -1 sizes: no limit but the training set.
  double eps_eim_k = 1e-5;
  bool eps_eim_k_relative = true;
  double eps_eim_g = 1e-5;
  bool eps_eim_g_relative = true;
  int eim_k_size = -1;
  int eim_g_size = -1;
  bool compression = true;  // Remark 7: drop the constraints never active on the training set
  // Supremizer enrichment of the primal basis (Niakh, Ehrlacher, Ern 2022; docs/offline-online.md):
  // after the POD modes, one vector s_r = M^-1 K(u(mu_r))' xi_r per dual generator xi_r (M the
  // inner product above, mu_r the snapshot the generator comes from), M-orthonormalized. Without
  // it the reduced saddle point (53) is not inf-sup stable when R > N and lambda_hat is not
  // determined by the reduced problem.
  bool supremizers = true;
  // The primal basis by extension (the greedy's; docs/offline-online.md, "Greedy sampling"): in
  // place of the POD, each snapshot's u_0 in set order, M-orthogonalized against the basis so far
  // (Gram-Schmidt twice, dropped when its norm falls below kExtensionDependence of its own), each
  // followed by the supremizers of the kept rows it is the first snapshot to activate; the basis is
  // stored snapshot components first, supremizers last. Row cone with compression only. A build
  // given a cache that holds the basis of the set's leading snapshots extends that basis and the
  // estimate's Riesz data (a QR update) instead of rebuilding them.
  bool extend_basis = false;
  // ReducedModel::training_jacobian (add_training_jacobians): the online preconditioner. A greedy
  // builds its steps without it and adds it to the model it returns.
  bool training_jacobians = true;
  // All four tolerances absolute (the paper's reading; the report and the demo use it).
  void set_absolute() { eps_pod_relative = eps_du_relative = eps_eim_k_relative = eps_eim_g_relative = false; }
};
// Throws contactrb::Error naming the first invalid setting.
void check_settings(const OfflineSettings& settings);

// OfflineSettings::extend_basis: a component (snapshot or supremizer) whose M-norm falls below
// this fraction of its own when orthogonalized against the basis adds nothing (round-off).
inline constexpr double kExtensionDependence = 1e-10;

struct OfflineReport {
  Eigen::VectorXd singular_values;  // POD, all P
  int N = 0;          // primal basis size: N_pod + supremizers
  int N_pod = 0;      // POD modes
  int N_supremizers = 0;
  // The absolute thresholds the relative tolerances came to (= the tolerance when absolute):
  // eps_pod sigma_1; eps_eim max |kappa|, max |gamma| (the dual one differs per mu).
  double pod_threshold = 0.0;
  double eim_kappa_threshold = 0.0;
  double eim_gamma_threshold = 0.0;
  int R_hf = 0;       // constraints before compression
  int R_kept = 0;     // after
  int R = 0;  // registered cone: its generators (errors below: of its registered profiles)
  std::vector<double> dual_errors;           // max_mu |lambda - Pi_{K_R} lambda|_Lambda against R
  std::vector<double> dual_relative_errors;
  std::string dual_status;
  double dual_condition_number = 0.0;        // of the generators in the Lambda norm
  int Mk = 0;
  int Mg = 0;
  std::vector<double> eim_kappa_errors;  // against M
  std::vector<double> eim_gamma_errors;
  std::string eim_kappa_status;
  std::string eim_gamma_status;
  // Wall times (s) of each step.
  double assembly_s = 0.0;
  double pod_s = 0.0;
  double supremizer_s = 0.0;
  double dual_s = 0.0;
  double eim_kappa_s = 0.0;
  double eim_gamma_s = 0.0;
  double reduction_s = 0.0;  // the reduced arrays (49), (54)-(55)
  double total_s = 0.0;
};

struct OfflineResult {
  contactrb::model::ReducedModel model;
  contactrb::model::ReducedReconstruction reconstruction;
  OfflineReport report;
};

// Throws contactrb::Error for a set that fails io::check_snapshot_set (an index out of range,
// negative or repeated, inconsistent sizes, a non-finite value: checked before any index is
// used), a set with a failed snapshot or a repeated training value, a set that does not match
// the spec (DOF counts), or invalid settings.
//
// `cache`: what successive builds on growing sets of one case, level and discretization share (a
// greedy's steps): the reference terms, the energy product's factor and the constant residual
// columns of the estimate, and each snapshot's geometric ratio, computed at the first build that
// needs them. The model is the same bits as without it, but for the ratios given to it
// (OfflineBuildCache::add_geometric_ratio: the same to round-off).
class OfflineBuildCache;

// Whether the models of these settings are solved on the exact contact rows only (Rows,
// Registered): they carry no EIM of kappa (M^k = 0) and their estimate has the geometric term
// (geometric_term.hpp).
bool solved_on_exact_rows(const OfflineSettings& settings);
OfflineResult build_reduced_model(const io::SnapshotSet& set, const cases::CaseSpec& spec,
                                  const OfflineSettings& settings = {}, OfflineBuildCache* cache = nullptr);

// ReducedModel::training_jacobian of a finished model (its training points and reduced
// solutions): the Jacobian of the reduced Kacanov map at each training point, for the row cone
// up to model::kMaxJacobianN (empty otherwise; a training value whose reduced solve does not
// converge keeps a zero block, the plain step there), from the linearized step
// (OnlineSolver::linearized_fixed_point_jacobian): one KKT system per point. With p > 1
// parameters also ReducedModel::training_u_sensitivity, by one-sided differences of the online
// solution (p more online solves per training point, each started from its answer). The points
// are shared out over `threads` threads, one OnlineSolver each (each point's blocks are its own:
// the result does not depend on the thread count).
void add_training_jacobians(model::ReducedModel& m, int threads = 1);

// More points for the online start and preconditioner of a finished row-cone model (up to
// model::kMaxJacobianN, as the Jacobians): `candidates` chosen farthest first from the model's
// training points (Euclidean in coordinates scaled to [0, 1] per parameter, ties to the lowest
// index) until the model holds `total` points, each with its online solution appended to
// training_mu, training_u_hat and training_lambda_hat (a point whose solve does not converge is
// left out; the model's Jacobians are dropped when points are added). Call before
// add_training_jacobians. Why: the preconditioned iteration's steps fall
// with the distance to the nearest Jacobian, and a greedy has solved the reduced problem over its
// whole training set (docs/offline-online.md, "Online: the preconditioned iteration"). The
// solves are shared out over `threads` threads, as add_training_jacobians.
void add_preconditioner_points(model::ReducedModel& m, const std::vector<cases::Mu>& candidates, int total,
                               int threads = 1);

class OfflineBuildCache {
 public:
  OfflineBuildCache();
  ~OfflineBuildCache();
  OfflineBuildCache(const OfflineBuildCache&) = delete;
  OfflineBuildCache& operator=(const OfflineBuildCache&) = delete;
  // eta_p of the snapshot at mu (geometric_term.hpp), computed by the caller from that
  // snapshot's HF solver (geometric_ratio(solver, snapshot): its factor of A_00(mu), not a
  // second one); the builds on this cache take it instead of computing it. Valid for the problem
  // of the builds to come; dropped with the rest when the cache restarts on another problem.
  void add_geometric_ratio(const cases::Mu& mu, double eta);
  struct Parts;

 private:
  friend OfflineResult build_reduced_model(const io::SnapshotSet&, const cases::CaseSpec&, const OfflineSettings&,
                                           OfflineBuildCache*);
  std::unique_ptr<Parts> parts_;
};

}  // namespace contactrb::offline
