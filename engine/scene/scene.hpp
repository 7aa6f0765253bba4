#pragma once
// Scene: the plain data of one TOML scene file (docs/scene.md), validated.
// Every optional key that the reader filled with a default is listed in `defaults`.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/mesh_algorithm.hpp"
#include "kernels/material.hpp"

namespace rockdd {

enum class Analysis { static_, quasi_static, dynamic };
using kernels::PlaneKind;
using kernels::TensionOnset;
enum class Integrator { dda, newmark };

using Vec2 = std::array<double, 2>;

/// Steps a scene may ask for unless time.max_steps raises it. A step costs about 0.1 ms
/// whatever the mesh (data/verification/free_fall.toml, 8 elements: 10 steps in 1 ms; the
/// block resting on its base of docs/stability.md: 1e5 steps in 14 s), so 1e7 steps take a
/// quarter of an hour at the least and hours on a real mesh: a scene beyond it is a slip of an
/// exponent far more often than a plan, and one that means it says so with time.max_steps.
inline constexpr std::int64_t kDefaultMaxSteps = 10'000'000;

/// time.energy_tolerance's default: chosen by measurement (docs/method-choices.md, "Energy
/// check").
inline constexpr double kDefaultEnergyTolerance = 1e-3;

/// [time]: first dt, end time or step count, and step control.
struct TimeSpec {
  double dt = 1.0;                              // s (1 in a static scene without [time])
  std::optional<double> end;                    // s; exactly one of end / steps is set
  std::optional<int> steps;                     // number of steps
  std::int64_t max_steps = kDefaultMaxSteps;    // the step budget (step_budget.hpp)
  double dt_min = 0.0;                          // s; 0 = dt * 1e-6 (default chosen)
  std::optional<double> max_step_displacement;  // m
  double dt_max = 0.0;                          // s; default = dt
  // The energy one step may create, as a share of the run's energy scale (EnergyCheck).
  double energy_tolerance = kDefaultEnergyTolerance;
  Integrator integrator = Integrator::dda;
  // Optional end on softening: the run stops once the history column `softening_probe`
  // ("<probe>.<field>") has fallen `stop_at_softening` (a fraction) below its peak magnitude.
  std::optional<double> stop_at_softening;
  std::string softening_probe;
};

/// [mesh]: where the triangles come from.
struct MeshSpec {
  enum class Kind { geo, msh, rectangle, disk };
  Kind kind = Kind::rectangle;
  std::filesystem::path file;            // geo / msh, absolute (resolved from the scene)
  std::optional<double> element_size;    // m, caps the mesh size
  Vec2 size{1.0, 1.0};                   // rectangle
  Vec2 origin{0.0, 0.0};                 // rectangle lower-left corner; disk centre
  std::array<int, 2> divisions{10, 10};  // rectangle (structured, two triangles a cell)
  double radius = 0.0;                   // disk
  double flat_half_angle_deg = 0.0;      // disk (0 = round)
  // Gmsh's 2D algorithm and smoothing passes for unstructured meshes (disk, rectangle with
  // element_size, .geo); nullopt leaves Gmsh's choice (its defaults, or a .geo's own
  // Mesh.Algorithm / Mesh.Smoothing). The scene reader fills them in for built-in shapes.
  std::optional<MeshAlgorithm> algorithm;
  std::optional<int> smoothing;  // in [0, kMaxMeshSmoothing]
};

/// [[material]]: elastic, damage and heterogeneity parameters of one body (or "*").
struct MaterialSpec {
  std::string body;
  double density = 0.0;
  double young = 0.0;
  double poisson = 0.0;
  std::optional<double> tensile_strength;
  std::optional<double> cohesion;
  std::optional<double> compressive_strength;
  std::optional<double> friction_angle;   // deg
  double residual = 0.1;                  // lambda
  double ultimate_strain = 5.0;           // eta
  std::optional<double> fracture_energy;  // G_f (J/m^2): crack band, eta per element from its size
  TensionOnset tension_onset = TensionOnset::stress;
  double detach_at_damage = 1.0;           // 1: only once fully broken (w = 1); 0: at onset
  std::optional<double> homogeneity;       // Weibull m
  std::vector<std::string> heterogeneous;  // "young", "tensile_strength", ...
  std::uint64_t seed = 0;
  bool weibull_size_scaling = false;
  bool has_damage() const { return tensile_strength || cohesion || compressive_strength; }
};

/// [[initial]]: initial motion of a body.
struct InitialSpec {
  std::string body;
  Vec2 velocity{0.0, 0.0};
  double angular_velocity = 0.0;
};

/// [[joint]]: contact properties between bodies ("crack" = fracture faces, "*" = all).
struct JointSpec {
  std::vector<std::string> between;
  double friction_angle = 0.0;
  double cohesion = 0.0;
  double tensile_strength = 0.0;
  std::optional<double> normal_stiffness;
  std::optional<double> shear_stiffness;
};

/// [[boundary]]: fixed components and imposed velocities on a physical curve or point.
struct BoundarySpec {
  std::string on;
  bool fix_x = false, fix_y = false;
  std::optional<double> velocity_x, velocity_y;  // m/s; `velocity = [..]` sets both
};

/// [[load]]: point/line force, pressure, or body force density.
struct LoadSpec {
  std::string on;                     // curve or point (force, pressure)
  std::string body;                   // body (force_density)
  std::optional<Vec2> force;          // N total
  std::optional<double> pressure;     // Pa, positive pushes inward
  std::optional<Vec2> force_density;  // N/m^3
};

/// [[probe]]: a column group in history.csv, or a line profile.
struct ProbeSpec {
  enum class Kind { point, curve, body, line };
  std::string name;
  Kind kind = Kind::point;
  Vec2 at{0.0, 0.0};           // point
  std::string on;              // curve
  std::string body;            // body
  std::array<Vec2, 2> line{};  // line
  int samples = 101;           // line
  bool nodal_stress = false;   // line: stress = "nodal" (recovered) sampling
  std::vector<std::string> fields;
};

/// [fracture]: the numerical devices of damage and fracture (docs/method-choices.md,
/// "Damage events" and "Fragment restraint"); docs/convergence.md measures each of them.
struct FractureSpec {
  double damage_band = 1e-6;    // a damage pass starts damage only in elements within this
                                // fraction of the most overstressed one's onset ratio
  int max_damage_passes = 500;  // damage passes per step before the step goes on regardless
  // Without inertia, a step re-solves while damage that grew in its last pass changed some
  // element's modulus by more than this fraction: the step ends with the moduli its own
  // strains call for. 0: a pass without new onsets ends the step.
  double growth_tolerance = 3e-4;    // docs/method-choices.md: the peaks converge from 3e-4 down
  bool locate_onsets = true;         // without inertia: a step that passes an undamaged element's
                                     // onset is cut at it, and the damage runs in a step of its own
  double fragment_stiffness = 1e-6;  // spring per corner, x E0 t, on blocks no boundary holds,
                                     // in steps without inertia
  double loose_part_support = 1.0;   // x E0 t: the springs of the statically determinate support
                                     // of a part that a damage cascade cuts loose inside a step
  // After a settling solve or a damage pass, the fragment restraint is re-anchored where the
  // parts settled while its springs hold more than this share of the stored energy (down to a
  // thousandth of it); 0: never.
  double restraint_relaxation = 1e-3;
  /// How a quasi-static run follows a damage cascade: re-solved at held boundaries, or, from
  /// the first cascade on, with inertia (Newmark) at snap_back_dt.
  enum class SnapBack { held, dynamic };
  SnapBack snap_back = SnapBack::held;
  std::optional<double> snap_back_dt;  // s; default from the mesh's wave transit time
};

/// [solver]: how the linear systems are solved; changes round-off only (docs/benchmarks.md).
struct SolverSpec {
  bool factor_updates = true;  // fold few changed springs or moduli into the factor
                               // (cholmod_updown) when a cost model expects it to be cheaper
};

/// [output]
struct OutputSpec {
  std::filesystem::path dir = "out";
  int every = 100;
  std::vector<std::string> fields{"displacement", "velocity", "stress",  "principal",
                                  "damage",       "block",    "material"};
  bool compress = true;  // VTU frames: zlib-compressed appended data; false: raw
  /// Not a scene key: rockdd mc sets it so that a realization keeps only its last VTU frame
  /// (written when the run ends) instead of one every `every` steps.
  bool last_frame_only = false;
};

/// The whole scene.
struct Scene {
  std::filesystem::path file;  // the scene file, absolute
  std::string name;
  Analysis analysis = Analysis::static_;
  PlaneKind plane = PlaneKind::stress;
  double thickness = 1.0;
  Vec2 gravity{0.0, 0.0};
  bool has_time = false;  // false: static scene without [time]
  TimeSpec time;
  MeshSpec mesh;
  std::vector<MaterialSpec> materials;
  std::vector<InitialSpec> initial;
  std::vector<JointSpec> joints;
  std::vector<BoundarySpec> boundaries;
  std::vector<LoadSpec> loads;
  std::vector<ProbeSpec> probes;
  FractureSpec fracture;
  SolverSpec solver;
  OutputSpec output;
  /// Defaults the reader chose, as ("key.path", "value") for summary.json.
  std::vector<std::pair<std::string, std::string>> defaults;
};

}  // namespace rockdd
