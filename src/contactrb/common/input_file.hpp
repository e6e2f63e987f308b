#pragma once
// Checks made before any reader opens an input file: the path names a regular file (a
// directory, a device such as /dev/zero, a FIFO or a socket could be read without end) whose
// size is below a limit, so that no reader allocates or loops without bound. The limits can
// be raised through environment variables (docs/file-formats.md, "Input files").
#include <cstdint>
#include <string>

namespace contactrb {

// Text inputs are read whole (.msh, TOML case files, parameter files, batch files); HDF5
// inputs (snapshot and model files) dataset by dataset.
enum class InputKind { Text, Hdf5 };
const char* to_string(InputKind kind);  // "text" | "hdf5"
InputKind input_kind_from_string(const std::string& name);  // throws contactrb::Error

// Default limits in MiB. A .msh of a 1e6-DOF mesh is about 70 MB; a snapshot file of
// 100 snapshots of 1e6 DOFs about 1 GB.
inline constexpr std::uintmax_t kDefaultTextInputLimitMiB = 256;
inline constexpr std::uintmax_t kDefaultHdf5InputLimitMiB = 65536;

// The environment variables that replace the defaults (a positive integer, in MiB).
inline constexpr const char* kTextInputLimitVariable = "CONTACTRB_MAX_TEXT_INPUT_MB";
inline constexpr const char* kHdf5InputLimitVariable = "CONTACTRB_MAX_HDF5_INPUT_MB";

// The limit in bytes. Throws contactrb::Error naming the variable when it is set to
// something other than a positive integer.
std::uintmax_t input_size_limit(InputKind kind);

// Throws contactrb::Error("<what> '<path>' ...") when `path` does not exist, is not a
// regular file (symbolic links are followed: a link to a regular file is fine), or is larger
// than the limit. Returns the file's size in bytes.
std::uintmax_t check_input_file(const std::string& path, const std::string& what, InputKind kind);

// check_input_file(path, what, InputKind::Text), then the whole content; never reads more
// than the limit even when the file grows meanwhile.
std::string read_text_input(const std::string& path, const std::string& what);

}  // namespace contactrb
