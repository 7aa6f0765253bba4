#include "engine/loading/named_nodes.hpp"

#include <algorithm>

#include "engine/common/errors.hpp"

namespace rockdd {
namespace {

std::string available_names(const Model& model) {
  std::string out;
  for (const auto& [name, edges] : model.sets.curve_edges) out += (out.empty() ? "" : ", ") + name;
  for (const auto& [name, nodes] : model.sets.points) out += (out.empty() ? "" : ", ") + name;
  return out.empty() ? "none" : out;
}

}  // namespace

std::vector<std::int32_t> nodes_named(const Model& model, const std::string& name,
                                      const std::string& scene_file, const std::string& key) {
  std::vector<std::int32_t> nodes;
  if (const auto c = model.sets.curve_edges.find(name); c != model.sets.curve_edges.end()) {
    nodes = c->second;
  } else if (const auto p = model.sets.points.find(name); p != model.sets.points.end()) {
    nodes = p->second;
  } else {
    throw InputError(scene_file, key,
                     "no physical curve or point named '" + name +
                         "' in the mesh (available: " + available_names(model) + ")");
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::int32_t body_named(const Model& model, const std::string& name, const std::string& scene_file,
                        const std::string& key) {
  if (name == "*") return -1;
  const auto& bodies = model.sets.bodies;
  const auto it = std::find(bodies.begin(), bodies.end(), name);
  if (it == bodies.end()) {
    std::string list;
    for (const auto& b : bodies) list += (list.empty() ? "" : ", ") + b;
    throw InputError(scene_file, key,
                     "no body (physical surface) named '" + name + "' (available: " + list + ")");
  }
  return static_cast<std::int32_t>(it - bodies.begin());
}

}  // namespace rockdd
