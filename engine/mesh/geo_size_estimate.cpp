#include "engine/mesh/geo_size_estimate.hpp"

#include <gmsh.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "engine/mesh/gmsh_session.hpp"

namespace rockdd {

namespace {

/// Gmsh's "no size here" (MAX_LC).
constexpr double kNoSize = 1e22;

/// Samples of a curve's parameter range for the integral of 1 / size along it.
constexpr int kSamples = 64;

/// What a .geo_unrolled file says about sizes: the size at each point that has one and the
/// node count of each transfinite curve.
struct UnrolledSizes {
  std::map<int, double> point_size;
  std::map<int, double> transfinite_nodes;
};

/// A number, or a variable "cl__N" of the file, or nullopt-like NaN.
double value_of(const std::string& text, const std::map<std::string, double>& variables) {
  std::istringstream fields(text);
  std::string word;
  fields >> word;
  if (const auto found = variables.find(word); found != variables.end()) return found->second;
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  return end != word.c_str() && *end == '\0' ? value : NAN;
}

std::vector<std::string> comma_separated(const std::string& list) {
  std::vector<std::string> items;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ',');) items.push_back(item);
  return items;
}

/// Gmsh 4.8 writes a point as "Point(3) = {x, y, z, cl__1};" after "cl__1 = 0.1;" (or with the
/// size as a number, or without one), and a transfinite curve as
/// "Transfinite Line {1, 2} = 11 Using Progression 1;".
UnrolledSizes read_unrolled(const std::filesystem::path& file) {
  static const std::regex variable(R"(^\s*(cl__\d+)\s*=\s*([^;]+);)");
  static const std::regex point(R"(^\s*Point\s*\(\s*(\d+)\s*\)\s*=\s*\{([^}]*)\})");
  static const std::regex transfinite(
      R"(^\s*Transfinite\s+(?:Line|Curve)\s*\{([^}]*)\}\s*=\s*([^\s;]+))");
  std::ifstream in(file);
  std::map<std::string, double> variables;
  UnrolledSizes sizes;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, variable)) {
      variables[m[1]] = value_of(m[2], variables);
    } else if (std::regex_search(line, m, point)) {
      const std::vector<std::string> fields = comma_separated(m[2]);
      if (fields.size() < 4) continue;
      const double size = value_of(fields[3], variables);
      if (std::isfinite(size) && size < kNoSize) sizes.point_size[std::stoi(m[1])] = size;
    } else if (std::regex_search(line, m, transfinite)) {
      const double nodes = value_of(m[2], variables);
      for (const std::string& tag : comma_separated(m[1])) {
        const double curve = value_of(tag, variables);
        if (std::isfinite(curve) && std::isfinite(nodes))
          sizes.transfinite_nodes[static_cast<int>(std::abs(curve))] = nodes;
      }
    }
  }
  return sizes;
}

/// The sizes read from the model written out in `scratch_dir`; none when it cannot be written.
UnrolledSizes model_sizes(const std::filesystem::path& scratch_dir) {
  const std::filesystem::path file =
      scratch_dir / ("rockdd-sizes-" + std::to_string(::getpid()) + ".geo_unrolled");
  UnrolledSizes sizes;
  if (first_gmsh_error([&] { gmsh::write(file.string()); }).empty()) sizes = read_unrolled(file);
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
  return sizes;
}

double option(const char* name) {
  double value = 0.0;
  gmsh::option::getNumber(name, value);
  return value;
}

}  // namespace

double geo_curve_segments_at_least(const std::filesystem::path& scratch_dir) {
  double box[6] = {0, 0, 0, 0, 0, 0};
  gmsh::model::getBoundingBox(-1, -1, box[0], box[1], box[2], box[3], box[4], box[5]);
  // Gmsh's default size: the model's extent (no curve is meshed coarser).
  const double model_size = std::hypot(box[3] - box[0], box[4] - box[1], box[5] - box[2]);
  if (!std::isfinite(model_size) || !(model_size > 0)) return 0.0;
  const UnrolledSizes sizes = model_sizes(scratch_dir);
  const bool from_points = option("Mesh.MeshSizeFromPoints") != 0;
  const double per_turn = option("Mesh.MeshSizeFromCurvature");
  const double size_min = option("Mesh.MeshSizeMin"), size_max = option("Mesh.MeshSizeMax");
  const double factor = option("Mesh.MeshSizeFactor");

  gmsh::vectorpair curves;
  gmsh::model::getEntities(curves, 1);
  double segments = 0.0;
  for (const auto& [dim, curve] : curves) {
    if (const auto found = sizes.transfinite_nodes.find(curve);
        found != sizes.transfinite_nodes.end()) {
      segments += std::max(found->second - 1.0, 0.0);
      continue;
    }
    gmsh::vectorpair ends;
    gmsh::model::getBoundary({{dim, curve}}, ends, false, false);
    auto size_at = [&](std::size_t end) {
      if (ends.empty()) return kNoSize;
      const auto found =
          sizes.point_size.find(std::abs(ends[std::min(end, ends.size() - 1)].second));
      return found == sizes.point_size.end() ? kNoSize : found->second;
    };
    const double size_begin = size_at(0), size_end = size_at(1);
    std::vector<double> low, high;
    gmsh::model::getParametrizationBounds(dim, curve, low, high);
    if (low.empty() || high.empty()) continue;
    std::vector<double> at(kSamples + 1), middle(kSamples), xyz, curvature;
    for (int i = 0; i <= kSamples; ++i) at[i] = low[0] + (high[0] - low[0]) * i / kSamples;
    for (int i = 0; i < kSamples; ++i) middle[i] = 0.5 * (at[i] + at[i + 1]);
    gmsh::model::getValue(dim, curve, at, xyz);
    if (per_turn > 0) gmsh::model::getCurvature(dim, curve, middle, curvature);
    if (xyz.size() != 3 * at.size()) continue;
    for (int i = 0; i < kSamples; ++i) {
      // The chord: never longer than the curve, so the bound stays a lower one.
      const double length = std::hypot(xyz[3 * i + 3] - xyz[3 * i], xyz[3 * i + 4] - xyz[3 * i + 1],
                                       xyz[3 * i + 5] - xyz[3 * i + 2]);
      double size = model_size;
      if (from_points && (size_begin < kNoSize || size_end < kNoSize)) {
        const double a = (i + 0.5) / kSamples;  // Gmsh interpolates along the parameter
        size = std::min(size, (1 - a) * size_begin + a * size_end);
      }
      if (per_turn > 0 && curvature.size() == middle.size() && curvature[i] > 0)
        size = std::min(size, 2 * std::numbers::pi / (curvature[i] * per_turn));
      size = std::min(std::max(size, size_min), size_max) * factor;
      if (size > 0 && std::isfinite(length)) segments += length / size;
    }
  }
  return segments;
}

double geo_triangles_at_least(double& longest) {
  std::vector<std::size_t> tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, true, false);
  std::unordered_map<std::size_t, std::size_t> at;
  at.reserve(tags.size());
  for (std::size_t n = 0; n < tags.size(); ++n) at.emplace(tags[n], n);
  // Each curve's segments as node positions along its orientation.
  std::map<int, std::vector<std::array<std::size_t, 2>>> segments;
  gmsh::vectorpair curves;
  gmsh::model::getEntities(curves, 1);
  longest = 0.0;
  for (const auto& [dim, curve] : curves) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> elements, nodes;
    gmsh::model::mesh::getElements(types, elements, nodes, dim, curve);
    auto& list = segments[curve];
    for (std::size_t t = 0; t < types.size(); ++t) {
      if (types[t] != 1) continue;  // 2-node lines; other orders are refused later
      for (std::size_t e = 0; e + 1 < nodes[t].size(); e += 2) {
        const auto a = at.find(nodes[t][e]), b = at.find(nodes[t][e + 1]);
        if (a == at.end() || b == at.end()) continue;
        list.push_back({a->second, b->second});
        longest = std::max(longest, std::hypot(xyz[3 * a->second] - xyz[3 * b->second],
                                               xyz[3 * a->second + 1] - xyz[3 * b->second + 1]));
      }
    }
  }
  if (!(longest > 0) || !std::isfinite(longest)) return 0.0;
  if (option("Mesh.MeshSizeExtendFromBoundary") == 0) {
    // Inside, Gmsh's sizes are the model's, capped, not the boundary's.
    double box[6] = {0, 0, 0, 0, 0, 0};
    gmsh::model::getBoundingBox(-1, -1, box[0], box[1], box[2], box[3], box[4], box[5]);
    const double model_size = std::hypot(box[3] - box[0], box[4] - box[1]);
    longest = std::max(
        longest, std::min(model_size, option("Mesh.MeshSizeMax")) * option("Mesh.MeshSizeFactor"));
  }
  // Each surface's area: the shoelace sum over its oriented boundary curves' segments.
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  double area = 0.0;
  for (const auto& surface : surfaces) {
    gmsh::vectorpair boundary;
    gmsh::model::getBoundary({surface}, boundary, false, true, false);
    double twice = 0.0;
    for (const auto& [dim, signed_curve] : boundary) {
      const auto found = segments.find(std::abs(signed_curve));
      if (found == segments.end()) continue;
      const double sign = signed_curve < 0 ? -1.0 : 1.0;
      for (const auto& [a, b] : found->second)
        twice += sign * (xyz[3 * a] * xyz[3 * b + 1] - xyz[3 * b] * xyz[3 * a + 1]);
    }
    area += 0.5 * std::abs(twice);
  }
  const double largest = 1.5 * longest;
  return area / (std::sqrt(3.0) / 4.0 * largest * largest);
}

}  // namespace rockdd
