#include "engine/scene/scene_entries.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <string>

namespace rockdd {
namespace {

std::string joined(const std::vector<std::string>& words, const std::string& separator) {
  std::string text;
  for (const std::string& w : words) text += (text.empty() ? "" : separator) + w;
  return text;
}

/// Refuses a value of `key` already used by an earlier entry (`seen` maps value → entry path).
void check_unique(const TableReader& table, std::string_view key, const std::string& value,
                  std::map<std::string, std::string>& seen, const std::string& what) {
  const auto [it, inserted] = seen.emplace(value, table.path());
  if (!inserted) {
    table.fail(key, "expected " + what + " given once, got \"" + value + "\" again (also in " +
                        it->second + ")");
  }
}

/// Probe names become history.csv columns `<probe>.<field>` and file names.
void check_probe_name(const TableReader& table, const std::string& name) {
  const bool plain = std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-';
  });
  if (!plain) {
    table.fail("name",
               "expected a name of letters, digits, '_' or '-' (it names CSV columns "
               "and files), got \"" +
                   name + "\"");
  }
}

void read_damage(TableReader& t, MaterialSpec& m) {
  m.tensile_strength = t.number("tensile_strength", above(0, true));
  m.cohesion = t.number("cohesion", above(0, true));
  m.compressive_strength = t.number("compressive_strength", above(0, true));
  m.friction_angle = t.number("friction_angle", between(0, true, 90, false));
  if (m.cohesion && m.compressive_strength) {
    t.fail("compressive_strength", "expected cohesion or compressive_strength, not both");
  }
  if ((m.cohesion || m.compressive_strength) && !m.friction_angle) {
    t.fail("friction_angle",
           "expected a number in [0, 90) with cohesion or compressive_strength (shear damage "
           "needs both), got nothing");
  }
  // Damage-law parameters are validated always but recorded as defaults only where used.
  const bool used = m.has_damage();
  const auto number = [&](std::string_view key, double fallback, const Range& range) {
    return used ? t.number_or(key, fallback, range) : t.number(key, range).value_or(fallback);
  };
  m.residual = number("residual", 0.1, between(0, true, 1, true));
  m.fracture_energy = t.number("fracture_energy", above(0));
  if (m.fracture_energy) {
    if (!m.tensile_strength) {
      t.fail("fracture_energy",
             "expected tensile_strength with fracture_energy (the crack band regularises the "
             "tensile law), got nothing");
    }
    if (t.has("ultimate_strain")) {
      t.fail("ultimate_strain",
             "expected ultimate_strain or fracture_energy, not both (with fracture_energy each "
             "element's ultimate strain follows from its size)");
    }
    // The element must stay in the continuum until it has dissipated its share of gf: an
    // element detached at onset would leave the rest to the crack joint.
    m.detach_at_damage = t.number_or("detach_at_damage", 1.0, between(0, true, 1, true));
    if (m.detach_at_damage != 1.0) {
      t.fail("detach_at_damage",
             "expected 1 (detach once fully broken) with fracture_energy, got " +
                 std::to_string(m.detach_at_damage) +
                 " (an element that detaches earlier leaves part of its fracture energy "
                 "undissipated)");
    }
  } else {
    m.ultimate_strain = number("ultimate_strain", 5.0, above(1, true));
    m.detach_at_damage = number("detach_at_damage", 1.0, between(0, true, 1, true));
  }
  const auto onset = used ? t.choice_or("tension_onset", {"stress", "strain"}, "stress")
                          : t.choice("tension_onset", {"stress", "strain"}).value_or("stress");
  m.tension_onset = onset == "strain" ? TensionOnset::strain : TensionOnset::stress;
}

void read_heterogeneity(TableReader& t, MaterialSpec& m) {
  m.homogeneity = t.number("homogeneity", above(0));
  const auto drawn =
      t.strings("heterogeneous", {"young", "tensile_strength", "cohesion", "compressive_strength"});
  if (drawn && !m.homogeneity) {
    t.fail("heterogeneous", "expected homogeneity (Weibull m) with heterogeneous, got nothing");
  }
  if (m.homogeneity && !drawn) {
    t.fail("homogeneity",
           "expected heterogeneous = [...] naming the parameters drawn with this homogeneity, "
           "got nothing");
  }
  if (auto seed = t.integer("seed", 0, LLONG_MAX)) m.seed = static_cast<std::uint64_t>(*seed);
  m.weibull_size_scaling = t.boolean("weibull_size_scaling").value_or(false);
  if (!m.homogeneity) return;
  for (const std::string& name : *drawn) {
    if (name != "young" && !t.has(name)) {
      t.fail("heterogeneous", "expected parameters the material has, got \"" + name +
                                  "\" without " + t.key_path(name));
    }
  }
  m.heterogeneous = *drawn;
  if (!t.has("seed")) t.record_default("seed", "0");
  if (!t.has("weibull_size_scaling")) t.record_default("weibull_size_scaling", "false");
}

MaterialSpec read_material(TableReader& t, PlaneKind plane) {
  t.allow_only({"body", "density", "young", "poisson", "tensile_strength", "cohesion",
                "compressive_strength", "friction_angle", "residual", "ultimate_strain",
                "fracture_energy", "tension_onset", "detach_at_damage", "homogeneity",
                "heterogeneous", "seed", "weibull_size_scaling"});
  MaterialSpec m;
  m.body = t.string("body").value_or(std::string(1, '*'));  // "*": every surface
  if (!t.has("body")) t.record_default("body", m.body);
  m.density = t.required_number("density", above(0));
  m.young = t.required_number("young", above(0));
  // Plane stress tolerates the incompressible limit; plane strain's D matrix divides by 1 - 2 nu.
  m.poisson = t.required_number("poisson", between(-1, false, 0.5, plane == PlaneKind::stress));
  read_damage(t, m);
  read_heterogeneity(t, m);
  return m;
}

InitialSpec read_initial_entry(TableReader& t) {
  t.allow_only({"body", "velocity", "angular_velocity"});
  InitialSpec initial;
  initial.body = t.required_string("body");
  if (auto velocity = t.vec2("velocity")) {
    initial.velocity = *velocity;
  } else {
    t.record_default("velocity", "[0, 0]");
  }
  initial.angular_velocity = t.number_or("angular_velocity", 0.0, Range{});
  return initial;
}

/// `between`: "crack", "*", or a pair of distinct body names.
std::vector<std::string> read_between(const TableReader& t) {
  const toml::node* node = t.find("between");
  const std::string want = "expected \"crack\", \"*\" or a pair of body names [\"a\", \"b\"], got ";
  if (!node) t.fail("between", want + "nothing (the key is required)");
  if (const auto* word = node->as_string()) {
    if (word->get() != "crack" && word->get() != "*") t.fail("between", want + describe(*node));
    return {word->get()};
  }
  const auto* pair = node->as_array();
  const auto name = [](const toml::node* n) {
    return n && n->is_string() && !n->as_string()->get().empty();
  };
  if (!pair || pair->size() != 2 || !name(pair->get(0)) || !name(pair->get(1)) ||
      pair->get(0)->as_string()->get() == pair->get(1)->as_string()->get()) {
    t.fail("between", want + describe(*node));
  }
  return {pair->get(0)->as_string()->get(), pair->get(1)->as_string()->get()};
}

JointSpec read_joint(TableReader& t) {
  t.allow_only({"between", "friction_angle", "cohesion", "tensile_strength", "normal_stiffness",
                "shear_stiffness"});
  JointSpec joint;
  joint.between = read_between(t);
  joint.friction_angle = t.number_or("friction_angle", 0.0, between(0, true, 90, false));
  joint.cohesion = t.number_or("cohesion", 0.0, above(0, true));
  joint.tensile_strength = t.number_or("tensile_strength", 0.0, above(0, true));
  joint.normal_stiffness = t.number("normal_stiffness", above(0));
  joint.shear_stiffness = t.number("shear_stiffness", above(0));
  return joint;
}

BoundarySpec read_boundary(TableReader& t) {
  t.allow_only({"on", "fix", "velocity", "velocity_x", "velocity_y"});
  BoundarySpec b;
  b.on = t.required_string("on");
  const auto fix = t.strings("fix", {"x", "y"});
  const auto velocity = t.vec2("velocity");
  const auto vx = t.number("velocity_x", Range{});
  const auto vy = t.number("velocity_y", Range{});
  if (!fix && !velocity && !vx && !vy) {
    t.fail_table("expected at least one of fix, velocity, velocity_x, velocity_y, got none");
  }
  if (fix && fix->empty())
    t.fail("fix", "expected at least one of \"x\", \"y\", got an empty array");
  if (velocity && vx) t.fail("velocity_x", "expected velocity or velocity_x, not both");
  if (velocity && vy) t.fail("velocity_y", "expected velocity or velocity_y, not both");
  b.fix_x = fix && std::count(fix->begin(), fix->end(), "x");
  b.fix_y = fix && std::count(fix->begin(), fix->end(), "y");
  b.velocity_x = velocity ? std::optional((*velocity)[0]) : vx;
  b.velocity_y = velocity ? std::optional((*velocity)[1]) : vy;
  for (const char* c : {"x", "y"}) {
    const bool fixed = *c == 'x' ? b.fix_x : b.fix_y;
    const auto& moving = *c == 'x' ? b.velocity_x : b.velocity_y;
    if (fixed && moving) {
      t.fail("fix", std::string("expected each component fixed or moving, not both; got ") + c +
                        " fixed and a velocity " + format_number(*moving) + " for " + c);
    }
  }
  return b;
}

/// A component of one curve or point may be constrained by one [[boundary]] only (fixing it
/// twice is harmless and allowed).
void check_components_once(const std::vector<TableReader>& tables,
                           const std::vector<BoundarySpec>& boundaries) {
  struct Owner {
    std::size_t entry;
    bool fixed;
  };
  std::map<std::pair<std::string, char>, Owner> owners;
  for (std::size_t i = 0; i < boundaries.size(); ++i) {
    const BoundarySpec& b = boundaries[i];
    const std::pair<bool, bool> xs{b.fix_x, b.velocity_x.has_value()};
    const std::pair<bool, bool> ys{b.fix_y, b.velocity_y.has_value()};
    for (const auto& [c, state] : {std::pair{'x', xs}, std::pair{'y', ys}}) {
      if (!state.first && !state.second) continue;
      const auto [it, inserted] = owners.emplace(std::pair{b.on, c}, Owner{i, state.first});
      if (inserted || (it->second.fixed && state.first)) continue;
      tables[i].fail_table(std::string("expected each component of \"") + b.on +
                           "\" constrained by one [[boundary]], got " + c + " also set by " +
                           tables[it->second.entry].path());
    }
  }
}

LoadSpec read_load(TableReader& t) {
  t.allow_only({"on", "body", "force", "pressure", "force_density"});
  const auto kinds = t.present({"force", "pressure", "force_density"});
  if (kinds.empty()) {
    t.fail_table("expected one of force, pressure, or body with force_density, got none");
  }
  if (kinds.size() > 1) {
    t.fail_table("expected exactly one of force, pressure, force_density, got " +
                 joined(kinds, " and "));
  }
  LoadSpec load;
  load.force = t.vec2("force");
  load.pressure = t.number("pressure", Range{});
  load.force_density = t.vec2("force_density");
  if (load.force_density) {
    load.body = t.required_string("body");
    if (t.has("on")) t.fail("on", "expected no on with force_density (it acts on a body), got one");
  } else {
    load.on = t.required_string("on");
    if (t.has("body")) {
      t.fail("body",
             "expected no body with " + kinds[0] + " (it acts on the entity `on`), got one");
    }
  }
  return load;
}

/// `line = [[x0, y0], [x1, y1]]`, two distinct points.
std::array<Vec2, 2> read_segment(const TableReader& t) {
  const toml::node& node = *t.find("line");
  const auto* ends = node.as_array();
  const auto point = [](const toml::node* n) {
    const auto* xy = n ? n->as_array() : nullptr;
    const auto finite = [](const toml::node* v) {
      return v && v->is_number() && std::isfinite(*v->value<double>());
    };
    return xy && xy->size() == 2 && finite(xy->get(0)) && finite(xy->get(1));
  };
  if (!ends || ends->size() != 2 || !point(ends->get(0)) || !point(ends->get(1))) {
    t.fail("line", "expected two points [[x0, y0], [x1, y1]], got " + describe(node));
  }
  std::array<Vec2, 2> segment;
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& xy = *ends->get(i)->as_array();
    segment[i] = {*xy.get(0)->value<double>(), *xy.get(1)->value<double>()};
  }
  if (segment[0] == segment[1])
    t.fail("line", "expected two distinct points, got " + describe(node));
  return segment;
}

/// Reads what a probe watches (its one key of at, on, body, line); returns its allowed fields.
std::vector<std::string_view> read_probe_target(const TableReader& t, const std::string& kind,
                                                ProbeSpec& probe) {
  if (kind == "at") {
    probe.kind = ProbeSpec::Kind::point;
    probe.at = *t.vec2("at");
    return {"ux", "uy", "vx", "vy"};
  }
  if (kind == "on") {
    probe.kind = ProbeSpec::Kind::curve;
    probe.on = *t.string("on");
    return {"fx", "fy", "ux", "uy"};
  }
  if (kind == "body") {
    probe.kind = ProbeSpec::Kind::body;
    probe.body = *t.string("body");
    return {"ux", "uy", "vx", "vy", "rotation", "area", "kinetic"};
  }
  probe.kind = ProbeSpec::Kind::line;
  probe.line = read_segment(t);
  // ux, uy extend the scene contract's list (docs/scene-extensions.md): displacement
  // interpolated at the sample point.
  return {"sxx", "syy", "sxy", "s1", "s2", "damage", "ux", "uy"};
}

ProbeSpec read_probe(TableReader& t) {
  t.allow_only({"name", "at", "on", "body", "line", "samples", "stress", "fields"});
  ProbeSpec probe;
  probe.name = t.required_string("name");
  check_probe_name(t, probe.name);
  const auto kinds = t.present({"at", "on", "body", "line"});
  if (kinds.empty()) t.fail_table("expected one of at, on, body, line, got none");
  if (kinds.size() > 1) {
    t.fail_table("expected exactly one of at, on, body, line, got " + joined(kinds, " and "));
  }
  const std::vector<std::string_view> allowed = read_probe_target(t, kinds[0], probe);
  if (probe.kind == ProbeSpec::Kind::line) {
    const auto samples = t.integer("samples", 2, INT_MAX);
    if (!samples) t.record_default("samples", "101");
    probe.samples = samples ? static_cast<int>(*samples) : 101;
    // "element" samples the element's constant stress (docs/scene.md); "nodal" interpolates
    // stresses averaged at the nodes, which follows steep gradients better.
    const auto sampling = t.choice("stress", {"element", "nodal"});
    if (!sampling) t.record_default("stress", "element");
    probe.nodal_stress = sampling && *sampling == "nodal";
  } else if (t.has("stress")) {
    t.fail("stress",
           "expected stress sampling only in a line probe, got one in a probe with " + kinds[0]);
  } else if (t.has("samples")) {
    t.fail("samples", "expected samples only in a line probe, got one in a probe with " + kinds[0]);
  }
  const auto fields = t.strings("fields", allowed);
  if (!fields || fields->empty()) {
    std::vector<std::string> names(allowed.begin(), allowed.end());
    t.fail("fields", "expected an array of at least one of " + joined(names, ", ") + ", got " +
                         (fields ? "an empty array" : "nothing (the key is required)"));
  }
  probe.fields = *fields;
  return probe;
}

}  // namespace

std::vector<MaterialSpec> read_materials(TableReader& root, PlaneKind plane) {
  auto tables = table_array(root, "material");
  if (tables.empty()) {
    root.fail("material",
              "expected at least one [[material]] with density, young and poisson, "
              "got none");
  }
  std::vector<MaterialSpec> materials;
  std::map<std::string, std::string> bodies;
  for (TableReader& t : tables) {
    materials.push_back(read_material(t, plane));
    check_unique(t, "body", materials.back().body, bodies, "each body's material");
  }
  return materials;
}

std::vector<InitialSpec> read_initial(TableReader& root) {
  std::vector<InitialSpec> initial;
  std::map<std::string, std::string> bodies;
  for (TableReader& t : table_array(root, "initial")) {
    initial.push_back(read_initial_entry(t));
    check_unique(t, "body", initial.back().body, bodies, "each body's initial motion");
  }
  return initial;
}

std::vector<JointSpec> read_joints(TableReader& root) {
  std::vector<JointSpec> joints;
  std::map<std::string, std::string> pairs;
  for (TableReader& t : table_array(root, "joint")) {
    joints.push_back(read_joint(t));
    std::vector<std::string> pair = joints.back().between;
    std::sort(pair.begin(), pair.end());  // ["a", "b"] and ["b", "a"] are the same joint
    check_unique(t, "between", joined(pair, "\", \""), pairs, "each joint");
  }
  return joints;
}

std::vector<BoundarySpec> read_boundaries(TableReader& root) {
  const auto tables = table_array(root, "boundary");
  std::vector<BoundarySpec> boundaries;
  for (TableReader t : tables) boundaries.push_back(read_boundary(t));
  check_components_once(tables, boundaries);
  return boundaries;
}

std::vector<LoadSpec> read_loads(TableReader& root) {
  std::vector<LoadSpec> loads;
  for (TableReader& t : table_array(root, "load")) loads.push_back(read_load(t));
  return loads;
}

std::vector<ProbeSpec> read_probes(TableReader& root) {
  std::vector<ProbeSpec> probes;
  std::map<std::string, std::string> names;
  for (TableReader& t : table_array(root, "probe")) {
    probes.push_back(read_probe(t));
    check_unique(t, "name", probes.back().name, names, "each probe name");
  }
  return probes;
}

}  // namespace rockdd
