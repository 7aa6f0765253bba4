#include "engine/mesh/mesh_bytes.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rockdd {

void write_mesh(ByteWriter& out, const Mesh& mesh) {
  out.array(mesh.xy);
  out.array(mesh.triangles);
  out.array(mesh.element_surface);
  out.value<std::uint64_t>(mesh.surface_body.size());
  for (const std::string& body : mesh.surface_body) out.text(body);
  out.value<std::uint64_t>(mesh.curves.size());
  for (const auto& [name, edges] : mesh.curves) {
    std::vector<std::int32_t> flat;
    flat.reserve(2 * edges.size());
    for (const auto& [a, b] : edges) flat.insert(flat.end(), {a, b});
    out.text(name);
    out.array(flat);
  }
  out.value<std::uint64_t>(mesh.points.size());
  for (const auto& [name, nodes] : mesh.points) {
    out.text(name);
    out.array(nodes);
  }
}

bool read_mesh(ByteReader& in, Mesh& mesh) {
  std::uint64_t bodies = 0, curves = 0, points = 0;
  if (!in.array(mesh.xy) || !in.array(mesh.triangles) || !in.array(mesh.element_surface) ||
      !in.value(bodies))
    return false;
  // One name at a time: a damaged count runs out of bytes instead of allocating for it.
  std::string name;
  for (std::uint64_t i = 0; i < bodies; ++i) {
    if (!in.text(name)) return false;
    mesh.surface_body.push_back(name);
  }
  if (!in.value(curves)) return false;
  for (std::uint64_t i = 0; i < curves; ++i) {
    std::vector<std::int32_t> flat;
    if (!in.text(name) || !in.array(flat) || flat.size() % 2 != 0) return false;
    auto& edges = mesh.curves[name];
    for (std::size_t k = 0; k < flat.size(); k += 2) edges.push_back({flat[k], flat[k + 1]});
  }
  if (!in.value(points)) return false;
  for (std::uint64_t i = 0; i < points; ++i)
    if (!in.text(name) || !in.array(mesh.points[name])) return false;
  return mesh.xy.size() % 2 == 0 && mesh.triangles.size() % 3 == 0 &&
         mesh.element_surface.size() == mesh.num_elements();
}

}  // namespace rockdd
