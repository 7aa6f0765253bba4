#pragma once
// VTK XML UnstructuredGrid (.vtu) frames with binary appended data (raw, or zlib-compressed as
// VTK's vtkZLibDataCompressor writes it), and .pvd collections.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rockdd {

/// One named data array: `components` values per point or cell, Float64 or Int32.
struct VtuArray {
  std::string name;
  int components = 1;
  std::span<const double> float64;  // set exactly one of float64 / int32
  std::span<const std::int32_t> int32;
  /// Names of the components (ParaView shows them instead of 0, 1, 2 or X, Y, Z); empty, or
  /// one per component.
  std::vector<std::string> component_names = {};
};

/// How the binary data is stored.
struct VtuEncoding {
  bool compress = false;                       // zlib blocks (VTK's vtkZLibDataCompressor)
  int level = 6;                               // zlib's level, 1 (fast) to 9 (small)
  std::size_t block_bytes = std::size_t{1} << 15;  // uncompressed bytes a block (VTK: 32 KiB)
};

/// Writes a triangle mesh (2D points written with z = 0) and its arrays, atomically.
void write_vtu(const std::filesystem::path& path, std::span<const double> points_xy,
               std::span<const std::int32_t> triangles, const std::vector<VtuArray>& point_data,
               const std::vector<VtuArray>& cell_data, const VtuEncoding& encoding = {});

/// Writes a ParaView collection listing (time, file relative to the .pvd) pairs, atomically.
void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& frames);

}  // namespace rockdd
