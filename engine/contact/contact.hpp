#pragma once
// One vertex-edge contact (METHOD.md "Contact"): the state the open-close iteration assumes,
// the springs it adds, and what it remembers from step to step.
#include <cstdint>

namespace rockdd {

/// Open: no spring. Sliding: normal spring, friction force. Locked: normal and shear springs.
enum class ContactState : std::uint8_t { open, sliding, locked };

/// The springs a contact adds to K: normal_stiffness g g^T (kn when closed), shear_stiffness
/// t t^T.
struct ContactSprings {
  double normal_stiffness = 0.0;  // N/m
  double shear_stiffness = 0.0;   // N/m
  bool operator==(const ContactSprings& other) const = default;
};

/// One vertex-edge contact and what it remembers across iterations and steps.
struct Contact {
  std::int32_t vertex = -1, a = -1, b = -1;  // nodes: vertex p, edge a->b
  std::int32_t edge = -1;                    // boundary edge index
  ContactState state = ContactState::open;   // state assumed in the current solve
  double shear_spring = 0.0;                 // committed elastic slip of a locked contact (m)
  double slip_sign = 0.0;                    // direction of sliding
  double friction_force = 0.0;  // of a sliding contact on its vertex, along t (last solve)
  double friction = 0.0, cohesion = 0.0;  // tan(phi), c (Pa) of the joint
  double tensile_strength = 0.0;          // of the joint (Pa)
  double area = 0.0;       // joint area the contact stands for (m^2), for cohesion and tension
  bool bonded = false;     // an intact joint: cohesion and tensile strength count until it fails
  std::uint8_t flips = 0;  // open <-> closed changes in this step attempt
  std::uint8_t shear_swings = 0;     // changes of the shear force beyond tolerance, this attempt
  double used_normal_force = 0.0;    // the normal force friction used in the last update
  double start_normal_force = -1.0;  // at the start of the step, if pressed then (else < 0)
  // The step's linearisation about its start (what the solve sees): gap(x) = gap_offset + g.x
  // and slip(x) = slip_offset + t.x over the dofs (p, a, b); see kernels/contact_geometry.
  double g[6] = {}, t[6] = {};
  double gap_offset = 0.0, slip_offset = 0.0;
  double gap_start = 0.0;           // the gap at the start of the step
  double slide_slip = 0.0;          // step slip where friction_force was set (without inertia)
  double slide_stiffness = 0.0;     // its sliding spring (N/m), softened while it slides freely
  double last_excess = 0.0;         // its shear force past the capacity, last iteration (N)
  double anchor_start = 0.0;        // shear_spring at the step start or when it closed (m)
  double end_gap = 0.0;             // the gap its force came from at the end of the last step (m)
  double unresisted_overlap = 0.0;  // its zero: an overlap no solve resisted (m)
  // Newmark's energy-consistent contact forces (ContactStage::add_solve_forces): whether its
  // spring was closed and whether locked at the start of the step, with its shear spring's
  // elastic slip then; and the line the solve takes twice the step's mean normal force on,
  // normal_force_line + normal_spring (gap - normal_gap_line): the tangent at the last iterate.
  bool closed_at_start = false;
  bool locked_at_start = false;
  double shear_spring_start = 0.0;  // m
  double normal_spring = 0.0;       // N/m
  double normal_force_line = 0.0;   // N
  double normal_gap_line = 0.0;     // m
};

}  // namespace rockdd
