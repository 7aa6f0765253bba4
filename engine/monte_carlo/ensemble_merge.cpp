#include "engine/monte_carlo/ensemble_merge.hpp"

#include <algorithm>
#include <map>

#include "engine/common/errors.hpp"
#include "engine/monte_carlo/ensemble_manifest.hpp"
#include "engine/monte_carlo/ensemble_table.hpp"
#include "engine/monte_carlo/monte_carlo.hpp"

namespace rockdd {
namespace {

/// One shard: its folder, the identity its manifest records, its latest rows.
struct ShardRows {
  std::filesystem::path dir;
  EnsembleIdentity identity;
  EnsembleTable table;
};

ShardRows read_shard(const std::filesystem::path& named) {
  const std::filesystem::path dir = ensemble_folder(named);
  const auto identity = read_manifest(dir);
  if (!identity)
    throw InputError((dir / kManifestName).string(), "",
                     "expected the manifest of a rockdd mc run beside its mc.csv, got none");
  EnsembleTable table = read_ensemble_table(dir / "mc.csv");
  table.rows = latest_rows(table.rows);
  return {dir, *identity, std::move(table)};
}

/// Refuses `shard` unless it is of the same ensemble, with the same columns, as `first`.
void check_compatible(const ShardRows& first, const ShardRows& shard) {
  if (const std::string what = identity_difference(first.identity, shard.identity); !what.empty())
    throw InputError((shard.dir / kManifestName).string(), "",
                     "expected a shard of the same ensemble as " + first.dir.string() + " (hash " +
                         first.identity.hash() + "), got hash " + shard.identity.hash() + ": " +
                         what);
  if (shard.table.columns != first.table.columns)
    throw InputError((shard.dir / "mc.csv").string(), "",
                     "expected the columns of " + (first.dir / "mc.csv").string() +
                         ", got others (another rockdd version?)");
}

}  // namespace

std::filesystem::path ensemble_folder(const std::filesystem::path& dir) {
  if (std::filesystem::exists(dir / "mc.csv")) return dir;
  std::vector<std::filesystem::path> found;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec))
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
      if (entry.is_directory() && std::filesystem::exists(entry.path() / "mc.csv"))
        found.push_back(entry.path());
  if (found.size() != 1)
    throw InputError(dir.string(), "",
                     found.empty() ? "expected a folder with mc.csv (or an --out folder with one "
                                     "such scene folder), got none"
                                   : "expected one scene folder with mc.csv, got " +
                                         std::to_string(found.size()) + "; name one of them");
  return found.front();
}

nlohmann::json merge_ensembles(const std::filesystem::path& out_dir,
                               const std::vector<std::filesystem::path>& shard_dirs) {
  if (shard_dirs.empty()) throw InputError("mc-merge", "", "expected shard folders, got none");
  std::vector<ShardRows> shards;
  for (const auto& named : shard_dirs) shards.push_back(read_shard(named));
  std::map<std::uint64_t, const ShardRows*> owner;  // the shard of each seed
  EnsembleTable merged{shards.front().table.columns, {}};
  for (const ShardRows& shard : shards) {
    std::error_code ec;
    if (std::filesystem::equivalent(shard.dir, out_dir, ec))
      throw InputError(out_dir.string(), "",
                       "expected an output folder apart from the shards, got one of them");
    check_compatible(shards.front(), shard);
    for (const EnsembleRow& row : shard.table.rows) {
      if (const auto [it, fresh] = owner.emplace(row.seed, &shard); !fresh)
        throw InputError(shard.dir.string(), "",
                         "expected shards with disjoint seeds, got seed " +
                             std::to_string(row.seed) + " here and in " + it->second->dir.string());
      merged.rows.push_back(row);
    }
  }
  std::sort(merged.rows.begin(), merged.rows.end(),
            [](const EnsembleRow& a, const EnsembleRow& b) { return a.seed < b.seed; });
  std::filesystem::create_directories(out_dir);
  // As on --restart: no moment where a manifest vouches for rows of another ensemble.
  std::filesystem::remove(out_dir / "mc.csv");
  write_manifest(out_dir, shards.front().identity, "");
  write_ensemble_table(out_dir / "mc.csv", merged);
  return write_ensemble_report(out_dir, shards.front().identity);
}

}  // namespace rockdd
