#include "engine/scene/mesh_algorithm.hpp"

namespace rockdd {

std::string_view mesh_algorithm_name(MeshAlgorithm algorithm) {
  switch (algorithm) {
    case MeshAlgorithm::meshadapt:
      return "meshadapt";
    case MeshAlgorithm::automatic:
      return "automatic";
    case MeshAlgorithm::delaunay:
      return "delaunay";
    case MeshAlgorithm::frontal_delaunay:
      return "frontal-delaunay";
    case MeshAlgorithm::bamg:
      return "bamg";
    case MeshAlgorithm::packing:
      return "packing";
  }
  return "unknown";
}

std::optional<MeshAlgorithm> scene_mesh_algorithm(std::string_view name) {
  for (const MeshAlgorithm algorithm : {MeshAlgorithm::frontal_delaunay, MeshAlgorithm::delaunay,
                                        MeshAlgorithm::meshadapt, MeshAlgorithm::automatic})
    if (mesh_algorithm_name(algorithm) == name) return algorithm;
  return std::nullopt;
}

}  // namespace rockdd
