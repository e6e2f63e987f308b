#pragma once
// The EIM magic-point values of kappa and gamma (paper (50)-(52)) for collocation and LAC-Simpson
// rows, from the slave nodes under the magic rows only ("restricted operator"): such a row is a
// W-weighted sum of pointwise rows (10)-(11),
//   K[r, n] = sum_s W(r, s) K_pt[s, n],   gamma_r = sum_s W(r, s) (g_pt[s] - K_pt[s, :] u_D,c(mu)).
// Internal to OnlineSolver (no stable API).
//
// The pointwise rows follow contact::project_slave_nodes exactly (projection.hpp): closest point
// on the deformed master polyline (the all-pairs answer, found by bounding boxes of
// segment blocks) with ties to the lowest segment index, the
// continuous normal field n2 (vertex normals = normalized average of the adjacent segment
// normals), the end-of-open-chain candidate rule, a zero K row and g = distance for
// non-candidates, contactrb::Error for a zero-length deformed master segment or a non-finite
// displacement. Unlike project_slave_nodes it allocates nothing per step, needs the
// displacement only on the master chain and on those slave nodes (w = u_D,c + Theta_c u_hat on
// those rows), and computes segment normals only where a closest point lies. The online tests
// compare it with the full contact-surface rows (constraint_rows) to 1e-10.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/segment_hit.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/online/affine_whitening.hpp"

namespace contactrb::online {

// Row-major: the rows of K(w) Theta_c are built by row updates, from rows of Theta_c.
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class MagicPointEvaluator {
 public:
  // kappa_row, gamma_row: magic rows in R_hf numbering; kappa_dof: contact-surface DOFs;
  // Theta_c (n_c x N), lift_c (n_c x J^D): the model's contact-surface rows.
  void setup(const model::ContactSurface& surface, const std::vector<int>& kappa_row, const std::vector<int>& kappa_dof,
             const std::vector<int>& gamma_row, const Eigen::MatrixXd& Theta_c);

  // Per mu: the contact-surface nodes in Omega(mu), the quadrature at mu (its W pattern decides
  // which slave nodes are needed; rebuilt only when it changes) and u_D,c(mu) (n_c).
  void prepare(const std::vector<Eigen::Vector2d>& nodes, const contact::ContactQuadrature& quadrature,
               const Eigen::VectorXd& lift_mu);

  // Per mu, after prepare (which selects every gamma row): evaluate_rows and evaluate_slack then
  // compute only the gamma rows listed (positions in the setup's gamma_row, increasing), from the
  // slave nodes under them; row j of their outputs is row rows[j]. Why: a registered dual basis
  // Xi(mu) is zero on the kept rows outside the predicted support, which add nothing to D or
  // Xi' gamma (docs/offline-online.md, "Cost of a query with the exact rows").
  void select_rows(const std::vector<int>& rows);

  // Per step: kappa_hat (Mk) and gamma_hat (Mg) at u_hat (N), sized by the caller.
  void evaluate(const Eigen::VectorXd& u_hat, Eigen::VectorXd& kappa_hat, Eigen::VectorXd& gamma_hat);

  // Per step, whole rows instead of magic entries: for each gamma row i, row i of K(w) Theta_c
  // (K_Theta, gamma rows x N, sized by the caller) and gamma_i (the exact contact rows of
  // ContactRows::Exact on the kept rows; setup with those as gamma rows and no kappa pair).
  void evaluate_rows(const Eigen::VectorXd& u_hat, RowMatrix& K_Theta, Eigen::VectorXd& gamma);
  // The same, and row i of K(w) Theta_c L^-T in K_E (sized as K_Theta; A = L L', `whitening`): from
  // the rows of Theta_c L^-T of the nodes the rows touch, solved the first time a step needs them
  // after prepare_solved, together (scaled rows of Theta_c V with a diagonal whitening). Why: E = L^-1 D' then costs 6 N per row and step instead of a
  // triangular solve (N^2 / 2 per row), and a query touches the same few nodes at every step
  // (docs/offline-online.md, "Cost of a query with the exact rows").
  void prepare_solved(const AffineWhitening& whitening);
  // A whitening in diagonal form (AffineWhitening::diagonal()): its basis V, once. The rows of
  // Theta_c L^-T are then those of Theta_c V scaled by d^-1/2 (N flops a row, no solve).
  void set_whitening_basis(const Eigen::MatrixXd& V);
  void evaluate_rows(const Eigen::VectorXd& u_hat, RowMatrix& K_Theta, Eigen::VectorXd& gamma, RowMatrix& K_E);
  // K_E and gamma only (half the row updates of evaluate_rows with K_Theta).
  void evaluate_solved_rows(const Eigen::VectorXd& u_hat, Eigen::VectorXd& gamma, RowMatrix& K_E);

  // Per step or per answer, without the rows of K(w) Theta_c: for each gamma row i the slack
  // s_i = g_i(w) - K_i(w) w at w = u_D,c + Theta_c u_hat ((28) - (27), >= 0 where the constraint
  // holds), and the contact load K(w)' lambda on the n_c contact DOFs (lambda: one entry per
  // gamma row; slack and load sized by the caller). What the exact-rows estimate needs
  // (ErrorEstimator::ExactContact) at the cost of the projections only.
  void evaluate_slack(const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda, Eigen::VectorXd& slack,
                      Eigen::VectorXd& load);

  // The rows K(w) of every gamma row over the n_c contact DOFs, from the projections of the last
  // evaluate_slack (gamma rows = every constraint row, in order): K = W K_pt as
  // contact::constraint_rows builds it for collocation and LAC-Simpson rows, without projecting
  // again.
  void assemble_rows(Eigen::Index num_dofs, Eigen::SparseMatrix<double, Eigen::RowMajor>& K) const;

  int num_slave_nodes() const { return static_cast<int>(slave_node_.size()); }  // restricted slave nodes

 private:
  struct Term {
    int slave = 0;  // restricted slave index
    double weight = 0.0;
  };
  struct Projection {  // what a pointwise row needs (projection.hpp)
    int a = 0, b = 0;  // local node indices of the closest segment's end points
    double xi = 0.0;
    Eigen::Vector2d normal{0.0, 0.0};
    double g = 0.0;
    bool candidate = false;
  };
  void rebuild(const contact::ContactQuadrature& quadrature);
  // The projections of the restricted slave nodes at w = u_D,c + Theta_c u_hat.
  void project(const Eigen::VectorXd& u_hat);
  double gamma_term(const Term& term) const;  // weight (g_pt - K_pt u_D) of one slave under a gamma row
  Eigen::Vector2d segment_normal(int k) const;
  Eigen::Vector2d vertex_normal(int j);
  // vertex_normal(j) and segment_normal(k) of this step's deformed chain, each computed once per
  // step (neighbouring slave nodes share their segments and end points).
  const Eigen::Vector2d& step_vertex_normal(int j);
  const Eigen::Vector2d& step_segment_normal(int k);
  double k_entry(const Projection& p, int slave_node, int dof) const;  // K_pt[s, dof]
  contact::SegmentHit nearest_segment(const Eigen::Vector2d& x);     // closest deformed master segment

  // Master segments per bounding box of the closest-segment search, and boxes per group box
  // above them: the search visits the nearest group and block first, then only the groups and
  // blocks not farther than the best hit (a few of each instead of all).
  static constexpr int kBlockSegments = 4;
  static constexpr int kGroupBlocks = 8;

  // Setup.
  std::vector<int> master_;                 // master chain (local node indices)
  std::vector<int> slave_chain_;            // slave chain
  bool closed_ = false;
  std::vector<int> kappa_row_, kappa_dof_, gamma_row_;
  Eigen::MatrixXd Theta_c_;
  // Restriction (from the W pattern).
  std::vector<int> pattern_;                // W columns of the magic rows, row by row (to detect changes)
  std::vector<int> slave_position_;         // restricted slave index -> position in the slave chain
  std::vector<int> slave_node_;             // restricted slave index -> local node
  std::vector<int> used_node_;              // nodes whose displacement is needed: master chain nodes, then slaves
  int master_slots_ = 0;                    // the first master_slots_ used nodes are the master chain's
  std::vector<int> node_slot_;              // local node -> index in used_node_ (-1)
  RowMatrix Theta_r_;                       // 2 |used| x N: the rows of Theta_c of used_node_
  // Per mu (prepare_solved): the rows of Theta_c L^-T of the used nodes solved so far.
  const AffineWhitening* whitening_ = nullptr;
  Eigen::MatrixXd V_;                       // set_whitening_basis's V (empty: none)
  RowMatrix ThetaV_r_;                      // 2 |used| x N: Theta_r_ V
  RowMatrix ThetaL_r_;                      // 2 |used| x N
  std::vector<char> solved_;                // per used node
  std::vector<int> pending_;                // used-node slots to solve at this step
  Eigen::MatrixXd solve_work_;              // N x 2 |pending|
  // Solves the rows of Theta_c L^-T of the nodes the step's candidate rows touch (projection_ set).
  void solve_touched_rows();
  // evaluate_rows: K_Theta and K_E where not null.
  void rows(const Eigen::VectorXd& u_hat, RowMatrix* K_Theta, Eigen::VectorXd& gamma, RowMatrix* K_E);
  // Per mu.
  std::vector<Term> kappa_terms_, gamma_terms_;
  std::vector<int> kappa_start_, gamma_start_;  // CSR-like offsets into the term lists
  std::vector<int> active_;                 // the gamma rows evaluated (select_rows; prepare: all)
  std::vector<char> slave_needed_;          // per restricted slave: under an active or kappa row
  std::vector<Eigen::Vector2d> X_;          // Omega(mu) position of each used node
  Eigen::VectorXd lift_r_;                  // u_D,c(mu) on the used nodes
  // Per step.
  Eigen::VectorXd w_r_;                     // displacement of the used nodes
  std::vector<Eigen::Vector2d> y_;          // deformed master chain
  std::vector<Eigen::Vector2d> y_normal_;   // its vertex normals, where y_normal_done_
  std::vector<char> y_normal_done_;
  std::vector<Eigen::Vector2d> segment_normal_;  // its segment normals, where segment_normal_done_
  std::vector<char> segment_normal_done_;
  std::vector<Projection> projection_;      // one per restricted slave node
  std::vector<Eigen::Vector2d> block_min_, block_max_;  // boxes of the deformed master blocks
  std::vector<double> block_bound_;         // squared distance of the current slave node to each box
  std::vector<Eigen::Vector2d> group_min_, group_max_;  // boxes of kGroupBlocks consecutive blocks
  std::vector<double> group_bound_;
  void scan_group(const Eigen::Vector2d& x, int group, contact::SegmentHit& best);
};

}  // namespace contactrb::online
