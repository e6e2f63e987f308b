#include "contactrb/online/online_many.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

#include "contactrb/common/error.hpp"
#include "contactrb/common/run_threads.hpp"

namespace contactrb::online {

using model::ReducedModel;

int hardware_jobs() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

namespace {

// The chunks [c chunk, (c + 1) chunk) of [0, count) from one counter, until none is left or `stop`.
void take_chunks(std::atomic<std::size_t>& next, std::size_t count, std::size_t chunk, const std::atomic<bool>& stop,
                 OnlineSolver& solver, const std::function<void(OnlineSolver& solver, std::size_t i)>& fn) {
  const std::size_t chunks = (count + chunk - 1) / chunk;
  for (std::size_t c = next.fetch_add(1); c < chunks && !stop; c = next.fetch_add(1)) {
    const std::size_t end = std::min(count, (c + 1) * chunk);
    for (std::size_t i = c * chunk; i < end; ++i) fn(solver, i);
  }
}

}  // namespace

void for_each_query(const ReducedModel& model, const OnlineSizes& sizes, std::size_t count, int jobs,
                    const std::function<void(OnlineSolver& solver, std::size_t i)>& fn, std::size_t chunk) {
  require(jobs >= 1, "the number of jobs must be >= 1 (got " + std::to_string(jobs) + ")");
  require(chunk >= 1, "the chunk size must be >= 1");
  if (count == 0) return;
  const std::size_t chunks = (count + chunk - 1) / chunk;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  run_threads(std::min(chunks, static_cast<std::size_t>(jobs)), [&](std::size_t) {
    OnlineSolver solver(model, sizes);  // built on its thread: in parallel
    take_chunks(next, count, chunk, stop, solver, fn);
  }, stop);
}

void for_each_query(const std::vector<std::unique_ptr<OnlineSolver>>& solvers, std::size_t count,
                    const std::function<void(OnlineSolver& solver, std::size_t i)>& fn, std::size_t chunk) {
  require(!solvers.empty(), "no online solver given");
  for (const auto& s : solvers) require(s != nullptr, "a null online solver");
  require(chunk >= 1, "the chunk size must be >= 1");
  if (count == 0) return;
  const std::size_t chunks = (count + chunk - 1) / chunk;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  run_threads(std::min(chunks, solvers.size()),
              [&](std::size_t t) { take_chunks(next, count, chunk, stop, *solvers[t], fn); }, stop);
}

std::vector<QueryAnswer> solve_many(const ReducedModel& model, const OnlineSizes& sizes, const OnlineSettings& settings,
                                    const std::vector<cases::Mu>& points, int jobs) {
  std::vector<QueryAnswer> answers(points.size());
  for_each_query(model, sizes, points.size(), jobs, [&](OnlineSolver& solver, std::size_t i) {
    try {
      answers[i].solution = solver.solve(points[i], settings);
      answers[i].answered = true;
    } catch (const Error& e) {
      answers[i].error = e.what();
    }
  });
  return answers;
}

}  // namespace contactrb::online
