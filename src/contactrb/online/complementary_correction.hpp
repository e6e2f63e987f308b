#pragma once
// The complementary correction of the exact-rows estimate (docs/offline-online.md, "The
// complementary bound"). A reduced answer (u_rb, lambda_rb) whose displacement crosses some HF
// rows (the registered cone meets the rows only in the mean) is corrected on the rows:
//     u~ = u_rb + v / t,   v = X^-1 K' c,   lambda~ = lambda_rb - c,
// with c chosen so that (u~, lambda~) is complementary on every row, i.e. lambda~ = z solves the
// linear complementarity problem
//     z >= 0,   q + (S / t) z >= 0,   z' (q + (S / t) z) = 0,   q = s - (S / t) lambda_rb,
// S = K X^-1 K' on the rows (X = A_00(mu_ref), the estimate's product) and s = g(w) - K(w) w the
// slack at the returned displacement. The residual of u~ then differs from that of u_rb only by
// the stiffness mismatch (A(mu) / t - X) v, and u~ carries no violation or complementarity term:
// the bound has no square-root floor. |v|_X = sqrt(c' S c) is what evaluate() returns.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contactrb/solve/nonnegative_qp.hpp"

namespace contactrb::online {

class ComplementaryCorrection {
 public:
  using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

  // load_T: the R-factor columns of the unit loads on the measured contact DOFs (the last
  // exact_dofs.size() columns of EstimateData::residual_exact), so that X^-1 restricted to them
  // is load_T' load_T; exact_dofs: those DOFs among the n_c contact DOFs.
  void setup(const Eigen::MatrixXd& load_T, const std::vector<int>& exact_dofs, Eigen::Index n_c);

  struct Result {
    bool available = false;  // false: a row outside the measured DOFs might close, or the LCP failed
    double v_norm = 0.0;     // |v|_X = sqrt(c' S c)
    int rows = 0;            // rows of the complementarity problem
  };
  // K: the HF rows at w (rows x n_c), slack s = g(w) - K(w) w and lambda_rb over every row;
  // t > 0: the stiffness scale of A(mu) against X.
  Result evaluate(const RowSparse& K, const Eigen::VectorXd& slack, const Eigen::VectorXd& lambda, double t);

 private:
  void form_gram();
  // The rows of K whose DOFs are all measured (measured_); false when a row with a multiplier is
  // not among them.
  bool gather_measured(const RowSparse& K, const Eigen::VectorXd& lambda);
  // S / t on the rows_ (KG_ = K_rows X^-1 on the measured DOFs).
  void form_schur(const RowSparse& K, double t);
  // Solves the complementarity problem on rows_ into c_; false when the QP fails.
  bool solve_on_rows(const Eigen::VectorXd& slack, const Eigen::VectorXd& lambda);
  // The gap change (S / t) c on every measured row into change_; adds to rows_ the measured rows
  // the correction closes (their slack below the change) and returns how many.
  int add_closed_rows(const RowSparse& K, const Eigen::VectorXd& slack, double t);

  Eigen::MatrixXd load_T_;   // rank x n_e (released once the Gram matrix is formed)
  Eigen::MatrixXd gram_;     // n_e x n_e: X^-1 on the measured DOFs
  std::vector<int> local_;   // contact DOF -> measured index, -1 when not measured
  std::vector<Eigen::Index> measured_, rows_;  // measured rows; the rows of the problem (sorted)
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> KG_;  // |rows| x n_e
  struct Entry {
    int local = 0;  // measured index of the DOF
    double value = 0.0;
  };
  std::vector<Entry> entries_;     // the entries of rows_'s rows, row after row
  std::vector<int> entry_start_;   // |rows| + 1 offsets into entries_
  Eigen::MatrixXd S_;        // |rows| x |rows|
  Eigen::VectorXd q_, lam_, c_, y_, change_;
  std::vector<int> warm_;
  solve::NonnegativeQPSolver qp_;
};

}  // namespace contactrb::online
