#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/mesher_process.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace rockdd {

namespace {

/// Where this code was loaded from: the rockdd executable, librockdd.so, a test or a Python
/// module. The Gmsh module is looked for beside it, in the build tree and the install tree.
std::filesystem::path own_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_directory), &info) == 0 || info.dli_fname == nullptr)
    return {};
  std::error_code error;
  const auto file = std::filesystem::canonical(info.dli_fname, error);
  return error ? std::filesystem::path() : file.parent_path();
}

std::vector<std::filesystem::path> module_candidates() {
  const char* name = "librockdd_gmsh.so";
  std::vector<std::filesystem::path> places;
  if (const char* given = std::getenv("ROCKDD_GMSH_MODULE"); given != nullptr && *given != '\0')
    places.emplace_back(given);
  const std::filesystem::path own = own_directory();
  if (!own.empty()) {
    if (own.filename() != "bin") places.push_back(own / "rockdd" / name);  // librockdd.so
    places.push_back(own.parent_path() / "lib" / "rockdd" / name);         // bin/ -> lib/rockdd/
    places.push_back(own.parent_path() / ROCKDD_INSTALL_LIBDIR / "rockdd" / name);
  }
  places.push_back(std::filesystem::path(ROCKDD_GMSH_MODULE_BUILD_DIR) / name);
  places.push_back(std::filesystem::path(ROCKDD_GMSH_MODULE_INSTALL_DIR) / name);
  std::vector<std::filesystem::path> unique;
  for (auto& place : places) {
    place = place.lexically_normal();
    if (std::find(unique.begin(), unique.end(), place) == unique.end()) unique.push_back(place);
  }
  return unique;
}

const GmshModuleEntry* open_module() {
  std::string tried;
  for (const auto& place : module_candidates()) {
    std::error_code error;
    if (!std::filesystem::exists(place, error)) {
      tried += "\n  " + place.string() + " (absent)";
      continue;
    }
    // RTLD_LOCAL: Gmsh's symbols stay inside the module. Never closed: Gmsh registers atexit
    // handlers and OpenCASCADE keeps static state.
    void* handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      tried += "\n  " + place.string() + " (" + (why ? why : "dlopen failed") + ")";
      continue;
    }
    using EntryFunction = const GmshModuleEntry* (*)();
    const auto entry = reinterpret_cast<EntryFunction>(dlsym(handle, "rockdd_gmsh_module_entry"));
    const GmshModuleEntry* table = entry != nullptr ? entry() : nullptr;
    if (table == nullptr || table->abi != kGmshModuleAbi) {
      tried += "\n  " + place.string() + " (not this build's Gmsh module)";
      continue;
    }
    return table;
  }
  throw std::runtime_error(
      "cannot open rockdd's Gmsh module librockdd_gmsh.so, which meshes "
      "scenes; set ROCKDD_GMSH_MODULE to its path. Looked at:" +
      tried);
}

}  // namespace

const GmshModuleEntry& gmsh_module() {
  static const GmshModuleEntry* entry = open_module();
  return *entry;
}

std::string gmsh_library_identity() {
  std::error_code error;
  const auto file = std::filesystem::canonical(ROCKDD_GMSH_LIBRARY, error);
  struct stat status {};
  if (error || stat(file.c_str(), &status) != 0) return {};
  return file.filename().string() + " " + std::to_string(status.st_size) + " " +
         std::to_string(status.st_mtim.tv_sec) + "." + std::to_string(status.st_mtim.tv_nsec);
}

Mesh build_mesh_in_this_process(const MeshSpec& spec, const std::filesystem::path& scene_file,
                                int gmsh_threads) {
  return gmsh_module().mesh(spec, scene_file, gmsh_threads);
}

Mesh build_mesh(const MeshSpec& spec, const std::filesystem::path& scene_file, int gmsh_threads) {
  return mesh_in_child_process(
      [&] { return build_mesh_in_this_process(spec, scene_file, gmsh_threads); }, meshing_limits(),
      MeshSource{scene_file.string(), mesh_key(spec)}, mesh_name(spec));
}

}  // namespace rockdd
