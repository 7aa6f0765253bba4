#pragma once
// VTK XML UnstructuredGrid (.vtu) frames with raw binary appended data, and .pvd collections.
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
};

/// Writes a triangle mesh (2D points written with z = 0) and its arrays, atomically.
void write_vtu(const std::filesystem::path& path, std::span<const double> points_xy,
               std::span<const std::int32_t> triangles, const std::vector<VtuArray>& point_data,
               const std::vector<VtuArray>& cell_data);

/// Writes a ParaView collection listing (time, file relative to the .pvd) pairs, atomically.
void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& frames);

}  // namespace rockdd
