// The one symbol librockdd_gmsh.so exports: the table the engine calls it through.
#include <gmsh.h>

#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/gmsh_session.hpp"

namespace {

std::string loaded_gmsh_version() {
  rockdd::GmshSession session;
  std::string text;
  gmsh::option::getString("General.Version", text);
  return text;
}

const rockdd::GmshModuleEntry kEntry{rockdd::kGmshModuleAbi, &rockdd::mesh_with_gmsh,
                                     &loaded_gmsh_version};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rockdd::GmshModuleEntry*
rockdd_gmsh_module_entry() {
  return &kEntry;
}
