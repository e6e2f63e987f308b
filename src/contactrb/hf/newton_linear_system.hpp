#pragma once
// The linear system of a semi-smooth Newton step on the active rows A (docs/theory.md,
// "Semi-smooth Newton", step 2; docs/solvers.md, "Newton linear algebra"):
//   [ A_00 + H    K_A' ] [ du       ]   [ b - A_00 u_0 ]
//   [ -D_A        0    ] [ lambda_A ] = [ d_A          ],     lambda = 0 off A,
// with the consistent linearization (D, H), or the frozen one (H = 0, D = -K: the Jacobian of
// the Kacanov step with the geometry frozen at u, a strictly convex QP since A_00 is SPD).
// ActiveSchur: A_00 = L L' once for the whole solve, z = A_00^-1 b. Each step then reads
//   u_0 + du = z - A_00^-1 P_E y,   y = H_E w + K_E' lambda_A,   w = du[E],
// and w, lambda_A solve the dense system of size |E| + |A| (exact: H, K_A, D_A vanish off E)
//   [ I + G H_E   G K_E' ] [ w        ]   [ z_E - u_0,E ]
//   [ -D_E        0      ] [ lambda_A ] = [ d_A         ],   G = (A_00^-1)[E, E].
// SaddleLU: one sparse LU of the whole saddle point per system.
// Amg: the whole saddle point by GMRES, preconditioned by one AMG V-cycle on A_00 and a sparse
// Schur approximation (solve/saddle_point_krylov.hpp); nothing factorized but the m x m Schur
// approximation.
// Internal to hf/semismooth_newton.cpp and hf/newton_steps.cpp.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "contactrb/hf/newton_iterate.hpp"
#include "contactrb/hf/semismooth_newton.hpp"
#include "contactrb/solve/amg_preconditioner.hpp"
#include "contactrb/solve/selected_inverse.hpp"
#include "contactrb/solve/sparse_lu.hpp"

namespace contactrb::hf {

// The linearization of the contact at the iterate (step 1) as the systems read it, on the free
// DOFs (K_0 is the iterate's own, NewtonIterate::K0).
struct NewtonLinearization {
  RowSparse D0;                               // D = d'(u); empty in the Kacanov phase
  std::vector<Eigen::Triplet<double>> H;      // H = (K(u)' lambda)'; empty in the Kacanov phase
  std::vector<int> read_dofs;                 // ActiveSchur: the free DOFs K_0 and D_0 read
  Eigen::VectorXd top;                        // SaddleLU: b - A_00 u_0
  int colours = 0;
};

// The point a system is written at: the iterate, or (chord correction, step 4) the full step's
// trial with the right-hand side terms of the iterate's Jacobian.
struct SystemPoint {
  const Eigen::VectorXd* z;       // ActiveSchur: A_00^-1 (b + f)
  const Eigen::VectorXd* top;     // SaddleLU: b - A_00 u_0 + f
  const Eigen::VectorXd* u0;
  const Eigen::VectorXd* d;
  const Eigen::VectorXd* lambda;
};

// A step (du, lambda). ActiveSchur: du = z - A_00^-1 P_E y_E - u_0 is first known on the read
// DOFs only (what the predicted active set reads: forward substitution along the
// elimination-tree chains of E, backward along those of the read DOFs); the whole du only for
// the step taken (NewtonLinearSystem::complete).
struct NewtonStep {
  Eigen::VectorXd du, lambda;
  std::vector<int> E;
  Eigen::VectorXd yE;
  bool complete = true;
};

class NewtonLinearSystem {
 public:
  NewtonLinearSystem(const NewtonAlgebra& problem, const NewtonSettings& settings, int dimension);
  bool schur() const { return schur_; }
  NewtonLinearSolver solver() const { return solver_; }
  // The BLAS threads of the BLAS-3 parts (0: the BLAS's own count; NewtonTuning::blas_threads).
  int blas_threads() const { return blas_threads_; }
  // ActiveSchur: A_00 = L L' and z = A_00^-1 b. False (message set) when A_00 is not SPD.
  // Amg: the AMG hierarchy of A_00. False (message set) when it cannot be built.
  bool factorize(NewtonTimings& timings, std::string& message);
  const Eigen::VectorXd& z() const { return z_; }
  // Newton iteration k begins. The frozen systems of the first one (from a cold start: the active
  // set of the unloaded overlap, much larger than the final one) take their dual matrix from the
  // active rows of K_0; later systems the block G, kept across iterations (rows_block_).
  // forcing: the GMRES tolerance of the iteration's systems (Amg; newton_forcing_term).
  void begin_iteration(int k, double forcing);
  // Sets lin.read_dofs: the free DOFs K_0 and D_0 read over every row (ActiveSchur).
  void set_read_dofs(const RowSparse& K0, NewtonLinearization& lin);
  // One system on the rows `active` at `at`: sets step. False when the system is singular
  // (message says why).
  bool solve(const std::vector<int>& active, bool frozen, const RowSparse& K0, const NewtonLinearization& lin,
             const SystemPoint& at, NewtonStep& step, NewtonIteration& it, std::string& message);
  // The whole du of a step known on the read DOFs only.
  void complete(NewtonStep& step, const SystemPoint& at) const;
  const solve::SelectedInverse& inverse() const { return inverse_; }
  // ActiveSchur after a successful factorize(): the factor, moved out (null otherwise).
  std::shared_ptr<solve::SelectedInverse> release_inverse();

 private:
  struct Reduced;
  Reduced reduce(const std::vector<int>& active, bool frozen, const RowSparse& K0, const NewtonLinearization& lin,
                 const SystemPoint& at, NewtonIteration& it);
  bool solve_frozen_dual(const Reduced& sys, const std::vector<int>& active, const RowSparse& K0, Eigen::VectorXd& yE,
                         Eigen::VectorXd& lambda, NewtonIteration& it, std::string& message);
  Eigen::MatrixXd frozen_dual_matrix(const Reduced& sys, const std::vector<int>& active, const RowSparse& K0,
                                     NewtonIteration& it);
  bool solve_krylov(const Reduced& sys, const std::vector<int>& active, const SystemPoint& at, Eigen::VectorXd& yE,
                    Eigen::VectorXd& lambda, NewtonIteration& it);
  bool solve_dense(const Reduced& sys, const std::vector<int>& active, Eigen::VectorXd& yE, Eigen::VectorXd& lambda,
                   std::string& message);
  bool solve_saddle_lu(const std::vector<int>& active, bool frozen, const RowSparse& K0,
                       const NewtonLinearization& lin, const SystemPoint& at, NewtonStep& step, std::string& message);
  bool factorize_amg(NewtonTimings& timings, std::string& message);
  bool solve_saddle_amg(const std::vector<int>& active, bool frozen, const RowSparse& K0,
                        const NewtonLinearization& lin, const SystemPoint& at, NewtonStep& step, NewtonIteration& it,
                        std::string& message);
  void set_step(const std::vector<int>& E, const Eigen::VectorXd& yE, const std::vector<int>& read_dofs,
                const SystemPoint& at, NewtonStep& step) const;

  const NewtonAlgebra& p_;
  const NewtonSettings& s_;
  const int dimension_;
  const NewtonLinearSolver solver_;  // resolved: never Auto
  const bool schur_;
  const int blas_threads_;
  // ActiveSchur: the first iteration's frozen systems take Q = K_E G K_E' from the rows of K_0
  // (SelectedInverse::row_block) instead of G (NewtonTuning::frozen_rows_from_dimension).
  const bool rows_block_;
  bool rows_now_ = false;
  double forcing_ = 0.0;  // Amg: the GMRES tolerance of the systems of this iteration
  solve::SelectedInverse inverse_;
  solve::SparseLU lu_;
  solve::AmgPreconditioner amg_;
  // Amg: the last system's solution (du, lambda on every row) at the point warm_at_, the initial
  // guess of the next system at that point (the passes of an iteration differ in a few rows).
  Eigen::VectorXd warm_du_, warm_lambda_;
  const Eigen::VectorXd* warm_at_ = nullptr;
  Eigen::VectorXd z_;
  std::vector<Eigen::Triplet<double>> a_trip_;  // SaddleLU: A_00
  std::vector<int> e_position_;                 // scratch: position in E, -1 outside
  // G = (A_00^-1)[E, E] and G K_E', in storage reused by every system (docs/performance.md, "Why
  // the defaults are what they are", "Newton: storage reused across systems").
  std::vector<double> g_storage_, gkt_storage_, q_storage_;
};

}  // namespace contactrb::hf
