#include "tools/mpi_ensemble.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tools/ensemble_peers.hpp"
#include "tools/realization_workers.hpp"

namespace rockdd::cli {
namespace {

/// The messages between a rank and rank 0, by tag.
enum Tag : int {
  kAsk = 1,       // rank -> 0, empty: "a job of mine is free"
  kSeed = 2,      // 0 -> rank, one uint64: run it
  kStop = 3,      // 0 -> rank, empty: no more seeds
  kFinished = 4,  // rank -> 0, JSON text: a FinishedRealization
};

/// How long a rank sleeps between looks at its messages and workers: short beside a
/// realization's seconds, and no busy core (a blocking MPI receive spins in Open MPI).
constexpr std::chrono::milliseconds kPollInterval{5};

/// MPI_Init and MPI_Finalize around an ensemble; only the main thread calls MPI.
class MpiSession {
 public:
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &ranks_on_node_);
    MPI_Comm_free(&node);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  int ranks_on_node() const { return ranks_on_node_; }

 private:
  int rank_ = 0, size_ = 1, ranks_on_node_ = 1;
};

nlohmann::json to_json(const FinishedRealization& done) {
  nlohmann::json j = {{"seed", done.seed}, {"seconds", done.seconds}};
  if (done.bad_input) {
    j["bad_input"] = *done.bad_input;
  } else {
    j["status"] = done.row.status;
    j["cells"] = done.row.cells;
    j["reason"] = done.row.reason;
  }
  return j;
}

FinishedRealization from_json(const nlohmann::json& j) {
  FinishedRealization done;
  done.seed = j.at("seed").get<std::uint64_t>();
  done.seconds = j.at("seconds").get<double>();
  if (j.contains("bad_input")) {
    done.bad_input = j["bad_input"].get<std::string>();
  } else {
    done.row.seed = done.seed;
    done.row.status = j.at("status").get<std::string>();
    done.row.cells = j.at("cells").get<std::vector<std::string>>();
    done.row.reason = j.at("reason").get<std::string>();
  }
  return done;
}

/// Rank 0's view of the other ranks.
class MpiPeers final : public EnsemblePeers {
 public:
  explicit MpiPeers(int size) : size_(size) {}

  int count() const override { return size_ - 1; }

  void begin(bool go) override {
    if (begun_) return;
    begun_ = true;
    int flag = go ? 1 : 0;
    MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD);
  }
  bool begun() const { return begun_; }

  std::vector<FinishedRealization> poll(std::deque<std::uint64_t>& queue, bool stop) override {
    std::vector<FinishedRealization> out;
    for (;;) {
      int waiting = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
      if (!waiting) return out;
      const int from = status.MPI_SOURCE;
      if (status.MPI_TAG == kAsk) {
        MPI_Recv(nullptr, 0, MPI_BYTE, from, kAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (stop || queue.empty()) {
          MPI_Send(nullptr, 0, MPI_BYTE, from, kStop, MPI_COMM_WORLD);
          stopped_[from] = true;
        } else {
          std::uint64_t seed = queue.front();
          queue.pop_front();
          MPI_Send(&seed, 1, MPI_UINT64_T, from, kSeed, MPI_COMM_WORLD);
          ++out_there_;
        }
      } else if (status.MPI_TAG == kFinished) {
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string text(static_cast<std::size_t>(length), '\0');
        MPI_Recv(text.data(), length, MPI_CHAR, from, kFinished, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        out.push_back(from_json(nlohmann::json::parse(text)));
        --out_there_;
      } else {
        throw std::runtime_error("mc: rank " + std::to_string(from) + " sent tag " +
                                 std::to_string(status.MPI_TAG));
      }
    }
  }

  long running() const override { return out_there_; }

  bool finished() const override {
    return out_there_ == 0 && static_cast<int>(stopped_.size()) == size_ - 1;
  }

 private:
  const int size_;
  bool begun_ = false;
  long out_there_ = 0;           // seeds handed out, rows not back
  std::map<int, bool> stopped_;  // ranks told to end
};

/// A rank other than 0: asks for seeds while a job is free, runs each in a worker process
/// and sends back what it finished, until rank 0 says stop and its workers are done.
int worker_rank(const MonteCarloOptions& options, const Scene& scene, const MonteCarloPlan& plan) {
  const JobPlan jobs = plan_jobs(options, plan.realizations);
  RealizationWorkers workers(scene, plan, ensemble_columns(scene), jobs.threads_per_run,
                             frame_mode(options));
  bool asked = false, stopped = false;
  for (;;) {
    if (!stopped && !asked && workers.running() < jobs.jobs) {
      MPI_Send(nullptr, 0, MPI_BYTE, 0, kAsk, MPI_COMM_WORLD);
      asked = true;
    }
    bool busy = false;
    int waiting = 0;
    MPI_Status status;
    if (asked) MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
    if (waiting) {
      busy = asked = false;
      if (status.MPI_TAG == kSeed) {
        std::uint64_t seed = 0;
        MPI_Recv(&seed, 1, MPI_UINT64_T, 0, kSeed, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        workers.launch(seed);
        busy = true;
      } else {
        MPI_Recv(nullptr, 0, MPI_BYTE, 0, kStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        stopped = true;
      }
    }
    if (const auto done = workers.reap(false)) {
      // A reason may quote bytes that are not UTF-8 (a path): replaced, not thrown over.
      const std::string text =
          to_json(*done).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kFinished, MPI_COMM_WORLD);
      busy = true;
    }
    if (stopped && workers.running() == 0) return 0;
    if (!busy) std::this_thread::sleep_for(kPollInterval);
  }
}

}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

int mpi_monte_carlo(MonteCarloOptions options) {
  MpiSession mpi;
  if (mpi.size() == 1) return monte_carlo(options);
  // A rank is the unit of parallelism here: one realization at a time per rank unless --jobs
  // says otherwise, on the hardware threads its node shares among its ranks.
  if (options.jobs == 0) options.jobs = 1;
  if (options.threads == 0)
    options.threads =
        std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / mpi.ranks_on_node());

  // Every rank reads the scene (on a cluster, from its own node); all go on only if all could.
  std::optional<Scene> scene;
  std::optional<MonteCarloPlan> plan;
  std::string problem;
  try {
    scene = load_scene(options.scene, options.overrides);
    plan = plan_monte_carlo(*scene, options.realizations, options.first_seed,
                            options.out.value_or(std::filesystem::path()), options.shard);
  } catch (const std::exception& e) {
    problem = e.what();
  }
  int ok = problem.empty() ? 1 : 0, all_ok = 0, root_ok = ok;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  MPI_Bcast(&root_ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!all_ok) {
    // Rank 0 reports its own problem; another rank's only when rank 0 had none.
    if (mpi.rank() == 0 && !ok) std::cerr << "rockdd: error: " << problem << '\n';
    if (mpi.rank() != 0 && !ok && root_ok)
      std::cerr << "rockdd: error (MPI rank " << mpi.rank() << "): " << problem << '\n';
    return 2;
  }

  if (mpi.rank() != 0) {
    int go = 0;
    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!go) return 2;  // rank 0 said why
    try {
      return worker_rank(options, *scene, *plan);
    } catch (const std::exception& e) {
      std::cerr << "rockdd: MPI rank " << mpi.rank() << ": " << e.what() << '\n';
      MPI_Abort(MPI_COMM_WORLD, 1);  // rank 0 would wait for its rows forever
      return 1;
    }
  }
  MpiPeers peers(mpi.size());
  try {
    return monte_carlo(options, &peers);
  } catch (const std::exception& e) {
    if (!peers.begun()) {
      // Refused before the start (a held lock, another ensemble's folder). Said before the
      // other ranks are told to end: once one of them exits 2, mpiexec may stop this rank
      // before its message is out.
      const bool input = dynamic_cast<const InputError*>(&e) != nullptr;
      std::cerr << (input ? "rockdd: error: " : "rockdd: ") << e.what() << std::endl;
      peers.begin(false);
      return input ? 2 : 1;
    }
    // Failed midway (a write error, say): the other ranks would wait for seeds that never
    // come. The rows written so far stay, and a rerun resumes from them.
    std::cerr << "rockdd: " << e.what() << '\n';
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return 1;
}

}  // namespace rockdd::cli
