#include "engine/assembly/internal_force.hpp"
#include "engine/assembly/for_each_element_by_color.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "engine/assembly/element_state.hpp"
#include "kernels/corotated_cst_batch.hpp"
#include "kernels/corotation.hpp"

namespace rockdd {

namespace {

/// One element's strain and stress (global frame) and nodal force f at displacement u.
inline void element_internal_force(const Model& model, std::int32_t e, std::span<const double> u,
                                   kernels::PlaneKind plane, bool corotational, double* eps,
                                   double* sig, double f[6]) {
  double xy[6], x[6], ue[6], d[9];
  gather_element(model.conn, e, model.X, xy);
  gather_element(model.conn, e, u, ue);
  for (int k = 0; k < 6; ++k) x[k] = xy[k] + ue[k];
  // Co-rotational: strain and stress in the element's own frame, forces turned back.
  const kernels::Rotation turn =
      corotational ? kernels::element_rotation_factor(xy, x) : kernels::Rotation{};
  if (corotational) kernels::corotated_displacement(xy, x, turn, ue);
  kernels::elasticity_matrix(kernels::damaged_modulus(model.young[e], model.damage[e]),
                             model.poisson[e], plane, d);
  kernels::cst_strain(xy, ue, eps);
  kernels::cst_stress(d, eps, sig);
  kernels::cst_internal_force(xy, sig, model.thickness, f);
  if (corotational) {
    kernels::rotate_nodal(turn, f);
    // Reported in the global frame: sigma = R sigma' R^T, likewise the strain.
    kernels::rotate_tensor(turn, sig);
    eps[2] *= 0.5;
    kernels::rotate_tensor(turn, eps);
    eps[2] *= 2.0;
  }
}

inline void add_element_force(const Model& model, std::int32_t e, const double f[6],
                              std::span<double> f_int) {
  for (int k = 0; k < 3; ++k) {
    const std::int32_t n = model.conn[3 * e + k];
    f_int[2 * n] += f[2 * k];
    f_int[2 * n + 1] += f[2 * k + 1];
  }
}

/// Element e's reference corners and its corners at displacement u, into `lane` of `batch`.
inline void load_corners(const Model& model, std::int32_t e, std::span<const double> u,
                         kernels::CstBatch& batch, int lane) {
  double xy[6], ue[6];
  gather_element(model.conn, e, model.X, xy);
  gather_element(model.conn, e, u, ue);
  for (int k = 0; k < 6; ++k) {
    batch.xy0[k][lane] = xy[k];
    batch.x[k][lane] = xy[k] + ue[k];
  }
}

/// The co-rotated forces of the elements of `chunks`, kernels::kCstBatch at a time: bitwise what
/// element_internal_force gives each (tests/test_corotation), in fewer instructions
/// (docs/performance.md). The forces are summed into f_int element by element in the chunks'
/// order, as one element at a time would.
void corotated_chunk_forces(const Model& model, const ElementColoring& coloring,
                            std::span<const std::int32_t> chunks, std::span<const double> u,
                            kernels::PlaneKind plane, std::span<double> strain,
                            std::span<double> stress, std::span<double> element_force,
                            std::span<double> f_int) {
  kernels::CstBatch batch;
  std::int32_t lane_element[kernels::kCstBatch];
  int count = 0;
  const auto flush = [&] {
    kernels::corotated_cst_forces(batch, count, plane, model.thickness);
    for (int i = 0; i < count; ++i) {
      const std::int32_t e = lane_element[i];
      const auto at = static_cast<std::size_t>(e);
      double f[6];
      for (int k = 0; k < 6; ++k) f[k] = batch.force[k][i];
      for (int k = 0; k < 3; ++k) {
        strain[3 * at + k] = batch.strain[k][i];
        stress[3 * at + k] = batch.stress[k][i];
      }
      if (!element_force.empty()) std::copy(f, f + 6, &element_force[6 * at]);
      add_element_force(model, e, f, f_int);
    }
    count = 0;
  };
  for (const std::int32_t chunk : chunks) {
    const std::int32_t end = coloring.chunk_end(chunk);
    for (std::int32_t e = coloring.chunk_begin(chunk); e < end; ++e) {
      load_corners(model, e, u, batch, count);
      batch.young[count] = kernels::damaged_modulus(model.young[e], model.damage[e]);
      batch.poisson[count] = model.poisson[e];
      lane_element[count] = e;
      if (++count == kernels::kCstBatch) flush();
    }
  }
  if (count > 0) flush();
}

}  // namespace

void compute_internal_force(const Model& model, const ElementColoring& coloring,
                            std::span<const double> u, std::span<double> strain,
                            std::span<double> stress, std::span<double> f_int, bool corotational,
                            std::span<double> element_force) {
  const kernels::PlaneKind plane = model.plane;
  std::fill(f_int.begin(), f_int.end(), 0.0);
  // Chunks of one colour share no node, so each node sums its elements in the colouring's order
  // whatever the threads do (sum_element_forces relies on that order).
  if (!corotational) {
    for_each_element_by_color(coloring, [&](std::int32_t e) {
      const auto at = static_cast<std::size_t>(e);
      double f[6];
      element_internal_force(model, e, u, plane, false, &strain[3 * at], &stress[3 * at], f);
      if (!element_force.empty()) std::copy(f, f + 6, &element_force[6 * at]);
      add_element_force(model, e, f, f_int);
    });
    return;
  }
  for_each_chunk_run_by_color(coloring, [&](std::span<const std::int32_t> chunks) {
    corotated_chunk_forces(model, coloring, chunks, u, plane, strain, stress, element_force, f_int);
  });
}

void refresh_element_forces(const Model& model, std::span<const double> u,
                            std::span<const std::int32_t> elements, std::span<double> element_force,
                            bool corotational, std::span<double> strain, std::span<double> stress) {
  const kernels::PlaneKind plane = model.plane;
  const bool keep_state = !strain.empty() && !stress.empty();
  for (const std::int32_t e : elements) {
    const auto at = static_cast<std::size_t>(e);
    double eps[3], sig[3];
    element_internal_force(model, e, u, plane, corotational, eps, sig, &element_force[6 * at]);
    if (keep_state)
      for (int k = 0; k < 3; ++k) {
        strain[3 * at + k] = eps[k];
        stress[3 * at + k] = sig[k];
      }
  }
}

void elements_moved_between(const Model& model, std::span<const double> u_from,
                            std::span<const double> u, std::vector<std::uint8_t>& node_moved,
                            std::vector<std::int32_t>& elements) {
  const auto num_nodes = static_cast<std::size_t>(model.num_nodes());
  node_moved.assign(num_nodes, 0);
  for (std::size_t n = 0; n < num_nodes; ++n)
    node_moved[n] = u[2 * n] != u_from[2 * n] || u[2 * n + 1] != u_from[2 * n + 1] ? 1 : 0;
  elements.clear();
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const std::int32_t* node = &model.conn[3 * static_cast<std::size_t>(e)];
    if (node_moved[node[0]] | node_moved[node[1]] | node_moved[node[2]]) elements.push_back(e);
  }
}

void sum_element_forces(const Model& model, const ElementColoring& coloring,
                        std::span<const double> element_force, std::span<double> f_int) {
  std::fill(f_int.begin(), f_int.end(), 0.0);
  for_each_element_by_color(coloring, [&](std::int32_t e) {
    add_element_force(model, e, &element_force[6 * static_cast<std::size_t>(e)], f_int);
  });
}

bool frames_turned_past(const Model& model, std::span<const double> u, double tolerance) {
  const bool framed = !model.rotation.empty();
  if (framed && (model.rotation_cos.size() != model.rotation.size() ||
                 model.rotation_sin.size() != model.rotation.size()))
    throw std::logic_error("frames_turned_past: Model::rotation set without its cos and sin");
  return tbb::parallel_reduce(
      tbb::blocked_range<std::int32_t>(0, model.num_elements(), 4096), false,
      [&](auto range, bool turned) {
        if (turned) return true;
        kernels::CstBatch batch;
        double frame_cos[kernels::kCstBatch], frame_sin[kernels::kCstBatch];
        bool within[kernels::kCstBatch];
        for (std::int32_t first = range.begin(); first < range.end(); first += kernels::kCstBatch) {
          const int count = std::min(kernels::kCstBatch, range.end() - first);
          for (int i = 0; i < count; ++i) {
            const std::int32_t e = first + i;
            load_corners(model, e, u, batch, i);
            frame_cos[i] = framed ? model.rotation_cos[e] : 1.0;
            frame_sin[i] = framed ? model.rotation_sin[e] : 0.0;
          }
          for (int i = count; i < kernels::kCstBatch; ++i) frame_cos[i] = 1.0, frame_sin[i] = 0.0;
          // Nearly every element has turned far less than the tolerance, which a test without
          // trigonometry shows; the exact angle decides for the others.
          kernels::turned_within(batch, count, frame_cos, frame_sin, tolerance, within);
          for (int i = 0; i < count; ++i) {
            if (within[i]) continue;
            const std::int32_t e = first + i;
            double xy[6], x[6];
            for (int k = 0; k < 6; ++k) {
              xy[k] = batch.xy0[k][i];
              x[k] = batch.x[k][i];
            }
            const double angle = framed ? model.rotation[e] : 0.0;
            // The difference of two angles, wrapped to (-pi, pi].
            const double change =
                std::remainder(kernels::element_rotation(xy, x) - angle, 2.0 * std::numbers::pi);
            if (std::abs(change) > tolerance) return true;
          }
        }
        return false;
      },
      [](bool a, bool b) { return a || b; });
}

namespace {

double current_rotation(const Model& model, std::span<const double> u, std::int32_t e) {
  double xy[6], x[6];
  gather_element(model.conn, e, model.X, xy);
  gather_element(model.conn, e, u, x);
  for (int k = 0; k < 6; ++k) x[k] += xy[k];
  return kernels::element_rotation(xy, x);
}

}  // namespace

void update_element_rotations(Model& model, std::span<const double> u) {
  const auto n = static_cast<std::size_t>(model.num_elements());
  model.rotation.resize(n);
  model.rotation_cos.resize(n);
  model.rotation_sin.resize(n);
  tbb::parallel_for(std::int32_t{0}, model.num_elements(), [&](std::int32_t e) {
    set_element_rotation(model, e, current_rotation(model, u, e));
  });
}

void update_element_rotations(Model& model, std::span<const double> u,
                              std::span<const std::int32_t> elements) {
  const auto n = static_cast<std::size_t>(model.num_elements());
  model.rotation.resize(n, 0.0);
  model.rotation_cos.resize(n, 1.0);
  model.rotation_sin.resize(n, 0.0);
  for (const std::int32_t e : elements)
    set_element_rotation(model, e, current_rotation(model, u, e));
}

double strain_energy(const Model& model, std::span<const double> strain,
                     std::span<const double> stress) {
  // Summed serially in element order: the value must not depend on the thread count.
  double energy = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const double* eps = &strain[3 * static_cast<std::size_t>(e)];
    const double* sig = &stress[3 * static_cast<std::size_t>(e)];
    energy += 0.5 * (sig[0] * eps[0] + sig[1] * eps[1] + sig[2] * eps[2]) * model.area0[e];
  }
  return energy * model.thickness;
}

}  // namespace rockdd
