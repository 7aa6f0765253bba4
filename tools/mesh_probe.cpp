// mesh_probe: meshes a scene's [mesh] as `rockdd run` does (build_mesh, no cache), times it,
// and prints the mesh's size, quality histograms and a fingerprint as one JSON object.
// tools/mesh_study drives it (docs/meshing.md): it measures the mesher without the solve a
// run would add, and reaches Gmsh algorithms and thread counts a scene does not offer.
//
// usage: mesh_probe SCENE [--set KEY=VALUE]... [--gmsh-algorithm N] [--gmsh-threads N]
//                         [--repeat K]
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "engine/common/content_hash.hpp"
#include "engine/common/errors.hpp"
#include "engine/engine.hpp"
#include "engine/mesh/mesh.hpp"

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Bins of the histograms: minimum angle in 2-degree bins over [0, 60]; aspect ratio
/// R / (2 r) (1 for an equilateral triangle) at these upper edges, the last unbounded.
constexpr int kAngleBins = 30;
const std::vector<double> kAspectEdges = {1.01, 1.02, 1.05, 1.1, 1.2, 1.5, 2.0, 3.0, 5.0};

struct Quality {
  std::vector<long> angle_hist = std::vector<long>(kAngleBins, 0);
  std::vector<long> aspect_hist = std::vector<long>(kAspectEdges.size() + 1, 0);
  double min_angle = 180.0, mean_min_angle = 0.0, max_aspect = 0.0, mean_aspect = 0.0;
};

Quality quality(const rockdd::Mesh& mesh) {
  Quality q;
  const double deg = 180.0 / std::acos(-1.0);
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      const auto n = static_cast<std::size_t>(mesh.triangles[3 * e + k]);
      x[k] = mesh.xy[2 * n];
      y[k] = mesh.xy[2 * n + 1];
    }
    double smallest = 180.0, len[3];
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const double ux = x[i] - x[k], uy = y[i] - y[k], vx = x[j] - x[k], vy = y[j] - y[k];
      smallest =
          std::min(smallest, deg * std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy));
      len[k] = std::hypot(x[i] - x[j], y[i] - y[j]);
    }
    const double area =
        0.5 * std::abs((x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]));
    const double s = 0.5 * (len[0] + len[1] + len[2]);
    const double aspect = len[0] * len[1] * len[2] * s / (8.0 * area * area);
    q.angle_hist[std::min(kAngleBins - 1, static_cast<int>(smallest / 2.0))]++;
    const auto bin = std::upper_bound(kAspectEdges.begin(), kAspectEdges.end(), aspect);
    q.aspect_hist[static_cast<std::size_t>(bin - kAspectEdges.begin())]++;
    q.min_angle = std::min(q.min_angle, smallest);
    q.max_aspect = std::max(q.max_aspect, aspect);
    q.mean_min_angle += smallest;
    q.mean_aspect += aspect;
  }
  q.mean_min_angle /= static_cast<double>(mesh.num_elements());
  q.mean_aspect /= static_cast<double>(mesh.num_elements());
  return q;
}

/// The mesh's exact bits: equal fingerprints, bitwise equal meshes (up to hash collisions).
std::string fingerprint(const rockdd::Mesh& mesh) {
  rockdd::Fnv1a h;
  h.add({reinterpret_cast<const char*>(mesh.xy.data()), mesh.xy.size() * sizeof(double)});
  h.add({reinterpret_cast<const char*>(mesh.triangles.data()),
         mesh.triangles.size() * sizeof(mesh.triangles[0])});
  return h.hex();
}

template <class T>
std::string json_list(const std::vector<T>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    char item[32];
    std::snprintf(item, sizeof item, "%.17g", static_cast<double>(values[i]));
    text += (i ? ", " : "") + std::string(item);
  }
  return text + "]";
}

int usage() {
  std::cerr << "usage: mesh_probe SCENE [--set KEY=VALUE]... [--gmsh-algorithm N] "
               "[--gmsh-threads N] [--repeat K]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_file;
  std::vector<std::string> overrides;
  int algorithm = 0, threads = 1, repeat = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 < argc && arg == "--set")
      overrides.emplace_back(argv[++i]);
    else if (i + 1 < argc && arg == "--gmsh-algorithm")
      algorithm = std::atoi(argv[++i]);
    else if (i + 1 < argc && arg == "--gmsh-threads")
      threads = std::max(1, std::atoi(argv[++i]));
    else if (i + 1 < argc && arg == "--repeat")
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (scene_file.empty() && arg[0] != '-')
      scene_file = arg;
    else
      return usage();
  }
  if (scene_file.empty()) return usage();
  try {
    rockdd::Scene scene = rockdd::load_scene(scene_file, overrides);
    // A number the scene does not offer (bamg, packing): the study's, unchecked here.
    if (algorithm) scene.mesh.algorithm = static_cast<rockdd::MeshAlgorithm>(algorithm);
    std::vector<double> wall, cpu;
    std::vector<std::string> prints;
    rockdd::Mesh mesh;
    for (int r = 0; r < repeat; ++r) {
      const double cpu0 = cpu_seconds();
      const auto wall0 = std::chrono::steady_clock::now();
      mesh = rockdd::build_mesh(scene.mesh, scene.file, threads);
      wall.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
      cpu.push_back(cpu_seconds() - cpu0);
      prints.push_back(fingerprint(mesh));
    }
    const bool same = std::all_of(prints.begin(), prints.end(),
                                  [&](const std::string& p) { return p == prints[0]; });
    const Quality q = quality(mesh);
    std::printf(
        "{\"elements\": %zu, \"nodes\": %zu, \"wall_seconds\": %s, \"cpu_seconds\": %s, "
        "\"fingerprint\": \"%s\", \"repeats_identical\": %s, \"min_angle_deg\": %.6g, "
        "\"mean_min_angle_deg\": %.6g, \"max_aspect\": %.6g, \"mean_aspect\": %.6g, "
        "\"angle_bin_deg\": 2, \"angle_hist\": %s, \"aspect_edges\": %s, \"aspect_hist\": %s}\n",
        mesh.num_elements(), mesh.num_nodes(), json_list(wall).c_str(), json_list(cpu).c_str(),
        prints[0].c_str(), same ? "true" : "false", q.min_angle, q.mean_min_angle, q.max_aspect,
        q.mean_aspect, json_list(q.angle_hist).c_str(), json_list(kAspectEdges).c_str(),
        json_list(q.aspect_hist).c_str());
  } catch (const rockdd::InputError& error) {
    std::cerr << "mesh_probe: " << error.what() << '\n';
    return 2;
  }
  return 0;
}
