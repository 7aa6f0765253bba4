#pragma once
// The rules contacts obey, fixed by the scene and the model: which blocks may touch, the joint
// of each pair of bodies (friction, cohesion, tensile strength), the penalty springs and their
// defaults, the search distance, and the joint area each boundary vertex stands for. The
// states of the contacts and Coulomb's law are the contact stage's (contact_stage).
#include <vector>

#include "engine/contact/contact_detection.hpp"
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Joint parameters that contacts use, derived from the scene.
struct ContactParameters {
  double normal_stiffness = 0.0;   // kn, N/m
  double shear_stiffness = 0.0;    // ks, N/m
  double reach = 0.0;              // search distance for candidates, m
  double force_tolerance = 1e-2;   // settled: forces within this fraction of the largest
  double penetration_limit = 0.0;  // settled only with no contact deeper than this, m
  double thickness = 1.0;
  // Shear spring of a sliding contact, on its slip since the last iterate (N/m): 0 with
  // inertia (friction is a bare load), a small fraction of ks without (analysis "static"
  // or "quasi-static"), where nothing else would hold a block that slides.
  double sliding_stiffness = 0.0;
  // Without inertia, an overlap found at a step's start that no solve resisted carries no
  // force and heals as the faces part (ContactStage::detect). With inertia the penalty
  // spring's push-back is part of the momentum balance and stays.
  bool forgive_unresisted_overlap = false;
};

/// The joint of each ordered pair of bodies, at body_a * num_bodies + body_b.
struct JointTable {
  std::vector<double> friction;  // tan(phi)
  std::vector<double> cohesion;  // Pa
  std::vector<double> tensile;   // Pa
};

/// Everything the contacts of one model obey.
struct ContactRulebook {
  ContactRules touching;  // which blocks may touch (contact detection)
  JointTable joints;
  ContactParameters parameters;
  std::vector<double> vertex_area;  // per boundary vertex: the joint area it stands for (m^2)
};

/// The rules of the scene's joints for `model` with block boundary `boundary`: every pair the
/// scene's [[joint]]s name, fracture faces of one body (the "crack" joint, or the material's
/// friction angle), the springs kn and ks (default 20 E t and 0.4 kn, E the stiffest
/// material), the search distance (half the median boundary edge), and for `analysis` the
/// sliding springs of steps without inertia (set_contact_analysis).
ContactRulebook contact_rules(const Scene& scene, const Model& model, const BlockBoundary& boundary,
                              Analysis analysis);

/// The sliding springs and forgiven overlaps of steps without inertia, or neither with it.
void set_contact_analysis(ContactParameters& parameters, Analysis analysis);

}  // namespace rockdd
