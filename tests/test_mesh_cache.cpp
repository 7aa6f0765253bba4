// The mesh cache (engine/mesh/mesh_cache): a hit is bitwise the mesh Gmsh makes, anything
// the mesh depends on changes the key, and a damaged entry is a miss, never a wrong mesh.
// The orderings kept beside the meshes: read back only for their mesh, key and exact
// pattern, and a damaged one is a miss.
// Also: a mesh does not depend on what the process meshed before (engine/mesh/gmsh_session).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "engine/mesh/mesh.hpp"
#include "engine/mesh/mesh_cache.hpp"
#include "support/mesh_file.hpp"
#include "support/same_mesh.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

const std::filesystem::path kScene = "scene.toml";
const std::filesystem::path kMeshes = std::filesystem::path(ROCKDD_SOURCE_DIR) / "tests/meshes";
const std::filesystem::path kData = std::filesystem::path(ROCKDD_SOURCE_DIR) / "data";

/// A cache folder not made yet (the cache makes it), inside a scratch folder removed at the end.
class CacheDir {
 public:
  const std::filesystem::path& path() const { return path_; }
  /// The one entry in the folder.
  std::filesystem::path entry() const {
    std::filesystem::path found;
    for (const auto& e : std::filesystem::directory_iterator(path_))
      if (e.path().extension() == ".mesh") found = e.path();
    return found;
  }

 private:
  test::TempDir root_;
  std::filesystem::path path_ = root_.path() / "mesh-cache";
};

MeshSpec disk(double element_size) {
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::disk;
  spec.radius = 0.025;
  spec.flat_half_angle_deg = 10.0;
  spec.element_size = element_size;
  return spec;
}

MeshSpec rectangle(std::array<int, 2> divisions) {
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::rectangle;
  spec.size = {0.04, 0.01};
  spec.divisions = divisions;
  return spec;
}

using test::expect_same_mesh;
using test::mesh_file;

TEST(MeshCache, AHitIsBitwiseTheMeshGmshMakes) {
  CacheDir cache;
  for (const MeshSpec& spec : {disk(1e-3), rectangle({96, 24}),
                               mesh_file(MeshSpec::Kind::geo, kData / "sliding_block.geo"),
                               mesh_file(MeshSpec::Kind::msh, kMeshes / "square_41.msh")}) {
    const Mesh fresh = build_mesh(spec, kScene);
    const CachedMesh first = build_mesh_with_cache(spec, kScene, cache.path());
    const CachedMesh second = build_mesh_with_cache(spec, kScene, cache.path());
    EXPECT_EQ(first.cache, MeshCacheOutcome::miss);
    EXPECT_EQ(second.cache, MeshCacheOutcome::hit);
    expect_same_mesh(first.mesh, fresh);
    expect_same_mesh(second.mesh, fresh);
  }
}

TEST(MeshCache, EveryInputOfTheMeshChangesTheKey) {
  const auto key = [](const MeshSpec& spec) { return mesh_cache_key(spec).value(); };
  const std::string base = key(disk(1e-3));
  EXPECT_EQ(key(disk(1e-3)), base);
  EXPECT_NE(key(disk(std::nextafter(1e-3, 1.0))), base);  // one ulp of element_size
  MeshSpec moved = disk(1e-3);
  moved.origin = {0.0, 1e-300};
  EXPECT_NE(key(moved), base);
  MeshSpec flatter = disk(1e-3);
  flatter.flat_half_angle_deg = 10.5;
  EXPECT_NE(key(flatter), base);
  EXPECT_NE(key(rectangle({96, 24})), key(rectangle({96, 25})));
  // Divisions do not mesh a rectangle that has an element size: they stay out of its key.
  MeshSpec sized = rectangle({96, 24}), sized_other = rectangle({1, 1});
  sized.element_size = sized_other.element_size = 1e-3;
  EXPECT_EQ(key(sized), key(sized_other));
  // Gmsh's 2D algorithm and smoothing passes; unset (Gmsh's own) differs from set.
  MeshSpec algorithm = disk(1e-3);
  algorithm.algorithm = MeshAlgorithm::frontal_delaunay;
  EXPECT_NE(key(algorithm), base);
  MeshSpec delaunay = algorithm;
  delaunay.algorithm = MeshAlgorithm::delaunay;
  EXPECT_NE(key(delaunay), key(algorithm));
  MeshSpec smoothing = disk(1e-3);
  smoothing.smoothing = 1;
  EXPECT_NE(key(smoothing), base);
  MeshSpec smoother = smoothing;
  smoother.smoothing = 3;
  EXPECT_NE(key(smoother), key(smoothing));
  EXPECT_NE(key(smoothing), key(algorithm));
}

TEST(MeshCache, AFileIsKeyedByItsBytesNotItsPath) {
  CacheDir dir;
  std::filesystem::create_directories(dir.path());
  const std::filesystem::path copy = dir.path() / "copy.geo";
  std::filesystem::copy_file(kMeshes / "square.geo", copy);
  const std::string original =
      mesh_cache_key(mesh_file(MeshSpec::Kind::geo, kMeshes / "square.geo")).value();
  EXPECT_EQ(mesh_cache_key(mesh_file(MeshSpec::Kind::geo, copy)).value(), original);
  std::ofstream(copy, std::ios::app) << "// an edit\n";
  EXPECT_NE(mesh_cache_key(mesh_file(MeshSpec::Kind::geo, copy)).value(), original);
}

TEST(MeshCache, AGeoThatReadsOtherFilesIsNotCached) {
  CacheDir dir;
  std::filesystem::create_directories(dir.path());
  const std::filesystem::path geo = dir.path() / "outer.geo";
  std::filesystem::copy_file(kMeshes / "square.geo", dir.path() / "square.geo");
  std::ofstream(geo) << "Include \"square.geo\";\n";
  EXPECT_FALSE(mesh_cache_key(mesh_file(MeshSpec::Kind::geo, geo)));
  const CachedMesh mesh =
      build_mesh_with_cache(mesh_file(MeshSpec::Kind::geo, geo), kScene, dir.path() / "cache");
  EXPECT_EQ(mesh.cache, MeshCacheOutcome::uncacheable);
  EXPECT_EQ(mesh.mesh.num_elements(), 8u);  // square.geo: 2 x 2 cells, 2 triangles each
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "cache"));
}

TEST(MeshCache, ADamagedEntryIsAMissAndIsWrittenAgain) {
  CacheDir cache;
  const MeshSpec spec = disk(2e-3);
  const Mesh fresh = build_mesh_with_cache(spec, kScene, cache.path()).mesh;
  const std::filesystem::path entry = cache.entry();
  const auto size = std::filesystem::file_size(entry);
  {
    std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put('\x7f');  // one byte of a coordinate
  }
  CachedMesh again = build_mesh_with_cache(spec, kScene, cache.path());
  EXPECT_EQ(again.cache, MeshCacheOutcome::miss);
  expect_same_mesh(again.mesh, fresh);
  std::filesystem::resize_file(entry, size / 3);  // a short entry
  again = build_mesh_with_cache(spec, kScene, cache.path());
  EXPECT_EQ(again.cache, MeshCacheOutcome::miss);
  EXPECT_EQ(build_mesh_with_cache(spec, kScene, cache.path()).cache, MeshCacheOutcome::hit);
}

TEST(MeshCache, AnEntryForAnotherKeyIsNeverRead) {
  CacheDir cache;
  const MeshSpec a = disk(2e-3), b = disk(3e-3);
  build_mesh_with_cache(a, kScene, cache.path());
  // b's file name made to hold a's entry: the key stored inside tells them apart.
  const std::filesystem::path entry_a = cache.entry();
  build_mesh_with_cache(b, kScene, cache.path());
  std::filesystem::path entry_b;
  for (const auto& e : std::filesystem::directory_iterator(cache.path()))
    if (e.path() != entry_a) entry_b = e.path();
  std::filesystem::copy_file(entry_a, entry_b, std::filesystem::copy_options::overwrite_existing);
  EXPECT_FALSE(read_cached_mesh(cache.path(), mesh_cache_key(b).value()));
  EXPECT_TRUE(read_cached_mesh(cache.path(), mesh_cache_key(a).value()));
}

TEST(MeshCache, TheFolderComesFromTheEnvironment) {
  ::setenv("ROCKDD_MESH_CACHE", "/some/where", 1);
  EXPECT_EQ(mesh_cache_dir(), std::filesystem::path("/some/where"));
  ::setenv("ROCKDD_MESH_CACHE", "off", 1);
  EXPECT_FALSE(mesh_cache_dir());
  ::setenv("ROCKDD_MESH_CACHE", "", 1);
  EXPECT_FALSE(mesh_cache_dir());
  ::unsetenv("ROCKDD_MESH_CACHE");
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  EXPECT_EQ(mesh_cache_dir(), std::filesystem::path("/xdg/rockdd/meshes"));
  ::unsetenv("XDG_CACHE_HOME");
  ::setenv("HOME", "/home/user", 1);
  EXPECT_EQ(mesh_cache_dir(), std::filesystem::path("/home/user/.cache/rockdd/meshes"));
}

TEST(MeshCache, AnUnwritableFolderCostsARemeshNotTheRun) {
  const CachedMesh mesh = build_mesh_with_cache(disk(3e-3), kScene, "/proc/rockdd-cannot-be-here");
  EXPECT_EQ(mesh.cache, MeshCacheOutcome::miss);
  EXPECT_GT(mesh.mesh.num_elements(), 0u);
}

/// A small upper-triangular pattern (a path of n equations) and an ordering of it.
struct OrderingCase {
  std::vector<std::int32_t> col_ptr{0}, row_idx;
  CachedOrdering ordering;
  explicit OrderingCase(std::int32_t n) {
    for (std::int32_t c = 0; c < n; ++c) {
      if (c > 0) row_idx.push_back(c - 1);
      row_idx.push_back(c);
      col_ptr.push_back(static_cast<std::int32_t>(row_idx.size()));
      ordering.perm.push_back(n - 1 - c);
    }
    ordering.method = "node_metis";
  }
};

TEST(OrderingCache, AnOrderingIsReadBackOnlyForItsMeshKeyAndPattern) {
  CacheDir cache;
  const MeshCacheSlot slot{cache.path(), mesh_cache_key(disk(2e-3)).value()};
  const OrderingCase c(50);
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx));
  write_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx, c.ordering);
  const std::optional<CachedOrdering> read =
      read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->perm, c.ordering.perm);
  EXPECT_EQ(read->method, "node_metis");
  // Another ordering strategy, another mesh, another pattern of the same size: misses.
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node_amd", c.col_ptr, c.row_idx));
  const MeshCacheSlot other_mesh{cache.path(), mesh_cache_key(disk(3e-3)).value()};
  EXPECT_FALSE(read_cached_ordering(other_mesh, "ordering node", c.col_ptr, c.row_idx));
  OrderingCase other(50);
  other.row_idx[3] = 0;  // column 2 couples 0 instead of 1
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node", other.col_ptr, other.row_idx));
  // ... even when that pattern's file name is made to hold the entry: the entry holds the
  // pattern and the key it was written for.
  std::filesystem::copy_file(
      cached_ordering_path(slot, "ordering node", c.col_ptr, c.row_idx),
      cached_ordering_path(slot, "ordering node", other.col_ptr, other.row_idx));
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node", other.col_ptr, other.row_idx));
  std::filesystem::copy_file(
      cached_ordering_path(slot, "ordering node", c.col_ptr, c.row_idx),
      cached_ordering_path(other_mesh, "ordering node", c.col_ptr, c.row_idx));
  EXPECT_FALSE(read_cached_ordering(other_mesh, "ordering node", c.col_ptr, c.row_idx));
  // Orderings live beside the mesh entries, under a name of their own.
  EXPECT_EQ(cached_ordering_path(slot, "ordering node", c.col_ptr, c.row_idx).extension(),
            ".order");
}

TEST(OrderingCache, ADamagedOrderingIsAMissNeverAnotherOrdering) {
  CacheDir cache;
  const MeshCacheSlot slot{cache.path(), mesh_cache_key(disk(2e-3)).value()};
  const OrderingCase c(200);
  write_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx, c.ordering);
  const std::filesystem::path entry =
      cached_ordering_path(slot, "ordering node", c.col_ptr, c.row_idx);
  const auto size = std::filesystem::file_size(entry);
  // Every byte of the entry, one at a time: flipped, the entry is not read.
  const std::string original = [&] {
    std::ifstream in(entry, std::ios::binary);
    return std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }();
  for (std::size_t at = 0; at < size; at += 7) {
    std::string mangled = original;
    mangled[at] = static_cast<char>(mangled[at] ^ 0x10);
    std::ofstream(entry, std::ios::binary | std::ios::trunc) << mangled;
    EXPECT_FALSE(read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx)) << at;
  }
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << original.substr(0, size / 2);
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx));
  // Written again, it is read again.
  write_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx, c.ordering);
  EXPECT_TRUE(read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx));
  // A "permutation" that repeats an equation is refused even with a valid checksum.
  CachedOrdering repeated = c.ordering;
  repeated.perm[5] = repeated.perm[6];
  write_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx, repeated);
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx));
}

TEST(OrderingCache, AnUnwritableFolderCostsAnOrderingNotTheRun) {
  const OrderingCase c(10);
  const MeshCacheSlot slot{"/proc/rockdd-cannot-be-here", "key"};
  write_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx, c.ordering);
  EXPECT_FALSE(read_cached_ordering(slot, "ordering node", c.col_ptr, c.row_idx));
}

TEST(MeshCache, AHitOrAMissNamesWhereTheMeshIsKept) {
  CacheDir cache;
  const MeshSpec spec = disk(3e-3);
  const CachedMesh miss = build_mesh_with_cache(spec, kScene, cache.path());
  const CachedMesh hit = build_mesh_with_cache(spec, kScene, cache.path());
  for (const CachedMesh* m : {&miss, &hit}) {
    ASSERT_TRUE(m->slot);
    EXPECT_EQ(m->slot->dir, cache.path());
    EXPECT_EQ(m->slot->key, mesh_cache_key(spec).value());
  }
  EXPECT_FALSE(build_mesh_with_cache(spec, kScene, std::nullopt).slot);
}

// Gmsh kept state across meshes in one process: the interior nodes of a transfinite rectangle
// moved by up to 1e-15 of their coordinates between the first mesh and later ones, and again
// after a .geo of another size. A cache would then store whichever came first.
TEST(GmshSession, AMeshDoesNotDependOnWhatTheProcessMeshedBefore) {
  const Mesh first = build_mesh(rectangle({96, 24}), kScene);
  const Mesh second = build_mesh(rectangle({96, 24}), kScene);
  build_mesh(mesh_file(MeshSpec::Kind::geo, kData / "sliding_block.geo"), kScene);
  const Mesh after_geo = build_mesh(rectangle({96, 24}), kScene);
  expect_same_mesh(second, first);
  expect_same_mesh(after_geo, first);
}

}  // namespace
}  // namespace rockdd
