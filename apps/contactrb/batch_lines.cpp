#include "batch_lines.hpp"

#include <climits>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <memory>
#include <ostream>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/online/online_many.hpp"
#include "batch_pipeline.hpp"
#include "mpi_gather.hpp"

#if CONTACTRB_HAVE_MPI
#include <mpi.h>
#endif

namespace contactrb::app {

namespace {

struct Line {
  std::string text;
  bool too_long = false;
  LineAnswer answer;
};

#if CONTACTRB_HAVE_MPI

// Strings as one byte buffer: length (8 bytes) then bytes, per string.
std::vector<char> pack(const std::vector<std::string>& items) {
  std::vector<char> b;
  for (const std::string& s : items) {
    const std::uint64_t n = s.size();
    b.insert(b.end(), reinterpret_cast<const char*>(&n), reinterpret_cast<const char*>(&n) + sizeof n);
    b.insert(b.end(), s.begin(), s.end());
  }
  return b;
}

std::vector<std::string> unpack(const char* data, std::size_t size) {
  std::vector<std::string> items;
  for (std::size_t at = 0; at < size;) {
    std::uint64_t n = 0;
    require(size - at >= sizeof n, "internal: a truncated batch message");
    std::memcpy(&n, data + at, sizeof n);
    at += sizeof n;
    require(n <= size - at, "internal: a truncated batch message");
    items.emplace_back(data + at, static_cast<std::size_t>(n));
    at += static_cast<std::size_t>(n);
  }
  return items;
}

int checked_int(std::size_t n) {
  require(n < static_cast<std::size_t>(INT_MAX), "internal: an MPI message of 2 GB or more");
  return static_cast<int>(n);
}

// Rank 0's chunk to every rank: "T"/"F" (too long) + text per line.
void broadcast_lines(std::vector<Line>& lines, std::size_t& m, bool root) {
  std::vector<std::string> items;
  if (root) {
    for (std::size_t i = 0; i < m; ++i) items.push_back((lines[i].too_long ? "T" : "F") + lines[i].text);
  }
  std::vector<char> bytes = root ? pack(items) : std::vector<char>();
  std::uint64_t size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(size));
  MPI_Bcast(bytes.data(), checked_int(bytes.size()), MPI_BYTE, 0, MPI_COMM_WORLD);
  if (root) return;
  items = unpack(bytes.data(), bytes.size());
  m = items.size();
  for (std::size_t i = 0; i < m; ++i) {
    lines[i].too_long = items[i][0] == 'T';
    lines[i].text = items[i].substr(1);
  }
}

// Every rank's answers of its block [begin, end) to rank 0, into lines[begin, end).
void gather_answers(MpiWorld& world, std::vector<Line>& lines, std::size_t m) {
  const auto [begin, end] = rank_block(m, world.rank(), world.size());
  std::vector<std::string> mine;
  for (std::size_t i = begin; i < end; ++i) {
    const LineAnswer& a = lines[i].answer;
    mine.push_back(std::string(1, static_cast<char>('0' + (a.bad ? 1 : 0) + (a.not_converged ? 2 : 0))) + a.text);
    mine.push_back(a.message);
  }
  const std::vector<char> bytes = pack(mine);
  int count = checked_int(bytes.size());
  std::vector<int> counts(static_cast<std::size_t>(world.size())), displs(counts.size());
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<char> all;
  if (world.rank() == 0) {
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      displs[r] = checked_int(total);
      total += static_cast<std::size_t>(counts[r]);
    }
    all.resize(total);
  }
  MPI_Gatherv(bytes.data(), count, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
  if (world.rank() != 0) return;
  const std::vector<std::string> items = unpack(all.data(), all.size());
  require(items.size() == 2 * m, "internal: gathered " + std::to_string(items.size() / 2) + " answers of " + std::to_string(m));
  for (std::size_t i = 0; i < m; ++i) {
    const std::string& a = items[2 * i];
    require(!a.empty(), "internal: an empty gathered answer");
    const int flags = a[0] - '0';
    lines[i].answer = {a.substr(1), items[2 * i + 1], (flags & 1) != 0, (flags & 2) != 0};
  }
}

#endif

}  // namespace

BatchCounts answer_batch_lines(const contactrb::model::ReducedModel& model, const online::OnlineSizes& sizes, int jobs,
                               const ReadLine& read, const AnswerLine& answer, std::ostream& out, MpiWorld* world) {
  require(jobs >= 0, "--jobs must be >= 0 (0: every hardware thread; got " + std::to_string(jobs) + ")");
  if (jobs == 0) jobs = online::hardware_jobs();
  const int ranks = world ? world->size() : 1;
  const bool root = !world || world->rank() == 0;
  const std::size_t chunk = jobs == 1 && ranks == 1 ? 1 : static_cast<std::size_t>(jobs) * 64 * static_cast<std::size_t>(ranks);
  std::vector<Line> lines(chunk);
  std::vector<std::unique_ptr<online::OnlineSolver>> solvers;  // one per thread, for the whole batch
  for (int j = 0; j < jobs; ++j) solvers.push_back(std::make_unique<online::OnlineSolver>(model, sizes));
  BatchCounts counts;
  if (!world && jobs > 1) return pipeline_batch_lines(solvers, chunk, read, answer, out);
  try {
  for (;;) {
    std::size_t m = 0;
    if (root) {
      while (m < chunk && read(lines[m].text, lines[m].too_long)) ++m;
    }
#if CONTACTRB_HAVE_MPI
    if (world) broadcast_lines(lines, m, root);
#endif
    if (m == 0) break;
    const int first = counts.lines + 1;
    const auto [begin, end] = rank_block(m, world ? world->rank() : 0, ranks);
    online::for_each_query(solvers, end - begin, [&](online::OnlineSolver& solver, std::size_t j) {
      const std::size_t i = begin + j;
      lines[i].answer = answer(solver, first + static_cast<int>(i), lines[i].text, lines[i].too_long);
    }, 4);
#if CONTACTRB_HAVE_MPI
    if (world) gather_answers(*world, lines, m);
#endif
    counts.lines += static_cast<int>(m);
    if (!root) continue;
    for (std::size_t i = 0; i < m; ++i) {
      out << lines[i].answer.text;
      std::cerr << lines[i].answer.message;
      counts.bad += lines[i].answer.bad ? 1 : 0;
      counts.not_converged += lines[i].answer.not_converged ? 1 : 0;
    }
    out.flush();  // answers stream through pipes
  }
  } catch (const std::exception& e) {
    if (!world) throw;
    // A rank that leaves the chunk loop would leave the others waiting for it: end the job.
    std::cerr << "contactrb: internal error on MPI rank " << world->rank() << ": " << e.what() << " (ending the MPI job)\n"
              << std::flush;
    world->abort(2);
  }
  return counts;
}

}  // namespace contactrb::app
