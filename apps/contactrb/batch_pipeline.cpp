#include "batch_pipeline.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <iostream>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

#include "contactrb/common/error.hpp"

namespace contactrb::app {

namespace {

// Chunks read ahead of the printer: enough to keep the workers busy while one chunk is being
// read and another printed.
constexpr std::size_t kDepth = 4;
// Lines a worker takes at a time (a few tens of microseconds of work each).
constexpr std::size_t kPiece = 4;

struct Line {
  std::string text;
  bool too_long = false;
  LineAnswer answer;
};

struct Chunk {
  std::vector<Line> lines;  // the first m are this chunk's
  std::size_t m = 0;
  int first = 0;            // line number of lines[0] (1-based)
  std::size_t next = 0;     // the next line to hand out
  std::size_t done = 0;     // lines answered
};

class Pipeline {
 public:
  Pipeline(std::size_t chunk, const AnswerLine& answer, std::ostream& out)
      : chunk_(chunk), answer_(answer), out_(out), slots_(kDepth) {
    for (std::size_t s = 0; s < kDepth; ++s) {
      slots_[s].lines.resize(chunk);
      free_.push_back(s);
    }
  }

  // A solver thread's loop: pieces of the oldest chunks with lines left, until the input is read
  // and every line handed out (or stop).
  void work(online::OnlineSolver& solver) {
    guarded([&] {
      std::unique_lock<std::mutex> lock(mutex_);
      for (;;) {
        Chunk* c = nullptr;
        work_cv_.wait(lock, [&] {
          if (stop_) return true;
          for (std::size_t s : order_) {
            if (slots_[s].next < slots_[s].m) {
              c = &slots_[s];
              return true;
            }
          }
          return eof_;
        });
        if (c == nullptr) return;  // stop, or nothing left to hand out
        const std::size_t begin = c->next, end = std::min(c->m, begin + kPiece);
        c->next = end;
        lock.unlock();
        // The lines [begin, end) belong to this thread until `done` counts them.
        for (std::size_t i = begin; i < end; ++i) {
          Line& line = c->lines[i];
          line.answer = answer_(solver, c->first + static_cast<int>(i), line.text, line.too_long);
        }
        lock.lock();
        c->done += end - begin;
        if (c->done == c->m) print_cv_.notify_one();
      }
    });
  }

  // The printer's loop: the oldest chunk once answered, until the input is read and printed.
  void print() {
    guarded([&] {
      std::string buffer, messages;
      std::unique_lock<std::mutex> lock(mutex_);
      for (;;) {
        print_cv_.wait(lock, [&] {
          return stop_ || (order_.empty() && eof_) || (!order_.empty() && slots_[order_.front()].done == slots_[order_.front()].m);
        });
        if (stop_ || order_.empty()) return;
        const std::size_t s = order_.front();
        lock.unlock();
        // Answered and not yet released: no other thread touches this slot.
        const Chunk& c = slots_[s];
        buffer.clear();
        messages.clear();
        for (std::size_t i = 0; i < c.m; ++i) {
          const LineAnswer& a = c.lines[i].answer;
          buffer += a.text;
          messages += a.message;
          counts_.bad += a.bad ? 1 : 0;
          counts_.not_converged += a.not_converged ? 1 : 0;
        }
        counts_.lines += static_cast<int>(c.m);
        out_.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        out_.flush();  // answers stream through pipes
        std::cerr << messages;
        lock.lock();
        order_.pop_front();
        free_.push_back(s);
        slot_cv_.notify_one();
      }
    });
  }

  // The reader's loop (the calling thread): chunks into free slots until the end of the input.
  void read_all(const ReadLine& read) {
    guarded([&] {
      int lines = 0;
      for (;;) {
        std::size_t s = 0;
        {
          std::unique_lock<std::mutex> lock(mutex_);
          slot_cv_.wait(lock, [&] { return stop_ || !free_.empty(); });
          if (stop_) return;
          s = free_.front();
          free_.pop_front();
        }
        // A free slot belongs to the reader until it is queued.
        Chunk& c = slots_[s];
        c.m = 0;
        while (c.m < chunk_ && !stopped() && read(c.lines[c.m].text, c.lines[c.m].too_long)) ++c.m;
        const bool end = c.m < chunk_;
        const std::lock_guard<std::mutex> lock(mutex_);
        if (c.m > 0) {
          c.first = lines + 1;
          c.next = 0;
          c.done = 0;
          lines += static_cast<int>(c.m);
          order_.push_back(s);
        } else {
          free_.push_back(s);
        }
        if (end) eof_ = true;
        // Workers: a new chunk, or the end; the printer: the end (an empty queue).
        work_cv_.notify_all();
        print_cv_.notify_one();
        if (end) return;
      }
    });
  }

  // Stops every loop (after an exception).
  void stop() {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    work_cv_.notify_all();
    print_cv_.notify_all();
    slot_cv_.notify_all();
  }

  void rethrow_error() const {
    if (error_) std::rethrow_exception(error_);
  }
  const BatchCounts& counts() const { return counts_; }

 private:
  bool stopped() const { return stop_; }

  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (...) {
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
      stop();
    }
  }

  const std::size_t chunk_;
  const AnswerLine& answer_;
  std::ostream& out_;
  std::vector<Chunk> slots_;
  std::mutex mutex_;
  std::condition_variable work_cv_, print_cv_, slot_cv_;
  std::deque<std::size_t> order_;  // slots read and not yet printed, in input order
  std::deque<std::size_t> free_;   // slots the reader may fill
  bool eof_ = false;
  std::atomic<bool> stop_{false};  // set under the mutex (the waits' conditions); read without it by the reader
  std::exception_ptr error_;
  BatchCounts counts_;  // the printer's
};

}  // namespace

BatchCounts pipeline_batch_lines(const std::vector<std::unique_ptr<online::OnlineSolver>>& solvers, std::size_t chunk,
                                 const ReadLine& read, const AnswerLine& answer, std::ostream& out) {
  require(!solvers.empty() && chunk >= 1, "internal: a batch pipeline without solvers or chunks");
  Pipeline pipeline(chunk, answer, out);
  std::vector<std::thread> threads;
  try {
    threads.emplace_back([&] { pipeline.print(); });
    for (const auto& s : solvers) threads.emplace_back([&pipeline, solver = s.get()] { pipeline.work(*solver); });
  } catch (...) {  // a thread that could not start: stop those that did
    pipeline.stop();
    for (std::thread& t : threads) t.join();
    throw;
  }
  pipeline.read_all(read);
  for (std::thread& t : threads) t.join();
  pipeline.rethrow_error();
  return pipeline.counts();
}

}  // namespace contactrb::app
