#pragma once
// Waiting for MPI without spinning (docs/parallel.md): OpenMPI's blocking calls spin, which
// takes a core from the solves running next to the waiter (rank 0's own solver thread, the other
// ranks of the machine). A waiter polls instead (MPI_Iprobe, MPI_Test) and sleeps between polls:
// first briefly, then each sleep twice the last up to a cap, so that a short wait adds little
// latency and a long one costs few wake-ups (at the cap of 1 ms: 1000 a second, each a few
// microseconds, against 5000 a second with the fixed 0.2 ms sleeps used before).
#include <algorithm>
#include <chrono>
#include <thread>

namespace contactrb::app {

class PollBackoff {
 public:
  using Duration = std::chrono::microseconds;
  explicit PollBackoff(Duration cap = Duration(1000), Duration first = Duration(20))
      : first_(first), cap_(std::max(first, cap)), next_(first) {}

  // Sleeps, and doubles the next sleep (up to the cap).
  void sleep() {
    std::this_thread::sleep_for(next_);
    next_ = std::min(cap_, next_ * 2);
  }
  // After a message: the next wait starts short again.
  void reset() { next_ = first_; }
  // The longest sleep (at least the first).
  void set_cap(Duration cap) {
    cap_ = std::max(first_, cap);
    next_ = std::min(next_, cap_);
  }

 private:
  Duration first_, cap_, next_;
};

}  // namespace contactrb::app
