#pragma once
// Snapshots as bytes, for sending between processes (apps/contactrb/mpi_snapshots.cpp): every
// field of io::Snapshot and offline::SnapshotLayout, bit for bit (the gathered file must equal the
// serial one). Both ends are the same executable, so the bytes are in the machine's own order.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace contactrb::offline {

// The result of one solve: its index in the set, the snapshot and the solver's layout.
std::vector<char> pack_solved(std::uint64_t index, const io::Snapshot& snapshot, const SnapshotLayout& layout);
// Throws contactrb::Error ("internal: ...") for bytes that are not a whole packed result.
void unpack_solved(const std::vector<char>& bytes, std::uint64_t& index, io::Snapshot& snapshot, SnapshotLayout& layout);

// A task: the index to solve and, when warm-starting, the snapshot to start from (only its
// `converged`, `u` and `lambda` are sent: what solve_snapshot uses of it).
std::vector<char> pack_task(std::uint64_t index, const io::Snapshot* start);
void unpack_task(const std::vector<char>& bytes, std::uint64_t& index, bool& has_start, io::Snapshot& start);

}  // namespace contactrb::offline
