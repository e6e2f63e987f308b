#include "contactrb/io/vtu_writer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <ostream>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "contactrb/common/error.hpp"
#include "contactrb/io/xml_text.hpp"
#include "contactrb/io/atomic_file.hpp"

namespace contactrb::io {

namespace {

// VTK cell types (vtkCellType.h): VTK_LINE, VTK_TRIANGLE, VTK_TETRA.
constexpr std::uint8_t kVtkLine = 3;
constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkTetra = 10;
constexpr const char* kBodyField = "body";


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
    if ((f.components == 2 || f.components == 3) && vectors.empty()) vectors = f.name;
  }
  std::string attrs;
  if (!scalars.empty()) attrs += " Scalars=\"" + xml_escape(scalars) + "\"";
  if (!vectors.empty()) attrs += " Vectors=\"" + xml_escape(vectors) + "\"";
  return attrs;
}

// The appended-data section: one block per array, each a UInt64 byte count followed by the
// values, little-endian (the file declares byte_order="LittleEndian", header_type="UInt64").
class AppendedBlocks {
 public:
  // Starts a block of `count` values of type T; returns its offset (the DataArray's `offset`
  // attribute: bytes from the character after the leading '_').
  template <class T>
  std::uint64_t begin(std::size_t count) {
    const std::uint64_t offset = bytes_.size();
    put(static_cast<std::uint64_t>(count * sizeof(T)));
    return offset;
  }

  template <class T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    std::array<char, sizeof(T)> raw{};
    std::memcpy(raw.data(), &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw.begin(), raw.end());
    bytes_.append(raw.data(), raw.size());
  }

  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// One <DataArray> element of the XML part (its values go to `blocks`).
void data_array_header(std::ostream& out, const char* indent, const char* type, const std::string& name,
                       int components, std::uint64_t offset, const std::string& extra = "") {
  out << indent << "<DataArray type=\"" << type << "\" Name=\"" << xml_escape(name) << "\"";
  if (components != 1) out << " NumberOfComponents=\"" << components << "\"";
  out << extra << " format=\"appended\" offset=\"" << offset << "\"/>\n";
}

// A Float64 field: 2D vectors with a third component 0, other fields as they are.
void write_field(std::ostream& out, AppendedBlocks& blocks, const VtuField& f) {
  const auto components = static_cast<std::size_t>(f.components);
  const std::size_t entities = f.values.size() / components;
  const std::size_t written_components = f.components == 2 ? 3 : components;
  const std::uint64_t offset = blocks.begin<double>(entities * written_components);
  for (std::size_t i = 0; i < entities; ++i) {
    for (std::size_t c = 0; c < components; ++c) blocks.put(f.values[components * i + c]);
    if (f.components == 2) blocks.put(0.0);
  }
  data_array_header(out, "        ", "Float64", f.name, static_cast<int>(written_components), offset);
}

std::vector<Eigen::Vector3d> points_3d(const std::vector<Eigen::Vector2d>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const Eigen::Vector2d& p : points) out.emplace_back(p.x(), p.y(), 0.0);
  return out;
}

}  // namespace

VtuWriter::VtuWriter(const mesh::Mesh& mesh)
    : points_(points_3d(mesh.nodes)),
      nodes_per_cell_(3),
      cell_type_(kVtkTriangle),
      has_body_(true),
      body_(mesh.body.begin(), mesh.body.end()) {
  connectivity_.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) connectivity_.insert(connectivity_.end(), tri.begin(), tri.end());
}

VtuWriter::VtuWriter(const mesh::Mesh3& mesh)
    : points_(mesh.nodes.begin(), mesh.nodes.end()),
      dim_(3),
      nodes_per_cell_(4),
      cell_type_(kVtkTetra),
      has_body_(true),
      body_(mesh.body.begin(), mesh.body.end()) {
  connectivity_.reserve(4 * mesh.tetrahedra.size());
  for (const auto& tet : mesh.tetrahedra) connectivity_.insert(connectivity_.end(), tet.begin(), tet.end());
}

VtuWriter VtuWriter::triangles(std::vector<Eigen::Vector3d> points, std::vector<std::array<int, 3>> triangles) {
  VtuWriter w;
  w.points_ = std::move(points);
  w.dim_ = 3;
  w.nodes_per_cell_ = 3;
  w.cell_type_ = kVtkTriangle;
  w.connectivity_.reserve(3 * triangles.size());
  for (const auto& t : triangles) w.connectivity_.insert(w.connectivity_.end(), t.begin(), t.end());
  return w;
}

VtuWriter VtuWriter::lines(std::vector<Eigen::Vector2d> points, std::vector<std::array<int, 2>> segments) {
  VtuWriter w;
  w.points_ = points_3d(points);
  w.nodes_per_cell_ = 2;
  w.cell_type_ = kVtkLine;
  w.connectivity_.reserve(2 * segments.size());
  for (const auto& s : segments) w.connectivity_.insert(w.connectivity_.end(), s.begin(), s.end());
  return w;
}

int VtuWriter::num_cells() const { return static_cast<int>(connectivity_.size()) / nodes_per_cell_; }

void VtuWriter::add(std::vector<VtuField>& section, const char* section_name, int entities,
                    const std::string& name, int components, std::span<const double> values) {
  require(!name.empty(), std::string("VTU ") + section_name + " field name must not be empty");
  require(find_field(section, name) == nullptr && !(&section == &cell_data_ && has_body_ && name == kBodyField),
          std::string("VTU ") + section_name + " field '" + name + "' is already defined");
  if (&section == &field_data_) {
    require(!values.empty(), "VTU field data '" + name + "' has no values");
  } else {
    const std::size_t expected = static_cast<std::size_t>(entities) * static_cast<std::size_t>(components);
    require(values.size() == expected,
            std::string("VTU ") + section_name + " field '" + name + "' has " + std::to_string(values.size()) +
                " values, expected " + std::to_string(expected) + " (" + std::to_string(components) + " per " +
                (&section == &cell_data_ ? "cell" : "node") + " x " + std::to_string(entities) + ")");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    require(std::isfinite(values[i]), std::string("VTU ") + section_name + " field '" + name +
                                          "' has a non-finite value at index " + std::to_string(i));
  }
  section.push_back(VtuField{name, components, std::vector<double>(values.begin(), values.end())});
}

namespace {
std::span<const double> as_span(const Eigen::Ref<const Eigen::VectorXd>& v) {
  // Eigen::Ref<const VectorXd> has unit inner stride (its default), so the data is contiguous.
  return {v.data(), static_cast<std::size_t>(v.size())};
}
}  // namespace

VtuWriter& VtuWriter::add_point_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(point_data_, "point", num_points(), name, 1, as_span(values));
  return *this;
}

VtuWriter& VtuWriter::add_point_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(point_data_, "point", num_points(), name, dim_, as_span(values));
  return *this;
}

VtuWriter& VtuWriter::add_cell_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(cell_data_, "cell", num_cells(), name, 1, as_span(values));
  return *this;
}

VtuWriter& VtuWriter::add_cell_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values) {
  add(cell_data_, "cell", num_cells(), name, dim_, as_span(values));
  return *this;
}

VtuWriter& VtuWriter::add_cell_field(const std::string& name, int components,
                                     const Eigen::Ref<const Eigen::VectorXd>& values) {
  require(components >= 1, "VTU cell field '" + name + "' needs at least one component");
  add(cell_data_, "cell", num_cells(), name, components, as_span(values));
  return *this;
}

VtuWriter& VtuWriter::add_field_data(const std::string& name, std::span<const double> values) {
  add(field_data_, "field", 0, name, 1, values);
  return *this;
}

VtuWriter& VtuWriter::add_field_data(const std::string& name, double value) {
  return add_field_data(name, std::span<const double>(&value, 1));
}

VtuWriter& VtuWriter::deform_by(const std::string& point_vector, double scale) {
  const VtuField* f = find_field(point_data_, point_vector);
  require(f != nullptr && f->components == dim_,
          "cannot deform the VTU mesh by '" + point_vector + "': no point vector field of that name");
  require(std::isfinite(scale), "VTU deformation scale must be finite");
  deform_field_ = point_vector;
  deform_scale_ = scale;
  return *this;
}

void VtuWriter::write(const std::string& path) const {
  const int n = num_points();
  const int m = num_cells();
  require(!has_body_ || static_cast<int>(body_.size()) == m,
          "cannot write '" + path + "': mesh has " + std::to_string(m) + " cells but " +
              std::to_string(body_.size()) + " body ids");
  for (std::size_t k = 0; k < connectivity_.size(); ++k) {
    const std::int64_t v = connectivity_[k];
    const std::size_t cell = k / static_cast<std::size_t>(nodes_per_cell_);
    require(v >= 0 && v < n, "cannot write '" + path + "': cell " + std::to_string(cell) + " refers to node " +
                                 std::to_string(v) + " of " + std::to_string(n));
  }
  const VtuField* deform = deform_field_.empty() ? nullptr : find_field(point_data_, deform_field_);

  // The XML part names each array's block in `blocks`, written after it in <AppendedData>.
  AppendedBlocks blocks;
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n";
  if (!field_data_.empty()) {
    xml << "    <FieldData>\n";
    for (const VtuField& f : field_data_) {
      const std::uint64_t offset = blocks.begin<double>(f.values.size());
      for (double v : f.values) blocks.put(v);
      data_array_header(xml, "      ", "Float64", f.name, 1, offset,
                        " NumberOfTuples=\"" + std::to_string(f.values.size()) + "\"");
    }
    xml << "    </FieldData>\n";
  }
  xml << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << m << "\">\n";

  xml << "      <PointData" << default_attributes(point_data_, "") << ">\n";
  for (const VtuField& f : point_data_) write_field(xml, blocks, f);
  xml << "      </PointData>\n";

  xml << "      <CellData" << default_attributes(cell_data_, has_body_ ? kBodyField : "") << ">\n";
  if (has_body_) {
    const std::uint64_t offset = blocks.begin<std::int32_t>(body_.size());
    for (std::int32_t b : body_) blocks.put(b);
    data_array_header(xml, "        ", "Int32", kBodyField, 1, offset);
  }
  for (const VtuField& f : cell_data_) write_field(xml, blocks, f);
  xml << "      </CellData>\n";

  {
    const std::uint64_t offset = blocks.begin<double>(3 * points_.size());
    for (std::size_t i = 0; i < points_.size(); ++i) {
      Eigen::Vector3d x = points_[i];
      for (int c = 0; deform != nullptr && c < dim_; ++c) {
        x(c) += deform_scale_ * deform->values[static_cast<std::size_t>(dim_) * i + static_cast<std::size_t>(c)];
      }
      blocks.put(x.x());
      blocks.put(x.y());
      blocks.put(x.z());
    }
    xml << "      <Points>\n";
    data_array_header(xml, "        ", "Float64", "Points", 3, offset);
    xml << "      </Points>\n";
  }

  xml << "      <Cells>\n";
  {
    const std::uint64_t offset = blocks.begin<std::int64_t>(connectivity_.size());
    for (std::int64_t v : connectivity_) blocks.put(v);
    data_array_header(xml, "        ", "Int64", "connectivity", 1, offset);
  }
  {
    const std::uint64_t offset = blocks.begin<std::int64_t>(static_cast<std::size_t>(m));
    for (int t = 0; t < m; ++t) blocks.put(static_cast<std::int64_t>(nodes_per_cell_) * (t + 1));
    data_array_header(xml, "        ", "Int64", "offsets", 1, offset);
  }
  {
    const std::uint64_t offset = blocks.begin<std::uint8_t>(static_cast<std::size_t>(m));
    for (int t = 0; t < m; ++t) blocks.put(cell_type_);
    data_array_header(xml, "        ", "UInt8", "types", 1, offset);
  }
  xml << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n";

  write_file_atomically(path, [&](std::ostream& out) {
    out << xml.str() << "  <AppendedData encoding=\"raw\">\n   _";
    out.write(blocks.bytes().data(), static_cast<std::streamsize>(blocks.bytes().size()));
    out << "\n  </AppendedData>\n</VTKFile>\n";
  });
}

void write_vtu(const mesh::Mesh& mesh, const std::string& path) { VtuWriter(mesh).write(path); }
void write_vtu(const mesh::Mesh3& mesh, const std::string& path) { VtuWriter(mesh).write(path); }

}  // namespace contactrb::io
