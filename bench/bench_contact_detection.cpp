// Contact detection throughput (boundary vertices/s) on a random pile of 1e3, 1e4 and 1e5
// blocks on 1 and 2 threads: the block boundary is extracted once (the topology of a step),
// detect_contacts (broad phase, KD-tree narrow phase, reduction) is what each iteration times.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <random>

#include "bench/bench_main.hpp"
#include "engine/contact/contact_detection.hpp"

namespace rockdd {
namespace {

/// The step's largest displacement, in grid spacings (reach is the contact stage's own choice).
constexpr double kInflation = 0.01;

/// n square blocks (two triangles each, one body) of side 0.8-0.9, rotated by up to 5 degrees,
/// centred on a unit grid jittered by 0.01: neighbours face each other across gaps of 0-0.2,
/// within the reach of 0.42, so every block has its four sides and corners near others (12
/// candidates per block), as in a settled pile.
Model random_pile(long n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> side(0.8, 0.9),
      angle(-std::numbers::pi / 36, std::numbers::pi / 36), jitter(-0.01, 0.01);
  const long columns = std::lround(std::ceil(std::sqrt(static_cast<double>(n))));
  Model model;
  model.num_blocks = static_cast<std::int32_t>(n);
  model.sets.bodies = {"rock"};
  for (long i = 0; i < n; ++i) {
    const double cx = static_cast<double>(i % columns) + jitter(rng);
    const double cy = static_cast<double>(i / columns) + jitter(rng);
    const double h = 0.5 * side(rng), t = angle(rng);
    const double c = h * std::cos(t), s = h * std::sin(t);
    const auto n0 = model.num_nodes();
    // Corners counter-clockwise: (-h,-h), (h,-h), (h,h), (-h,h) rotated by t.
    for (const auto& [dx, dy] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
      model.X.push_back(cx + dx * c - dy * s);
      model.X.push_back(cy + dx * s + dy * c);
      model.node_block.push_back(static_cast<std::int32_t>(i));
    }
    for (const int k : {0, 1, 2, 0, 2, 3}) model.conn.push_back(n0 + k);
    for (int e = 0; e < 2; ++e) {
      model.element_block.push_back(static_cast<std::int32_t>(i));
      model.element_body.push_back(0);
    }
  }
  model.u.assign(model.X.size(), 0.0);
  return model;
}

/// Everything detection needs, built once per size and shared by the benchmarks.
struct Setup {
  Model model;
  BlockBoundary boundary;
  ContactRules rules;
  std::vector<double> positions;
  double reach = 0;
};

Setup& setup_for(long blocks) {
  // The engine's process keeps large blocks in the heap (CholmodSolver sets this for the whole
  // process, engine/solver/cholmod_solver.cpp): detection then reuses the memory of the previous
  // call. Without it glibc maps and unmaps its large arrays on every call, and page-faults them
  // in again (1e5 blocks, one thread: 491 instead of 356 ms).
  static const bool heap = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, -1);
    return true;
  }();
  (void)heap;
  static std::map<long, std::unique_ptr<Setup>> cache;
  auto& slot = cache[blocks];
  if (!slot) {
    slot = std::make_unique<Setup>();
    slot->model = random_pile(blocks);
    slot->boundary = extract_block_boundary(slot->model);
    slot->rules.num_bodies = 1;
    slot->rules.allowed = {1};  // blocks of the one body touch each other
    slot->rules.block_body.assign(static_cast<std::size_t>(blocks), 0);
    slot->positions = slot->model.X;
    // Reach as the contact stage picks it: half the median boundary edge.
    const auto& b = slot->boundary;
    std::vector<double> lengths(b.edge_block.size());
    for (std::size_t i = 0; i < lengths.size(); ++i) {
      const double* x = slot->positions.data();
      lengths[i] = std::hypot(x[2 * b.edge_nodes[2 * i + 1]] - x[2 * b.edge_nodes[2 * i]],
                              x[2 * b.edge_nodes[2 * i + 1] + 1] - x[2 * b.edge_nodes[2 * i] + 1]);
    }
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    slot->reach = 0.5 * lengths[lengths.size() / 2];
  }
  return *slot;
}

void BM_DetectContacts(benchmark::State& state) {
  Setup& s = setup_for(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  std::size_t contacts = 0;
  for (auto _ : state) {
    const auto found = detect_contacts(s.boundary, s.positions, s.rules, s.reach, kInflation);
    contacts = found.size();
    benchmark::DoNotOptimize(found.data());
  }
  const auto vertices = static_cast<std::int64_t>(s.boundary.vertices.size());
  state.SetItemsProcessed(state.iterations() * vertices);
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["contacts_per_block"] =
      static_cast<double>(contacts) / static_cast<double>(state.range(0));
}

void BM_ExtractBlockBoundary(benchmark::State& state) {
  Setup& s = setup_for(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(extract_block_boundary(s.model));
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
}

void sizes_and_threads(benchmark::internal::Benchmark* b) {
  for (const long blocks : {1'000L, 10'000L, 100'000L})
    for (const long threads : {1L, 2L}) b->Args({blocks, threads});
  b->ArgNames({"blocks", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_DetectContacts)->Apply(sizes_and_threads);
BENCHMARK(BM_ExtractBlockBoundary)
    ->ArgName("blocks")
    ->Arg(1'000)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}
