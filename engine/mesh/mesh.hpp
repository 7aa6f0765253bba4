#pragma once
// Mesh: triangles and named physical groups as Gmsh produced them, before blocks are formed.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// Nodes, counter-clockwise triangles, and the physical names a scene refers to.
/// Only nodes used by at least one triangle are kept, numbered 0..n-1 without gaps
/// (build_mesh numbers them by reverse Cuthill–McKee and sorts elements by their lowest node).
/// Curve edges run along triangle sides, a boundary edge counter-clockwise around its triangle
/// (material on its left); point node lists are sorted.
struct Mesh {
  std::vector<double> xy;                     // 2 per node
  std::vector<std::int32_t> triangles;        // 3 per element, counter-clockwise
  std::vector<std::int32_t> element_surface;  // per element: index into surface_body
  std::vector<std::string> surface_body;      // per Gmsh surface entity: physical name or ""
  std::map<std::string, std::vector<std::array<std::int32_t, 2>>> curves;  // physical curve → edges
  std::map<std::string, std::vector<std::int32_t>> points;  // physical point → nodes
  std::size_t num_nodes() const { return xy.size() / 2; }
  std::size_t num_elements() const { return triangles.size() / 3; }
};

/// Meshes (or reads) what `spec` describes through the Gmsh API; validates the result.
/// `scene_file` names the scene in error messages. Throws InputError on bad input.
/// Gmsh runs in a child process with memory and time limits (mesher_process): a mesh beyond
/// them, or a crash in Gmsh, is an InputError too.
/// `gmsh_threads`: Gmsh's General.NumThreads (GmshSession); the engine passes 1, since Gmsh's
/// threaded meshing is not deterministic (docs/meshing.md). More only for tools/mesh_study.
Mesh build_mesh(const MeshSpec& spec, const std::filesystem::path& scene_file,
                int gmsh_threads = 1);

/// Checks triangles (zero or inverted area, bad node ids, duplicates, unused nodes, none at
/// all) and names; throws InputError(source, "", message) naming elements by their index.
/// build_mesh runs the same checks, naming elements by their Gmsh tags.
void validate_mesh(const Mesh& mesh, const std::string& source);

}  // namespace rockdd
