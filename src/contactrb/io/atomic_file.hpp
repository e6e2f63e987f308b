#pragma once
// Writing a file so that readers never see a half-written one: the content goes to a new
// temporary file in the same directory, which is renamed over the target only once it is
// complete and flushed (rename is atomic within one file system). The implementation lives in
// common/output_file.hpp, which the mesh writer shares; io keeps its historical name.
#include "contactrb/common/output_file.hpp"

namespace contactrb::io {

using contactrb::write_file_atomically;

}  // namespace contactrb::io
