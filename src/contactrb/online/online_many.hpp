#pragma once
// Many-query online solves on threads (docs/parallel.md, "Many queries"): `online --batch --jobs J`,
// `contactrb sample`. Each thread has its own OnlineSolver (it holds per-query workspaces),
// built from the same model and sizes; the indices are handed out in chunks from one shared
// counter, and every answer goes to the slot of its index, so the output order is the input
// order whatever J. A solver's answer at mu does not depend on the queries it answered before
// (each query starts from its own initial guess and clears the QP warm start), so the answers
// equal the serial ones bit for bit (tests/offline/test_online_many.cpp).
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::online {

// The number of hardware threads (at least 1): the default of --jobs for many queries.
int hardware_jobs();

// Calls fn(solver, i) for every i in [0, count) on min(jobs, chunks) threads (jobs >= 1), each
// with its own solver; `chunk` consecutive indices at a time. fn runs concurrently on different
// threads with different i: it may write only what belongs to i. The first exception (of fn or
// of a solver's construction) is rethrown once every thread has stopped (the others stop taking
// new chunks). Throws contactrb::Error for jobs < 1 or chunk < 1.
void for_each_query(const contactrb::model::ReducedModel& model, const OnlineSizes& sizes, std::size_t count, int jobs,
                    const std::function<void(OnlineSolver& solver, std::size_t i)>& fn, std::size_t chunk = 16);

// The same with solvers made beforehand (kept across calls: a batch answered chunk by chunk):
// thread t uses solvers[t], min(solvers.size(), chunks) threads. Throws contactrb::Error when
// `solvers` is empty or holds a null pointer.
void for_each_query(const std::vector<std::unique_ptr<OnlineSolver>>& solvers, std::size_t count,
                    const std::function<void(OnlineSolver& solver, std::size_t i)>& fn, std::size_t chunk = 16);

// One point's answer: the solution, or the message of the contactrb::Error the solver threw
// for it (a point outside the domain, of the wrong size).
struct QueryAnswer {
  bool answered = false;
  std::string error;
  OnlineSolution solution;
};

// Every point solved with `settings`, answers in the order of `points`.
std::vector<QueryAnswer> solve_many(const contactrb::model::ReducedModel& model, const OnlineSizes& sizes,
                                    const OnlineSettings& settings, const std::vector<cases::Mu>& points, int jobs);

}  // namespace contactrb::online
