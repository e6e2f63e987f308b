#pragma once
// Writing outputs without ever losing a file (docs/file-formats.md, "Output files"):
// - an output replaces only a regular file: a symbolic link, a device (/dev/null, /dev/full),
//   a FIFO or a directory at the output path is refused, never followed or replaced;
// - the content goes to a new temporary file next to the target (created exclusively, so an
//   existing file or link of that name is never opened), renamed over the target once it is
//   complete (rename is atomic within one file system);
// - temporary files of processes that died (SIGKILL, power loss) are removed the next time
//   the same target is written;
// - OutputLock serializes the writing of a set of files into one directory, so that two
//   concurrent runs never leave files of one beside files of the other.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace contactrb {

// True when `a` and `b` name the same file: the same inode when both exist (hard links and
// symbolic links included), otherwise the same absolute path after resolving the part that
// exists (a path that does not exist yet: "d/../x" and "x").
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws contactrb::Error naming `path` when it exists and is not a regular file (checked
// without following a symbolic link).
void check_output_target(const std::filesystem::path& path);

// A fresh temporary name next to `target`: "<target>.contactrb-tmp.<pid>.<counter>".
std::filesystem::path temporary_path(const std::filesystem::path& target);

// Removes the temporary files (and staging directories, with their content) of `target`
// (temporary_path's form) whose process is gone. Files of a running process are left alone; errors are ignored (a cleanup, not a step).
void remove_stale_temporaries(const std::filesystem::path& target);

// Renames the complete temporary file `tmp` to `target` after check_output_target(target);
// removes `tmp` and throws contactrb::Error naming `target` when that fails. Inside an
// OutputSet of this thread the rename waits for OutputSet::commit.
void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& target);

// The files one command writes appear together or not at all (a full disk half way through
// must not leave a solution.json saying "converged" without its fields). While an OutputSet
// lives, every complete temporary file this thread hands to commit_temporary (every writer of
// the library does) stays under its temporary name; commit() renames them all to their
// targets, in order (a rename within a directory needs no space). An OutputSet destroyed
// without commit() (an exception) removes them, and the targets keep their earlier contents.
// One per thread at a time; writes from other threads are committed at once as usual.
class OutputSet {
 public:
  OutputSet();
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Where `target`'s content is until commit(): its temporary file when it was written in this
  // set, else `target` itself (for a program that reads an output of this run, e.g. a plot).
  std::filesystem::path staged(const std::filesystem::path& target) const;
  // Adds a temporary file written by other means (a script) to commit as `target`.
  void add(const std::filesystem::path& tmp, const std::filesystem::path& target);
  // Renames every staged file to its target, after checking every target (check_output_target).
  // Throws contactrb::Error naming the first target that cannot be replaced; when a check fails
  // no file is renamed, and the files not renamed are removed.
  void commit();

 private:
  struct Staged {
    std::filesystem::path tmp, target;
  };
  std::vector<Staged> staged_;
  OutputSet* outer_ = nullptr;
  friend void commit_temporary(const std::filesystem::path&, const std::filesystem::path&);
};

// A new, empty directory next to `target` (temporary_path's name), for a program that writes the
// files of an output set itself (a plotting script); OutputSet::add then commits its files.
// Removed with whatever is left in it when destroyed; one left by a killed process is removed by
// the next StagingDirectory of the same target (remove_stale_temporaries). Throws
// contactrb::Error when it cannot be created.
class StagingDirectory {
 public:
  explicit StagingDirectory(const std::filesystem::path& target);
  ~StagingDirectory();
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Calls write(stream) on a new temporary file next to `path`, then renames it to `path`.
// Throws contactrb::Error naming `path` when the target is not a regular file, the directory
// is not writable, the stream fails, or the rename fails; the temporary file is removed and
// `path` is left untouched. An exception thrown by `write` itself also removes the temporary
// file and propagates.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// An exclusive advisory lock (flock) on a directory, held for the lifetime of the object;
// released by the kernel when the process dies, so a killed run never blocks the next one.
// Waits up to `wait_seconds` for another holder, then throws contactrb::Error. On a file
// system without flock support the lock is skipped (the outputs are still atomic one by one).
class OutputLock {
 public:
  explicit OutputLock(const std::filesystem::path& directory, double wait_seconds = 600.0);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace contactrb
