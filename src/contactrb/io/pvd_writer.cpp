#include "contactrb/io/pvd_writer.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <ostream>

#include "contactrb/common/error.hpp"
#include "contactrb/io/xml_text.hpp"
#include "contactrb/io/atomic_file.hpp"

namespace contactrb::io {

namespace {

// Shortest text that reads back to the same double.
std::string number_text(double v) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), result.ptr);
}


}  // namespace

void write_pvd(const std::string& path, const std::vector<PvdDataSet>& datasets) {
  for (std::size_t k = 0; k < datasets.size(); ++k) {
    require(std::isfinite(datasets[k].timestep),
            "cannot write '" + path + "': data set " + std::to_string(k) + " has a non-finite time step");
    require(!datasets[k].file.empty(), "cannot write '" + path + "': data set " + std::to_string(k) + " has no file");
  }
  write_file_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const PvdDataSet& d : datasets) {
      out << "    <DataSet timestep=\"" << number_text(d.timestep) << "\" group=\"\" part=\"0\" file=\""
          << xml_escape(d.file) << "\"/>\n";
    }
    out << "  </Collection>\n"
        << "</VTKFile>\n";
  });
}

}  // namespace contactrb::io
