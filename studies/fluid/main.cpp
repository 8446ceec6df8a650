// Study `fluid`: verification of the incompressible Navier-Stokes solver of Section 2.1 (eqs. 2.1-2.9,
// Appendix A) against exact solutions, for both time integrators (backward-forward Euler and Peskin's
// 2-stage scheme), and the solver claims of Section 2.1 (no table in the seed): Helmholtz PCG with
// Chebyshev preconditioning in O(10) iterations, multigrid-preconditioned Poisson PCG in O(1)
// iterations to tau = 1e-11 for dt = 1e-8 .. 1e-6 s. Steps: 1. spatial orders (dt ~ h^2 for
// backward-forward Euler, dt ~ h for Peskin) on (i) the Taylor-Green vortex, (ii) start-up Couette
// flow in the whole-blood channel, (iii) a manufactured 3D flow; 1b. Couette flow from rest (the
// seed's set-up; not checked); 2. temporal orders by successive differences; 3. divergence after
// projection over every step; 4. iteration counts on the whole-blood box with a force blob;
// 5. speed versus error (the runs of step 1).
//
// Run:  build/studies/study_fluid --scale quick|full --out DIR   (or: python3 -m harness run fluid)
#include "cases.hpp"
#include "common/study.hpp"

#include "rbfib/core/units.hpp"

#include <cmath>
#include <sstream>

using namespace rbfib;
using namespace rbfib::study;

namespace {

const char* short_name(TimeIntegrator i) { return i == TimeIntegrator::backward_forward_euler ? "BFE" : "Peskin"; }

struct Spec {
  std::string problem;
  std::vector<int> cells;                    // refinement sequence (spatial)
  std::function<ExactProblem(int)> make;
  double dt_bfe_coarse, dt_peskin_coarse;    // dt on the coarsest grid
  int temporal_cells;
  double dt_temporal_coarse;
  int temporal_levels;
};

/// 1. Spatial orders (and 5. speed versus error): each problem and integrator on its grids, error
/// against the exact solution.
Json space_orders(const Options& opt, const std::vector<Spec>& specs, double& worst_div) {
  Json space = table({"problem", "integrator", "series", "N", "h_um", "dt_s", "steps", "err_inf", "err_l2", "seconds",
                      "max_div_rel", "helmholtz_iterations", "poisson_iterations"},
                     {"", "", "", "", "um", "s", "", "", "", "s", "", "", ""});
  for (const Spec& sp : specs)
    for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
      const bool bfe = ti == TimeIntegrator::backward_forward_euler;
      for (size_t k = 0; k < sp.cells.size(); ++k) {
        const int n = sp.cells[k];
        const double r = double(n) / sp.cells[0];
        const double dt = bfe ? sp.dt_bfe_coarse / (r * r) : sp.dt_peskin_coarse / r;
        ExactProblem pb = sp.make(n);
        const ExactRun res = run_exact(pb, ti, dt);
        const int d = pb.name == "couette" ? 1 : 0;
        const double h_um = pb.grid.h(d) / units::um;
        worst_div = std::max(worst_div, res.max_div_rel);
        space["rows"].push(row({sp.problem, short_name(ti), sp.problem + "/" + short_name(ti), n, h_um, dt, res.steps,
                                res.err_inf, res.err_l2, res.seconds, res.max_div_rel, res.helmholtz_iterations,
                                res.poisson_iterations}));
        std::ostringstream m;
        m << sp.problem << " " << short_name(ti) << " N=" << n << " dt=" << dt << " steps=" << res.steps
          << " err_inf=" << res.err_inf << " err_l2=" << res.err_l2 << " div=" << res.max_div_rel
          << " its H/P=" << res.helmholtz_iterations << "/" << res.poisson_iterations << " " << res.seconds << " s";
        log(opt, m.str());
      }
    }
  return space;
}

Json couette_from_rest(const Options& opt) {
  // 1b. Couette flow started from rest (the seed's set-up): the jump of the data at the moving wall
  // at t = 0 is an initial layer; errors at t = 20 us are reported, not checked.
  Json rest = table({"integrator", "N", "h_um", "dt_s", "steps", "err_inf", "err_l2", "seconds"},
                    {"", "", "um", "s", "", "", "", "s"});
  for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage})
    for (int n : {15, 30, 60}) {
      ExactProblem pb = couette(n, 4);
      pb.t0 = 0.0;
      pb.from_rest = true;
      const double r = n / 15.0;
      const double dt = ti == TimeIntegrator::backward_forward_euler ? 1e-6 / (r * r) : 1e-6 / r;
      const ExactRun res = run_exact(pb, ti, dt);
      rest["rows"].push(row({short_name(ti), n, pb.grid.h(1) / units::um, dt, res.steps, res.err_inf, res.err_l2, res.seconds}));
      log(opt, std::string("couette from rest ") + short_name(ti) + " N=" + std::to_string(n) + " err_inf=" + std::to_string(res.err_inf));
    }
  return rest;
}

/// 2. Temporal orders by successive differences.
Json time_orders(const Options& opt, const std::vector<Spec>& specs, double& worst_div) {
  Json time = table({"problem", "integrator", "N", "dt_s", "steps", "diff_inf", "err_inf", "seconds"},
                    {"", "", "", "s", "", "", "", "s"});
  for (const Spec& sp : specs)
    for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
      ExactProblem pb = sp.make(sp.temporal_cells);
      ExactRun prev;
      double prev_dt = 0;
      for (int k = 0; k <= sp.temporal_levels; ++k) {
        const double dt = sp.dt_temporal_coarse / double(1 << k);
        ExactRun res = run_exact(pb, ti, dt);
        worst_div = std::max(worst_div, res.max_div_rel);
        if (k > 0) {
          const double diff = relative_difference(prev.u, res.u, pb.grid.dims);
          time["rows"].push(row({sp.problem, short_name(ti), sp.temporal_cells, prev_dt, prev.steps, diff, prev.err_inf,
                                 prev.seconds}));
          std::ostringstream m;
          m << sp.problem << " " << short_name(ti) << " dt=" << prev_dt << " |u_dt - u_dt/2| = " << diff;
          log(opt, m.str());
        }
        prev = std::move(res);
        prev_dt = dt;
      }
    }
  return time;
}

Json iterations(const Options& opt, Json& par, bool quick, double& worst_div, double& poisson_min, double& poisson_max) {
  // 4. iteration counts on the whole-blood box at h = 0.4 and 0.2 um (the whole-blood grid of
  // Section 5.2), and 0.1 um at full scale: O(1) and O(10) mean counts bounded independently of
  // the grid and the step.
  Json its = table({"nx", "integrator", "dt_s", "helmholtz_iterations", "poisson_iterations", "max_div_rel", "step_seconds"},
                   {"", "", "s", "", "", "", "s"});
  par["iteration_grids"] = std::string("nx x 3nx/4 x nx cells on the 16 x 12 x 16 um whole-blood box, nx = 40, 80") + (quick ? "" : ", 160") +
                           "; Couette + Gaussian force blob";
  for (const int nx : quick ? std::vector<int>{40, 80} : std::vector<int>{40, 80, 160}) {
    const int ny = 3 * nx / 4;
    ExactProblem pb = couette(ny, nx);
    pb.grid.cells = {nx, ny, nx};
    const double F0 = 1e5;  // dyn/cm^3, blob of radius 1 um at the channel centre, pointing in x
    const double sig = 1 * units::um;
    for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage})
      for (double dt : {1e-8, 1e-7, 1e-6}) {
        NavierStokesOptions o;
        o.integrator = ti;
        o.dt = dt;
        o.solvers = FluidSolvers::multigrid;  // the iteration counts of the seed's solver family
        NavierStokesSolver ns(pb.grid, pb.fluid, o, pb.boundary);
        FluidState s = ns.zero_state(0.0);
        for (int a = 0; a < 3; ++a)
          s.u[a] = sample(ns.operators().component_box(a), [&](double x, double y, double z) {
            return pb.velocity(a, 10 * units::us, x, y, z);
          });
        VectorField f;
        for (int a = 0; a < 3; ++a)
          f[a] = sample(ns.operators().component_box(a), [&](double x, double y, double z) {
            const double r2 = std::pow(x - 8 * units::um, 2) + std::pow(y - 6 * units::um, 2) + std::pow(z - 8 * units::um, 2);
            return a == 0 ? F0 * std::exp(-r2 / (sig * sig)) : 0.0;
          });
        StepStats st;
        double secs = 0;
        const int steps = quick ? 2 : 4;
        double helm = 0, pois = 0;
        int hn = 0, pn = 0;
        double umax = 0;
        for (int n = 0; n < steps; ++n) {
          const double start = median_seconds(1, [&] { st = ns.step(s, &f); });
          if (n == 0) continue;  // the first step starts from phi = 0, p = 0: report the later ones
          secs += start;
          for (int k = 0; k < st.stages; ++k) {
            for (int a = 0; a < 3; ++a) helm += st.helmholtz_iterations[k][a], ++hn;
            pois += st.poisson_iterations[k], ++pn;
          }
        }
        for (int a = 0; a < 3; ++a) umax = std::max(umax, blas::norm_inf(s.u[a]));
        const double div_rel = st.max_divergence * pb.grid.h(0) / umax;
        worst_div = std::max(worst_div, div_rel);
        its["rows"].push(row({double(nx), short_name(ti), dt, helm / hn, pois / pn, div_rel, secs / (steps - 1)}));
        poisson_min = std::min(poisson_min, pois / pn), poisson_max = std::max(poisson_max, pois / pn);
        std::ostringstream m;
        m << "iterations nx=" << nx << " " << short_name(ti) << " dt=" << dt << ": helmholtz " << helm / hn << ", poisson " << pois / pn
          << ", div " << div_rel << ", " << secs / (steps - 1) << " s/step";
        log(opt, m.str());
      }
  }
  return its;
}

}  // namespace

int main(int argc, char** argv) {
  return run_main("fluid", [&] {
    Options opt = parse_command_line(argc, argv, "fluid",
                                     "Navier-Stokes solver verification: orders in space and time, divergence, "
                                     "iteration counts (Section 2.1)");
    const bool quick = opt.scale == Scale::quick;
    Json results = make_results(opt);
    Json& par = results["parameters"];
    par["density_g_per_cm3"] = 1.0;
    par["viscosity_cP"] = 0.1;
    par["viscosity_source"] = "seed, Chapter 2 opening: plasma mu = 0.1 cP, rho = 1 g/cm^3";
    par["solver_tolerance"] = 1e-11;
    par["helmholtz_chebyshev_steps"] = HelmholtzOptions{}.chebyshev_steps;
    par["poisson_smoothing_steps"] = PoissonOptions{}.smoothing_steps;
    par["taylor_green"] = "periodic [0,16um]^2 x [0,16um], U = 1 cm/s, t = 0..4 us";
    par["couette"] = "channel 16 x 12 x 16 um, periodic x,z, walls y, top wall 12 mm/s in x, t = 10..20 us";
    par["manufactured"] = "[0,1]^3 cm, periodic x, moving no-slip walls y,z, rho = 1 g/cm^3, mu = 0.1 P, t = 0..0.04 s";
    par["quick_grids"] = "Taylor-Green n x n x 4 cells (the flow is z-independent), Couette 4 x n x 4 (x,z-independent)";

    const int tz = quick ? 4 : 0;  // Taylor-Green z cells (0: n)
    std::vector<Spec> specs = {
        {"taylor_green", quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64},
         [&](int n) { return taylor_green(n, tz ? tz : n); }, 4e-7, 8e-7, 16, 8e-7, quick ? 3 : 5},
        {"couette", quick ? std::vector<int>{15, 30, 60} : std::vector<int>{15, 30, 60, 120},
         [&](int n) { return couette(n, 4); }, 1e-6, 1e-6, 30, 2e-6, quick ? 3 : 5},
        {"manufactured", quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64},
         [&](int n) { return manufactured(n); }, 8e-3, 1e-2, 16, 2e-2, quick ? 3 : 5},
    };

    double worst_div = 0.0, poisson_min = INFINITY, poisson_max = 0;
    results["tables"]["space_orders"] = space_orders(opt, specs, worst_div);
    results["tables"]["couette_from_rest"] = couette_from_rest(opt);
    results["tables"]["time_orders"] = time_orders(opt, specs, worst_div);
    results["tables"]["iterations"] = iterations(opt, par, quick, worst_div, poisson_min, poisson_max);
    results["values"]["poisson_iterations_spread"] = poisson_max - poisson_min;  // over grids, dt and integrators
    results["values"]["max_div_rel"] = worst_div;
    write_results(opt, results);
    return 0;
  });
}

