#include "engine/monte_carlo/ensemble_manifest.hpp"

#include <cstdio>
#include <fstream>
#include <iterator>

#include "engine/common/atomic_file.hpp"
#include "engine/common/content_hash.hpp"
#include "engine/common/errors.hpp"

namespace rockdd {
namespace {

std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::string text = "[";
  for (std::size_t i = 0; i < items.size(); ++i) text += (i ? ", '" : "'") + items[i] + "'";
  return text + "]";
}

}  // namespace

std::string EnsembleIdentity::hash() const {
  Fnv1a h;
  h.add(scene);
  h.add(scene_hash);
  h.add(std::to_string(overrides.size()));
  for (const std::string& o : overrides) h.add(o);
  h.add(std::to_string(first_seed));
  return h.hex();
}

EnsembleIdentity ensemble_identity(const Scene& scene, const std::vector<std::string>& overrides,
                                   std::uint64_t first_seed) {
  Fnv1a content;
  content.add(file_bytes(scene.file));
  // A scene that reads its mesh from a file changes when that file does.
  if (scene.mesh.kind == MeshSpec::Kind::geo || scene.mesh.kind == MeshSpec::Kind::msh)
    content.add(file_bytes(scene.mesh.file));
  return {scene.name, content.hex(), overrides, first_seed};
}

std::string identity_difference(const EnsembleIdentity& recorded, const EnsembleIdentity& now) {
  std::string what;
  auto add = [&](const std::string& part) { what += (what.empty() ? "" : "; ") + part; };
  if (recorded.scene != now.scene)
    add("the scene name ('" + recorded.scene + "', now '" + now.scene + "')");
  if (recorded.scene_hash != now.scene_hash) add("the scene file's content (or its mesh file)");
  if (recorded.overrides != now.overrides)
    add("the --set overrides (" + quoted_list(recorded.overrides) + ", now " +
        quoted_list(now.overrides) + ")");
  if (recorded.first_seed != now.first_seed)
    add("the first seed (" + std::to_string(recorded.first_seed) + ", now " +
        std::to_string(now.first_seed) + ")");
  return what;
}

void write_manifest(const std::filesystem::path& dir, const EnsembleIdentity& identity,
                    const std::string& shard) {
  const nlohmann::json manifest = {
      {"scene", identity.scene},
      {"scene_hash", identity.scene_hash},
      {"overrides", identity.overrides},
      {"first_seed", identity.first_seed},
      {"hash", identity.hash()},
      {"shard", shard.empty() ? nlohmann::json(nullptr) : nlohmann::json(shard)},
      {"rockdd_version", ROCKDD_VERSION}};
  write_file_durably(dir / kManifestName, manifest.dump(2) + "\n");
}

std::optional<EnsembleIdentity> read_manifest(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / kManifestName;
  if (!std::filesystem::exists(file)) return std::nullopt;
  try {
    const nlohmann::json m = nlohmann::json::parse(file_bytes(file));
    return EnsembleIdentity{m.at("scene").get<std::string>(), m.at("scene_hash").get<std::string>(),
                            m.at("overrides").get<std::vector<std::string>>(),
                            m.at("first_seed").get<std::uint64_t>()};
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string(), "",
                     std::string("expected a Monte Carlo manifest: ") + e.what());
  }
}

}  // namespace rockdd
