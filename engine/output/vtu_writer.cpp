#include "engine/output/vtu_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <sstream>
#include <stdexcept>

#include "engine/common/atomic_file.hpp"
#include "engine/common/number_format.hpp"

namespace rockdd {
namespace {

// Raw appended data is the host's bytes as they lie in memory; the header promises little-endian.
static_assert(std::endian::native == std::endian::little,
              "VTU writer assumes a little-endian host");

constexpr std::uint8_t kVtkTriangle = 5;

/// Text safe inside a double-quoted XML attribute.
std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Lays out the appended section. Raw: each block is a UInt64 byte count followed by the
/// bytes. Compressed (VTK's vtkZLibDataCompressor, header_type UInt64): each array is cut into
/// blocks of `block_bytes`, each compressed on its own; its header holds the block count, the
/// block size, the size of a last partial block (0 when the last is full) and each block's
/// compressed size, followed by the compressed blocks.
class AppendedLayout {
 public:
  explicit AppendedLayout(const VtuEncoding& encoding) : encoding_(encoding) {}

  /// Registers a block and returns its offset from the '_' marker.
  template <class T>
  std::uint64_t add(std::span<const T> values) {
    const std::uint64_t offset = size_;
    if (!encoding_.compress) {
      const std::span<const std::byte> bytes = std::as_bytes(values);
      const std::uint64_t count = bytes.size();
      append(&count, sizeof count);
      append(bytes.data(), bytes.size());
    } else {
      compress(std::as_bytes(values));
    }
    size_ = data_.size();
    return offset;
  }
  /// Writes every block in order.
  void write(std::ostream& out) const {
    out.write(data_.data(), static_cast<std::streamsize>(data_.size()));
  }

 private:
  void append(const void* bytes, std::size_t count) {
    const char* begin = static_cast<const char*>(bytes);
    data_.insert(data_.end(), begin, begin + count);
  }

  void compress(std::span<const std::byte> bytes) {
    const std::size_t block = std::max<std::size_t>(1, encoding_.block_bytes);
    const std::size_t blocks = (bytes.size() + block - 1) / block;
    std::vector<std::uint64_t> header(3 + blocks);
    header[0] = blocks;
    header[1] = block;
    header[2] = bytes.size() % block;
    std::vector<char> packed;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t begin = b * block, length = std::min(block, bytes.size() - begin);
      uLongf room = compressBound(static_cast<uLong>(length));
      const std::size_t at = packed.size();
      packed.resize(at + room);
      const int status = compress2(reinterpret_cast<Bytef*>(packed.data() + at), &room,
                                   reinterpret_cast<const Bytef*>(bytes.data() + begin),
                                   static_cast<uLong>(length), encoding_.level);
      if (status != Z_OK)
        throw std::runtime_error("write_vtu: zlib compress2 failed (" + std::to_string(status) +
                                 ")");
      packed.resize(at + room);
      header[3 + b] = room;
    }
    append(header.data(), header.size() * sizeof(std::uint64_t));
    append(packed.data(), packed.size());
  }

  VtuEncoding encoding_;
  std::vector<char> data_;
  std::uint64_t size_ = 0;
};

/// Checks an array's length against its entity count; a mismatch would make an unreadable file.
void check_array(const VtuArray& array, std::size_t count, const char* where) {
  if (array.components < 1)
    throw std::invalid_argument(std::string(where) + " array '" + array.name +
                                "' has no components");
  if (!array.float64.empty() && !array.int32.empty())
    throw std::invalid_argument(std::string(where) + " array '" + array.name +
                                "' sets both float64 and int32");
  if (!array.component_names.empty() &&
      array.component_names.size() != static_cast<std::size_t>(array.components))
    throw std::invalid_argument(std::string(where) + " array '" + array.name + "' names " +
                                std::to_string(array.component_names.size()) + " of its " +
                                std::to_string(array.components) + " components");
  const std::size_t expected = count * static_cast<std::size_t>(array.components);
  const std::size_t given = array.float64.empty() ? array.int32.size() : array.float64.size();
  if (given != expected)
    throw std::invalid_argument(std::string(where) + " array '" + array.name + "' has " +
                                std::to_string(given) + " values, expected " +
                                std::to_string(expected));
}

/// The <DataArray> elements of a PointData or CellData section, registering their blocks.
void describe_arrays(std::ostream& xml, const char* section, const std::vector<VtuArray>& arrays,
                     AppendedLayout& layout) {
  xml << "      <" << section << ">\n";
  for (const VtuArray& array : arrays) {
    // An empty array (no entities) is written as Float64 unless it says int32 explicitly.
    const bool is_int = array.float64.empty() && !array.int32.empty();
    const std::uint64_t offset = is_int ? layout.add(array.int32) : layout.add(array.float64);
    xml << "        <DataArray type=\"" << (is_int ? "Int32" : "Float64") << "\" Name=\""
        << xml_escaped(array.name) << "\" NumberOfComponents=\"" << array.components << '"';
    for (std::size_t c = 0; c < array.component_names.size(); ++c)
      xml << " ComponentName" << c << "=\"" << xml_escaped(array.component_names[c]) << '"';
    xml << " format=\"appended\" offset=\"" << offset << "\"/>\n";
  }
  xml << "      </" << section << ">\n";
}

}  // namespace

void write_vtu(const std::filesystem::path& path, std::span<const double> points_xy,
               std::span<const std::int32_t> triangles, const std::vector<VtuArray>& point_data,
               const std::vector<VtuArray>& cell_data, const VtuEncoding& encoding) {
  if (points_xy.size() % 2 != 0)
    throw std::invalid_argument("write_vtu: odd number of point coordinates");
  if (triangles.size() % 3 != 0)
    throw std::invalid_argument("write_vtu: triangle list not a multiple of 3");
  const std::size_t num_points = points_xy.size() / 2;
  const std::size_t num_cells = triangles.size() / 3;
  for (const std::int32_t node : triangles)
    if (node < 0 || static_cast<std::size_t>(node) >= num_points)
      throw std::invalid_argument("write_vtu: triangle node " + std::to_string(node) +
                                  " out of range");
  for (const VtuArray& array : point_data) check_array(array, num_points, "point");
  for (const VtuArray& array : cell_data) check_array(array, num_cells, "cell");

  std::vector<double> points(3 * num_points, 0.0);
  for (std::size_t n = 0; n < num_points; ++n) {
    points[3 * n] = points_xy[2 * n];
    points[3 * n + 1] = points_xy[2 * n + 1];
  }
  std::vector<std::int32_t> offsets(num_cells);
  for (std::size_t c = 0; c < num_cells; ++c) offsets[c] = static_cast<std::int32_t>(3 * (c + 1));
  const std::vector<std::uint8_t> types(num_cells, kVtkTriangle);

  AppendedLayout layout(encoding);
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (encoding.compress ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << num_points << "\" NumberOfCells=\"" << num_cells
      << "\">\n";
  describe_arrays(xml, "PointData", point_data, layout);
  describe_arrays(xml, "CellData", cell_data, layout);
  xml << "      <Points>\n"
      << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" "
         "offset=\""
      << layout.add(std::span<const double>(points)) << "\"/>\n"
      << "      </Points>\n"
      << "      <Cells>\n"
      << "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"appended\" offset=\""
      << layout.add(triangles) << "\"/>\n"
      << "        <DataArray type=\"Int32\" Name=\"offsets\" format=\"appended\" offset=\""
      << layout.add(std::span<const std::int32_t>(offsets)) << "\"/>\n"
      << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\""
      << layout.add(std::span<const std::uint8_t>(types)) << "\"/>\n"
      << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "  <AppendedData encoding=\"raw\">\n"
      << "   _";

  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << xml.str();
  layout.write(out);
  out << "\n  </AppendedData>\n</VTKFile>\n";
  file.commit();
}

void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& frames) {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const auto& [time, file] : frames)
    xml << "    <DataSet timestep=\"" << format_number(time) << "\" group=\"\" part=\"0\" file=\""
        << xml_escaped(file) << "\"/>\n";
  xml << "  </Collection>\n"
      << "</VTKFile>\n";
  write_file_atomically(path, xml.str());
}

}  // namespace rockdd
