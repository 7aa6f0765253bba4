#pragma once
// The other processes of one ensemble run (MPI ranks), as the process that owns mc.csv sees
// them: it hands them seeds when they ask, and gets their rows back.
#include <cstdint>
#include <deque>
#include <vector>

#include "tools/realization_workers.hpp"

namespace rockdd::cli {

/// Peers that run realizations for the owner of mc.csv; tools/mpi_ensemble.cpp is one.
class EnsemblePeers {
 public:
  virtual ~EnsemblePeers() = default;
  /// How many peers there are.
  virtual int count() const = 0;
  /// Tells the peers whether the ensemble goes ahead (false: the owner refused it, say for a
  /// held lock); called once, before the first poll.
  virtual void begin(bool go) = 0;
  /// Without waiting: gives each peer that asked the front seed of `queue` (none left, or
  /// `stop`: it is told to end), and returns the realizations the peers finished.
  virtual std::vector<FinishedRealization> poll(std::deque<std::uint64_t>& queue, bool stop) = 0;
  /// Seeds handed out whose rows have not come back.
  virtual long running() const = 0;
  /// True once every peer was told to end and every seed handed out came back.
  virtual bool finished() const = 0;
};

}  // namespace rockdd::cli
