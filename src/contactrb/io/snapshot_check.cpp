// check_snapshot_set (snapshot_file.hpp): every index, size and value of a snapshot set,
// checked by the writer, the reader and offline::build_reduced_model before any use. The messages
// name each field by its path in the file (docs/file-formats.md, "Snapshot file").
#include <Eigen/Core>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/io/mesh_group.hpp"
#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::io {

namespace {

using hdf5::list_entry_name;

[[noreturn]] void invalid(const std::string& what) { throw Error(what); }

// Shortest text that reads back as the same double: a value just outside the domain must not
// print as its bound.
std::string exact(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// Index list `name`: every entry in [0, bound), no entry twice (except that a closed chain
// may repeat its first node once, at the end). Duplicates are found by sorting a copy: the
// memory is that of the list, not of `bound` (a damaged num_dofs may be huge).
void check_indices(const std::vector<int>& v, int bound, const std::string& name, const std::string& bound_name,
                   bool closed_chain_allowed = false) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] < 0 || v[i] >= bound) {
      invalid(name + "[" + std::to_string(i) + "] = " + std::to_string(v[i]) + " is outside [0, " + bound_name +
              " = " + std::to_string(bound) + ")");
    }
  }
  const bool closed = closed_chain_allowed && v.size() >= 3 && v.back() == v.front();
  std::vector<std::pair<int, std::size_t>> sorted;  // (index, position)
  for (std::size_t i = 0; i + (closed ? 1 : 0) < v.size(); ++i) sorted.emplace_back(v[i], i);
  std::sort(sorted.begin(), sorted.end());
  std::size_t first = v.size();  // earliest position that repeats an earlier entry
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    if (sorted[k].first == sorted[k - 1].first) first = std::min(first, sorted[k].second);
  }
  if (first < v.size()) {
    invalid(name + "[" + std::to_string(first) + "] = " + std::to_string(v[first]) + " appears twice");
  }
}

// The first non-finite entry of a converged snapshot's array, named (a NaN in u0 would
// become a NaN POD basis, in K a NaN EIM, silently).
template <typename Derived>
void check_finite(const Eigen::DenseBase<Derived>& a, const std::string& name) {
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      if (!std::isfinite(a(i, j))) {
        std::ostringstream os;
        os << name << " holds a non-finite value (" << a(i, j) << ") at ";
        if (a.cols() == 1) {
          os << "entry " << i;
        } else {
          os << "(" << i << ", " << j << ")";
        }
        invalid(os.str());
      }
    }
  }
}

// The same for K, whose stored entries are its non-zeros (named by row and column).
void check_finite(const SnapshotRows& K, const std::string& name) {
  for (Eigen::Index r = 0; r < K.outerSize(); ++r) {
    for (SnapshotRows::InnerIterator it(K, r); it; ++it) {
      if (!std::isfinite(it.value())) {
        std::ostringstream os;
        os << name << " holds a non-finite value (" << it.value() << ") at (" << r << ", " << it.col() << ")";
        invalid(os.str());
      }
    }
  }
}

bool known_constraint(const std::string& c) { return c == "collocation" || c == "lac" || c == "lac-simpson"; }

// The case, the parameter domains and the Kacanov settings.
void check_header(const SnapshotSet& set) {
  if (set.case_kind != "builtin" && set.case_kind != "toml") {
    invalid("/case/kind is '" + set.case_kind + "' (expected builtin or toml)");
  }
  if (set.level < 0 || set.level > mesh::kMaxMeshLevel) {
    invalid("/case/level is " + std::to_string(set.level) + " (expected 0 to " + std::to_string(mesh::kMaxMeshLevel) +
            ", the finest built-in level)");
  }
  if (set.parameters.empty()) invalid("/parameter holds no parameter");
  for (std::size_t k = 0; k < set.parameters.size(); ++k) {
    const SnapshotParameter& q = set.parameters[k];
    if (!std::isfinite(q.min) || !std::isfinite(q.max) || q.min > q.max) {
      invalid("the domain [" + exact(q.min) + ", " + exact(q.max) + "] of parameter '" + q.name + "' (/parameter/" +
              list_entry_name(k) + " min, max) is not an interval");
    }
  }
  if (!(std::isfinite(set.kacanov_alpha) && set.kacanov_alpha > 0.0 && set.kacanov_alpha <= 1.0) ||
      !(std::isfinite(set.kacanov_tolerance) && set.kacanov_tolerance > 0.0) || set.kacanov_max_iterations < 1) {
    invalid("the Kacanov settings (/settings) are invalid (alpha in (0, 1], tolerance > 0, max_iterations >= 1)");
  }
  if (set.solver != "kacanov" && set.solver != "newton") {
    invalid("the solver (/settings solver) is '" + set.solver + "' (expected kacanov or newton)");
  }
}

// contact_dofs is derived from the chains (every component of each contact node, ascending):
// anything else would make K's columns mean other DOFs.
void check_contact_dofs(const SnapshotSet& set) {
  std::vector<int> nodes = set.slave;
  nodes.insert(nodes.end(), set.master.begin(), set.master.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const auto d = static_cast<std::size_t>(set.dimension);
  bool contact_ok = set.contact_dofs.size() == d * nodes.size();
  for (std::size_t i = 0; contact_ok && i < nodes.size(); ++i) {
    for (std::size_t c = 0; c < d; ++c) {
      contact_ok = contact_ok && set.contact_dofs[d * i + c] == set.dimension * nodes[i] + static_cast<int>(c);
    }
  }
  if (!contact_ok) {
    invalid("/discretization/contact_dofs (" + std::to_string(set.contact_dofs.size()) + " entries) are not the " +
            std::string(d == 2 ? "two" : "three") + " components of the " + std::to_string(nodes.size()) +
            " slave and master nodes in ascending order");
  }
}

// Every index is checked before anyone uses it.
void check_discretization(const SnapshotSet& set) {
  const bool has_layout = set.num_dofs != 0;
  if (set.dimension != 2 && set.dimension != 3) {
    invalid("the dimension is " + std::to_string(set.dimension) + " (expected 2 or 3)");
  }
  if (set.num_dofs < 0 || set.num_dofs % set.dimension != 0) {
    invalid("/discretization num_dofs = " + std::to_string(set.num_dofs) + " (expected " +
            std::to_string(set.dimension) + " x nodes, >= 0)");
  }
  if (!has_layout) {
    // Every solve threw before its discretization existed: nothing but failures to record.
    if (!set.free_dofs.empty() || !set.contact_dofs.empty() || !set.slave.empty() || !set.master.empty()) {
      invalid("/discretization has index lists but num_dofs = 0");
    }
  } else if (!known_constraint(set.constraint)) {
    invalid("/case/constraint is '" + set.constraint + "' (expected collocation, lac or lac-simpson)");
  }
  const int num_nodes = set.num_dofs / set.dimension;
  check_indices(set.free_dofs, set.num_dofs, "/discretization/free_dofs", "num_dofs");
  check_indices(set.slave, num_nodes, "/discretization/slave", "nodes");
  // A closed master loop exists in 2D only (3D: the master nodes, sorted).
  check_indices(set.master, num_nodes, "/discretization/master", "nodes", /*closed_chain_allowed=*/set.dimension == 2);
  if (has_layout && (set.slave.empty() || set.master.size() < 2)) {
    invalid("/discretization: the slave chain has " + std::to_string(set.slave.size()) + " node(s), the master " +
            std::to_string(set.master.size()) + " (at least 1 and 2 are needed)");
  }
  check_contact_dofs(set);
}

// The stored reference mesh (format 4): valid, and the mesh of these DOFs; only the mesh of
// the set's dimension.
template <int Dim>
void check_mesh_of(const mesh::SimplexMesh<Dim>& m, int num_dofs) {
  if (m.nodes.empty()) return;
  try {
    mesh::validate(m);
  } catch (const Error& e) {
    invalid(std::string("/mesh: ") + e.what());
  }
  if (m.num_dofs() != num_dofs) {
    invalid("/mesh has " + std::to_string(m.num_nodes()) + " nodes (" + std::to_string(m.num_dofs()) +
            " DOFs), /discretization num_dofs = " + std::to_string(num_dofs));
  }
}

void check_reference_mesh(const SnapshotSet& set) {
  const bool other_dimension = set.dimension == 3 ? !set.mesh.nodes.empty() : !set.mesh3.nodes.empty();
  if (other_dimension) {
    invalid("the set of dimension " + std::to_string(set.dimension) + " holds a reference mesh of the other dimension");
  }
  if (set.dimension == 3) {
    check_mesh_of(set.mesh3, set.num_dofs);
  } else {
    check_mesh_of(set.mesh, set.num_dofs);
  }
}

// Snapshot i's point (in the stored domains), record (times, iterations, status) and array
// sizes; a converged one's arrays present and finite.
// A negative pressure below this fraction of the largest one is not round-off.
constexpr double kPressureRoundOff = 1e-10;

void check_snapshot(const SnapshotSet& set, std::size_t i) {
  const Snapshot& s = set.snapshots[i];
  const std::string where = "/snapshots/" + list_entry_name(i);
  if (s.mu.size() != static_cast<Eigen::Index>(set.parameters.size())) {
    invalid(where + ": mu has " + std::to_string(s.mu.size()) + " values for " + std::to_string(set.parameters.size()) +
            " parameters");
  }
  for (std::size_t k = 0; k < set.parameters.size(); ++k) {
    const double v = s.mu(static_cast<Eigen::Index>(k));
    const SnapshotParameter& q = set.parameters[k];
    if (!std::isfinite(v) || v < q.min || v > q.max) {
      invalid(where + ": mu = " + exact(v) + " (" + q.name + ") is outside the stored domain [" + exact(q.min) + ", " +
              exact(q.max) + "]");
    }
  }
  if (!std::isfinite(s.time_s) || s.time_s < 0.0 || !std::isfinite(s.cpu_time_s) || s.cpu_time_s < 0.0) {
    invalid(where + ": its time_s or cpu_time_s is negative or not finite");
  }
  if (s.iterations < 0) invalid(where + ": iterations = " + std::to_string(s.iterations) + " (expected >= 0)");
  if (s.converged != (s.status == "converged")) {
    invalid(where + ": status '" + s.status + "' disagrees with /snapshots/converged = " + (s.converged ? "1" : "0"));
  }
  const auto num_free = static_cast<Eigen::Index>(set.free_dofs.size());
  const auto nc = static_cast<Eigen::Index>(set.contact_dofs.size());
  const auto S = static_cast<Eigen::Index>(set.slave.size());
  const auto R = s.lambda.size();
  const auto expect = [&](bool ok, const std::string& what) {
    if (!ok) invalid(where + ": " + what);
  };
  expect(s.u0.size() == 0 || s.u0.size() == num_free,
         "u0 has " + std::to_string(s.u0.size()) + " entries, expected " + std::to_string(num_free));
  expect(s.u.size() == 0 || s.u.size() == set.num_dofs,
         "u has " + std::to_string(s.u.size()) + " entries, expected " + std::to_string(set.num_dofs));
  expect(s.K.size() == 0 || (s.K.rows() == R && s.K.cols() == nc),
         "K is " + std::to_string(s.K.rows()) + " x " + std::to_string(s.K.cols()) + ", expected " + std::to_string(R) +
             " x " + std::to_string(nc));
  expect(s.g.size() == 0 || s.g.size() == R, "g and lambda differ in size");
  expect(s.weight.size() == 0 || s.weight.size() == R, "weight and lambda differ in size");
  expect(s.gap_pointwise.size() == 0 || s.gap_pointwise.size() == S, "gap_pointwise and the slave chain differ in size");
  if (!s.converged) return;  // a failed solve is a record: its last iterate may be anything
  expect(set.num_dofs != 0 && s.u0.size() > 0 && s.u.size() > 0 && R > 0 && s.K.size() > 0 && s.g.size() == R &&
             s.weight.size() == R && s.gap_pointwise.size() == S,
         "a converged snapshot needs u0, u, lambda, K, g, weight and gap_pointwise");
  check_finite(s.u0, where + "/u0");
  check_finite(s.u, where + "/u");
  check_finite(s.lambda, where + "/lambda");
  check_finite(s.K, where + "/K_data");
  check_finite(s.g, where + "/g");
  check_finite(s.weight, where + "/weight");
  check_finite(s.gap_pointwise, where + "/gap_pointwise");
  // Contact pressures (lambda >= 0, paper (26)), to the round-off of the solvers' last step.
  const double scale = s.lambda.cwiseAbs().maxCoeff();
  if (s.lambda.minCoeff() < -kPressureRoundOff * scale) {
    invalid(where + "/lambda: a contact pressure is negative (" + number_text(s.lambda.minCoeff()) +
            "): a pressure is >= 0");
  }
  if ((s.weight.array() < 0.0).any()) invalid(where + "/weight: a weight |I_r| is negative");
}

}  // namespace

void check_snapshot_set(const SnapshotSet& set) {
  check_header(set);
  check_discretization(set);
  check_reference_mesh(set);
  for (std::size_t i = 0; i < set.snapshots.size(); ++i) check_snapshot(set, i);
}

}  // namespace contactrb::io
