#pragma once
// Self-describing HDF5 fields shared by the snapshot and reduced-model files
// (docs/file-formats.md): strings as fixed-length UTF-8 string attributes (h5py reads them as
// numpy.bytes_), numbers as scalar attributes, arrays as contiguous datasets whose HDF5 shape
// is the documented one (C order: a rows x cols matrix is stored rows x cols), each with the
// descriptive attributes `shape_meaning` and `units`.
// Internal to io/: include only from io/*.cpp (io links HDF5 privately).
#include <hdf5.h>

#include <cstdlib>
#include <string>

#include "contactrb/io/hdf5_handle.hpp"

namespace contactrb::io::hdf5 {

// A fixed-length UTF-8 string type of `size` bytes, padded with NUL bytes (no terminator).
// Strings are never variable-length: HDF5 1.10 crashes reading a variable-length string whose
// global-heap entry or length is damaged, and a file can be damaged and sealed again
// (docs/file-formats.md, "What the seal protects against").
inline Handle fixed_string_type(std::size_t size) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create a string type");
  check(H5Tset_size(type.get(), size), "cannot size a string type");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "cannot set string padding");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot set string encoding");
  return type;
}

// Attribute `name` of `loc` (a group or dataset), a scalar fixed-length string of the value's
// byte length (1 for the empty string, stored as one NUL byte).
inline void write_string_attribute(hid_t loc, const std::string& name, const std::string& value) {
  if (value.find('\0') != std::string::npos) throw Failure{"attribute '" + name + "' contains a NUL byte"};
  const std::size_t size = value.empty() ? 1 : value.size();
  Handle type = fixed_string_type(size);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
  Handle attr(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  std::string data = value;
  data.resize(size, '\0');
  check(H5Awrite(attr.get(), type.get(), data.data()), "cannot write attribute '" + name + "'");
}

// A scalar number attribute.
template <typename T>
void write_number_attribute(hid_t loc, const std::string& name, T value, hid_t file_type, hid_t mem_type) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
  Handle attr(H5Acreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  check(H5Awrite(attr.get(), mem_type, &value), "cannot write attribute '" + name + "'");
}

inline Handle open_attribute(hid_t loc, const std::string& name) {
  if (H5Aexists(loc, name.c_str()) <= 0) throw Failure{"missing attribute '" + name + "'"};
  Handle attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute '" + name + "'");
  // A scalar: a dataspace of more than one element would overflow the one value read.
  Handle space(H5Aget_space(attr.get()), H5Sclose, "cannot read the shape of attribute '" + name + "'");
  if (H5Sget_simple_extent_npoints(space.get()) != 1) throw Failure{"attribute '" + name + "' is not a scalar"};
  return attr;
}

// File-creation properties with a user block of kSealBlock bytes for the seal
// (common/file_seal.hpp), written after HDF5 has closed the file.
inline Handle sealed_file_properties() {
  Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "cannot create file-creation properties");
  check(H5Pset_userblock(fcpl.get(), 512), "cannot reserve the user block");
  return fcpl;
}

// True when attribute `name` of `loc` exists and is a variable-length string: told from its
// type alone, its value is never read (the files of older formats; see fixed_string_type).
inline bool is_vlen_string_attribute(hid_t loc, const std::string& name) {
  if (H5Aexists(loc, name.c_str()) <= 0) return false;
  Handle attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute '" + name + "'");
  Handle type(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of attribute '" + name + "'");
  return H5Tget_class(type.get()) == H5T_STRING && H5Tis_variable_str(type.get()) > 0;
}

// A scalar fixed-length string attribute (any padding and character set; trailing NUL bytes
// dropped). A variable-length one is refused, not read (see fixed_string_type).
inline std::string read_string_attribute(hid_t loc, const std::string& name) {
  Handle attr = open_attribute(loc, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of attribute '" + name + "'");
  if (H5Tget_class(type.get()) != H5T_STRING) throw Failure{"attribute '" + name + "' is not a string"};
  if (H5Tis_variable_str(type.get()) != 0) {
    throw Failure{"attribute '" + name + "' is a variable-length string, which this format never stores (not read)"};
  }
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > (1u << 24)) throw Failure{"attribute '" + name + "' has an invalid string size"};
  std::string value(size, '\0');
  check(H5Aread(attr.get(), type.get(), value.data()), "cannot read attribute '" + name + "'");
  const std::size_t end = value.find_last_not_of('\0');
  value.resize(end == std::string::npos ? 0 : end + 1);
  return value;
}

template <typename T>
T read_number_attribute(hid_t loc, const std::string& name, hid_t mem_type, H5T_class_t expected) {
  Handle attr = open_attribute(loc, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of attribute '" + name + "'");
  if (H5Tget_class(type.get()) != expected) throw Failure{"attribute '" + name + "' has the wrong type"};
  T value{};
  check(H5Aread(attr.get(), mem_type, &value), "cannot read attribute '" + name + "'");
  return value;
}

// What a dataset's axes and values mean (docs/file-formats.md): every dataset has both.
struct Description {
  const char* shape_meaning;  // e.g. "n_free x N: column j is basis vector j on the free DOFs"
  const char* units;          // e.g. "length", "1" (dimensionless), "index" (0-based), "count"
};

// A contiguous dataset `name` of `loc` with shape dims[0..rank), C order, and its description.
inline void write_dataset(hid_t loc, const std::string& name, const void* data, int rank, const hsize_t* dims,
                          hid_t file_type, hid_t mem_type, const Description& d) {
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "cannot create the dataspace of '" + name + "'");
  Handle set(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             "cannot create dataset '" + name + "'");
  hsize_t total = 1;
  for (int i = 0; i < rank; ++i) total *= dims[i];
  if (total > 0) {
    check(H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset '" + name + "'");
  }
  write_string_attribute(set.get(), "shape_meaning", d.shape_meaning);
  write_string_attribute(set.get(), "units", d.units);
}

// Opens dataset `name` of `loc`, checks its rank and type class, fills dims[0..rank) and
// bounds the element count by the file's size (a damaged header) before the caller allocates.
inline Handle open_dataset(hid_t loc, const std::string& name, int rank, H5T_class_t expected, hsize_t* dims,
                           std::size_t element_size) {
  if (H5Lexists(loc, name.c_str(), H5P_DEFAULT) <= 0) throw Failure{"missing dataset '" + name + "'"};
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset '" + name + "'");
  Handle space(H5Dget_space(set.get()), H5Sclose, "cannot read the shape of dataset '" + name + "'");
  const int actual = H5Sget_simple_extent_ndims(space.get());
  if (actual != rank) {
    throw Failure{"dataset '" + name + "' has rank " + std::to_string(actual) + ", expected " + std::to_string(rank)};
  }
  check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), "cannot read the shape of dataset '" + name + "'");
  Handle type(H5Dget_type(set.get()), H5Tclose, "cannot read the type of dataset '" + name + "'");
  if (H5Tget_class(type.get()) != expected) throw Failure{"dataset '" + name + "' has the wrong type"};
  checked_element_count(set.get(), dims, rank, element_size, name);
  return set;
}

// A group `name` of `loc` with its `description` attribute.
inline Handle create_group(hid_t loc, const std::string& name, const std::string& description) {
  Handle g(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
           "cannot create group '" + name + "'");
  write_string_attribute(g.get(), "description", description);
  return g;
}

inline Handle open_group(hid_t loc, const std::string& name) {
  if (H5Lexists(loc, name.c_str(), H5P_DEFAULT) <= 0) throw Failure{"missing group '" + name + "'"};
  Handle g(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group '" + name + "'");
  return g;
}

}  // namespace contactrb::io::hdf5
