#pragma once
// Writing a file so that readers never see a half-written one: the content goes to a
// temporary file in the same directory, which is renamed over the target only once it is
// complete and flushed (rename is atomic within one file system).
#include <functional>
#include <ostream>
#include <string>

namespace contactrb::io {

// Calls write(stream) on a temporary file next to `path`, then renames it to `path`.
// Throws contactrb::Error naming `path` when the directory is not writable, the stream
// fails, or the rename fails; the temporary file is removed and `path` is left untouched.
// An exception thrown by `write` itself also removes the temporary file and propagates.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace contactrb::io
