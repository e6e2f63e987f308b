#include "contactrb/common/run_threads.hpp"

#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace contactrb {

void run_threads(std::size_t threads, const std::function<void(std::size_t t)>& work, std::atomic<bool>& stop) {
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto guarded = [&](std::size_t t) {
    try {
      work(t);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
  };
  if (threads <= 1) {
    guarded(0);
  } else {
    std::vector<std::thread> pool;
    pool.reserve(threads);
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(guarded, t);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

void run_threads(std::size_t threads, const std::function<void(std::size_t t)>& work) {
  std::atomic<bool> stop{false};
  run_threads(threads, work, stop);
}

}  // namespace contactrb
