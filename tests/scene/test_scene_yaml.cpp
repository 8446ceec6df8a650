// Scenes both ways: to_yaml writes a scene that parse_scene reads back to an equal scene (every
// field, to the bit), for every example scene and for a scene filled in C++; the text is a fixed
// point of write-read-write.
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace rbfib::scene {
namespace {

void expect_same_sites(const surface::SphereSites& a, const surface::SphereSites& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (index_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.lambda[i], b.lambda[i]) << what << " site " << i;
    ASSERT_EQ(a.theta[i], b.theta[i]) << what << " site " << i;
  }
}

/// Every field a scene carries, compared exactly (doubles bit for bit).
void expect_equal(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(a.grid.length[d], b.grid.length[d]);
    EXPECT_EQ(a.grid.cells[d], b.grid.cells[d]);
    EXPECT_EQ(a.grid.periodic(d), b.grid.periodic(d));
    for (int side = 0; side < 2; ++side) {
      const WallMotion &p = a.walls[d][side], &q = b.walls[d][side];
      EXPECT_EQ(p.velocity, q.velocity);
      EXPECT_EQ(p.turning, q.turning);
      EXPECT_EQ(p.speed, q.speed);
      EXPECT_EQ(p.from, q.from);
      EXPECT_EQ(p.to, q.to);
      EXPECT_EQ(p.over, q.over);
      EXPECT_EQ(p.axis, q.axis);
    }
  }
  EXPECT_EQ(a.initial_shear, b.initial_shear);
  EXPECT_EQ(a.fluid.density, b.fluid.density);
  EXPECT_EQ(a.fluid.viscosity, b.fluid.viscosity);
  EXPECT_EQ(a.fluid_options.integrator, b.fluid_options.integrator);
  EXPECT_EQ(a.fluid_options.dt, b.fluid_options.dt);
  EXPECT_EQ(a.t_end, b.t_end);
  EXPECT_EQ(a.ib.coupling, b.ib.coupling);
  EXPECT_EQ(a.ib.kernel, b.ib.kernel);
  EXPECT_EQ(a.ib.body_force, b.ib.body_force);
  EXPECT_EQ(a.ib.adaptive.enabled, b.ib.adaptive.enabled);
  EXPECT_EQ(a.ib.adaptive.dt_min, b.ib.adaptive.dt_min);
  EXPECT_EQ(a.ib.adaptive.max_level, b.ib.adaptive.max_level);
  EXPECT_EQ(a.ib.adaptive.grow_after, b.ib.adaptive.grow_after);
  ASSERT_EQ(a.types.size(), b.types.size());
  for (std::size_t t = 0; t < a.types.size(); ++t) {
    const CellTypeEntry &p = a.types[t], &q = b.types[t];
    EXPECT_EQ(p.spec.name, q.spec.name);
    EXPECT_EQ(p.preset, q.preset);
    EXPECT_EQ(p.radius, q.radius);
    EXPECT_EQ(p.degree, q.degree);
    expect_same_sites(p.spec.data_sites, q.spec.data_sites, p.spec.name + " data sites");
    expect_same_sites(p.spec.sample_sites, q.spec.sample_sites, p.spec.name + " sample sites");
    const cells::ForceModel &m = p.spec.model, &n = q.spec.model;
    ASSERT_EQ(m.elastic.size(), n.elastic.size());
    for (std::size_t e = 0; e < m.elastic.size(); ++e) {
      EXPECT_EQ(m.elastic[e].kind, n.elastic[e].kind);
      EXPECT_EQ(m.elastic[e].a, n.elastic[e].a);
      EXPECT_EQ(m.elastic[e].b, n.elastic[e].b);
    }
    EXPECT_EQ(m.kappa, n.kappa);
    EXPECT_EQ(m.H0, n.H0);
    EXPECT_EQ(m.H0_reference, n.H0_reference);
    EXPECT_EQ(m.nu, n.nu);
  }
  ASSERT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t c = 0; c < a.cells.size(); ++c) {
    EXPECT_EQ(a.cells[c].type, b.cells[c].type);
    EXPECT_EQ(a.cells[c].placement.center, b.cells[c].placement.center);
    EXPECT_EQ(a.cells[c].placement.axis, b.cells[c].placement.axis);
    EXPECT_EQ(a.cells[c].placement.angle, b.cells[c].placement.angle);
    EXPECT_EQ(a.cells[c].placement.stretch, b.cells[c].placement.stretch);
    EXPECT_EQ(a.cells[c].force, b.cells[c].force);
  }
  ASSERT_EQ(a.point_sets.size(), b.point_sets.size());
  for (std::size_t k = 0; k < a.point_sets.size(); ++k) {
    EXPECT_EQ(a.point_sets[k].name, b.point_sets[k].name);
    EXPECT_EQ(a.point_sets[k].k, b.point_sets[k].k);
    EXPECT_EQ(a.point_sets[k].eta, b.point_sets[k].eta);
    EXPECT_EQ(point_positions(a.point_sets[k].surface, a.grid.length), point_positions(b.point_sets[k].surface, b.grid.length));
  }
  EXPECT_EQ(a.diagnostics_every, b.diagnostics_every);
  EXPECT_EQ(a.checkpoint_every, b.checkpoint_every);
  EXPECT_EQ(a.snapshot_every, b.snapshot_every);
}

TEST(SceneYaml, EveryExampleSceneReadsBackEqual) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(RBFIB_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const Scene original = load_scene(entry.path().string());
    const std::string text = to_yaml(original);
    const Scene again = parse_scene(text, "again");
    expect_equal(original, again);
    EXPECT_EQ(to_yaml(again), text);  // a fixed point
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(SceneYaml, ASceneFilledInCodeReadsBackEqual) {
  using namespace units;
  Scene s;
  s.name = "a scene: filled in code";  // needs quoting
  s.grid.length = {16 * um, 12 * um, 16 * um};
  s.grid.cells = {40, 30, 40};
  s.grid.dims = 3;
  for (int d = 0; d < 3; ++d) s.grid.lower[d] = s.grid.upper[d] = d == 1 ? MacBoundary::dirichlet : MacBoundary::periodic;
  s.walls[1][1].turning = true;
  s.walls[1][1].speed = 1.6;
  s.walls[1][1].to = 0.7853981633974483;
  s.walls[1][1].over = 7.2e-3;
  s.walls[1][0].velocity = {0.1, 0, -0.3};
  s.fluid.density = 1;
  s.fluid.viscosity = 0.01;
  s.fluid_options.integrator = TimeIntegrator::peskin_two_stage;
  s.fluid_options.dt = 0.2 * us;
  s.t_end = 1 * ms / 3;
  s.ib.coupling = sim::Coupling::midpoint;
  s.ib.adaptive.enabled = true;
  s.ib.adaptive.dt_min = 50 * ns;
  s.ib.adaptive.max_level = 4;
  s.ib.body_force = {1.0 / 3, 0, 2};
  s.types.push_back(cell_type("red cell", "red_cell", 400, 1600));
  s.types.push_back(cell_type("sphere", "skalak_sphere", 0, 0, 2 * um / 3));
  s.types.back().spec.model.elastic.push_back(mechanics::EnergyDensity::surface_tension(1e-3 / 7));
  s.types.back().spec.model.H0_reference = true;
  CellEntry c;
  c.type = "red cell";
  c.placement.center = {8 * um / 3, 6 * um, 4 * um};
  c.placement.axis = {0.3, -0.4, 0.5};
  c.placement.angle = 1.1;
  c.placement.stretch = {1, 1 / 1.1, 1.1};
  c.force = {1e-9 / 3, 0, 0};
  s.cells.push_back(c);
  c.type = "sphere";
  c.placement = {};
  c.placement.center = {8 * um, 8 * um, 12 * um};
  c.force = {};
  s.cells.push_back(c);
  s.point_sets.push_back({"endothelium", {true, 1, 0.75 * um, {0, 0}, 1000, 1 * um}, 2.5e-3, 2.5e-7});
  s.point_sets.push_back({"plane", {false, 1, 11 * um, {8, 6}, 0, 0}, 1e-3, 0});
  s.diagnostics_every = 7;
  s.snapshot_every = 10 * us;
  const Scene back = checked(s, "two lines\nof comment");
  expect_equal(s, back);
  EXPECT_EQ(back.source.rfind("# two lines\n# of comment\nname: \"a scene: filled in code\"\n", 0), 0u) << back.source;
  EXPECT_EQ(to_yaml(back), to_yaml(s));
}

TEST(SceneYaml, AnUnknownPresetIsNamed) {
  EXPECT_THROW(
      {
        try {
          cell_type("x", "blood_cell");
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("blood_cell"), std::string::npos);
          throw;
        }
      },
      InputError);
}

}  // namespace
}  // namespace rbfib::scene
