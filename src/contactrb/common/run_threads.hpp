#pragma once
// The one thread pool of the library's parallel loops (snapshots --jobs, evaluate --jobs, the
// greedy's estimate sweep, many online queries): start the workers, join them, and hand the first
// exception back to the caller, since an exception escaping a std::thread ends the process.
#include <atomic>
#include <cstddef>
#include <functional>

namespace contactrb {

// Runs work(t) for t = 0 .. threads - 1, each on its own thread (on the calling thread when
// threads <= 1), and returns once all have returned. When a work(t) throws, `stop` is set (work
// should poll it and return early) and the first exception caught is rethrown after the join.
void run_threads(std::size_t threads, const std::function<void(std::size_t t)>& work, std::atomic<bool>& stop);

// The same for work that has no use for an early stop.
void run_threads(std::size_t threads, const std::function<void(std::size_t t)>& work);

}  // namespace contactrb
