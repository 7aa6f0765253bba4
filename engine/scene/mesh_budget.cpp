#include "engine/scene/mesh_budget.hpp"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "engine/common/number_format.hpp"

namespace rockdd {

double triangles_over_area(double area, double element_size) {
  return area / (std::sqrt(3.0) / 4.0 * element_size * element_size);
}

std::optional<double> estimated_triangles(const MeshSpec& mesh) {
  switch (mesh.kind) {
    case MeshSpec::Kind::rectangle:
      if (!mesh.element_size) return 2.0 * mesh.divisions[0] * mesh.divisions[1];
      return triangles_over_area(mesh.size[0] * mesh.size[1], *mesh.element_size);
    case MeshSpec::Kind::disk:
      // The flats cut a little off the circle: the full circle bounds the count from above.
      return triangles_over_area(std::numbers::pi * mesh.radius * mesh.radius,
                                 mesh.element_size.value_or(mesh.radius));
    case MeshSpec::Kind::geo:
    case MeshSpec::Kind::msh:
      return std::nullopt;
  }
  return std::nullopt;
}

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream fields(line.substr(13));
    double kib = 0.0;
    if (fields >> kib) return kib * 1024.0;
  }
  return static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) *
         static_cast<double>(sysconf(_SC_PAGESIZE));
}

std::string count_text(double count) {
  return count < 1e15 ? std::to_string(static_cast<long long>(std::ceil(count)))
                      : format_number(count);
}

std::string mesh_budget_problem(double triangles, double available, bool at_least) {
  const double bytes = triangles * kBytesPerTriangle;
  const std::string estimate =
      std::string(at_least ? "at least " : "an estimated ") + count_text(triangles) + " triangles";
  if (!(bytes <= available)) {
    return "expected a mesh whose run fits in the memory available (" + count_text(available) +
           " bytes, MemAvailable), got " + estimate + " needing about " + count_text(bytes) +
           " bytes (" + format_number(kBytesPerTriangle) + " bytes a triangle, measured)";
  }
  if (!(triangles <= kMostTriangles)) {
    return "expected at most " + format_number(kMostTriangles) + " triangles, got " + estimate;
  }
  return "";
}

}  // namespace rockdd
