#include "engine/mesh/mesh_errors.hpp"

#include <charconv>

#include "engine/common/errors.hpp"

namespace rockdd {

void MeshSource::fail(const std::string& message) const {
  throw InputError(where, key, message);
}

std::string mesh_key(const MeshSpec& spec) {
  switch (spec.kind) {
    case MeshSpec::Kind::geo:
      return "mesh.geo";
    case MeshSpec::Kind::msh:
      return "mesh.msh";
    case MeshSpec::Kind::rectangle:
    case MeshSpec::Kind::disk:
      return "mesh.shape";
  }
  return "mesh";
}

std::string mesh_name(const MeshSpec& spec) {
  switch (spec.kind) {
    case MeshSpec::Kind::geo:
    case MeshSpec::Kind::msh:
      return spec.file.string();
    case MeshSpec::Kind::rectangle:
      return "the rectangle";
    case MeshSpec::Kind::disk:
      return "the disk";
  }
  return "the mesh";
}

std::string point_text(double x, double y) {
  std::string text = "(";
  text += format_number(x);
  text += ',';
  text += format_number(y);
  text += ')';
  return text;
}

}  // namespace rockdd
