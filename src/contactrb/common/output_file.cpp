#include "contactrb/common/output_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <system_error>
#include <thread>

#include "contactrb/common/error.hpp"
#include "contactrb/common/printable.hpp"

namespace contactrb {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTemporaryMarker = ".contactrb-tmp.";

// Built by appending: g++ 12 warns (-Wrestrict, a false positive) on "'" + std::string + "'".
std::string quoted(const fs::path& p) {
  std::string out(1, '\'');
  out += printable(p.string());
  out += '\'';
  return out;
}

void remove_quietly(const fs::path& p) {
  std::error_code ignored;
  fs::remove(p, ignored);
}

// The absolute form of `p` with "." and ".." resolved and the existing part's links followed.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) r = fs::absolute(p, ec).lexically_normal();
  return r;
}

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return resolved(a) == resolved(b);
}

void check_output_target(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  switch (st.type()) {
    case fs::file_type::not_found:
    case fs::file_type::regular:
      return;
    case fs::file_type::symlink:
      throw Error("output " + quoted(path) + " is a symbolic link: contactrb does not write through or replace "
                  "links; remove it or choose another path");
    case fs::file_type::directory:
      throw Error("output " + quoted(path) + " is a directory");
    default:
      if (ec) throw Error("output " + quoted(path) + " cannot be examined: " + ec.message());
      throw Error("output " + quoted(path) + " is not a regular file (a device, FIFO or socket); "
                  "choose a file path");
  }
}

fs::path temporary_path(const fs::path& target) {
  static std::atomic<unsigned long> counter{0};
  fs::path tmp = target;
  tmp += kTemporaryMarker + std::to_string(static_cast<long>(::getpid())) + "." + std::to_string(counter++);
  return tmp;
}

void remove_stale_temporaries(const fs::path& target) {
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string prefix = target.filename().string() + kTemporaryMarker;
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  if (ec) return;
  for (const fs::directory_entry& entry : it) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    // "<pid>.<counter>": the pid is the digits up to the next dot.
    const std::string rest = name.substr(prefix.size());
    const std::size_t dot = rest.find('.');
    if (dot == 0 || dot == std::string::npos || dot > 9) continue;
    bool digits = true;
    for (std::size_t k = 0; k < dot; ++k) digits = digits && rest[k] >= '0' && rest[k] <= '9';
    if (!digits) continue;
    const auto pid = static_cast<pid_t>(std::stol(rest.substr(0, dot)));
    // ESRCH: no such process. EPERM means it exists (another user's): leave its file alone.
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      // A StagingDirectory is removed with its content; a link is removed, never followed.
      if (entry.symlink_status(ignored).type() == fs::file_type::directory) {
        fs::remove_all(entry.path(), ignored);
      } else {
        remove_quietly(entry.path());
      }
    }
  }
}

namespace {
thread_local OutputSet* current_set = nullptr;
}  // namespace

OutputSet::OutputSet() : outer_(current_set) { current_set = this; }

OutputSet::~OutputSet() {
  if (current_set == this) current_set = outer_;
  for (const Staged& s : staged_) remove_quietly(s.tmp);
}

fs::path OutputSet::staged(const fs::path& target) const {
  for (auto it = staged_.rbegin(); it != staged_.rend(); ++it) {
    if (it->target == target) return it->tmp;
  }
  return target;
}

void OutputSet::add(const fs::path& tmp, const fs::path& target) { staged_.push_back({tmp, target}); }

void OutputSet::commit() {
  // From here on this set stages nothing: later writes of this thread go to the enclosing set,
  // if any, or straight to their targets.
  if (current_set == this) current_set = outer_;
  std::vector<Staged> pending;
  pending.swap(staged_);
  // Every target checked before the first rename: a directory or link at one of them must not
  // leave the files before it renamed and those after it lost.
  try {
    for (const Staged& s : pending) check_output_target(s.target);
  } catch (...) {
    for (const Staged& s : pending) remove_quietly(s.tmp);
    throw;
  }
  for (std::size_t i = 0; i < pending.size(); ++i) {
    try {
      commit_temporary(pending[i].tmp, pending[i].target);
    } catch (...) {
      for (std::size_t j = i + 1; j < pending.size(); ++j) remove_quietly(pending[j].tmp);
      throw;
    }
  }
}

void commit_temporary(const fs::path& tmp, const fs::path& target) {
  try {
    check_output_target(target);  // a link or device may have appeared while we wrote
  } catch (...) {
    remove_quietly(tmp);
    throw;
  }
  if (current_set != nullptr) {
    current_set->staged_.push_back({tmp, target});
    return;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    remove_quietly(tmp);
    throw Error("cannot write " + quoted(target) + ": rename failed: " + ec.message());
  }
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  require(!path.empty(), "cannot write a file with an empty path");
  const fs::path target(path);
  check_output_target(target);
  remove_stale_temporaries(target);
  const fs::path tmp = temporary_path(target);
  // O_EXCL | O_NOFOLLOW: a new file of our own, never an existing file or link of that name.
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) {
    const std::string reason = std::strerror(errno);
    throw Error("cannot write " + quoted(target) + ": " + reason);
  }
  ::close(fd);
  {
    std::ofstream out(tmp, std::ios::out | std::ios::trunc | std::ios::binary);
    if (!out) {
      remove_quietly(tmp);
      throw Error("cannot write " + quoted(target) + ": cannot open the temporary file");
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      remove_quietly(tmp);
      throw;
    }
    out.flush();
    const bool written = static_cast<bool>(out);
    out.close();
    if (!written || out.fail()) {
      remove_quietly(tmp);
      throw Error("cannot write " + quoted(target) + ": write failed (disk full?)");
    }
  }
  commit_temporary(tmp, target);
}

StagingDirectory::StagingDirectory(const fs::path& target) {
  remove_stale_temporaries(target);
  path_ = temporary_path(target);
  std::error_code ec;
  // create_directory is false when the name exists: never a directory of another process.
  if (!fs::create_directory(path_, ec) || ec) {
    const std::string reason = ec ? ec.message() : "it exists";
    path_.clear();
    throw Error("cannot create the staging directory for " + quoted(target) + ": " + reason);
  }
}

StagingDirectory::~StagingDirectory() {
  if (path_.empty()) return;
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

OutputLock::OutputLock(const fs::path& directory, double wait_seconds) {
  const fs::path dir = directory.empty() ? fs::path(".") : directory;
  fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) {
    const std::string reason = std::strerror(errno);
    throw Error("cannot open output directory " + quoted(dir) + ": " + reason);
  }
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(wait_seconds);
  while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EINTR) continue;
    if (errno != EWOULDBLOCK) {  // no flock on this file system: atomic files are all we have
      ::close(fd_);
      fd_ = -1;
      return;
    }
    if (Clock::now() >= deadline) {
      ::close(fd_);
      fd_ = -1;
      throw Error("output directory " + quoted(dir) + " is being written by another contactrb run (waited " +
                  std::to_string(static_cast<int>(wait_seconds)) + " s)");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the descriptor releases the lock
}

}  // namespace contactrb
