// common/run_threads: every worker runs once, the pool is really parallel, and an exception of a
// worker reaches the caller (instead of std::terminate) after every worker has returned.
#include "contactrb/common/run_threads.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace contactrb {
namespace {

TEST(RunThreads, EveryWorkerRunsOnceOnItsOwnThread) {
  for (std::size_t threads : {std::size_t{0}, std::size_t{1}, std::size_t{4}}) {
    const std::size_t n = std::max<std::size_t>(threads, 1);
    std::vector<int> calls(n, 0);
    std::vector<std::thread::id> ids(n);
    run_threads(threads, [&](std::size_t t) {
      ++calls[t];
      ids[t] = std::this_thread::get_id();
    });
    for (std::size_t t = 0; t < n; ++t) EXPECT_EQ(calls[t], 1) << "threads " << threads << ", worker " << t;
    if (threads <= 1) {
      EXPECT_EQ(ids[0], std::this_thread::get_id());  // the caller's thread: no pool for one job
    } else {
      for (std::size_t t = 0; t < n; ++t) {
        EXPECT_NE(ids[t], std::this_thread::get_id());
        for (std::size_t s = 0; s < t; ++s) EXPECT_NE(ids[s], ids[t]);
      }
    }
  }
}

TEST(RunThreads, WorkersRunConcurrently) {
  // Two workers that each wait for the other: finishes only if both run at the same time.
  std::atomic<int> arrived{0};
  run_threads(2, [&](std::size_t) {
    ++arrived;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (arrived.load() < 2) {
      if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("the other worker never started");
      std::this_thread::yield();
    }
  });
  EXPECT_EQ(arrived.load(), 2);
}

TEST(RunThreads, FirstExceptionIsRethrownAfterAllWorkersReturnAndStopIsSet) {
  std::atomic<bool> stop{false};
  std::atomic<int> returned{0};
  try {
    run_threads(3, [&](std::size_t t) {
      if (t == 1) throw std::runtime_error("worker 1 failed");
      // The others poll `stop`, as the library's loops do, and return once it is set.
      while (!stop) std::this_thread::yield();
      ++returned;
    }, stop);
    FAIL() << "no exception reached the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "worker 1 failed");
  }
  EXPECT_TRUE(stop.load());
  EXPECT_EQ(returned.load(), 2);  // joined before the rethrow
}

}  // namespace
}  // namespace contactrb
