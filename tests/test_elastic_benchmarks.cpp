// The paper's elastic benchmarks, run from the scenes in data/.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"
#include "support/csv_columns.hpp"
#include "support/data_file.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

struct Outputs {
  std::filesystem::path dir;
  RunResult result;
};

Outputs run_data_scene(const std::string& file, const test::TempDir& tmp) {
  const Scene scene = load_scene(test::data_file(file));
  Simulation sim(scene, build_scene_model(scene));
  RunOptions options;
  options.out_root = tmp.path();
  Outputs out{tmp.path() / scene.name, sim.run(options)};
  return out;
}

// Timoshenko beam theory for a cantilever with an end load P:
//   v(L) = P L^3 / (3 E I) + P L / (kappa G A),  I = t h^3 / 12, A = t h, kappa = 5/6,
//   G = E / (2 (1 + nu)) (plane stress).
double timoshenko_tip_deflection() {
  const double P = 1e4, L = 0.04, h = 0.01, t = 1.0, E = 10e9, nu = 0.3;
  const double I = t * h * h * h / 12.0, A = t * h, G = E / (2.0 * (1.0 + nu));
  return P * L * L * L / (3.0 * E * I) + P * L / (5.0 / 6.0 * G * A);
}

TEST(Cantilever, ModelsOneToFourConvergeMonotonicallyToTimoshenko) {
  const double exact = timoshenko_tip_deflection();  // 2.6848e-4 m
  double previous_error = INFINITY;
  for (int model = 1; model <= 4; ++model) {
    test::TempDir tmp;
    const Outputs out = run_data_scene("cantilever_model_" + std::to_string(model) + ".toml", tmp);
    ASSERT_TRUE(out.result.ok) << out.result.reason;
    const auto history = test::read_csv(out.dir / "history.csv");
    const double tip = -history.at("tip.uy").back();
    const double error = std::abs(tip - exact) / exact;
    // A displacement FE model is too stiff: the deflection approaches the theory from below.
    EXPECT_LT(tip, exact * 1.02) << "model " << model;
    EXPECT_LT(error, previous_error) << "model " << model << " error " << error;
    previous_error = error;
    // The clamped edge carries the whole load: reaction = -(applied) = +10 kN upwards.
    EXPECT_NEAR(history.at("support.fy").back(), 1e4, 1e-6 * 1e4);
    if (model == 4) {
      EXPECT_LT(error, 0.02) << "tip " << tip << " theory " << exact;
    }
  }
}

// Huang et al. (2015), paper eqs. (15)-(16): stresses along the loaded diameter of a
// flattened Brazilian disk (radius R, flats of half-angle a, thickness t, load P).
void huang_stresses(double y, double P, double R, double a, double t, double& sx, double& sy) {
  const double c = R * std::cos(a), s = R * std::sin(a);
  const double A1 = (c + y) * (c + y) + s * s, A2 = (c - y) * (c - y) + s * s;
  const double B1 = (c + y) * s, B2 = (c - y) * s;
  const double C1 = -std::atan(s / (c + y)), C2 = -std::atan(s / (c - y));
  const double k = P / (std::numbers::pi * R * t);
  sx = k / std::sin(a) * (B1 / A1 + C1 + B2 / A2 + C2) + k * std::cos(a);
  sy = -k / std::sin(a) * (B1 / A1 - C1 + B2 / A2 - C2) + k * std::cos(a);
}

TEST(BrazilianDisk, ElasticStressesAlongTheDiameterMatchHuang2015) {
  test::TempDir tmp;
  const Outputs out = run_data_scene("brazilian_disk_elastic.toml", tmp);
  ASSERT_TRUE(out.result.ok) << out.result.reason;
  const int elements = out.result.summary["elements"];
  EXPECT_GT(elements, 16000);
  EXPECT_LT(elements, 20000);
  const double R = 0.025, a = 10.0 * std::numbers::pi / 180.0, t = 1.0;
  const double P = 19.2478e6 * 2.0 * R * std::sin(a) * t;  // the scene's flat pressure x width
  const double scale = P / (std::numbers::pi * t * R);
  std::filesystem::path profile;
  for (const auto& f : std::filesystem::directory_iterator(out.dir / "profiles"))
    profile = f.path();
  const auto p = test::read_csv(profile);
  // Huang's eqs. (15)-(16) are an approximation: integrated over the loaded diameter their
  // sigma_x leaves a net horizontal force of -1.76 % of P (it should be 0 by statics), and a
  // 4x finer mesh (74k elements) converges to within 2 % (sigma_x) but to 4.5 % (sigma_y at
  // 0.8 R) of them. So: sigma_x within 3 % of P/(pi t R) over the central 80 % of the
  // diameter; sigma_y, whose gap to the formula is 2.4 % at the centre and grows towards the
  // flats, within 4 % over the central 60 % and 7 % over the central 80 %.
  int compared = 0;
  double worst_x = 0, worst_y_60 = 0, worst_y_80 = 0;
  const auto& ys = p.at("y");
  for (std::size_t i = 0; i < ys.size(); ++i) {
    const double y = ys[i];
    if (std::abs(y) > 0.8 * R) continue;
    double sx = 0, sy = 0;
    huang_stresses(y, P, R, a, t, sx, sy);
    worst_x = std::max(worst_x, std::abs(p.at("sxx")[i] - sx) / scale);
    worst_y_80 = std::max(worst_y_80, std::abs(p.at("syy")[i] - sy) / scale);
    if (std::abs(y) <= 0.6 * R)
      worst_y_60 = std::max(worst_y_60, std::abs(p.at("syy")[i] - sy) / scale);
    ++compared;
  }
  EXPECT_GE(compared, 75);
  EXPECT_LT(worst_x, 0.03);
  EXPECT_LT(worst_y_60, 0.04);
  EXPECT_LT(worst_y_80, 0.07);
  // At the centre eqs. (15)-(16) give sx = (3 cos a - 2a / sin a) P/(pi t R) ~ 0.944 (tension).
  double sx0 = 0, sy0 = 0;
  huang_stresses(0.0, P, R, a, t, sx0, sy0);
  EXPECT_NEAR(sx0 / scale, 3 * std::cos(a) - 2 * a / std::sin(a), 1e-12);
}

}  // namespace
}  // namespace rockdd
