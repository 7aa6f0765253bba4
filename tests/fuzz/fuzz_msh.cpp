// libFuzzer harness: the fuzz input is a Gmsh .msh file, read as `mesh.msh` by build_mesh's
// own steps in this process (build_mesh_in_this_process), not in its meshing process: a crash
// in Gmsh, which the meshing process would turn into an InputError, must be seen here, since
// it is a file the checks before Gmsh let through. Gmsh reads only files, so each input is
// written to a file of this process first.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/mesh.hpp"
#include "fuzz_input_error.hpp"

namespace {

const std::filesystem::path kSceneFile = "fuzz_msh_scene.toml";

/// A file per process: libFuzzer's -jobs/-workers run several processes in one folder.
const std::filesystem::path& mesh_file() {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("rockdd_fuzz_" + std::to_string(getpid()) + ".msh");
  return file;
}

/// Removes the input's file once Gmsh has read it: libFuzzer may end the process without
/// running static destructors, and a run leaves no file behind unless it crashed.
struct RemovedAfterwards {
  ~RemovedAfterwards() {
    std::error_code ignored;
    std::filesystem::remove(mesh_file(), ignored);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const RemovedAfterwards cleanup;
  {
    std::ofstream out(mesh_file(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  rockdd::MeshSpec spec;
  spec.kind = rockdd::MeshSpec::Kind::msh;
  spec.file = mesh_file();
  rockdd::fuzz::expect_success_or_input_error(
      kSceneFile.string(), [&] { rockdd::build_mesh_in_this_process(spec, kSceneFile); });
  return 0;
}
