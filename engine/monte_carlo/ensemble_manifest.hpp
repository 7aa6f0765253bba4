#pragma once
// mc.manifest.json: what an ensemble folder's rows were computed from, written when an
// ensemble starts. A re-run resumes only the same ensemble; mc-merge joins only shards of one.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// What makes two `rockdd mc` runs one ensemble: the scene's content, the --set overrides
/// (in their order) and the first seed. Threads, jobs, frames and shards change no row.
struct EnsembleIdentity {
  std::string scene;       // the scene's name
  std::string scene_hash;  // of the scene file's bytes and of the mesh file it reads, if any
  std::vector<std::string> overrides;
  std::uint64_t first_seed = 0;
  /// One hash of all of the above (16 hex digits).
  std::string hash() const;
};

/// The identity of an ensemble of `scene` (read from scene.file) from `first_seed`.
EnsembleIdentity ensemble_identity(const Scene& scene, const std::vector<std::string>& overrides,
                                   std::uint64_t first_seed);

/// What differs between a recorded identity and this one, in words; empty when nothing does.
std::string identity_difference(const EnsembleIdentity& recorded, const EnsembleIdentity& now);

/// The manifest's name in an ensemble folder.
inline constexpr const char* kManifestName = "mc.manifest.json";

/// Writes `dir`/mc.manifest.json (durably: temp, fsync, rename); `shard` is "i/n" or empty.
void write_manifest(const std::filesystem::path& dir, const EnsembleIdentity& identity,
                    const std::string& shard);

/// The identity recorded in `dir`/mc.manifest.json; nothing when there is no manifest.
/// Throws InputError naming the file when it cannot be read.
std::optional<EnsembleIdentity> read_manifest(const std::filesystem::path& dir);

}  // namespace rockdd
