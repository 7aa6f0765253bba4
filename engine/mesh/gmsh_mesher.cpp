#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>

#include "engine/common/errors.hpp"
#include "engine/mesh/builtin_shapes.hpp"
#include "engine/mesh/finish_mesh.hpp"
#include "engine/mesh/geo_size_estimate.hpp"
#include "engine/mesh/gmsh_model_reader.hpp"
#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/gmsh_session.hpp"
#include "engine/mesh/mesh.hpp"
#include "engine/mesh/msh2_node_references.hpp"
#include "engine/mesh/msh4_contents.hpp"
#include "engine/mesh/msh_header.hpp"
#include "engine/mesh/msh_physical_names.hpp"
#include "engine/mesh/validate_mesh.hpp"
#include "engine/scene/geometry_limits.hpp"
#include "engine/scene/mesh_algorithm.hpp"
#include "engine/scene/mesh_budget.hpp"

namespace rockdd {

namespace {

/// Gmsh's own words for the exception in flight (Gmsh throws std::string or std::exception).
std::string gmsh_message() {
  try {
    throw;
  } catch (const std::string& text) {
    return text;
  } catch (const std::exception& error) {
    return error.what();
  } catch (...) {
  }
  return "unknown Gmsh error";
}

/// Runs a step of Gmsh API calls, turning Gmsh's own errors into InputError "<doing>: <message>".
template <class Step>
void gmsh_step(const MeshSource& source, const std::string& doing, Step&& step) {
  try {
    step();
  } catch (const InputError&) {
    throw;
  } catch (...) {
    source.fail(doing + ": " + gmsh_message());
  }
}

void require_file(const std::filesystem::path& file, const MeshSource& source) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    source.fail("file not found: " + file.string());
}

/// Runs a Gmsh step that may fail inside Gmsh's parser or mesher; fails with "<doing>: <error>",
/// naming `file` when Gmsh's message does not.
void checked_gmsh_step(const MeshSource& source, const std::string& doing,
                       const std::function<void()>& step, const std::filesystem::path& file = {}) {
  std::string error = first_gmsh_error(step);
  if (error.empty()) return;
  if (!file.empty() && error.find(file.filename().string()) == std::string::npos)
    error += " (in " + file.string() + ")";
  source.fail(doing + ": " + error);
}

/// Checks a .geo's model before Gmsh meshes it. Coordinates the engine cannot compute with
/// (geometry_limits) send Gmsh's 1D mesher into endless recursion: a square of side 1e308 has
/// an infinite diagonal, its size field is inf / inf = NaN, and the adaptive integration of
/// each curve subdivides for ever, growing to GBs. Sizes far below the extent mesh for ever
/// too: a size cap of 1e-3 on a 1e9 m curve, or a point size of 1e-9 on a 25 mm disk (issue
/// 28: Gmsh grew by 60 MB/s). A triangulation has at least as many triangles as its boundary
/// has segments less 2, and the outer boundary is at least twice the box's longer side long,
/// so both the cap and the curves' own sizes (geo_size_estimate) bound the count from below.
void check_geo_model(const MeshSpec& spec, const MeshSource& source) {
  double box[6] = {NAN, NAN, NAN, NAN, NAN, NAN};
  const std::string error = first_gmsh_error(
      [&] { gmsh::model::getBoundingBox(-1, -1, box[0], box[1], box[2], box[3], box[4], box[5]); });
  if (!error.empty() || !(box[0] <= box[3])) return;  // an empty model: meshing says so
  for (const double x : box)
    if (!coordinate_in_range(x))
      source.fail("expected a model with coordinates in [-" + format_number(kLongestLength) + ", " +
                  format_number(kLongestLength) + "] m, got one from " +
                  point_text(box[0], box[1]) + " to " + point_text(box[3], box[4]));
  // The engine is plane: a model out of z = 0 (to 1e-9 of its extent, as the mesh reader
  // checks) is refused before Gmsh meshes it. Found by fuzzing (issue 28): a point of
  // halved_disk.geo at z = 2 made Gmsh mesh a non-plane "plane" surface for 1 s (3.4 s in the
  // sanitized harness) before the mesh was refused.
  const double extent = std::hypot(box[3] - box[0], box[4] - box[1]);
  if (std::max(std::abs(box[2]), std::abs(box[5])) > 1e-9 * extent)
    source.fail("expected a model in the plane z = 0 (a 2D mesh), got one from z = " +
                format_number(box[2]) + " to " + format_number(box[5]) + " (in " +
                spec.file.string() + ")");
  double file_cap = 0.0;
  gmsh::option::getNumber("Mesh.MeshSizeMax", file_cap);
  const double cap = std::min(spec.element_size.value_or(file_cap), file_cap);
  const double segments = 2.0 * std::max(box[3] - box[0], box[4] - box[1]) / cap;
  std::string problem =
      mesh_budget_problem(std::max(segments - 2.0, 0.0), available_memory_bytes(), true);
  if (!problem.empty())
    (spec.element_size ? MeshSource{source.where, "mesh.element_size"} : source).fail(problem);
  double on_curves = 0.0;
  const std::string sizes_error = first_gmsh_error(
      [&] { on_curves = geo_curve_segments_at_least(std::filesystem::temp_directory_path()); });
  if (!sizes_error.empty()) return;  // meshing will report it
  problem = mesh_budget_problem(std::max(on_curves - 2.0, 0.0), available_memory_bytes(), true);
  if (!problem.empty())
    source.fail(problem + " (from its sizes Gmsh would put at least " + count_text(on_curves) +
                " segments on its curves, and a triangulation has at least as many triangles "
                "as boundary segments less 2; in " +
                spec.file.string() + ")");
}

/// Checks a .geo's surfaces once Gmsh has meshed its curves: a size field far below the
/// extent (1e-4 on a unit square: 1.2e8 triangles) is invisible to the sizes of the points,
/// but not to the curves' segments (geo_triangles_at_least).
void check_geo_surfaces(const MeshSpec& spec, const MeshSource& source) {
  double longest = 0.0, triangles = 0.0;
  if (!first_gmsh_error([&] { triangles = geo_triangles_at_least(longest); }).empty()) return;
  const std::string problem = mesh_budget_problem(triangles, available_memory_bytes(), true);
  if (!problem.empty())
    source.fail(problem + " (its curves meshed, their longest segment is " +
                format_number(longest) +
                " m, and no triangle of its surfaces is larger than 1.5 "
                "times that a side; in " +
                spec.file.string() + ")");
}

/// Hands Gmsh the scene's 2D algorithm and smoothing passes (nullopt: Gmsh's or the .geo's own).
/// Library callers may hand over a MeshSpec the scene reader never saw: the same limits apply.
void set_mesher_options(const MeshSpec& spec, const MeshSource& source) {
  if (spec.smoothing && !(*spec.smoothing >= 0 && *spec.smoothing <= kMaxMeshSmoothing))
    MeshSource{source.where, "mesh.smoothing"}.fail("expected an integer in [0, " +
                                                    std::to_string(kMaxMeshSmoothing) + "], got " +
                                                    std::to_string(*spec.smoothing));
  if (spec.algorithm) {
    if (mesh_algorithm_name(*spec.algorithm) == "unknown")
      MeshSource{source.where, "mesh.algorithm"}.fail(
          "expected a Gmsh 2D algorithm rockdd knows, got number " +
          std::to_string(static_cast<int>(*spec.algorithm)));
    gmsh::option::setNumber("Mesh.Algorithm", static_cast<int>(*spec.algorithm));
  }
  if (spec.smoothing) gmsh::option::setNumber("Mesh.Smoothing", *spec.smoothing);
}

/// Fills the current Gmsh model with the 2D mesh `spec` describes.
void make_gmsh_mesh(const MeshSpec& spec, const MeshSource& source) {
  auto open = [&] {
    require_file(spec.file, source);
    checked_gmsh_step(
        source, "Gmsh could not read the file", [&] { gmsh::open(spec.file.string()); }, spec.file);
  };
  auto generate = [&](const std::string& what) {
    checked_gmsh_step(
        source, "Gmsh could not mesh " + what, [] { gmsh::model::mesh::generate(2); },
        spec.kind == MeshSpec::Kind::geo ? spec.file : std::filesystem::path{});
  };
  switch (spec.kind) {
    case MeshSpec::Kind::geo:
      open();
      // Set after reading so that it overrides the file's own Mesh.MeshSizeMax.
      if (spec.element_size) gmsh::option::setNumber("Mesh.MeshSizeMax", *spec.element_size);
      set_mesher_options(spec, source);
      check_geo_model(spec, source);
      // The curves first: their mesh, size fields included, bounds the surfaces' from below
      // before Gmsh meshes them. generate(2) goes on from it; without renumbering in between
      // (Mesh.Renumber, restored for the end) the mesh is bitwise the one generate(2) makes
      // alone (renumbered, the notched bar got 10,620 triangles instead of 10,610).
      checked_gmsh_step(
          source, "Gmsh could not mesh the curves of the file",
          [] {
            double renumber = 1.0;
            gmsh::option::getNumber("Mesh.Renumber", renumber);
            gmsh::option::setNumber("Mesh.Renumber", 0);
            gmsh::model::mesh::generate(1);
            gmsh::option::setNumber("Mesh.Renumber", renumber);
          },
          spec.file);
      check_geo_surfaces(spec, source);
      generate("the file");
      return;
    case MeshSpec::Kind::msh:
      require_file(spec.file, source);
      check_msh_header(spec.file, source);
      check_msh2_node_references(spec.file, source);
      check_msh_physical_names(spec.file, source);
      check_msh4_contents(spec.file, source);
      open();
      return;
    case MeshSpec::Kind::rectangle:
      gmsh_step(source, "Gmsh could not draw the rectangle", [&] { add_rectangle(spec, source); });
      // Divisions make a transfinite (structured) mesh, which neither option changes.
      if (spec.element_size) set_mesher_options(spec, source);
      generate("the rectangle");
      return;
    case MeshSpec::Kind::disk:
      gmsh_step(source, "Gmsh could not draw the disk", [&] { add_disk(spec, source); });
      set_mesher_options(spec, source);
      generate("the disk");
      return;
  }
}

}  // namespace

Mesh mesh_with_gmsh(const MeshSpec& spec, const std::filesystem::path& scene_file,
                    int gmsh_threads) {
  const MeshSource source{scene_file.string(), mesh_key(spec)};
  TaggedMesh raw;
  {
    GmshSession session(gmsh_threads);
    make_gmsh_mesh(spec, source);
    gmsh_step(source, "Gmsh could not give its mesh", [&] { raw = read_gmsh_model(source); });
  }
  // A file's triangle count is known only now: refuse, before the model and the solver take
  // memory, a mesh whose run would not fit (built-in shapes were estimated before meshing).
  const std::string problem =
      mesh_budget_problem(static_cast<double>(raw.mesh.num_elements()), available_memory_bytes());
  if (!problem.empty()) source.fail(problem);
  TaggedMesh mesh = finish_mesh(raw, source);
  validate_mesh(mesh.mesh, source, mesh.element_tags);
  return std::move(mesh.mesh);
}

}  // namespace rockdd
