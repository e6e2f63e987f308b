#pragma once
// ParaView data collection (.pvd): an XML list of datasets, each with a time step, that
// ParaView opens as one time series (the "Time" toolbar steps through it). Used for the
// solutions of `contactrb online --batch ... --out DIR` (docs/file-formats.md, "Batch input and output").
#include <string>
#include <vector>

namespace contactrb::io {

struct PvdDataSet {
  double timestep = 0.0;
  std::string file;  // relative to the directory of the .pvd (ParaView resolves it there)
};

// Writes the collection through a temporary file renamed at the end (common/output_file.hpp).
// Throws contactrb::Error naming the path when it cannot be written, or naming the data set for
// a non-finite time step or an empty file name. An empty list is a valid, empty collection.
void write_pvd(const std::string& path, const std::vector<PvdDataSet>& datasets);

}  // namespace contactrb::io
