#pragma once
// Reduced model files (HDF5): the whole online state of a model::ReducedModel in one file
// (rbOOmit: one file serves every N below the maxima). Self-describing layout
// (docs/file-formats.md): groups /meta, /parameters, /theta, /primal, /dual, /eim/kappa,
// /eim/gamma, /surface, /estimate; scalars and strings (variable-length UTF-8) as group
// attributes; every array a dataset of its documented shape (a rows x cols matrix is stored
// rows x cols) with the attributes `shape_meaning` and `units`. The root attributes `format`,
// `format_version`, `checksum` (FNV-1a over every field, io/field_checksum.hpp) and `complete`
// (written last). Writing goes to a temporary file renamed over the target.
//
// Layering: io serializes the records of model/ (STYLE.md 3: online objects are serialized by
// io/), which sit below both io/ and online/. The semantic check of the loaded arrays is
// online::check_model (online/model_check.hpp), which OnlineSolver runs.
// Not stored: the parameter's named sets (ParameterSpec::sets; not needed online).
//
// Optional group /reconstruction (model::ReducedReconstruction: the HF-size basis, lift and dual
// basis that map a reduced solution back to the HF mesh) and /mesh (its reference mesh, so
// that no .msh file is needed). They have their own format version, checksum and `complete`
// mark (attributes of /reconstruction). read_reduced_model_file never opens them (the online
// model holds nothing of HF size); files without them (the model-only overload) stay valid.
#include <string>

#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::io {

inline constexpr const char* kReducedModelFormatName = "contactrb-reduced-model";

// Throws contactrb::Error naming `path` when the file cannot be written.
void write_reduced_model_file(const contactrb::model::ReducedModel& model, const std::string& path);
// Same, with the reconstruction data in the group "reconstruction".
void write_reduced_model_file(const contactrb::model::ReducedModel& model,
                              const contactrb::model::ReducedReconstruction& reconstruction, const std::string& path);

// Throws contactrb::Error naming `path` for a missing file, a file that is not HDF5, another
// format, another format version, a truncated or damaged file, an incomplete one, or a
// checksum mismatch.
contactrb::model::ReducedModel read_reduced_model_file(const std::string& path);

inline constexpr int kReconstructionFormatVersion = 2;  // 2: the layout of model formats 5 and 6, /mesh

// Whether the model file holds the group "reconstruction". Throws contactrb::Error naming
// `path` for a missing file or a file that is not HDF5 (same messages as the reader).
bool has_reconstruction(const std::string& path);

// The reconstruction data of a model file. Throws contactrb::Error naming `path` when the
// file has none (a model written without them: rerun `contactrb offline`), or when the group
// is damaged, incomplete, of another version, or fails its checksum or size checks.
contactrb::model::ReducedReconstruction read_reconstruction(const std::string& path);

}  // namespace contactrb::io
