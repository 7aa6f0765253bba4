#include "engine/monte_carlo/ensemble_resume.hpp"

#include <map>

#include "engine/common/errors.hpp"

namespace rockdd {
namespace {

/// The refusal of rows that are not this ensemble's.
InputError refusal(const std::filesystem::path& file, const std::string& why) {
  return InputError(file.string(), "",
                    why + "; pass --restart to discard the rows of " +
                        (file.parent_path() / "mc.csv").string() + " and start over");
}

/// Refuses the rows in `dir` unless they are of `identity` with `columns`.
void check_same_ensemble(const std::filesystem::path& dir, const EnsembleIdentity& identity,
                         const std::vector<std::string>& columns, const EnsembleTable& table) {
  const auto recorded = read_manifest(dir);
  if (!recorded)
    throw refusal(dir / kManifestName,
                  "mc.csv has no manifest (written by an older rockdd?), so its rows cannot be "
                  "matched to this scene");
  if (const std::string what = identity_difference(*recorded, identity); !what.empty())
    throw refusal(dir / kManifestName, "the rows there are of another ensemble: " + what);
  if (table.columns != columns)
    throw refusal(dir / "mc.csv", "its columns differ from this scene's (another rockdd version?)");
}

}  // namespace

EnsembleTable prepare_ensemble_folder(const std::filesystem::path& dir,
                                      const EnsembleIdentity& identity,
                                      const std::vector<std::string>& columns, bool restart,
                                      const std::string& shard) {
  const std::filesystem::path csv = dir / "mc.csv";
  EnsembleTable table{columns, {}};
  if (restart) {
    // The rows go before the new manifest: a crash in between must not leave old rows
    // under a manifest that vouches for them.
    std::filesystem::remove(csv);
    std::filesystem::remove(dir / "mc.json");
  } else if (std::filesystem::exists(csv)) {
    table = read_ensemble_table(csv);
    check_same_ensemble(dir, identity, columns, table);
  }
  // Without mc.csv an old manifest vouches for no row: it is simply replaced.
  write_manifest(dir, identity, shard);
  return table;
}

std::vector<std::uint64_t> seeds_to_run(const std::vector<std::uint64_t>& seeds,
                                        const std::vector<EnsembleRow>& rows) {
  std::map<std::uint64_t, bool> completed;  // by the last row of each seed
  for (const EnsembleRow& row : rows) completed[row.seed] = row.completed();
  std::vector<std::uint64_t> out;
  for (const std::uint64_t s : seeds)
    if (const auto found = completed.find(s); found == completed.end() || !found->second)
      out.push_back(s);
  return out;
}

}  // namespace rockdd
