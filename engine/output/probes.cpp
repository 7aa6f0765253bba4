#include "engine/output/probes.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "engine/common/atomic_file.hpp"
#include "engine/common/errors.hpp"
#include "engine/common/number_format.hpp"
#include "engine/loading/named_nodes.hpp"
#include "kernels/cst.hpp"
#include "kernels/principal.hpp"

namespace rockdd {
namespace {

/// nanoflann adaptor over element centroids.
struct CentroidCloud {
  std::vector<double> xy;
  std::size_t kdtree_get_point_count() const { return xy.size() / 2; }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return xy[2 * i + dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using CentroidTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CentroidCloud>,
                                        CentroidCloud, 2, std::size_t>;

/// Barycentric coordinates of (x, y) in element e of the reference mesh.
void barycentric(const Model& model, std::int32_t e, double x, double y, double w[3]) {
  double xy[6];
  for (int k = 0; k < 3; ++k) {
    xy[2 * k] = model.X[2 * model.conn[3 * e + k]];
    xy[2 * k + 1] = model.X[2 * model.conn[3 * e + k] + 1];
  }
  const double area = kernels::cst_signed_area(xy);
  for (int k = 0; k < 3; ++k) {
    double sub[6] = {xy[0], xy[1], xy[2], xy[3], xy[4], xy[5]};
    sub[2 * k] = x;
    sub[2 * k + 1] = y;
    w[k] = kernels::cst_signed_area(sub) / area;
  }
}

std::vector<LineSample> locate_line_samples(const Model& model, const ProbeSpec& spec) {
  CentroidCloud cloud;
  cloud.xy.resize(2 * static_cast<std::size_t>(model.num_elements()));
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    for (int d = 0; d < 2; ++d)
      cloud.xy[2 * e + d] =
          (model.X[2 * model.conn[3 * e] + d] + model.X[2 * model.conn[3 * e + 1] + d] +
           model.X[2 * model.conn[3 * e + 2] + d]) /
          3.0;
  CentroidTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();

  const auto& [p0, p1] = spec.line;
  const double length = std::hypot(p1[0] - p0[0], p1[1] - p0[1]);
  std::vector<LineSample> samples;
  const std::size_t k = std::min<std::size_t>(32, cloud.kdtree_get_point_count());
  std::vector<std::size_t> index(k);
  std::vector<double> dist(k);
  for (int i = 0; i < spec.samples; ++i) {
    const double f = static_cast<double>(i) / (spec.samples - 1);
    LineSample s;
    s.s = f * length;
    s.x = p0[0] + f * (p1[0] - p0[0]);
    s.y = p0[1] + f * (p1[1] - p0[1]);
    const double q[2] = {s.x, s.y};
    const std::size_t found = tree.knnSearch(q, k, index.data(), dist.data());
    for (std::size_t j = 0; j < found && s.element < 0; ++j) {
      const auto e = static_cast<std::int32_t>(index[j]);
      double w[3];
      barycentric(model, e, s.x, s.y, w);
      if (std::min({w[0], w[1], w[2]}) >= -1e-9) {
        s.element = e;
        std::copy(w, w + 3, s.bary);
      }
    }
    if (s.element >= 0) samples.push_back(s);  // points outside the mesh are left out
  }
  return samples;
}

/// Stress at each node: the area-weighted mean of the stresses of the elements around it.
/// Nodes are split between blocks, so the mean never mixes stresses across a crack.
std::vector<double> nodal_stress(const Model& model) {
  std::vector<double> stress(3 * static_cast<std::size_t>(model.num_nodes()), 0.0);
  std::vector<double> weight(static_cast<std::size_t>(model.num_nodes()), 0.0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = model.conn[3 * e + k];
      weight[n] += model.area0[e];
      for (int c = 0; c < 3; ++c) stress[3 * n + c] += model.area0[e] * model.stress[3 * e + c];
    }
  for (std::int32_t n = 0; n < model.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) stress[3 * n + c] /= weight[n];
  return stress;
}

}  // namespace

Probes::Probes(const Scene& scene, const Model& model) {
  const std::string file = scene.file.string();
  for (std::size_t i = 0; i < scene.probes.size(); ++i) {
    const ProbeSpec& spec = scene.probes[i];
    const std::string key = "probe[" + std::to_string(i) + "]";
    Resolved r{&spec, {}, {}, false, {}, 0.0, -1};
    switch (spec.kind) {
      case ProbeSpec::Kind::point: {
        std::int32_t best = 0;
        double best_d = INFINITY;
        for (std::int32_t n = 0; n < model.num_nodes(); ++n) {
          const double d = std::hypot(model.X[2 * n] - spec.at[0], model.X[2 * n + 1] - spec.at[1]);
          if (d < best_d) {
            best_d = d;
            best = n;
          }
        }
        r.nodes = {best};
        break;
      }
      case ProbeSpec::Kind::curve:
        r.nodes = nodes_named(model, spec.on, file, key + ".on");
        break;
      case ProbeSpec::Kind::body: {
        const std::int32_t body = body_named(model, spec.body, file, key + ".body");
        r.body = body;
        std::vector<std::uint8_t> in(static_cast<std::size_t>(model.num_nodes()), 0);
        for (std::int32_t e = 0; e < model.num_elements(); ++e)
          if (body < 0 || model.element_body[e] == body)
            for (int k = 0; k < 3; ++k) in[model.conn[3 * e + k]] = 1;
        for (std::int32_t n = 0; n < model.num_nodes(); ++n)
          if (in[n]) r.nodes.push_back(n);
        double cx = 0, cy = 0, m = 0;
        for (const std::int32_t n : r.nodes) {
          cx += model.node_mass[n] * model.X[2 * n];
          cy += model.node_mass[n] * model.X[2 * n + 1];
          m += model.node_mass[n];
        }
        cx /= m;
        cy /= m;
        for (const std::int32_t n : r.nodes) {
          r.ref_centered.push_back(model.X[2 * n] - cx);
          r.ref_centered.push_back(model.X[2 * n + 1] - cy);
        }
        break;
      }
      case ProbeSpec::Kind::line:
        break;
    }
    if (spec.kind != ProbeSpec::Kind::line)
      for (const auto& field : spec.fields) columns_.push_back(spec.name + "." + field);
    probes_.push_back(std::move(r));
  }
}

void Probes::carry_state_from(const Probes& old) {
  for (std::size_t i = 0; i < probes_.size() && i < old.probes_.size(); ++i) {
    probes_[i].rotation = old.probes_[i].rotation;
    if (old.probes_[i].located) {
      probes_[i].samples = old.probes_[i].samples;  // elements do not change when nodes split
      probes_[i].located = true;
    }
  }
}

bool Probes::has_line_probes() const {
  return std::any_of(probes_.begin(), probes_.end(),
                     [](const Resolved& r) { return r.spec->kind == ProbeSpec::Kind::line; });
}

void Probes::evaluate(const Model& model, std::span<const double> reaction,
                      std::vector<double>& row) {
  for (Resolved& r : probes_) {
    const ProbeSpec& spec = *r.spec;
    if (spec.kind == ProbeSpec::Kind::line) continue;
    // Means (mass-weighted for bodies) of displacement and velocity, sums of reactions.
    double w_sum = 0, ux = 0, uy = 0, vx = 0, vy = 0, fx = 0, fy = 0;
    for (const std::int32_t n : r.nodes) {
      const double w = spec.kind == ProbeSpec::Kind::body ? model.node_mass[n] : 1.0;
      w_sum += w;
      ux += w * model.u[2 * n];
      uy += w * model.u[2 * n + 1];
      vx += w * model.v[2 * n];
      vy += w * model.v[2 * n + 1];
      fx += reaction[2 * n];
      fy += reaction[2 * n + 1];
    }
    ux /= w_sum;
    uy /= w_sum;
    vx /= w_sum;
    vy /= w_sum;
    double rotation = 0, area = 0, kinetic = 0;
    if (spec.kind == ProbeSpec::Kind::body) {
      // Best-fit rigid rotation of the body (2D Procrustes), unwrapped against the last value.
      double dot = 0, cross = 0;
      for (std::size_t i = 0; i < r.nodes.size(); ++i) {
        const std::int32_t n = r.nodes[i];
        const double m = model.node_mass[n];
        const double px = r.ref_centered[2 * i], py = r.ref_centered[2 * i + 1];
        const double qx = px + model.u[2 * n] - ux, qy = py + model.u[2 * n + 1] - uy;
        dot += m * (px * qx + py * qy);
        cross += m * (px * qy - py * qx);
        kinetic +=
            0.5 * m * (model.v[2 * n] * model.v[2 * n] + model.v[2 * n + 1] * model.v[2 * n + 1]);
      }
      const double angle = std::atan2(cross, dot);
      const double two_pi = 2.0 * std::numbers::pi;
      r.rotation += std::remainder(angle - r.rotation, two_pi);
      rotation = r.rotation;
      const std::int32_t body = r.body;
      for (std::int32_t e = 0; e < model.num_elements(); ++e) {
        if (body >= 0 && model.element_body[e] != body) continue;
        double xy[6];
        for (int k = 0; k < 3; ++k)
          for (int d = 0; d < 2; ++d) {
            const std::int32_t n = model.conn[3 * e + k];
            xy[2 * k + d] = model.X[2 * n + d] + model.u[2 * n + d];
          }
        area += kernels::cst_signed_area(xy);
      }
    }
    for (const auto& field : spec.fields) {
      double value = 0.0;
      if (field == "ux")
        value = ux;
      else if (field == "uy")
        value = uy;
      else if (field == "vx")
        value = vx;
      else if (field == "vy")
        value = vy;
      else if (field == "fx")
        value = fx;
      else if (field == "fy")
        value = fy;
      else if (field == "rotation")
        value = rotation;
      else if (field == "area")
        value = area;
      else if (field == "kinetic")
        value = kinetic;
      row.push_back(value);
    }
  }
}

void Probes::write_profiles(const Model& model, const std::filesystem::path& dir, long step) {
  std::vector<double> at_nodes;
  for (Resolved& r : probes_) {
    const ProbeSpec& spec = *r.spec;
    if (spec.kind != ProbeSpec::Kind::line) continue;
    if (!r.located) {
      r.samples = locate_line_samples(model, spec);
      r.located = true;
    }
    if (spec.nodal_stress && at_nodes.empty()) at_nodes = nodal_stress(model);
    std::ostringstream out;
    out << "s,x,y";
    for (const auto& field : spec.fields) out << ',' << field;
    out << '\n';
    for (const LineSample& s : r.samples) {
      out << format_number(s.s) << ',' << format_number(s.x) << ',' << format_number(s.y);
      double sig[3] = {0.0, 0.0, 0.0};
      for (int c = 0; c < 3; ++c) {
        if (!spec.nodal_stress) {
          sig[c] = model.stress[3 * static_cast<std::size_t>(s.element) + c];
          continue;
        }
        for (int k = 0; k < 3; ++k)
          sig[c] += s.bary[k] * at_nodes[3 * model.conn[3 * s.element + k] + c];
      }
      double s1 = 0, s2 = 0;
      kernels::principal_values(sig[0], sig[1], sig[2], s1, s2);
      for (const auto& field : spec.fields) {
        double value = 0.0;
        if (field == "sxx")
          value = sig[0];
        else if (field == "syy")
          value = sig[1];
        else if (field == "sxy")
          value = sig[2];
        else if (field == "s1")
          value = s1;
        else if (field == "s2")
          value = s2;
        else if (field == "damage")
          value = model.damage[s.element];
        else if (field == "ux" || field == "uy") {
          const int d = field == "ux" ? 0 : 1;
          for (int k = 0; k < 3; ++k)
            value += s.bary[k] * model.u[2 * model.conn[3 * s.element + k] + d];
        }
        out << ',' << format_number(value);
      }
      out << '\n';
    }
    char name[32];
    std::snprintf(name, sizeof name, "_%06ld.csv", step);
    write_file_atomically(dir / (spec.name + name), out.str());
  }
}

}  // namespace rockdd
