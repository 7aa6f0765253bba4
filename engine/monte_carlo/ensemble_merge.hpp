#pragma once
// rockdd mc-merge: the shards of one ensemble (run apart with --shard, e.g. as a cluster job
// array) joined into one table and one set of statistics.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockdd {

/// The ensemble folder named by `dir`: `dir` itself when it holds mc.csv, else its only
/// subfolder that does (an --out root). Throws InputError when there is none or several.
std::filesystem::path ensemble_folder(const std::filesystem::path& dir);

/// Writes into `out_dir` the mc.csv of every shard's rows (the last row of each seed, sorted
/// by seed), its mc.json and a manifest; returns mc.json's content. Throws InputError (bad
/// input, exit 2) for shards of different ensembles (manifest hashes) or columns, a seed in
/// two shards, or `out_dir` among the shards.
nlohmann::json merge_ensembles(const std::filesystem::path& out_dir,
                               const std::vector<std::filesystem::path>& shard_dirs);

}  // namespace rockdd
