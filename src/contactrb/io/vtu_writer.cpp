#include "contactrb/io/vtu_writer.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <ostream>
#include <string_view>

#include "contactrb/common/error.hpp"
#include "contactrb/io/atomic_file.hpp"

namespace contactrb::io {

namespace {

// VTK cell type of a linear triangle (vtkCellType.h: VTK_TRIANGLE).
constexpr int kVtkTriangle = 5;
constexpr const char* kBodyField = "body";

// Shortest text that reads back to the same double (round-trip exact).
void put_double(std::ostream& out, double v) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  out.write(buf.data(), result.ptr - buf.data());
}

std::string xml_escape(std::string_view s) {
  std::string r;
  r.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default: r += c;
    }
  }
  return r;
}

const VtuField* find_field(const std::vector<VtuField>& section, const std::string& name) {
  for (const VtuField& f : section) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// First scalar and first vector field, named in the <PointData>/<CellData> attributes so
// that ParaView colours by them by default.
std::string default_attributes(const std::vector<VtuField>& section, const char* scalar_default) {
  std::string scalars = scalar_default;
  std::string vectors;
  for (const VtuField& f : section) {
    if (f.components == 1 && scalars.empty()) scalars = f.name;
    if (f.components == 2 && vectors.empty()) vectors = f.name;
  }
  std::string attrs;
  if (!scalars.empty()) attrs += " Scalars=\"" + xml_escape(scalars) + "\"";
  if (!vectors.empty()) attrs += " Vectors=\"" + xml_escape(vectors) + "\"";
  return attrs;
}

void write_field(std::ostream& out, const VtuField& f) {
  // Scalars omit NumberOfComponents (VTK's default is 1); 2D vectors are written with z = 0.
  out << "        <DataArray type=\"Float64\" Name=\"" << xml_escape(f.name) << "\""
      << (f.components == 2 ? " NumberOfComponents=\"3\"" : "") << " format=\"ascii\">\n";
  const std::size_t entities = f.values.size() / static_cast<std::size_t>(f.components);
  for (std::size_t i = 0; i < entities; ++i) {
    out << "          ";
    if (f.components == 2) {
      put_double(out, f.values[2 * i]);
      out << ' ';
      put_double(out, f.values[2 * i + 1]);
      out << " 0\n";
    } else {
      put_double(out, f.values[i]);
      out << '\n';
    }
  }
  out << "        </DataArray>\n";
}

}  // namespace

VtuWriter::VtuWriter(const mesh::Mesh& mesh) : mesh_(mesh) {}

void VtuWriter::add(std::vector<VtuField>& section, const char* section_name, int entities,
                    const std::string& name, int components, const Eigen::Ref<const Eigen::VectorXd>& values) {
  require(!name.empty(), std::string("VTU ") + section_name + " field name must not be empty");
  require(find_field(section, name) == nullptr && !(&section == &cell_data_ && name == kBodyField),
          std::string("VTU ") + section_name + " field '" + name + "' is already defined");
  const Eigen::Index expected = static_cast<Eigen::Index>(entities) * components;
  require(values.size() == expected, std::string("VTU ") + section_name + " field '" + name + "' has " +
                                         std::to_string(values.size()) + " values, expected " +
                                         std::to_string(expected) + " (" + std::to_string(components) +
                                         " per " + (&section == &cell_data_ ? "triangle" : "node") + " x " +
                                         std::to_string(entities) + ")");
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    require(std::isfinite(values[i]), std::string("VTU ") + section_name + " field '" + name +
                                          "' has a non-finite value at index " + std::to_string(i));
  }
  section.push_back(VtuField{name, components, std::vector<double>(values.begin(), values.end())});
}

VtuWriter& VtuWriter::add_point_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(point_data_, "point", mesh_.num_nodes(), name, 1, values);
  return *this;
}

VtuWriter& VtuWriter::add_point_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(point_data_, "point", mesh_.num_nodes(), name, 2, values);
  return *this;
}

VtuWriter& VtuWriter::add_cell_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(cell_data_, "cell", mesh_.num_triangles(), name, 1, values);
  return *this;
}

VtuWriter& VtuWriter::add_cell_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(cell_data_, "cell", mesh_.num_triangles(), name, 2, values);
  return *this;
}

VtuWriter& VtuWriter::deform_by(const std::string& point_vector, double scale) {
  const VtuField* f = find_field(point_data_, point_vector);
  require(f != nullptr && f->components == 2,
          "cannot deform the VTU mesh by '" + point_vector + "': no point vector field of that name");
  require(std::isfinite(scale), "VTU deformation scale must be finite");
  deform_field_ = point_vector;
  deform_scale_ = scale;
  return *this;
}

void VtuWriter::write(const std::string& path) const {
  const int n = mesh_.num_nodes();
  const int m = mesh_.num_triangles();
  require(static_cast<int>(mesh_.body.size()) == m,
          "cannot write '" + path + "': mesh has " + std::to_string(m) + " triangles but " +
              std::to_string(mesh_.body.size()) + " body ids");
  for (int t = 0; t < m; ++t) {
    for (int v : mesh_.triangles[static_cast<std::size_t>(t)]) {
      require(v >= 0 && v < n, "cannot write '" + path + "': triangle " + std::to_string(t) + " refers to node " +
                                   std::to_string(v) + " of " + std::to_string(n));
    }
  }
  const VtuField* deform = deform_field_.empty() ? nullptr : find_field(point_data_, deform_field_);

  write_file_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << m << "\">\n";

    out << "      <PointData" << default_attributes(point_data_, "") << ">\n";
    for (const VtuField& f : point_data_) write_field(out, f);
    out << "      </PointData>\n";

    out << "      <CellData" << default_attributes(cell_data_, kBodyField) << ">\n"
        << "        <DataArray type=\"Int32\" Name=\"" << kBodyField << "\" format=\"ascii\">\n";
    for (int t = 0; t < m; ++t) out << "          " << mesh_.body[static_cast<std::size_t>(t)] << '\n';
    out << "        </DataArray>\n";
    for (const VtuField& f : cell_data_) write_field(out, f);
    out << "      </CellData>\n";

    out << "      <Points>\n"
        << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (int i = 0; i < n; ++i) {
      Eigen::Vector2d x = mesh_.nodes[static_cast<std::size_t>(i)];
      if (deform != nullptr) {
        x.x() += deform_scale_ * deform->values[2 * static_cast<std::size_t>(i)];
        x.y() += deform_scale_ * deform->values[2 * static_cast<std::size_t>(i) + 1];
      }
      out << "          ";
      put_double(out, x.x());
      out << ' ';
      put_double(out, x.y());
      out << " 0\n";
    }
    out << "        </DataArray>\n"
        << "      </Points>\n";

    out << "      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& tri : mesh_.triangles) {
      out << "          " << tri[0] << ' ' << tri[1] << ' ' << tri[2] << '\n';
    }
    out << "        </DataArray>\n"
        << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (int t = 0; t < m; ++t) out << "          " << 3 * (t + 1) << '\n';
    out << "        </DataArray>\n"
        << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (int t = 0; t < m; ++t) out << "          " << kVtkTriangle << '\n';
    out << "        </DataArray>\n"
        << "      </Cells>\n"
        << "    </Piece>\n"
        << "  </UnstructuredGrid>\n"
        << "</VTKFile>\n";
  });
}

void write_vtu(const mesh::Mesh& mesh, const std::string& path) { VtuWriter(mesh).write(path); }

}  // namespace contactrb::io
