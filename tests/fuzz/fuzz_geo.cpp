// libFuzzer harness: the fuzz input is a Gmsh .geo file, meshed by build_mesh as `mesh.geo`,
// under the meshing budget (issue 28): the estimate from the curves' sizes, then Gmsh in a
// meshing process with memory and time limits. What it must hold: whatever the .geo asks for,
// this process gets a mesh or an InputError naming the scene, within the limits. Gmsh's own
// crashes on a script are contained by the meshing process (an InputError that says so); they
// are counted on stderr ("fuzz_geo: contained"), not findings, since Gmsh's .geo language is
// not rockdd's to fix.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include "engine/common/errors.hpp"
#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/mesh.hpp"
#include "fuzz_input_error.hpp"

namespace {

const std::filesystem::path kSceneFile = "fuzz_geo_scene.toml";

/// A file per process: libFuzzer's -jobs/-workers run several processes in one folder.
const std::filesystem::path& geo_file() {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("rockdd_fuzz_" + std::to_string(getpid()) + ".geo");
  return file;
}

struct RemovedAfterwards {
  ~RemovedAfterwards() {
    std::error_code ignored;
    std::filesystem::remove(geo_file(), ignored);
  }
};

/// A .geo may run shell commands and ONELAB clients: no fuzz input gets to.
bool runs_programs(std::string_view text) {
  for (const char* word : {"System", "Onelab", "OnelabRun", "Exit"})
    if (text.find(word) != std::string_view::npos) return true;
  return false;
}

/// With ROCKDD_FUZZ_GEO_KEEP set to a folder, an input the meshing process had to stop is
/// copied there (contained_<n>.geo), for a long run's notes.
void keep_contained(std::string_view text) {
  const char* folder = std::getenv("ROCKDD_FUZZ_GEO_KEEP");
  if (folder == nullptr || *folder == '\0') return;
  static int kept = 0;
  std::ofstream(std::filesystem::path(folder) / ("contained_" + std::to_string(++kept) + ".geo"),
                std::ios::binary)
      .write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Small limits keep each input to seconds; the budget's machinery is what is fuzzed. The
  // module is opened here once, so that each meshing process inherits it instead of opening
  // Gmsh's ~90 libraries again (0.14 s).
  ::setenv("ROCKDD_MESHING_SECONDS", "3", 0);
  ::setenv("ROCKDD_MESHING_BYTES", "1e9", 0);
  rockdd::gmsh_module();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (runs_programs(text)) return -1;  // not added to the corpus
  const RemovedAfterwards cleanup;
  {
    std::ofstream out(geo_file(), std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  }
  rockdd::MeshSpec spec;
  spec.kind = rockdd::MeshSpec::Kind::geo;
  spec.file = geo_file();
  rockdd::fuzz::expect_success_or_input_error(kSceneFile.string(), [&] {
    try {
      rockdd::build_mesh(spec, kSceneFile);
    } catch (const rockdd::InputError& error) {
      // What the meshing process stopped, for the counts of a long run.
      for (const char* what : {"got Gmsh killed by signal", "within the meshing time limit",
                               "within the meshing memory limit"})
        if (error.expected().find(what) != std::string::npos) {
          std::fprintf(stderr, "fuzz_geo: contained: %s\n",
                       error.expected().substr(0, 160).c_str());
          keep_contained(text);
        }
      throw;
    }
  });
  return 0;
}
