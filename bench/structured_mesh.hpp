#pragma once
// A structured triangle mesh built in memory (no Gmsh), for benchmarks at any size.
#include <cstdint>

#include "engine/mesh/mesh.hpp"
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd::bench {

/// nx x ny unit cells of size h, two triangles each, named curve "left".
inline Mesh structured_mesh(int nx, int ny, double h = 1e-3) {
  Mesh mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      mesh.xy.push_back(i * h);
      mesh.xy.push_back(j * h);
    }
  auto node = [&](int i, int j) { return static_cast<std::int32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int32_t a = node(i, j), b = node(i + 1, j), c = node(i + 1, j + 1),
                         d = node(i, j + 1);
      for (const std::int32_t n : {a, b, c, a, c, d}) mesh.triangles.push_back(n);
    }
  mesh.element_surface.assign(mesh.triangles.size() / 3, 0);
  mesh.surface_body = {"rock"};
  auto& left = mesh.curves["left"];
  for (int j = 0; j < ny; ++j) left.push_back({node(0, j), node(0, j + 1)});
  return mesh;
}

/// A static scene with one elastic material and the left edge clamped.
inline Scene clamped_scene() {
  Scene scene;
  scene.name = "bench";
  scene.file = "bench.toml";
  MaterialSpec rock;
  rock.body = "*";
  rock.density = 2700;
  rock.young = 50e9;
  rock.poisson = 0.2;
  scene.materials.push_back(rock);
  BoundarySpec clamp;
  clamp.on = "left";
  clamp.fix_x = clamp.fix_y = true;
  scene.boundaries.push_back(clamp);
  return scene;
}

}  // namespace rockdd::bench
