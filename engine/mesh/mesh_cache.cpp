#include "engine/mesh/mesh_cache.hpp"

#include <bit>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <span>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "engine/common/atomic_file.hpp"
#include "engine/common/content_hash.hpp"
#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/mesh_bytes.hpp"
#include "engine/mesh/mesh_errors.hpp"
#include "engine/scene/mesh_budget.hpp"

#ifndef ROCKDD_MESH_CODE_HASH
#error "ROCKDD_MESH_CODE_HASH: the build's hash of engine/mesh (engine/mesh/CMakeLists.txt)"
#endif

namespace rockdd {
namespace {

// Bumped when the entry layout changes; the code that makes meshes is in the key already.
constexpr std::string_view kMagic = "rockdd-mesh-cache 1\n";

/// The whole file in one read (an istreambuf_iterator copy took 0.1 s for the 17 MB of
/// entries of a 277k-element mesh).
std::optional<std::string> file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return std::nullopt;
  const std::streamoff size = in.tellg();
  if (size < 0) return std::nullopt;
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), size) || in.gcount() != size) return std::nullopt;
  if (in.peek() != std::char_traits<char>::eof()) return std::nullopt;  // grew while read
  return bytes;
}

/// The exact bits of a double, so that two keys agree only for equal values.
std::string bits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

/// The Gmsh library that would mesh (the library's, which may differ from the header's): its
/// file, with the full version in its name, without loading it, so that a hit never loads
/// Gmsh; else the version the loaded library reports.
const std::string& gmsh_identity() {
  static const std::string identity = [] {
    const std::string file = gmsh_library_identity();
    return file.empty() ? "version " + gmsh_module().version() : "library " + file;
  }();
  return identity;
}

/// True when a .geo names other files, whose content the key would not see.
bool reads_other_files(const std::string& geo) {
  static const std::regex other_file(
      R"(\b(Include|Merge|MergeWithBoundingBox|ShapeFromFile|Open|Import)\b)");
  return std::regex_search(geo, other_file);
}

std::filesystem::path entry_path(const std::filesystem::path& dir, const std::string& key) {
  Fnv1a h;
  h.add(key);
  return dir / (h.hex() + ".mesh");
}

std::uint64_t checksum(std::string_view payload) {
  Fnv1a h;
  h.add(payload);
  return h.value();
}

/// Reads a file of payload + checksum; nullopt when missing, short or damaged.
std::optional<std::string> checked_payload(const std::filesystem::path& file) {
  std::optional<std::string> bytes = file_bytes(file);
  if (!bytes || bytes->size() < sizeof(std::uint64_t)) return std::nullopt;
  const std::size_t size = bytes->size() - sizeof(std::uint64_t);
  std::uint64_t stored = 0;
  std::memcpy(&stored, bytes->data() + size, sizeof stored);
  if (stored != checksum(std::string_view(bytes->data(), size))) return std::nullopt;
  bytes->resize(size);
  return bytes;
}

/// Appends the checksum and writes the entry atomically; failures are ignored.
void store_entry(const std::filesystem::path& dir, const std::filesystem::path& file,
                 ByteWriter& out) {
  out.value(checksum(out.bytes()));
  try {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    write_file_atomically(file, out.bytes());
  } catch (const std::exception&) {  // a read-only or full disk: the next run computes again
  }
}

// Ordering entries: their own magic, so that neither kind of entry is ever read as the other.
constexpr std::string_view kOrderingMagic = "rockdd-ordering-cache 1\n";

std::string ordering_entry_key(const MeshCacheSlot& slot, const std::string& ordering_key) {
  return slot.key + ordering_key + '\n';
}

/// A quick hash of a pattern for the entry's file name, so that patterns of one mesh under
/// different restraints get different files. The entry holds the pattern itself: this hash
/// only spreads the names.
std::uint64_t pattern_name_hash(std::span<const std::int32_t> col_ptr,
                                std::span<const std::int32_t> row_idx) {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL ^ (col_ptr.size() * 0x100000001b3ULL) ^ row_idx.size();
  auto mix = [&h](std::span<const std::int32_t> words) {
    for (const std::int32_t w : words) {
      h ^= static_cast<std::uint32_t>(w);
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 29;
    }
  };
  mix(col_ptr);
  mix(row_idx);
  return h;
}

}  // namespace

CachedMesh build_mesh_with_cache(const MeshSpec& spec, const std::filesystem::path& scene_file,
                                 const std::optional<std::filesystem::path>& cache_dir) {
  if (!cache_dir) return {build_mesh(spec, scene_file), MeshCacheOutcome::off, std::nullopt};
  const std::optional<std::string> key = mesh_cache_key(spec);
  if (!key) return {build_mesh(spec, scene_file), MeshCacheOutcome::uncacheable, std::nullopt};
  if (std::optional<Mesh> mesh = read_cached_mesh(*cache_dir, *key)) {
    // Stored when it fitted; this machine may have less memory free now.
    const std::string problem =
        mesh_budget_problem(static_cast<double>(mesh->num_elements()), available_memory_bytes());
    if (!problem.empty()) MeshSource{scene_file.string(), "mesh"}.fail(problem);
    return {std::move(*mesh), MeshCacheOutcome::hit, MeshCacheSlot{*cache_dir, *key}};
  }
  Mesh mesh = build_mesh(spec, scene_file);
  write_cached_mesh(*cache_dir, *key, mesh);
  return {std::move(mesh), MeshCacheOutcome::miss, MeshCacheSlot{*cache_dir, *key}};
}

const char* mesh_cache_outcome_name(MeshCacheOutcome outcome) {
  switch (outcome) {
    case MeshCacheOutcome::off:
      return "off";
    case MeshCacheOutcome::hit:
      return "hit";
    case MeshCacheOutcome::miss:
      return "miss";
    case MeshCacheOutcome::uncacheable:
      return "uncacheable";
  }
  return "off";
}

std::optional<std::filesystem::path> mesh_cache_dir() {
  if (const char* dir = std::getenv("ROCKDD_MESH_CACHE")) {
    const std::string_view value(dir);
    if (value.empty() || value == "off") return std::nullopt;
    return std::filesystem::path(value);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "rockdd" / "meshes";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "rockdd" / "meshes";
  return std::nullopt;
}

std::optional<std::string> mesh_cache_key(const MeshSpec& spec) {
  std::ostringstream key;
  key << kMagic << "gmsh " << gmsh_identity() << "\nmesh code " << ROCKDD_MESH_CODE_HASH << '\n';
  switch (spec.kind) {
    case MeshSpec::Kind::rectangle:
      key << "rectangle size " << bits(spec.size[0]) << ' ' << bits(spec.size[1]) << " origin "
          << bits(spec.origin[0]) << ' ' << bits(spec.origin[1]);
      if (!spec.element_size) key << " divisions " << spec.divisions[0] << ' ' << spec.divisions[1];
      break;
    case MeshSpec::Kind::disk:
      key << "disk radius " << bits(spec.radius) << " centre " << bits(spec.origin[0]) << ' '
          << bits(spec.origin[1]) << " flat half-angle " << bits(spec.flat_half_angle_deg);
      break;
    case MeshSpec::Kind::geo:
    case MeshSpec::Kind::msh: {
      const std::optional<std::string> bytes = file_bytes(spec.file);
      if (!bytes) return std::nullopt;
      if (spec.kind == MeshSpec::Kind::geo && reads_other_files(*bytes)) return std::nullopt;
      Fnv1a content;
      content.add(*bytes);
      // The path stays out of the key: a moved or copied file meshes the same.
      key << (spec.kind == MeshSpec::Kind::geo ? "geo" : "msh") << " bytes " << bytes->size()
          << " fnv1a " << content.hex();
      break;
    }
  }
  if (spec.element_size) key << " element_size " << bits(*spec.element_size);
  // Unset: Gmsh's defaults or the .geo's own, which the file's bytes already cover.
  if (spec.algorithm) key << " algorithm " << static_cast<int>(*spec.algorithm);
  if (spec.smoothing) key << " smoothing " << *spec.smoothing;
  key << '\n';
  return key.str();
}

std::optional<Mesh> read_cached_mesh(const std::filesystem::path& dir, const std::string& key) {
  const std::optional<std::string> payload = checked_payload(entry_path(dir, key));
  if (!payload) return std::nullopt;

  ByteReader in(*payload);
  std::string magic, entry_key;
  std::uint32_t endian = 0;
  Mesh mesh;
  if (!in.text(magic) || magic != kMagic || !in.value(endian) || endian != 0x01020304u ||
      !in.text(entry_key) || entry_key != key || !read_mesh(in, mesh) || !in.done())
    return std::nullopt;
  return mesh;
}

void write_cached_mesh(const std::filesystem::path& dir, const std::string& key, const Mesh& mesh) {
  ByteWriter out;
  out.text(kMagic);
  out.value<std::uint32_t>(0x01020304u);
  out.text(key);
  write_mesh(out, mesh);
  store_entry(dir, entry_path(dir, key), out);
}

std::filesystem::path cached_ordering_path(const MeshCacheSlot& slot,
                                           const std::string& ordering_key,
                                           std::span<const std::int32_t> col_ptr,
                                           std::span<const std::int32_t> row_idx) {
  Fnv1a h;
  h.add(ordering_entry_key(slot, ordering_key));
  char pattern[17];
  std::snprintf(pattern, sizeof pattern, "%016llx",
                static_cast<unsigned long long>(pattern_name_hash(col_ptr, row_idx)));
  return slot.dir / (h.hex() + '-' + pattern + ".order");
}

std::optional<CachedOrdering> read_cached_ordering(const MeshCacheSlot& slot,
                                                   const std::string& ordering_key,
                                                   std::span<const std::int32_t> col_ptr,
                                                   std::span<const std::int32_t> row_idx) {
  const std::optional<std::string> payload =
      checked_payload(cached_ordering_path(slot, ordering_key, col_ptr, row_idx));
  if (!payload) return std::nullopt;
  ByteReader in(*payload);
  std::string magic, entry_key;
  std::uint32_t endian = 0;
  CachedOrdering ordering;
  if (!in.text(magic) || magic != kOrderingMagic || !in.value(endian) || endian != 0x01020304u ||
      !in.text(entry_key) || entry_key != ordering_entry_key(slot, ordering_key) ||
      !in.same_array(col_ptr) || !in.same_array(row_idx) || !in.text(ordering.method) ||
      !in.array(ordering.perm) || !in.done())
    return std::nullopt;
  // Equations 0..n-1, each once: anything else is damage the checksum missed.
  const std::size_t n = col_ptr.empty() ? 0 : col_ptr.size() - 1;
  if (ordering.perm.size() != n || ordering.method.empty()) return std::nullopt;
  std::vector<std::uint8_t> seen(n, 0);
  for (const std::int32_t e : ordering.perm) {
    if (e < 0 || static_cast<std::size_t>(e) >= n || seen[e]) return std::nullopt;
    seen[e] = 1;
  }
  return ordering;
}

void write_cached_ordering(const MeshCacheSlot& slot, const std::string& ordering_key,
                           std::span<const std::int32_t> col_ptr,
                           std::span<const std::int32_t> row_idx, const CachedOrdering& ordering) {
  ByteWriter out;
  out.text(kOrderingMagic);
  out.value<std::uint32_t>(0x01020304u);
  out.text(ordering_entry_key(slot, ordering_key));
  out.array(col_ptr);
  out.array(row_idx);
  out.text(ordering.method);
  out.array(ordering.perm);
  store_entry(slot.dir, cached_ordering_path(slot, ordering_key, col_ptr, row_idx), out);
}

}  // namespace rockdd
