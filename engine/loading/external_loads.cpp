#include "engine/loading/external_loads.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/common/errors.hpp"
#include "engine/loading/named_nodes.hpp"
#include "kernels/cst.hpp"

namespace rockdd {
namespace {

/// Spreads a total force over a curve by length, or equally over a point's nodes.
void add_distributed_force(const Model& model, const std::string& name, const Vec2& force,
                           const std::string& file, const std::string& key,
                           std::vector<double>& f) {
  if (const auto c = model.sets.curve_edges.find(name); c != model.sets.curve_edges.end()) {
    const auto& edges = c->second;
    double length = 0.0;
    for (std::size_t i = 0; i + 1 < edges.size(); i += 2)
      length += std::hypot(model.X[2 * edges[i + 1]] - model.X[2 * edges[i]],
                           model.X[2 * edges[i + 1] + 1] - model.X[2 * edges[i] + 1]);
    if (length <= 0.0) throw InputError(file, key, "curve '" + name + "' has zero length");
    for (std::size_t i = 0; i + 1 < edges.size(); i += 2) {
      const double l = std::hypot(model.X[2 * edges[i + 1]] - model.X[2 * edges[i]],
                                  model.X[2 * edges[i + 1] + 1] - model.X[2 * edges[i] + 1]);
      for (const std::int32_t n : {edges[i], edges[i + 1]})
        for (int c2 = 0; c2 < 2; ++c2) f[2 * n + c2] += 0.5 * force[c2] * l / length;
    }
    return;
  }
  const auto nodes = nodes_named(model, name, file, key);
  for (const std::int32_t n : nodes)
    for (int c = 0; c < 2; ++c) f[2 * n + c] += force[c] / static_cast<double>(nodes.size());
}

/// Pressure p on each edge of a curve: p l t along the inward normal, half to each end.
void add_pressure(const Model& model, const std::string& name, double p, const std::string& file,
                  const std::string& key, std::vector<double>& f) {
  const auto c = model.sets.curve_edges.find(name);
  if (c == model.sets.curve_edges.end()) {
    nodes_named(model, name, file, key);  // throws for unknown names
    throw InputError(file, key, "pressure needs a physical curve, '" + name + "' is a point");
  }
  const auto& edges = c->second;
  const auto& owner = model.sets.curve_edge_element.at(name);
  for (std::size_t i = 0; 2 * i + 1 < edges.size(); ++i) {
    const std::int32_t a = edges[2 * i], b = edges[2 * i + 1], e = owner[i];
    std::int32_t third = model.conn[3 * e];
    for (int k = 0; k < 3; ++k)
      if (model.conn[3 * e + k] != a && model.conn[3 * e + k] != b) third = model.conn[3 * e + k];
    const double tx = model.X[2 * b] - model.X[2 * a], ty = model.X[2 * b + 1] - model.X[2 * a + 1];
    double nx = -ty, ny = tx;  // |n| = edge length
    const double to_third_x = model.X[2 * third] - model.X[2 * a];
    const double to_third_y = model.X[2 * third + 1] - model.X[2 * a + 1];
    if (nx * to_third_x + ny * to_third_y < 0.0) {
      nx = -nx;
      ny = -ny;
    }
    for (const std::int32_t n : {a, b}) {
      f[2 * n] += 0.5 * p * model.thickness * nx;
      f[2 * n + 1] += 0.5 * p * model.thickness * ny;
    }
  }
}

}  // namespace

std::vector<double> build_reference_loads(const Scene& scene, const Model& model) {
  std::vector<double> f(model.X.size(), 0.0);
  const std::string file = scene.file.string();
  for (std::size_t i = 0; i < scene.loads.size(); ++i) {
    const LoadSpec& load = scene.loads[i];
    const std::string key = "load[" + std::to_string(i) + "]";
    if (load.force) add_distributed_force(model, load.on, *load.force, file, key + ".on", f);
    if (load.pressure) add_pressure(model, load.on, *load.pressure, file, key + ".on", f);
    if (load.force_density) {
      const std::int32_t body = body_named(model, load.body, file, key + ".body");
      for (std::int32_t e = 0; e < model.num_elements(); ++e) {
        if (body >= 0 && model.element_body[e] != body) continue;
        const double volume_share = model.area0[e] * model.thickness / 3.0;
        for (int k = 0; k < 3; ++k)
          for (int c = 0; c < 2; ++c)
            f[2 * model.conn[3 * e + k] + c] += (*load.force_density)[c] * volume_share;
      }
    }
  }
  if (scene.gravity[0] != 0.0 || scene.gravity[1] != 0.0)
    for (std::int32_t n = 0; n < model.num_nodes(); ++n)
      for (int c = 0; c < 2; ++c) f[2 * n + c] += model.node_mass[n] * scene.gravity[c];
  return f;
}

double load_factor(Analysis analysis, double time, double end_time) {
  if (analysis != Analysis::static_) return 1.0;
  return std::min(time / end_time, 1.0);
}

}  // namespace rockdd
