// Stability suite (issue 13): scenes at the edges of what the engine accepts. Each case says
// which behaviour it must show: finite numbers with bounded energy, a clean dt reduction, or a
// clear error (exit 1 or 2); never NaN, a hang or a crash. docs/stability.md tabulates the
// cases with what the engine does, measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "engine/common/number_format.hpp"
#include "support/block_on_base.hpp"
#include "support/command_line.hpp"
#include "support/end_loaded_plate.hpp"
#include "support/file_text.hpp"
#include "support/rectangle_geo.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

const std::filesystem::path kSource = ROCKDD_SOURCE_DIR;

/// Seconds a command-line case may take before it counts as a hang (each returns in < 1 s).
constexpr int kHangSeconds = 30;

/// Every number of every history row, and every displacement, is finite.
void expect_finite(const test::SceneRun& run) {
  for (const auto& [column, values] : run.history)
    for (std::size_t i = 0; i < values.size(); ++i)
      ASSERT_TRUE(std::isfinite(values[i])) << column << " row " << i;
  for (std::size_t d = 0; d < run.model.u.size(); ++d)
    ASSERT_TRUE(std::isfinite(run.model.u[d])) << "u[" << d << "]";
}

/// The largest energy the run created over its history: kinetic + strain + dissipated, less
/// the external work and the kinetic energy it started with (J). <= 0 when energy is bounded
/// by what went in; DDA's numerical damping makes it negative.
double energy_gain(const test::SceneRun& run) {
  const auto& h = run.history;
  const auto& kinetic = h.at("energy.kinetic");
  double gain = -INFINITY;
  for (std::size_t i = 0; i < kinetic.size(); ++i)
    gain = std::max(gain, kinetic[i] + h.at("energy.strain")[i] + h.at("energy.dissipated")[i] -
                              h.at("energy.external_work")[i] - kinetic.front());
  return gain;
}

/// The largest |x| of a vector.
double largest(const std::vector<double>& x) {
  double m = 0.0;
  for (const double v : x) m = std::max(m, std::abs(v));
  return m;
}

// --- Geometry the kernels cannot compute with (task 1 of issue 13) ---------------------------

TEST(Stability, HugeCoordinatesAreRefusedNotMeshedForEver) {
  // Required: exit 2 naming the key, within seconds. Before the fix `rockdd check` of a
  // 1e308 m rectangle (and of a .geo square of that side) never returned: Gmsh's 1D mesher
  // recursed on NaN sizes, growing to GBs; a .msh with such nodes ran to NaN energies, exit 1.
  test::TempDir tmp;
  const auto scene = kSource / "tests/scenes/bad/rectangle_size_overflow.toml";
  const auto shape = test::rockdd_cli("check '" + scene.string() + "'", tmp.path(), kHangSeconds);
  EXPECT_EQ(shape.exit_code, 2) << shape.output;
  EXPECT_NE(shape.output.find("mesh.size"), std::string::npos) << shape.output;

  const std::string material = test::material("", 2600.0, 1e10, 0.3);
  std::ofstream(tmp.path() / "huge.geo") << test::rectangle_geo(0, 0.0, 0.0, 1e308, 1e308, 1e307)
                                         << "Physical Surface(\"plate\") = {1};\n";
  std::ofstream(tmp.path() / "geo.toml") << "[scene]\nname = \"huge\"\n[mesh]\ngeo = \"huge.geo\"\n"
                                         << material;
  const auto geo = test::rockdd_cli("check geo.toml", tmp.path(), kHangSeconds);
  EXPECT_EQ(geo.exit_code, 2) << geo.output;
  EXPECT_NE(geo.output.find("mesh.geo: expected a model with coordinates in"), std::string::npos)
      << geo.output;

  // The one-triangle mesh with its nodes scaled to 1e308 m, then to 1e-300 m (areas underflow).
  const std::string triangle = test::read_text(kSource / "tests/meshes/one_triangle.msh");
  for (const auto& [scale, phrase] :
       {std::pair<std::string, std::string>{"1e308", "expected node coordinates in"},
        {"1e-300", "expected a mesh whose extent"}}) {
    std::string scaled = triangle;
    for (const char* node : {"2 1 0 0\n", "3 0 1 0\n"}) {
      std::string moved = node;
      moved.replace(moved.find('1', 1), 1, scale);
      scaled.replace(scaled.find(node), std::string(node).size(), moved);
    }
    std::ofstream(tmp.path() / "scaled.msh") << scaled;
    std::ofstream(tmp.path() / "msh.toml")
        << "[scene]\nname = \"scaled\"\n[mesh]\nmsh = \"scaled.msh\"\n"
        << material;
    const auto msh = test::rockdd_cli("run msh.toml --out out", tmp.path(), kHangSeconds);
    EXPECT_EQ(msh.exit_code, 2) << scale << ": " << msh.output;
    EXPECT_NE(msh.output.find(phrase), std::string::npos) << scale << ": " << msh.output;
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << scale;
  }
}

TEST(Stability, SceneBeyondMemoryIsRefusedBeforeMeshing) {
  // Required: exit 2 within seconds, the message giving the estimated triangles, the bytes
  // they need and the bytes available (divisions [1e5, 1e5]: 2e10 triangles, 4e13 bytes).
  test::TempDir tmp;
  const auto scene = kSource / "tests/scenes/bad/divisions_beyond_memory.toml";
  const auto inv = test::rockdd_cli("check '" + scene.string() + "'", tmp.path(), kHangSeconds);
  EXPECT_EQ(inv.exit_code, 2) << inv.output;
  for (const char* phrase :
       {"mesh.divisions", "20000000000 triangles", "40000000000000 bytes", "bytes, MemAvailable"})
    EXPECT_NE(inv.output.find(phrase), std::string::npos) << phrase << ": " << inv.output;
}

// --- Meshes and materials at their limits ---------------------------------------------------

TEST(Stability, OneTriangleSolvesToTheClosedForm) {
  // Required: a finite solution or a clear error. Measured: it solves. Nodes (0, 0), (1, 0),
  // (0, 1), the base fixed, F down at the apex: only the apex moves, and its CST stiffness is
  // t A diag(G, E / (1 - nu^2)) (plane stress, A = 1/2), so u_y = -2 F (1 - nu^2) / (E t),
  // u_x = 0, exactly.
  const double E = 10e9, nu = 0.25, F = 1e6;
  const std::string scene = test::scene_table("one-triangle", "") + "[mesh]\nmsh = \"" +
                            (kSource / "tests/meshes/one_triangle.msh").string() + "\"\n" +
                            test::material("", 2600.0, E, nu) + test::fixed("base") +
                            "[[load]]\non = \"apex\"\nforce = [0.0, " + test::toml_number(-F) +
                            "]\n" + test::probe_on("apex", "apex", {"ux", "uy"}) +
                            test::no_frames();
  const auto run = test::run_scene_text(scene);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  ASSERT_EQ(run.model.num_elements(), 1);
  expect_finite(run);
  const double uy = -2.0 * F * (1.0 - nu * nu) / E;
  EXPECT_NEAR(run.history.at("apex.uy").back(), uy, 1e-12 * std::abs(uy));
  EXPECT_NEAR(run.history.at("apex.ux").back(), 0.0, 1e-12 * std::abs(uy));
}

TEST(Stability, ExtremeYoungModulusScalesTheCantileverDisplacement) {
  // Required: finite displacements equal to the E = 1e10 Pa result times 1e10 / E, to 1e-6
  // relative (a static linear solve: u ~ 1/E). Measured: 1.5e-13 at E = 1e3 Pa (the tip moves
  // 1,685 m: small strain, as a static analysis is), 1e-13 at E = 1e13 Pa.
  const auto reference = test::run_data_scene("cantilever_model_1.toml");
  ASSERT_TRUE(reference.result.ok) << reference.result.reason;
  const double scale = largest(reference.model.u);
  for (const double E : {1e3, 1e13}) {
    SCOPED_TRACE(E);
    const auto run =
        test::run_data_scene("cantilever_model_1.toml", {"material.0.young=" + format_number(E)});
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    expect_finite(run);
    ASSERT_EQ(run.model.u.size(), reference.model.u.size());
    for (std::size_t d = 0; d < run.model.u.size(); ++d)
      EXPECT_NEAR(run.model.u[d] * E / 1e10, reference.model.u[d], 1e-6 * scale) << d;
  }
}

TEST(Stability, NearlyIncompressiblePlaneStrainBlockMatchesTheClosedForm) {
  // Required: finite, bounded displacement. A 2 m x 1 m block in plane strain, nu = 0.4999
  // (1 - 2 nu = 2e-4: D's volumetric entries are 2,500 E), rollers on the left, pulled by
  // sigma = F / (h t) on the right. Uniaxial stress in plane strain (eps_zz = 0):
  //   u_x = (1 - nu^2) sigma x / E,   u_y = -nu (1 + nu) sigma y / E,
  // exact for CST on any mesh (patch test). Measured: every node within 1e-10 of the largest
  // displacement (PatchTest.NearlyIncompressiblePlaneStrainStaysFinite checks the stress).
  const double E = 40e9, nu = 0.4999, sigma = 2e6;
  const test::EndLoadedPlate plate{.name = "incompressible", .plane = "strain", .poisson = nu};
  const auto run = test::run_scene_text(plate.toml());
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  expect_finite(run);
  const double ux_end = (1 - nu * nu) * sigma * 2.0 / E;
  for (std::int32_t n = 0; n < run.model.num_nodes(); ++n) {
    const double x = run.model.X[2 * n], y = run.model.X[2 * n + 1];
    EXPECT_NEAR(run.model.u[2 * n], (1 - nu * nu) * sigma * x / E, 1e-8 * ux_end) << n;
    EXPECT_NEAR(run.model.u[2 * n + 1], -nu * (1 + nu) * sigma * y / E, 1e-8 * ux_end) << n;
  }
}

TEST(Stability, SliverTrianglesPassThePatchTest) {
  // Required: finite, and the exact constant-stress answer. tests/meshes/slivers_1deg.msh is a
  // 4 m x 1 m strip whose unit squares each hold a needle triangle with angles of 1, 1 and
  // 178 degrees; pulled by sigma = 1 MPa, every element carries sigma_xx = sigma and every
  // node sits at u_x = sigma x / E, u_y = -nu sigma y / E (plane stress). Measured: 1e-11.
  const double E = 40e9, nu = 0.25, sigma = 1e6;
  const std::string scene = test::scene_table("slivers", "") + "[mesh]\nmsh = \"" +
                            (kSource / "tests/meshes/slivers_1deg.msh").string() + "\"\n" +
                            test::material("", 2500.0, E, nu) + test::fixed("left", {"x"}) +
                            test::fixed("origin") +
                            "[[load]]\non = \"right\"\nforce = [1e6, 0.0]\n" + test::no_frames();
  const auto run = test::run_scene_text(scene);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  ASSERT_EQ(run.model.num_elements(), 16);
  expect_finite(run);
  for (std::int32_t e = 0; e < run.model.num_elements(); ++e) {
    EXPECT_NEAR(run.model.stress[3 * e], sigma, 1e-8 * sigma) << e;
    EXPECT_NEAR(run.model.stress[3 * e + 1], 0.0, 1e-8 * sigma) << e;
    EXPECT_NEAR(run.model.stress[3 * e + 2], 0.0, 1e-8 * sigma) << e;
  }
  for (std::int32_t n = 0; n < run.model.num_nodes(); ++n) {
    EXPECT_NEAR(run.model.u[2 * n], sigma * run.model.X[2 * n] / E, 1e-12) << n;
    EXPECT_NEAR(run.model.u[2 * n + 1], -nu * sigma * run.model.X[2 * n + 1] / E, 1e-12) << n;
  }
}

TEST(Stability, FreeFloatingBlockInAStaticSceneIsRefused) {
  // Required (docs/method-choices.md, "Static restraint"): a static scene whose block no
  // boundary holds is refused before any work, exit 2, naming the block and its free motion,
  // nothing written. Model I's cantilever with its clamp removed.
  test::TempDir tmp;
  std::string text = test::read_text(kSource / "data/cantilever_model_1.toml");
  for (const std::string cut : {"[[boundary]]\non = \"left\"\nfix = [\"x\", \"y\"]\n",
                                "[[probe]]\nname = \"support\"\non = \"left\"\n"
                                "fields = [\"fx\", \"fy\"]\n"}) {
    ASSERT_NE(text.find(cut), std::string::npos) << cut;
    text.erase(text.find(cut), cut.size());
  }
  std::ofstream(tmp.path() / "free.toml") << text;
  const auto inv = test::rockdd_cli("run free.toml --out out", tmp.path(), kHangSeconds);
  EXPECT_EQ(inv.exit_code, 2) << inv.output;
  EXPECT_NE(inv.output.find("block 0 (body 'body') is free in"), std::string::npos) << inv.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

// --- Contact -----------------------------------------------------------------------------------

/// A 1 m x 0.5 m block on a 4 m x 1 m base, meshed separately at 0.25 m, the base's top split
/// where the block stands so that "base_contact" and "block_bottom" face each other.
std::string block_on_base_geo() {
  return R"(Point(1) = {0, 0, 0, 0.25};
Point(2) = {4, 0, 0, 0.25};
Point(3) = {4, 1, 0, 0.25};
Point(4) = {1.5, 1, 0, 0.25};
Point(5) = {0.5, 1, 0, 0.25};
Point(6) = {0, 1, 0, 0.25};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
)" + test::rectangle_geo(10, 0.5, 1.0, 1.5, 1.5, 0.25) +
         R"(Physical Surface("base") = {1};
Physical Surface("block") = {11};
Physical Curve("base_bottom") = {1};
Physical Curve("base_contact") = {4};
Physical Curve("block_bottom") = {11};
Physical Curve("block_top") = {13};
)";
}

/// The block resting on the base under gravity, joint friction 20 deg, with probes of the
/// facing edges, the block's top and the block; the [time] and materials are the caller's.
std::string block_on_base(const std::string& analysis, const std::string& time,
                          const std::string& materials) {
  return test::BlockOnBaseScene{.analysis = analysis,
                                .time = time,
                                .materials = materials,
                                .friction_angle = 20.0,
                                .more = test::probe_on("base", "base_contact", {"uy"}) +
                                        test::probe_on("bottom", "block_bottom", {"uy"}) +
                                        test::probe_on("top", "block_top", {"uy"}) +
                                        test::probe_body("block", "block", {"uy", "vy"})}
      .toml();
}

const std::string kRock = test::material("*", 2600.0, 10e9, 0.25);

/// Materials of base and block: the block's young modulus `block_E`, the base's `base_E`.
std::string two_materials(double base_E, double block_E) {
  return test::material("base", 2600.0, base_E, 0.25) +
         test::material("block", 2600.0, block_E, 0.25);
}

test::SceneRun run_block_on_base(const std::string& scene,
                                 const std::vector<std::string>& overrides = {}) {
  return test::run_scene_text(scene, overrides, 2, {{"block_on_base.geo", block_on_base_geo()}});
}

TEST(Stability, ContactPenaltyFrom1e2To1e5TimesEShrinksTheOverlap) {
  // Required: finite, the overlap of block and base decreasing as the penalty grows, the
  // settlement converging. Quasi-static, three steps. Measured: overlap 8.5e-10, 8.5e-11,
  // 8.5e-12, 8.5e-13 m at kn = 1e2, 1e3, 1e4, 1e5 x E (exactly 1/kn); the block's top
  // settles 2.36e-6 m whatever kn, within 4e-4.
  const std::string scene = block_on_base("quasi-static", "dt = 1e-3\nsteps = 3", kRock);
  std::vector<double> overlap, top;
  for (const double factor : {1e2, 1e3, 1e4, 1e5}) {
    SCOPED_TRACE(factor);
    const auto run =
        run_block_on_base(scene, {"joint.0.normal_stiffness=" + format_number(factor * 10e9)});
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    expect_finite(run);
    EXPECT_LE(energy_gain(run), 1e-9);
    overlap.push_back(run.history.at("base.uy").back() - run.history.at("bottom.uy").back());
    top.push_back(run.history.at("top.uy").back());
  }
  for (std::size_t i = 0; i < overlap.size(); ++i) {
    EXPECT_GT(overlap[i], 0.0) << i;
    if (i == 0) continue;
    EXPECT_GT(overlap[i - 1] / overlap[i], 5.0) << i;
    EXPECT_LT(overlap[i - 1] / overlap[i], 20.0) << i;
    EXPECT_NEAR(top[i], top[0], 1e-3 * std::abs(top[0])) << i;
  }
  EXPECT_LT(top[0], -1e-6);  // it did settle
}

TEST(Stability, StiffnessContrast1e6BetweenTouchingBlocks) {
  // Required: finite, bounded energy, the soft block's own answer. A block of E = 1e7 Pa on a
  // base of 1e13 Pa (kn = 20 E_max = 2e14 N/m, 2e7 x the block's E): the block shortens under
  // its weight by rho g H^2 / (2 E) = 3.25e-4 m (a free column); its compression times E must
  // be that of a block of 1e10 Pa on the same base (contrast 1e3) to 1e-3, and the closed form
  // within 5 % (measured -3.4 %: friction at the base holds its Poisson spread; -1e-4 between
  // the two contrasts). Quasi-static with dt = 1 s, so that the mass term 2M/dt^2 is small
  // against the soft block's stiffness and three steps settle it. The reverse, a block of
  // 1e16 Pa on a base of 1e10 Pa, must stay finite with bounded energy.
  const double rho = 2600.0, g = 10.0, H = 0.5;
  auto compression_times_E = [&](double base_E, double block_E) {
    const auto run = run_block_on_base(
        block_on_base("quasi-static", "dt = 1.0\nsteps = 3", two_materials(base_E, block_E)));
    EXPECT_TRUE(run.result.ok) << run.result.reason;
    expect_finite(run);
    EXPECT_LE(energy_gain(run), 1e-9 * run.history.at("energy.external_work").back());
    return (run.history.at("bottom.uy").back() - run.history.at("top.uy").back()) * block_E;
  };
  const double soft = compression_times_E(1e13, 1e7);
  const double moderate = compression_times_E(1e13, 1e10);
  EXPECT_NEAR(soft, moderate, 1e-3 * moderate);
  EXPECT_NEAR(soft, rho * g * H * H / 2.0, 0.05 * rho * g * H * H / 2.0);
  EXPECT_GT(compression_times_E(1e10, 1e16), 0.0);
}

TEST(Stability, BlockRestingForManyStepsDoesNotCreep) {
  // Required: no creep (displacement drift bounded) and no energy gain. Dynamic, DDA, dt = 1 ms.
  // The issue asks for 1e5 steps: measured 14 s on 2 cores (top drift 2.3e-16 m over the last
  // 5e4 steps, energy created at most 2e-23 J), too slow for this suite: cut to 2e4 steps
  // (about 3 s). After the first 1,000 steps (the drop of gravity settles under DDA's
  // damping) the top must not move by more than 1e-12 m.
  const auto run = run_block_on_base(block_on_base("dynamic", "dt = 1e-3\nsteps = 20000", kRock));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  expect_finite(run);
  EXPECT_LE(energy_gain(run), 1e-9);
  const auto& top = run.history.at("top.uy");
  ASSERT_EQ(top.size(), 20001u);
  const auto [lo, hi] = std::minmax_element(top.begin() + 1000, top.end());
  EXPECT_LT(*hi - *lo, 1e-12);
  EXPECT_LT(top.back(), -1e-6);  // resting on the base, not floating
  EXPECT_GT(top.back(), -1e-5);  // nor sinking through it
}

TEST(Stability, BlockRestingWithNewmarkDoesNotGainEnergy) {
  // Required: no energy gain. Newmark (average acceleration, no numerical damping) with the
  // penalty contact of kn = 20 E t: the contact period (about 1.6e-4 s) is below dt = 1 ms.
  // With Newmark's trapezoid on the contact forces the energy grew (3.5 J created by
  // t = 0.2 s, 50 kJ by t = 100 s, when the block had been thrown off its base), and then the
  // energy check held it only by cutting dt until the spring was resolved: 23,276 steps to
  // t = 0.3 s (1,169 redone), 166,815 to 2 s, still creating 0.30 J to 0.3 s. The contact
  // forces are now energy-consistent (kernels/contact_energy, docs/method-choices.md "Newmark
  // and contacts"): to t = 0.3 s, 1,628 steps (15 redone by the energy check, 65 by the
  // open-close iteration), kinetic + strain energy at most 5.8e-5 J over the work; the block
  // stays on its base. Bound: under 5,000 steps, so that dt is not cut back to where the spring
  // is resolved.
  const auto run = run_block_on_base(
      block_on_base("dynamic", "dt = 1e-3\nsteps = 300\nintegrator = \"newmark\"", kRock));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  expect_finite(run);
  EXPECT_LE(energy_gain(run), 1e-3);
  EXPECT_LT(run.result.summary["steps"].get<long>(), 5000);
  EXPECT_LT(run.history.at("top.uy").back(), -1e-6);  // resting on the base, not thrown off
  EXPECT_GT(run.history.at("top.uy").back(), -1e-5);  // nor sinking through it
}

// --- Time stepping and impact ------------------------------------------------------------------

TEST(Stability, Dt1000TimesTheDefaultIsReducedCleanly) {
  // Required: a clean dt reduction, then the right answer. The paper's sliding block with
  // dt = 1 s instead of its 1 ms: steps that the open-close iteration cannot settle are redone
  // with dt / 2. Measured: 32 steps, 6 redone, dt halved from 1 s down to 1/64 s and grown
  // back by 1.5 x after 10 good steps; block II at the analytic
  // u_x = g cos(th) sin(th) t^2 / 2 = 4.8714 m within 3e-6 (the 1 ms run: 6e-6).
  const auto run = test::run_data_scene("sliding_block.toml", {"time.dt=1.0", "output.every=0"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  expect_finite(run);
  EXPECT_GT(run.result.summary["redone_steps"].get<long>(), 0);
  const auto& dt = run.history.at("dt");
  EXPECT_LT(*std::min_element(dt.begin() + 1, dt.end()), 0.1);
  EXPECT_LE(energy_gain(run), 1e-6 * run.history.at("energy.external_work").back());
  const double theta = std::numbers::pi / 6.0, t = 1.5, g = 10.0;
  const double ux = 0.5 * g * std::cos(theta) * std::sin(theta) * t * t;
  EXPECT_NEAR(run.history.at("time").back(), t, 1e-9);
  EXPECT_NEAR(run.history.at("block2.ux").back(), ux, 1e-4 * ux);
}

TEST(Stability, ImpactAt100MetresPerSecondStaysBounded) {
  // Required: finite, bounded energy. The block hits the base at 100 m/s (10 cm per 1 ms
  // step, a fifth of its height); DDA, 50 steps. Measured: it bounces back at 68 m/s; of the
  // 6.5 MJ it brought, 3.0 MJ are left (DDA's damping takes the rest), none created.
  const auto run = run_block_on_base(block_on_base("dynamic", "dt = 1e-3\nend = 0.05", kRock) +
                                     "[[initial]]\nbody = \"block\"\nvelocity = [0.0, -100.0]\n");
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  expect_finite(run);
  const double kinetic0 = run.history.at("energy.kinetic").front();
  EXPECT_NEAR(kinetic0, 0.5 * 2600.0 * 0.5 * 100.0 * 100.0, 1e-6 * kinetic0);
  EXPECT_LE(energy_gain(run), 1e-9 * kinetic0);
  const double rebound = run.history.at("block.vy").back();
  EXPECT_GT(rebound, 0.0);    // it bounced
  EXPECT_LT(rebound, 100.0);  // no faster than it came
}

TEST(Stability, ImpactAt100MetresPerSecondWithNewmarkStaysBounded) {
  // Required: finite, bounded energy, and a rebound no faster than the impact. With Newmark's
  // trapezoid on the contact forces (and no energy check) the block left at 122 m/s and the
  // energy grew from 6.5 MJ to 13.9 MJ in the first step it spent in contact; the energy check
  // then cut those steps until it left at 64 m/s. With energy-consistent contact forces it
  // leaves at 56 m/s, kinetic 4.45 MJ and strain 1.89 MJ (the block rings, undamped): 317
  // steps (14 redone by the energy check, 4 by the open-close iteration), kinetic + strain
  // never above the 6.5 MJ it brought, no step creating more than 0.1 % of it.
  const auto run = run_block_on_base(
      block_on_base("dynamic", "dt = 1e-3\nend = 0.05\nintegrator = \"newmark\"", kRock) +
      "[[initial]]\nbody = \"block\"\nvelocity = [0.0, -100.0]\n");
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  expect_finite(run);
  const double kinetic0 = run.history.at("energy.kinetic").front();
  EXPECT_LE(energy_gain(run), 1e-9 * kinetic0);
  const double rebound = run.history.at("block.vy").back();
  EXPECT_GT(rebound, 0.0);    // it bounced
  EXPECT_LE(rebound, 100.0);  // no faster than it came
  EXPECT_LE(run.result.summary["energy_check"]["largest_step_created_share"].get<double>(),
            1e-3 * (1 + 1e-9));
}

// --- Damage --------------------------------------------------------------------------------

/// Model I's beam (tension damage, ft = 2 MPa, E = 10 GPa) held on the left, in one static step;
/// the loading of its right end is the caller's.
const std::string kBeamToBreak =
    test::scene_table("all-damaged", "") + "[time]\ndt = 1.0\nsteps = 1\n" +
    test::rectangle_mesh(0.04, 0.01, {8, 2}) +
    test::material("", 2600.0, 10e9, 0.25, "tensile_strength = 2e6\n") +
    test::fixed("left", {"x"}) + test::fixed("bottom_left") +
    test::probe_on("right", "right", {"fx", "ux"}) + test::no_frames();

TEST(Stability, EveryElementFullyDamagedInOneStep) {
  // Required: finite numbers, no energy created, and every element at w = 1 (or a clear
  // error). Model I's beam pulled in one static step to 100 x its tensile onset strain
  // (eps = 0.02 > eta eps_t0 = 1e-3), by the displacement of its right end, then by a force of
  // 100 x its tensile strength. Measured: every element damages fully in one pass and
  // detaches (32 blocks); under the imposed displacement the right end carries 3 N (the
  // stiffness floor 1e-6 E0); under the force the stiffness floor lets it stretch 800 m
  // (small strain, as a static analysis is), finite. The step is cut at the first onset and
  // the cascade runs in a step of its own; under the force, the next step would pull the 32
  // blocks 800 m apart through each other's contact reach, so the run ends there and says why.
  for (const std::string loading : {"[[boundary]]\non = \"right\"\nvelocity_x = 8e-4\n",
                                    "[[load]]\non = \"right\"\nforce = [2e6, 0.0]\n"}) {
    SCOPED_TRACE(loading);
    const auto run = test::run_scene_text(kBeamToBreak + loading);
    const bool force = loading.find("force") != std::string::npos;
    if (force && !run.result.ok)
      EXPECT_NE(run.result.reason.find("exceeds the contact search distance"), std::string::npos)
          << run.result.reason;
    else
      ASSERT_TRUE(run.result.ok) << run.result.reason;
    expect_finite(run);
    for (std::int32_t e = 0; e < run.model.num_elements(); ++e)
      EXPECT_EQ(run.model.damage[e], 1.0) << e;
    EXPECT_EQ(run.result.summary["blocks"].get<int>(), 32);
    // A static step's balance is strain against work (its kinetic column is the mean
    // velocity du/dt squared, 2e-8 J here, not energy the step holds).
    const auto& h = run.history;
    EXPECT_LE(h.at("energy.strain").back(), (1 + 1e-9) * h.at("energy.external_work").back());
  }
}

TEST(Stability, EveryElementFullyDamagedInOneStepBalancesItsEnergy) {
  // Required: bounded energy, strain + dissipated = work to round-off in a static step (the
  // balance is exact before fracture, docs/method-choices.md "Energy balance"). Measured, the
  // imposed displacement: work 800 J, dissipated 800 J. The damage pass releases
  // 1/2 (w - w') E0 eps : eps at the trial strain eps = 0.02, where the undamaged beam stood
  // while its end moved; the step's work is counted at the first solve's reactions (the
  // cascade after it runs at a fixed end). Counted on the forces after damage, as it once
  // was, the work was 8e-4 J against 800 J dissipated.
  const auto run =
      test::run_scene_text(kBeamToBreak + "[[boundary]]\non = \"right\"\nvelocity_x = 8e-4\n");
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& h = run.history;
  EXPECT_NEAR(h.at("energy.strain").back() + h.at("energy.dissipated").back(),
              h.at("energy.external_work").back(), 1e-6 * h.at("energy.external_work").back());
}

}  // namespace
}  // namespace rockdd
