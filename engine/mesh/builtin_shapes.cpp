#include "engine/mesh/builtin_shapes.hpp"

#include <gmsh.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engine/scene/geometry_limits.hpp"
#include "engine/scene/mesh_budget.hpp"

namespace rockdd {

namespace {

namespace geo = gmsh::model::geo;

/// Library callers may hand over a MeshSpec the scene reader never saw: the same limits on
/// lengths (geometry_limits) apply here.
void require_length(double value, const std::string& what, const MeshSource& source) {
  if (!length_in_range(value))
    source.fail(what + " must be a length " + length_range_text() + ", got " +
                format_number(value));
}

/// Refuses a count of triangles that would not fit in memory (mesh_budget), before meshing.
void require_within_budget(const MeshSpec& spec, const MeshSource& source) {
  const std::string problem =
      mesh_budget_problem(estimated_triangles(spec).value_or(0.0), available_memory_bytes());
  if (!problem.empty()) source.fail(problem);
}

void name_group(int dim, const std::vector<int>& tags, const std::string& name) {
  gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, tags), name);
}

/// Caps the mesh size at `size` everywhere (points carry it too, so curves honour it).
void cap_mesh_size(double size) {
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
}

}  // namespace

void add_rectangle(const MeshSpec& spec, const MeshSource& source) {
  const MeshSource size_key{source.where, "mesh.size"};
  require_length(spec.size[0], "the width", size_key);
  require_length(spec.size[1], "the height", size_key);
  const auto [x0, y0] = spec.origin;
  const double x1 = x0 + spec.size[0], y1 = y0 + spec.size[1];
  const double size = spec.element_size.value_or(0.0);  // 0: Gmsh ignores point sizes
  if (spec.element_size) {
    const MeshSource size_cap{source.where, "mesh.element_size"};
    require_length(size, "element_size", size_cap);
    require_within_budget(spec, size_cap);
  } else {
    const MeshSource divisions_key{source.where, "mesh.divisions"};
    if (spec.divisions[0] < 1 || spec.divisions[1] < 1)
      divisions_key.fail("divisions must be at least 1 in each direction");
    require_within_budget(spec, divisions_key);
  }
  const int bottom_left = geo::addPoint(x0, y0, 0.0, size);
  const int bottom_right = geo::addPoint(x1, y0, 0.0, size);
  const int top_right = geo::addPoint(x1, y1, 0.0, size);
  const int top_left = geo::addPoint(x0, y1, 0.0, size);
  const int bottom = geo::addLine(bottom_left, bottom_right);
  const int right = geo::addLine(bottom_right, top_right);
  const int top = geo::addLine(top_right, top_left);
  const int left = geo::addLine(top_left, bottom_left);
  const int surface = geo::addPlaneSurface({geo::addCurveLoop({bottom, right, top, left})});
  geo::synchronize();

  if (spec.element_size) {
    cap_mesh_size(size);
  } else {
    gmsh::model::mesh::setTransfiniteCurve(bottom, spec.divisions[0] + 1);
    gmsh::model::mesh::setTransfiniteCurve(top, spec.divisions[0] + 1);
    gmsh::model::mesh::setTransfiniteCurve(right, spec.divisions[1] + 1);
    gmsh::model::mesh::setTransfiniteCurve(left, spec.divisions[1] + 1);
    gmsh::model::mesh::setTransfiniteSurface(surface, "AlternateLeft",
                                             {bottom_left, bottom_right, top_right, top_left});
  }
  name_group(2, {surface}, "body");
  name_group(1, {bottom}, "bottom");
  name_group(1, {right}, "right");
  name_group(1, {top}, "top");
  name_group(1, {left}, "left");
  name_group(0, {bottom_left}, "bottom_left");
  name_group(0, {bottom_right}, "bottom_right");
  name_group(0, {top_right}, "top_right");
  name_group(0, {top_left}, "top_left");
}

void add_disk(const MeshSpec& spec, const MeshSource& source) {
  const double r = spec.radius;
  require_length(r, "radius", {source.where, "mesh.radius"});
  const MeshSource size_key{source.where, "mesh.element_size"};
  if (!spec.element_size) size_key.fail("element_size is required for shape = \"disk\"");
  const double size = *spec.element_size;
  require_length(size, "element_size", size_key);
  const double alpha_deg = spec.flat_half_angle_deg;
  if (!(alpha_deg >= 0.0 && alpha_deg < 90.0))
    MeshSource{source.where, "mesh.flat_half_angle_deg"}.fail(
        "flat_half_angle_deg must be in [0, 90), got " + format_number(alpha_deg));
  const double alpha = alpha_deg * std::numbers::pi / 180.0;
  require_within_budget(spec, size_key);

  // Flat ends at y = ±R cos(alpha), from x = -R sin(alpha) to R sin(alpha); alpha = 0 leaves a
  // plain circle whose top and bottom are (0, ±R). Every named point is a curve end or
  // embedded, so it is a mesh node; arcs stay below pi as Gmsh requires.
  // Not a structured binding: clang before 16 cannot capture those in the lambda below.
  const double cx = spec.origin[0], cy = spec.origin[1];
  const double half_width = r * std::sin(alpha), flat_y = r * std::cos(alpha);
  auto point = [&](double x, double y) { return geo::addPoint(cx + x, cy + y, 0.0, size); };
  const int center = point(0.0, 0.0);
  const int right = point(r, 0.0), left = point(-r, 0.0);
  const int top = point(0.0, flat_y), bottom = point(0.0, -flat_y);
  std::vector<int> loop, rim, top_flat, bottom_flat;
  auto arc = [&](int from, int to) {
    rim.push_back(geo::addCircleArc(from, center, to));
    loop.push_back(rim.back());
  };
  auto flat = [&](int from, int to, std::vector<int>& named) {
    named.push_back(geo::addLine(from, to));
    loop.push_back(named.back());
  };
  if (alpha_deg > 0.0) {
    const int bottom_right = point(half_width, -flat_y), top_right = point(half_width, flat_y);
    const int top_left = point(-half_width, flat_y), bottom_left = point(-half_width, -flat_y);
    flat(bottom, bottom_right, bottom_flat);
    arc(bottom_right, right);
    arc(right, top_right);
    flat(top_right, top, top_flat);
    flat(top, top_left, top_flat);
    arc(top_left, left);
    arc(left, bottom_left);
    flat(bottom_left, bottom, bottom_flat);
  } else {
    arc(bottom, right);
    arc(right, top);
    arc(top, left);
    arc(left, bottom);
  }
  const int surface = geo::addPlaneSurface({geo::addCurveLoop(loop)});
  geo::synchronize();
  gmsh::model::mesh::embed(0, {center}, 2, surface);
  cap_mesh_size(size);

  name_group(2, {surface}, "body");
  name_group(1, rim, "rim");
  if (!top_flat.empty()) name_group(1, top_flat, "top_flat");
  if (!bottom_flat.empty()) name_group(1, bottom_flat, "bottom_flat");
  name_group(0, {center}, "center");
  name_group(0, {top}, "top");
  name_group(0, {bottom}, "bottom");
  name_group(0, {left}, "left");
  name_group(0, {right}, "right");
}

}  // namespace rockdd
