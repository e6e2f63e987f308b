#pragma once
// Snapshot sets computed in parts, for array jobs without MPI (docs/parallel.md):
// `contactrb snapshots --part k/K` solves part k of K of the parameter values and writes an
// ordinary snapshot file of them; `contactrb merge` checks the K parts and writes the one file
// the serial run writes (the same bytes but the timings).
//
// Part k holds the values of index i with i mod K = k - 1 (strided: neighbouring values, whose
// solve times are alike, go to different parts). A part records which part it is in its set
// name, "training [part 2/4 of 37 values, 0123456789abcdef]": the set, k/K, the number of
// values of the whole set and a 64-bit hash of all of them, so that the merge can tell parts
// of different runs apart and name a missing or repeated part.
//
// The parts are solved cold (no warm start; the default Kacanov method never warm-starts):
// a warm start would start from points of other parts.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace contactrb::offline {

struct SnapshotPart {
  int k = 1;      // 1..count
  int count = 1;  // K
};

// "k/K" with 1 <= k <= K. Throws contactrb::Error naming `flag`.
SnapshotPart parse_snapshot_part(const std::string& text, const std::string& flag = "--part");

// The indices of part `part` of n values: k - 1, k - 1 + K, ... (ascending).
std::vector<std::size_t> part_indices(std::size_t n, SnapshotPart part);

// What a part's set name records.
struct PartTag {
  std::string set;  // the name of the whole set ("training", "custom", ...)
  SnapshotPart part;
  std::size_t total = 0;     // values of the whole set
  std::uint64_t values = 0;  // values_hash of them
};
std::string part_tag_text(const PartTag& tag);
// nullopt when `set_name` is not the name of a part.
std::optional<PartTag> parse_part_tag(const std::string& set_name);

// FNV-1a over p and the bytes of every point, in order.
std::uint64_t values_hash(const std::vector<cases::Mu>& mu);

// Restricts `request` to its part: request.mu becomes the part's values and request.set_name
// its tag. Throws contactrb::Error when K exceeds the number of values (a part would be empty).
void restrict_to_part(SnapshotRequest& request, SnapshotPart part);

// One part as read from its file.
struct PartFile {
  std::string path;
  io::SnapshotSet set;
};

// The whole set of the parts (any order). Throws contactrb::Error naming the files when a file
// is not a part, parts come from different runs (case, level, parameters, Kacanov settings,
// discretization, set, K or values), a part is given twice, a part is missing (all missing
// parts named), or a part does not hold the values of its index.
io::SnapshotSet merge_snapshot_parts(const std::vector<PartFile>& parts);

// Throws contactrb::Error naming `path` when `set` is one part of a set (a model built from it
// would silently miss the other parts' values).
void refuse_snapshot_part(const io::SnapshotSet& set, const std::string& path);

}  // namespace contactrb::offline
