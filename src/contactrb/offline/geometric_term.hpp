#pragma once
// The geometric term of the error estimate with the exact contact rows (docs/offline-online.md,
// "Error estimate"). With u the HF and u_rb the reduced displacement, e = u - u_rb and r the
// residual of u_rb,
//   e'A(mu)e = r'e + [linear contact terms] - e'H e + O(|e|^3),
// H = (K(u)' lambda)' the geometric stiffness of the contact forces (contact_linearization.hpp):
// the rows K(w) turn with the deformed master surface, so the contact forces do work on e that
// the elastic energy alone does not bound. eta bounds -e'He / e'A(mu)e over the displacements that
// keep the active rows closed (D_A e = 0, D = d'(u)), the directions an error between two solutions
// with the same contact zone takes:
//   eta_p = max { v'(-H)v / v'A(mu_p)v : D_A v = 0 },
// reduced exactly to the DOFs H and D_A touch by the Schur complement of A_00(mu_p) there (the
// minimum energy of every extension), whose inverse is the block of A_00(mu_p)^-1 on them (a
// selected inverse); its largest eigenvalue by Lanczos on that block, the Schur complement never
// formed (solve/constrained_eigenvalue.hpp). The estimate then solves
// (1 - eta)|e|^2 <= 2 c1 |e| + c2.
#include <utility>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::offline {

// eta_p at one converged snapshot (its mu, u and lambda), on the case's problem at mu_p.
double geometric_ratio(const cases::CaseSpec& spec, const mesh::Mesh& reference, contact::Discretization d,
                       const io::Snapshot& snapshot);

// The same from the HF solver that computed the snapshot (at its mu, on its discretization), with
// the block of A_00(mu_p)^-1 taken from the factor the solver holds (hf::BasicHFSolver::
// held_inverse_block: the Kacanov method's condensation, or the Newton method's supernodal
// factor when the solver keeps it) instead of a second factorization; A_00(mu_p) is factored
// here only when the solver holds none. Equal to the other form to round-off (the Kacanov
// factor is Eigen's simplicial LLT, this one's CHOLMOD's supernodal one; tests/offline/
// test_exact_estimate.cpp).
double geometric_ratio(const hf::HFSolver& solver, const io::Snapshot& snapshot);

// eta_p of the snapshots already seen, by parameter value (a greedy's builds share them: each
// snapshot's eta_p is computed once).
using GeometricRatios = std::vector<std::pair<cases::Mu, double>>;

// max_p eta_p over the converged snapshots of `set` (0 without contact). Its value at the training
// points is calibrated, not bounded, for other parameter values. With `known`, the snapshots whose
// mu it holds are not solved again and the others are added to it.
double max_geometric_ratio(const io::SnapshotSet& set, const cases::CaseSpec& spec, const mesh::Mesh& reference,
                           contact::Discretization d, GeometricRatios* known = nullptr);

}  // namespace contactrb::offline
