#pragma once
// Comparing two meshes field by field, for the mesh tests (only the mesh library behind them).
#include <gtest/gtest.h>

#include "engine/mesh/mesh.hpp"

namespace rockdd::test {

/// Expects two meshes to be the same in every field a model is built from.
inline void expect_same_mesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.xy, b.xy);  // doubles compared bit for bit (no NaN in a mesh)
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.element_surface, b.element_surface);
  EXPECT_EQ(a.surface_body, b.surface_body);
  EXPECT_EQ(a.curves, b.curves);
  EXPECT_EQ(a.points, b.points);
}

}  // namespace rockdd::test
