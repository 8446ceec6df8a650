#include "whole_blood_step.hpp"

#include "common/force_call.hpp"
#include "common/machine.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/units.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::cells_study {

namespace {
const double um = units::um;

std::vector<double> volumes(const cells::Batch& b) {
  cells::CellForces f;
  cells::compute_forces(b, f);
  return f.cells.volume;
}
}  // namespace

StepSplit time_steps(sim::ImmersedBoundary& ib, int steps) {
  std::vector<std::vector<double>> v0;
  for (index_t b = 0; b < ib.batches(); ++b) v0.push_back(volumes(ib.batch(b)));
  ib.step();
  std::vector<double> t[4];
  for (int n = 0; n < steps; ++n) {
    const sim::IbStepReport r = ib.step();
    const double phase[4] = {r.seconds_interpolation, r.seconds_forces, r.seconds_spreading, r.seconds_fluid};
    for (int q = 0; q < 4; ++q) t[q].push_back(phase[q]);
  }
  StepSplit s{study::median(t[0]), study::median(t[1]), study::median(t[2]), study::median(t[3]), 0};
  for (index_t b = 0; b < ib.batches(); ++b) {
    const std::vector<double> v = volumes(ib.batch(b));
    for (std::size_t c = 0; c < v.size(); ++c) s.volume_change = std::max(s.volume_change, std::abs(v[c] / v0[b][c] - 1));
  }
  return s;
}

void whole_blood_parameters(Json& P, index_t rbc_nd, index_t rbc_ns) {
  P["whole_blood_box_um"] = "16 x 12 x 16 (x, z periodic; walls in y, the top one at 12 mm/s: shear 1000/s)";
  P["whole_blood_grid"] = "80 x 60 x 80, h = 0.2 um";
  P["whole_blood_red_cells"] = "8 at " + to_text(rbc_nd) + " / " + to_text(rbc_ns) + " sites (Skalak, bending, dissipation)";
  P["whole_blood_platelets"] = "2 at 900 / 900 sites (neo-Hookean, bending about the reference curvature)";
  P["whole_blood_endothelium"] = "16,000 tethered points (128 x 125 lattice) at y = 1 um, k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm";
  P["whole_blood_dt_ns"] = 50;
  P["whole_blood_fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; at 0.1 cP its endothelium is unstable at 50 ns)";
}

scene::Scene whole_blood_scene(index_t rbc_nd, index_t rbc_ns) {
  scene::Scene sc;
  sc.name = "whole_blood_step";
  sc.grid = make_mac_grid(3, {80, 60, 80}, {16 * um, 12 * um, 16 * um}, {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  sc.walls[1][1].velocity = {0, 0, 12 * units::mm};
  sc.initial_shear = true;
  sc.fluid = {1, 1 * units::cP};  // g/cm^3, P
  sc.fluid_options.integrator = TimeIntegrator::backward_forward_euler;
  sc.fluid_options.dt = 50 * units::ns;
  sc.t_end = 1 * units::ms;
  sc.ib.kernel = ib::Kernel::bspline3;
  sc.types.push_back(scene::cell_type("red cell", "red_cell", rbc_nd, rbc_ns));
  sc.types.push_back(scene::cell_type("platelet", "platelet", 900, 900));
  for (int c = 0; c < 8; ++c) sc.cells.push_back({"red cell", {{(4 + 8 * (c / 4)) * um, 6 * um, (2 + 4 * (c % 4) + 2 * (c / 4)) * um}}});
  for (int c = 0; c < 2; ++c) sc.cells.push_back({"platelet", {{8 * um, 1.8 * um, (4 + 8 * c) * um}, {1, 0, 0}, 90 * (pi / 180)}});
  sc.point_sets.push_back({"endothelium", {false, 1, 1 * um, {128, 125}}, 2.5, 2.5e-7});
  return sc;
}

double whole_blood_step(const study::Options& opt, Json& results, sim::ImmersedBoundary& ib, int steps, index_t dgemm_n, int repeats,
                        double ceiling) {
  Json& V = results["values"];
  const StepSplit s = time_steps(ib, steps);
  const double step = s.total();
  V["whole_blood_step_seconds"] = step;
  V["whole_blood_interp_spread_share"] = (s.interpolation + s.spreading) / step;
  V["whole_blood_volume_change_rel"] = s.volume_change;
  Json wb = study::table({"component", "seconds", "share"}, {"", "s", ""});
  const std::pair<const char*, double> parts[4] = {
      {"interpolation", s.interpolation}, {"forces", s.forces}, {"spreading", s.spreading}, {"fluid", s.fluid}};
  for (const auto& [name, sec] : parts) wb["rows"].push(study::row({name, sec, sec / step}));
  const double ceiling_now = study::dgemm_rate(dgemm_n, repeats);
  V["dgemm_gflops_before_whole_blood"] = ceiling_now / 1e9;
  const double best = std::max(ceiling, ceiling_now);
  double flops = 0, product_seconds = 0;
  Json fc = study::table({"type", "cells", "seconds", "products_seconds", "product_fraction_of_dgemm"}, {"", "", "s", "s", ""});
  for (index_t b = 0; b < ib.batches(); ++b) {
    double total = 0;
    const cells::ForceTimings t = study::median_force_timings(ib.batch(b), repeats, total);
    const cells::ProductFlops pf = cells::product_flops(ib.batch(b).type().spec(), ib.batch(b).size());
    flops += pf.total();
    product_seconds += t.products();
    fc["rows"].push(study::row({ib.batch(b).type().name(), double(ib.batch(b).size()), total, t.products(), pf.total() / t.products() / best}));
  }
  V["whole_blood_product_fraction_of_dgemm"] = flops / product_seconds / best;
  results["tables"]["whole_blood_step"] = wb;
  results["tables"]["whole_blood_force_calls"] = fc;
  study::log(opt, "2. whole-blood-size " + s.describe() + "; products at " + to_text(flops / product_seconds / best) + " of DGEMM");
  return s.volume_change;
}

}  // namespace rbfib::cells_study
