// Reproduces seed Sec. 4.2.2.1, Tables 4.3 and 4.4: a Skalak sphere, stretched by 1.1 in z and
// compressed by 1.1 in y, relaxes in a 16 um triply periodic box at rest; successive grids
// h = 1, 0.5, 0.25 um (0.125 at full scale) with n_d = 625 data sites and n_s = 220 x 4^k sample
// sites, dt = 1.6, 0.4, 0.1 (0.025) us, to t = 16 us. Errors between successive grids:
//   velocity: u_h - (cubic spline of u_{h/2} evaluated at the points of grid h), per component;
//   positions: X_h - X_{h/2} at the 625 data sites (the same sites on every grid).
// The coupled step is sim::ImmersedBoundary (the seed's coupling (a)-(g)), backward-forward Euler,
// the B3 kernel; the fluid is plasma, rho = 1 g/cm^3, mu = 0.1 cP.
//
// Run:   build/studies/study_chapter4_elastic --scale quick --out runs/chapter4_elastic
#include "common/study.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/grid/periodic_spline.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <chrono>
#include <fstream>
#include <cmath>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;

namespace {

struct Run {
  double h_um = 0, dt_us = 0;
  index_t n_sample = 0;
  std::array<host_vector<double>, 3> u;  // final velocity (cm/s)
  std::vector<double> X;                 // final data-site positions (cm)
  double volume0 = 0, volume = 0, seconds = 0, seconds_per_step = 0;
  int steps = 0;
};

/// The coupling and fluid scheme of a run: the seed's (a)-(g) with backward-forward Euler unless
/// stated (the temporal orders compare the others).
struct Scheme {
  sim::Coupling coupling = sim::Coupling::seed;
  TimeIntegrator integrator = TimeIntegrator::backward_forward_euler;
  std::string name() const {
    return std::string(coupling == sim::Coupling::seed ? "seed (a)-(g)" : "midpoint") + " + " +
           (integrator == TimeIntegrator::backward_forward_euler ? "backward-forward Euler" : "Peskin two-stage");
  }
};

/// A run's setup as a scene (scene/, docs/scenes.md), kept beside the results, where `rbfib run` reruns it.
scene::Scene relaxation_scene(int cells_per_axis, double dt, index_t n_sample, double radius, double t_end, Scheme scheme) {
  scene::Scene sc;
  sc.grid.length = {16 * units::um, 16 * units::um, 16 * units::um};  // periodic on every axis
  sc.grid.cells = {cells_per_axis, cells_per_axis, cells_per_axis};
  sc.fluid = {1, 0.1 * units::cP};  // g/cm^3, P
  sc.fluid_options.integrator = scheme.integrator;
  sc.fluid_options.dt = dt;
  sc.t_end = t_end;
  sc.ib.coupling = scheme.coupling;
  sc.ib.kernel = ib::Kernel::bspline3;
  sc.types.push_back(scene::cell_type("sphere", "skalak_sphere", 625, n_sample, radius));
  const double c = 8 * units::um;
  sc.cells.push_back({"sphere", {{c, c, c}, {0, 0, 1}, 0, {1, 1 / 1.1, 1.1}}});
  return sc;
}

Run relax(int cells_per_axis, double dt, index_t n_sample, double radius, double t_end, const st::Options& opt,
          Scheme scheme = {}) {
  const std::string tag = to_text(cells_per_axis) + "_dt" + to_text(std::lround(dt / units::ns)) + "ns_" +
                          (scheme.coupling == sim::Coupling::midpoint ? "midpoint" : "seed") +
                          (scheme.integrator == TimeIntegrator::peskin_two_stage ? "_peskin" : "_bfe");
  scene::Scene sc = relaxation_scene(cells_per_axis, dt, n_sample, radius, t_end, scheme);
  sc.name = "chapter4_elastic_n" + tag;
  sc = scene::checked(sc, "chapter4_elastic: a stretched Skalak sphere relaxing (Sec. 4.2.2.1)");
  std::ofstream(opt.out_dir + "/scene_n" + tag + ".yaml") << sc.source;
  sim::ImmersedBoundary ib = scene::build(sc);
  const MacGrid& g = ib.fluid().grid();
  Run r;
  r.h_um = g.h(0) / units::um;
  r.dt_us = dt / units::us;
  r.n_sample = n_sample;
  cells::CellGeometry f;
  cells::measure(ib.batch(0), f);
  r.volume0 = f.cells.volume[0];
  r.steps = int(std::lround(t_end / dt));
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < r.steps; ++n) ib.step();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.seconds_per_step = r.seconds / r.steps;
  cells::measure(ib.batch(0), f);
  r.volume = f.cells.volume[0];
  for (int a = 0; a < 3; ++a) r.u[a] = ib.fluid_state().u[a];
  r.X = ib.batch(0).positions_host();
  st::log(opt, scheme.name() + ", h = " + to_text(r.h_um) + " um, dt = " + to_text(r.dt_us) + " us, n_s = " + to_text(n_sample) + ": " +
                   to_text(r.steps) + " steps in " + to_text(r.seconds) + " s, volume change " +
                   to_text((r.volume - r.volume0) / r.volume0));
  return r;
}

/// Root-mean-square and largest |X_a - X_b| over the data sites (um).
std::pair<double, double> position_difference(const Run& a, const Run& b) {
  double x2 = 0, xinf = 0;
  for (std::size_t i = 0; i < a.X.size(); ++i) {
    const double e = (a.X[i] - b.X[i]) / units::um;
    x2 += e * e;
    xinf = std::max(xinf, std::abs(e));
  }
  return {std::sqrt(x2 / double(a.X.size())), xinf};
}

double volume_change(const Run& r) { return (r.volume - r.volume0) / r.volume0; }

/// Tables 4.3 and 4.4: errors between successive grids, velocity (the fine grid's spline at the
/// coarse grid's points) and positions; and each run's volume change.
void grid_errors(Json& results, const std::vector<Run>& runs, const std::vector<int>& grids) {
  Json tu = st::table({"h_um", "dt_us", "u_err_2", "u_err_inf", "seconds"}, {"um", "us", "cm/s", "cm/s", "s"});
  Json tx = st::table({"h_um", "n_sample", "X_err_2", "X_err_inf", "seconds"}, {"um", "", "um", "um", "s"});
  Json tv = st::table({"h_um", "volume_change_rel", "seconds_per_step"}, {"um", "", "s"});
  for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
    const Run &c = runs[k], &f = runs[k + 1];
    const double hc = c.h_um * units::um;
    double s2 = 0, sinf = 0;
    for (int a = 0; a < 3; ++a) {
      const std::vector<double> fc =
          restrict_mac_component(std::vector<double>(f.u[a].begin(), f.u[a].end()), grids[k + 1], f.h_um * units::um, a);
      for (std::size_t i = 0; i < fc.size(); ++i) {
        const double e = c.u[a][i] - fc[i];
        s2 += e * e * hc * hc * hc;
        sinf = std::max(sinf, std::abs(e));
      }
    }
    const auto [x2, xinf] = position_difference(c, f);
    tu["rows"].push(st::row({c.h_um, c.dt_us, std::sqrt(s2 / std::pow(16 * units::um, 3)), sinf, c.seconds}));
    tx["rows"].push(st::row({c.h_um, double(c.n_sample), x2, xinf, c.seconds}));
  }
  for (const Run& r : runs) tv["rows"].push(st::row({r.h_um, volume_change(r), r.seconds_per_step}));
  results["tables"]["table43_velocity"] = tu;
  results["tables"]["table44_positions"] = tx;
  results["tables"]["volume"] = tv;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter4_elastic", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter4_elastic",
                                                   "Sec. 4.2.2.1, Tables 4.3-4.4: a stretched Skalak sphere relaxing, successive grids");
    const bool full = opt.scale == st::Scale::full;

    // ---- 1. Parameters -----------------------------------------------------------------------
    // The seed does not state the sphere's radius: n_s = 220 sample sites about h / 1.1 apart at
    // h = 1 um give an area of 220 (1/1.1)^2 um^2, R = 3.80 um.
    const double radius = std::sqrt(220.0 / (1.1 * 1.1) / (4 * 3.14159265358979323846)) * units::um;
    const double t_end = 16 * units::us;
    std::vector<int> grids = {16, 32, 64};
    if (full) grids.push_back(128);
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 16 x 16, triply periodic, fluid at rest";
    P["radius_um"] = radius / units::um;
    P["radius_source"] = "not stated in the seed: from n_s = 220 sites about h/1.1 apart at h = 1 um";
    P["moduli"] = "Skalak E = 2.5e-3 dyn/cm, G = 2.5e-1 dyn/cm (Sec. 2.2)";
    P["initial_deformation"] = "stretch 1.1 in z, compress 1.1 in y";
    P["t_end_us"] = t_end / units::us;
    P["fluid"] = "rho = 1 g/cm^3, mu = 0.1 cP";
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";
    P["data_sites"] = 625;

    // ---- 2. One run per grid -----------------------------------------------------------------
    std::vector<Run> runs;
    for (std::size_t k = 0; k < grids.size(); ++k) {
      const double dt = 1.6 * units::us / std::pow(4.0, double(k));
      runs.push_back(relax(grids[k], dt, index_t(220) << (2 * k), radius, t_end, opt));
    }

    // ---- 3. Errors between successive grids (Tables 4.3, 4.4) --------------------------------
    grid_errors(results, runs, grids);
    double worst_volume = 0;
    for (const Run& r : runs) worst_volume = std::max(worst_volume, std::abs(volume_change(r)));

    // ---- 4. Temporal order of each coupling (Sec. 2.4) on the h = 1 um grid ---------------------
    // The data sites after 16 us for dt = 1.6 ... 0.1 us; differences between dt and dt/2.
    Json tt = st::table({"scheme", "dt_us", "X_err_2", "X_err_inf", "seconds"}, {"", "us", "um", "um", "s"});
    const Scheme schemes[3] = {{sim::Coupling::seed, TimeIntegrator::backward_forward_euler},
                               {sim::Coupling::seed, TimeIntegrator::peskin_two_stage},
                               {sim::Coupling::midpoint, TimeIntegrator::peskin_two_stage}};
    for (const Scheme& sc : schemes) {
      std::vector<Run> byt;
      for (double dt : {1.6, 0.8, 0.4, 0.2, 0.1}) {
        byt.push_back(relax(grids[0], dt * units::us, 220, radius, t_end, opt, sc));
        worst_volume = std::max(worst_volume, std::abs(volume_change(byt.back())));
      }
      for (std::size_t k = 0; k + 1 < byt.size(); ++k) {
        const auto [x2, xinf] = position_difference(byt[k], byt[k + 1]);
        tt["rows"].push(st::row({sc.name(), byt[k].dt_us, x2, xinf, byt[k].seconds}));
      }
    }
    results["tables"]["temporal_orders"] = tt;
    results["values"]["max_volume_change_rel"] = worst_volume;
    st::write_results(opt, results);
    return 0;
  });
}
