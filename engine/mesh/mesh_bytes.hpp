#pragma once
// A Mesh as bytes (byte_io): the body of a mesh cache entry, and what a meshing process
// hands back to the process that asked for the mesh.
#include "engine/mesh/byte_io.hpp"
#include "engine/mesh/mesh.hpp"

namespace rockdd {

/// Appends every field of `mesh`.
void write_mesh(ByteWriter& out, const Mesh& mesh);

/// Reads what write_mesh wrote into `mesh`; false when the bytes are short or inconsistent
/// (lengths that do not make nodes, triangles and one surface per triangle).
bool read_mesh(ByteReader& in, Mesh& mesh);

}  // namespace rockdd
