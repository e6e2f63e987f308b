#pragma once
// Index convention for the EIM of the contact map kappa (50)-(51): for each training parameter
// the contact map restricted to the contact-surface DOFs is an R x n_c matrix K (row r: constraint,
// column n: contact-surface DOF). It becomes one column of the EIM snapshot matrix F by row-major
// flattening:
//     row(r, n) = r * n_c + n,     r = row / n_c,  n = row % n_c.
// So a magic point of kappa is a pair (constraint r, DOF n), as in (52).
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace contactrb::offline {

// F (R n_c) x P from P matrices of equal size R x n_c. Throws contactrb::Error on size mismatch
// (the message names the offending index and both sizes).
Eigen::MatrixXd flatten_columns(const std::vector<Eigen::MatrixXd>& matrices);
// One column of F back to the R x n_c matrix. Throws unless column.size() == R * n_c.
Eigen::MatrixXd unflatten_column(const Eigen::VectorXd& column, Eigen::Index R, Eigen::Index n_c);
// row -> (r, n). Throws for n_c <= 0 or a negative row.
std::pair<int, int> unflatten_index(int row, int n_c);
// (r, n) -> row.
inline int flatten_index(int r, int n, int n_c) { return r * n_c + n; }

}  // namespace contactrb::offline
