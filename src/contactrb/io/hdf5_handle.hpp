#pragma once
// HDF5 C API support shared by the io/ readers and writers (snapshot and reduced-model
// files): failures become exceptions carrying HDF5's own reason, identifiers are closed by
// RAII, and HDF5's automatic error printing is silenced while a file is handled.
// Internal to io/: include only from io/*.cpp (io links HDF5 privately).
#include <hdf5.h>

#include <cstddef>
#include <string>
#include <utility>

namespace contactrb::io::hdf5 {

// A failure inside a reader or writer; the public functions prefix the file name.
struct Failure {
  std::string what;
};

// HDF5 closes the identifiers still open at process exit (its atexit handler). A file whose
// flush failed (a full disk) cannot be closed: its identifier stays open, and closing it again
// at exit crashes the process or loops ("infinite loop closing library"). Our files are closed
// explicitly on every successful path, and a failed write's temporary is removed: the handler
// is not needed, so it is turned off before the library starts (a no-op when it already has).
inline void no_cleanup_at_exit() {
  static const bool once = [] {
    H5dont_atexit();
    return true;
  }();
  (void)once;
}

// Silences HDF5's automatic error printing for the lifetime of the object and restores the
// previous handler. Every public reader and writer starts with one, before any other HDF5 call.
class Quiet {
 public:
  Quiet() {
    no_cleanup_at_exit();
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~Quiet() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  Quiet(const Quiet&) = delete;
  Quiet& operator=(const Quiet&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// The system's message inside an HDF5 description of a failed system call ("file write
// failed: time = ..., errno = 28, error message = 'No space left on device', buf = ...") or, when
// there is none, the description itself: one line either way.
inline std::string system_message(const std::string& desc) {
  const std::string key = "error message = '";
  const std::size_t at = desc.find(key);
  if (at == std::string::npos) return desc;
  const std::size_t begin = at + key.size();
  const std::size_t end = desc.find('\'', begin);
  return end == std::string::npos ? desc : desc.substr(begin, end - begin);
}

// The innermost description on HDF5's error stack (e.g. "truncated file: eof = ...").
inline std::string reason() {
  std::string out;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
        auto* r = static_cast<std::string*>(data);
        if (n == 0 && e->desc != nullptr) *r = e->desc;
        return 0;
      },
      &out);
  return system_message(out);
}

inline Failure failure(const std::string& what) {
  const std::string r = reason();
  return Failure{what + (r.empty() ? "" : " (" + r + ")")};
}

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw failure(what);
}

// The element count of a dataset of shape dims[0..rank), checked before anything is
// allocated for it: our files store every dataset contiguous and uncompressed, so a dataset
// cannot hold more bytes than its file; a damaged header declaring more (or a count that
// overflows) would otherwise end in an allocation failure. Throws Failure naming the dataset.
inline hsize_t checked_element_count(hid_t dataset, const hsize_t* dims, int rank, std::size_t element_size,
                                     const std::string& name) {
  hsize_t file_size = 0;
  const hid_t file = H5Iget_file_id(dataset);
  if (file < 0 || H5Fget_filesize(file, &file_size) < 0) file_size = 0;
  if (file >= 0) H5Fclose(file);  // H5Iget_file_id opened a new reference
  const hsize_t limit = file_size / element_size;
  hsize_t total = 1;
  for (int i = 0; i < rank; ++i) {
    if (dims[i] != 0 && total > limit / dims[i]) {
      throw Failure{"dataset '" + name + "' declares more elements than the file can hold (damaged file)"};
    }
    total *= dims[i];
  }
  return total;
}

// An HDF5 identifier closed by `close` on destruction.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw failure(what);
  }
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      if (id_ >= 0) close_(id_);
      id_ = std::exchange(o.id_, -1);
      close_ = o.close_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  // Closes now and reports a failure (H5Fclose flushes: its status matters).
  void close(const std::string& what) {
    const herr_t status = close_(id_);
    id_ = -1;
    if (status < 0) throw failure(what);
  }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

}  // namespace contactrb::io::hdf5
