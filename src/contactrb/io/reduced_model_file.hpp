#pragma once
// Reduced model files (HDF5): the whole online state of a rb::ReducedModel in one file
// (rbOOmit: one file serves every N below the maxima). Every field is one dataset of the root
// group (strings as bytes, scalars as one-element arrays, lists of arrays as name/0, name/1, ...),
// followed by an FNV-1a 64-bit checksum over every field in a fixed order and the dataset
// `complete`, written last. Writing goes to a temporary file renamed over the target.
//
// Layering: io serializes the rb record (STYLE.md 3: online objects are serialized by io/);
// only the plain struct is used, no rb function (rb links io, not the other way round). The
// semantic check of the loaded arrays is rb::check_model, which OnlineSolver runs.
// Not stored: the parameter's named sets (ParameterSpec::sets; not needed online).
//
// Optional group "reconstruction" (rb::ReducedReconstruction: the HF-size basis, lift and dual
// basis that map a reduced solution back to the HF mesh). It has its own format version,
// FNV-1a checksum and `complete` mark, inside the group. read_reduced_model_file never opens
// it (the online model holds nothing of HF size); files without it (written before it
// existed, or by the model-only overload) stay valid model files of the same format version.
#include <string>

#include "contactrb/online/reconstruction.hpp"
#include "contactrb/online/reduced_model.hpp"

namespace contactrb::io {

inline constexpr const char* kReducedModelFormatName = "contactrb-reduced-model";

// Throws contactrb::Error naming `path` when the file cannot be written.
void write_reduced_model_file(const rb::ReducedModel& model, const std::string& path);
// Same, with the reconstruction data in the group "reconstruction".
void write_reduced_model_file(const rb::ReducedModel& model, const rb::ReducedReconstruction& reconstruction,
                              const std::string& path);

// Throws contactrb::Error naming `path` for a missing file, a file that is not HDF5, another
// format, another format version, a truncated or damaged file, an incomplete one, or a
// checksum mismatch.
rb::ReducedModel read_reduced_model_file(const std::string& path);

inline constexpr int kReconstructionFormatVersion = 1;

// Whether the model file holds the group "reconstruction". Throws contactrb::Error naming
// `path` for a missing file or a file that is not HDF5 (same messages as the reader).
bool has_reconstruction(const std::string& path);

// The reconstruction data of a model file. Throws contactrb::Error naming `path` when the
// file has none (a model written without them: rerun `contactrb offline`), or when the group
// is damaged, incomplete, of another version, or fails its checksum or size checks.
rb::ReducedReconstruction read_reconstruction(const std::string& path);

}  // namespace contactrb::io
