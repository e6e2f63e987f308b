#include "contactrb/offline/snapshot_wire.hpp"

#include <cstring>
#include <type_traits>

#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_rows.hpp"

namespace contactrb::offline {

namespace {

class Writer {
 public:
  template <typename T>
  void put(const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(&x, sizeof x);
  }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    raw(s.data(), s.size());
  }
  void put(const std::vector<int>& v) {
    put<std::uint64_t>(v.size());
    raw(v.data(), sizeof(int) * v.size());
  }
  void put(const Eigen::VectorXd& v) {
    put<std::int64_t>(v.size());
    raw(v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
  }
  void put(const std::vector<double>& v) {
    put<std::uint64_t>(v.size());
    raw(v.data(), sizeof(double) * v.size());
  }
  // Its shape and its compressed-row arrays (io/snapshot_rows.hpp).
  void put(const io::SnapshotRows& K) {
    put<std::int64_t>(K.rows());
    put<std::int64_t>(K.cols());
    const io::CsrArrays a = io::csr_of(K);
    put(a.indptr);
    put(a.indices);
    put(a.data);
  }
  std::vector<char> bytes;

 private:
  void raw(const void* p, std::size_t n) {
    const auto* c = static_cast<const char*>(p);
    bytes.insert(bytes.end(), c, c + n);
  }
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T x;
    raw(&x, sizeof x);
    return x;
  }
  void get(std::string& s) {
    s.resize(count(1));
    raw(s.data(), s.size());
  }
  void get(std::vector<int>& v) {
    v.resize(count(sizeof(int)));
    raw(v.data(), sizeof(int) * v.size());
  }
  void get(Eigen::VectorXd& v) {
    v.resize(static_cast<Eigen::Index>(count(sizeof(double))));
    raw(v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
  }
  void get(std::vector<double>& v) {
    v.resize(count(sizeof(double)));
    raw(v.data(), sizeof(double) * v.size());
  }
  void get(io::SnapshotRows& K) {
    const auto rows = get<std::int64_t>();
    const auto cols = get<std::int64_t>();
    io::CsrArrays a;
    get(a.indptr);
    get(a.indices);
    get(a.data);
    if (a.indptr.empty()) {
      require(rows == 0 && cols == 0, "internal: a packed sparse matrix has a shape but no rows");
      K = io::SnapshotRows();
      return;
    }
    require(rows == static_cast<std::int64_t>(a.indptr.size()) - 1 && cols >= 0 && cols <= INT32_MAX,
            "internal: a packed sparse matrix disagrees with its row pointers");
    K = io::rows_from_csr(a, cols, "internal: a packed snapshot");
  }
  void finish() const { require(at_ == bytes_.size(), "internal: a packed message has trailing bytes"); }

 private:
  std::size_t left() const { return bytes_.size() - at_; }
  // An element count, checked against the bytes left before anything is allocated.
  std::size_t count(std::size_t element) {
    const auto n = get<std::uint64_t>();
    require(n <= left() / element, "internal: a packed array is longer than its message");
    return static_cast<std::size_t>(n);
  }
  void raw(void* p, std::size_t n) {
    require(n <= left(), "internal: a packed message is truncated");
    if (n > 0) std::memcpy(p, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<char> pack_solved(std::uint64_t index, const io::Snapshot& s, const SnapshotLayout& l) {
  Writer w;
  w.put(index);
  w.put(s.mu);
  w.put<std::uint8_t>(s.converged ? 1 : 0);
  w.put(s.status);
  w.put(s.message);
  w.put(s.iterations);
  w.put(s.time_s);
  w.put(s.cpu_time_s);
  w.put(s.u0);
  w.put(s.u);
  w.put(s.lambda);
  w.put(s.K);
  w.put(s.g);
  w.put(s.weight);
  w.put(s.gap_pointwise);
  w.put<std::uint8_t>(l.valid ? 1 : 0);
  w.put(l.num_dofs);
  w.put(l.free_dofs);
  w.put(l.contact_dofs);
  w.put(l.slave);
  w.put(l.master);
  w.put(l.constraint);
  return std::move(w.bytes);
}

void unpack_solved(const std::vector<char>& bytes, std::uint64_t& index, io::Snapshot& s, SnapshotLayout& l) {
  Reader r(bytes);
  index = r.get<std::uint64_t>();
  r.get(s.mu);
  s.converged = r.get<std::uint8_t>() != 0;
  r.get(s.status);
  r.get(s.message);
  s.iterations = r.get<int>();
  s.time_s = r.get<double>();
  s.cpu_time_s = r.get<double>();
  r.get(s.u0);
  r.get(s.u);
  r.get(s.lambda);
  r.get(s.K);
  r.get(s.g);
  r.get(s.weight);
  r.get(s.gap_pointwise);
  l.valid = r.get<std::uint8_t>() != 0;
  l.num_dofs = r.get<int>();
  r.get(l.free_dofs);
  r.get(l.contact_dofs);
  r.get(l.slave);
  r.get(l.master);
  r.get(l.constraint);
  r.finish();
}

std::vector<char> pack_task(std::uint64_t index, const io::Snapshot* start) {
  Writer w;
  w.put(index);
  w.put<std::uint8_t>(start != nullptr ? 1 : 0);
  if (start != nullptr) {
    w.put<std::uint8_t>(start->converged ? 1 : 0);
    w.put(start->u);
    w.put(start->lambda);
  }
  return std::move(w.bytes);
}

void unpack_task(const std::vector<char>& bytes, std::uint64_t& index, bool& has_start, io::Snapshot& start) {
  Reader r(bytes);
  index = r.get<std::uint64_t>();
  has_start = r.get<std::uint8_t>() != 0;
  start = io::Snapshot{};
  if (has_start) {
    start.converged = r.get<std::uint8_t>() != 0;
    r.get(start.u);
    r.get(start.lambda);
  }
  r.finish();
}

}  // namespace contactrb::offline
