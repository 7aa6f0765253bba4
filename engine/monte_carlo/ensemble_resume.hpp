#pragma once
// Resuming an ensemble: a re-run of `rockdd mc` in the same folder keeps the rows of its
// earlier runs and runs only the seeds without one, if the rows are of the same ensemble.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/monte_carlo/ensemble_manifest.hpp"
#include "engine/monte_carlo/ensemble_table.hpp"

namespace rockdd {

/// Readies the ensemble folder `dir` for `identity` and returns the rows already in its
/// mc.csv. A new folder gets its manifest; a folder of the same ensemble keeps its rows.
/// Rows of another ensemble (another scene content, --set overrides or first seed), or of
/// other columns, or an mc.csv without a manifest, are refused with an InputError that names
/// the file and says to pass --restart; with `restart` they are discarded (mc.csv, mc.json)
/// and the ensemble starts over. `shard` ("i/n" or "") is recorded in the manifest.
EnsembleTable prepare_ensemble_folder(const std::filesystem::path& dir,
                                      const EnsembleIdentity& identity,
                                      const std::vector<std::string>& columns, bool restart,
                                      const std::string& shard);

/// The seeds of `seeds` without a completed row (ok or failed) in `rows`, in order; a seed
/// whose last row is "crashed" is run again.
std::vector<std::uint64_t> seeds_to_run(const std::vector<std::uint64_t>& seeds,
                                        const std::vector<EnsembleRow>& rows);

}  // namespace rockdd
