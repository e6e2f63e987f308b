#pragma once
// Helpers of the snapshot tests: bitwise comparison of snapshot sets, temporary directories.
#include <gtest/gtest.h>

#include "support/temp_dir.hpp"

#include <Eigen/Core>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::test {

// Same shape and the same bytes (so -0.0 != 0.0 and NaN == NaN with the same payload).
template <typename Derived>
bool same_bits(const Eigen::DenseBase<Derived>& a, const Eigen::DenseBase<Derived>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  const typename Derived::PlainObject pa = a, pb = b;
  return pa.size() == 0 || std::memcmp(pa.data(), pb.data(), sizeof(double) * static_cast<std::size_t>(pa.size())) == 0;
}

// Same shape and the same stored entries: positions and value bytes.
inline bool same_bits(const io::SnapshotRows& a, const io::SnapshotRows& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  for (Eigen::Index r = 0; r < a.outerSize(); ++r) {
    io::SnapshotRows::InnerIterator x(a, r), y(b, r);
    for (; x && y; ++x, ++y) {
      const double vx = x.value(), vy = y.value();
      if (x.col() != y.col() || std::memcmp(&vx, &vy, sizeof vx) != 0) return false;
    }
    if (x || y) return false;
  }
  return true;
}

// Every array, status and count; timings only when `with_timings`.
inline void expect_same_data(const io::SnapshotSet& a, const io::SnapshotSet& b, bool with_timings) {
  EXPECT_EQ(a.case_name, b.case_name);
  EXPECT_EQ(a.case_kind, b.case_kind);
  EXPECT_EQ(a.case_spec, b.case_spec);
  EXPECT_EQ(a.level, b.level);
  EXPECT_EQ(a.constraint, b.constraint);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t k = 0; k < a.parameters.size(); ++k) {
    EXPECT_EQ(a.parameters[k].name, b.parameters[k].name);
    EXPECT_EQ(a.parameters[k].kind, b.parameters[k].kind);
    EXPECT_EQ(a.parameters[k].units, b.parameters[k].units);
    EXPECT_EQ(a.parameters[k].min, b.parameters[k].min);
    EXPECT_EQ(a.parameters[k].max, b.parameters[k].max);
  }
  EXPECT_EQ(a.set_name, b.set_name);
  EXPECT_EQ(a.solver, b.solver);
  EXPECT_EQ(a.kacanov_alpha, b.kacanov_alpha);
  EXPECT_EQ(a.kacanov_tolerance, b.kacanov_tolerance);
  EXPECT_EQ(a.kacanov_max_iterations, b.kacanov_max_iterations);
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.mesh.nodes.size(), b.mesh.nodes.size());
  EXPECT_EQ(a.mesh3.nodes.size(), b.mesh3.nodes.size());
  EXPECT_EQ(a.mesh3.tetrahedra, b.mesh3.tetrahedra);
  EXPECT_EQ(a.num_dofs, b.num_dofs);
  EXPECT_EQ(a.free_dofs, b.free_dofs);
  EXPECT_EQ(a.contact_dofs, b.contact_dofs);
  EXPECT_EQ(a.slave, b.slave);
  EXPECT_EQ(a.master, b.master);
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
  for (std::size_t i = 0; i < a.snapshots.size(); ++i) {
    const io::Snapshot& x = a.snapshots[i];
    const io::Snapshot& y = b.snapshots[i];
    SCOPED_TRACE("snapshot " + std::to_string(i));
    EXPECT_TRUE(same_bits(x.mu, y.mu));
    EXPECT_EQ(x.converged, y.converged);
    EXPECT_EQ(x.status, y.status);
    EXPECT_EQ(x.message, y.message);
    EXPECT_EQ(x.iterations, y.iterations);
    if (with_timings) {
      EXPECT_EQ(x.time_s, y.time_s);
      EXPECT_EQ(x.cpu_time_s, y.cpu_time_s);
    }
    EXPECT_TRUE(same_bits(x.u0, y.u0));
    EXPECT_TRUE(same_bits(x.u, y.u));
    EXPECT_TRUE(same_bits(x.lambda, y.lambda));
    EXPECT_TRUE(same_bits(x.K, y.K));
    EXPECT_TRUE(same_bits(x.g, y.g));
    EXPECT_TRUE(same_bits(x.weight, y.weight));
    EXPECT_TRUE(same_bits(x.gap_pointwise, y.gap_pointwise));
  }
}



}  // namespace contactrb::test
