// Study `bench_fluid`: speed of the Navier-Stokes solver of Section 2.1 (no table in the seed; its
// claim is that the Poisson solve takes about 60% of the wall clock time). Reports, per grid and
// integrator, the median time per step and per component (advection, Helmholtz solves, Poisson
// solve, projection), and the achieved memory bandwidth of the matrix-free Helmholtz/Laplacian
// apply against a STREAM-like triad measured in the same run, on the same backend.
//
// Run:  build/studies/study_bench_fluid --scale quick|full --out DIR
//
// Steps:
//  1. Triad a = b + s c on 2^24 doubles per array (384 MiB, beyond any cache): bytes moved 3 x 8 n.
//  2. Laplacian apply out = alpha I~ u + beta L u on a velocity-component box of each grid and of
//     128^3 and 256^3 (the last out of every cache, as the triad): bytes moved at least 2 x 8 n (read u,
//     write out); achieved bandwidth and its fraction of the triad.
//  3. Steps of the full solver on each grid (quick: 32^3, 64^3; full: 32^3, 64^3, 128^3 and the
//     whole-blood grid 80 x 60 x 80 with h = 0.2 um), both integrators, dt = 50 ns (Section 5.2):
//     one warm-up step, then the median over repeats of each component's time.
#include "common/machine.hpp"
#include "common/study.hpp"
#include "poisson_peers.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/fluid/navier_stokes.hpp"
#include "rbfib/linalg/blas.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

using namespace rbfib;
using namespace rbfib::study;

namespace {

struct GridSpec {
  std::string name;
  MacGrid grid;
};

MacGrid cube(int n) {
  const double L = 16 * units::um;
  return make_mac_grid(3, {n, n, n}, {L, L, L}, {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
}

MacGrid whole_blood() {
  return make_mac_grid(3, {80, 60, 80}, {16 * units::um, 12 * units::um, 16 * units::um},
                       {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
}

/// The figures the values read, over every thread count.
struct Summary {
  double whole_blood_speedup = 0.0, whole_blood_fourier_share = 1.0, worst_agreement = 0.0, best_fraction = 0.0, dram_fraction = 0.0;
};

/// 1. The triad and 2. the Laplacian apply on a velocity-component box of each grid (and of 128^3,
/// 256^3: 134 MB per array, out of every cache like the triad's): achieved bandwidths.
void bandwidths(const Options& opt, int threads, std::vector<GridSpec> grids, bool quick, Json& triad, Json& bw, Summary& sum) {
  const index_t nt = index_t(1) << 24;
  const double t_triad = triad_seconds(nt);
  const double bw_triad = 3.0 * 8.0 * double(nt) / t_triad;
  triad["rows"].push(row({threads, t_triad, bw_triad / 1e9}));
  log(opt, "threads " + std::to_string(threads) + ": triad " + std::to_string(bw_triad / 1e9) + " GB/s");
  if (quick) grids.push_back({"128^3", cube(128)});
  grids.push_back({"256^3", cube(256)});
  for (const GridSpec& g : grids) {
    const Box box = g.grid.component(1);
    StaggeredLaplacian L(box, Correction::appendix_a);
    dvec u(box.size(), 1.0), out(box.size());
    L.apply(u, out, 1.0, -0.5);
    const int reps = std::max(5, int(2e7 / double(box.size())));
    const double t = best_seconds(reps, [&] { L.apply(u, out, 1.0, -0.5); });
    const double bwl = 2.0 * 8.0 * double(box.size()) / t;
    sum.best_fraction = std::max(sum.best_fraction, bwl / bw_triad);
    if (g.name == "256^3") sum.dram_fraction = std::max(sum.dram_fraction, bwl / bw_triad);
    bw["rows"].push(row({threads, g.name, double(box.size()), t, bwl / 1e9, bwl / bw_triad}));
    log(opt, "laplacian apply " + g.name + ": " + std::to_string(bwl / 1e9) + " GB/s (" + std::to_string(100 * bwl / bw_triad) + "% of triad)");
  }
}

/// The state and force of a timed run: Taylor-Green (1 cm/s) on the cubes, the Couette profile
/// (top wall 12 mm/s) in the channel, plus a Gaussian force blob at the centre.
void initial_flow(const NavierStokesSolver& ns, const MacGrid& grid, double U, FluidState& s, VectorField& f) {
  const bool channel = !grid.periodic(1);
  const double L = 16 * units::um, k = 2 * rbfib::pi / L;
  for (int a = 0; a < 3; ++a) {
    const Box box = ns.operators().component_box(a);
    s.u[a] = sample(box, [&](double x, double y, double) {
      if (channel) return a == 0 ? U * y / (12 * units::um) : 0.0;
      return a == 0 ? std::sin(k * x) * std::cos(k * y) : a == 1 ? -std::cos(k * x) * std::sin(k * y) : 0.0;
    });
    f[a] = sample(box, [&](double x, double y, double z) {
      const double r2 = std::pow(x - 8 * units::um, 2) + std::pow(y - 0.5 * grid.length[1], 2) + std::pow(z - 8 * units::um, 2);
      return a == 0 ? 1e5 * std::exp(-r2 / (units::um * units::um)) : 0.0;
    });
  }
}

/// Medians over repeats of a step's phases (after one warm-up step) and of its mean iteration counts.
struct StepMedians {
  double total, advection, helmholtz, poisson, projection, other, helmholtz_iterations, poisson_iterations;
};

StepMedians time_steps(NavierStokesSolver& ns, FluidState& s, const VectorField& f, int repeats) {
  ns.step(s, &f);  // warm-up
  std::vector<double> v[8];
  for (int r = 0; r < repeats; ++r) {
    StepStats st;
    const double t = median_seconds(1, [&] { st = ns.step(s, &f); });
    double h = 0, p = 0;
    for (int k2 = 0; k2 < st.stages; ++k2) {
      for (int a = 0; a < 3; ++a) h += st.helmholtz_iterations[k2][a];
      p += st.poisson_iterations[k2];
    }
    const double x[8] = {t, st.seconds_advection, st.seconds_helmholtz, st.seconds_poisson, st.seconds_projection, st.seconds_other,
                         h / (3 * st.stages), p / st.stages};
    for (int q = 0; q < 8; ++q) v[q].push_back(x[q]);
  }
  return {median(v[0]), median(v[1]), median(v[2]), median(v[3]), median(v[4]), median(v[5]), median(v[6]), median(v[7])};
}

/// 3. Solver steps on each grid and integrator: the multigrid path and the direct Fourier path (x
/// and z periodic: every grid here) from the same state, the same steps; their velocities compared.
void solver_steps(const Options& opt, int threads, bool first_pass, const std::vector<GridSpec>& grids, int repeats, double dt, Json& steps,
                  Summary& sum) {
  const double U = 12 * units::mm / units::s;
  for (const GridSpec& g : grids)
    for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
      const bool channel = !g.grid.periodic(1);
      BoundaryVelocity bc;
      if (channel) bc = [U](int a, int d, int side, double, double, double, double) { return (a == 0 && d == 1 && side) ? U : 0.0; };
      const char* iname = ti == TimeIntegrator::backward_forward_euler ? "BFE" : "Peskin";
      double T_multigrid = 0.0;
      VectorField u_multigrid;
      for (FluidSolvers solvers : {FluidSolvers::multigrid, FluidSolvers::fourier}) {
        NavierStokesOptions o;
        o.integrator = ti;
        o.dt = dt;
        o.solvers = solvers;
        NavierStokesSolver ns(g.grid, FluidParameters{1.0, 0.1 * units::cP}, o, bc);
        FluidState s = ns.zero_state();
        VectorField f;
        initial_flow(ns, g.grid, U, s, f);
        const StepMedians m = time_steps(ns, s, f, repeats);
        const double T = m.total, P = m.poisson;
        double diff = 0.0;  // max |u_F - u_MG| / max |u_MG| after the same steps
        if (solvers == FluidSolvers::multigrid) {
          T_multigrid = T;
          u_multigrid = s.u;
        } else {
          diff = max_rel_diff(s.u, u_multigrid);
          sum.worst_agreement = std::max(sum.worst_agreement, diff);
          if (channel && ti == TimeIntegrator::backward_forward_euler && first_pass) {
            sum.whole_blood_speedup = T_multigrid / T;
            sum.whole_blood_fourier_share = P / T;
          }
        }
        steps["rows"].push(row({threads, g.name, iname, to_string(solvers), double(g.grid.cells[0]) * g.grid.cells[1] * g.grid.cells[2], T,
                                m.advection, m.helmholtz, P, m.projection, m.other, P / T, m.helmholtz_iterations, m.poisson_iterations,
                                solvers == FluidSolvers::multigrid ? Json() : Json(diff)}));
        std::ostringstream msg;
        msg << "threads " << threads << ", " << g.name << " " << iname << ", " << to_string(solvers) << ": " << T << " s/step (advection "
            << m.advection << ", helmholtz " << m.helmholtz << ", poisson " << P << " = " << 100 * P / T << "%, projection " << m.projection
            << ")";
        if (solvers != FluidSolvers::multigrid) msg << "; velocity vs multigrid " << diff;
        log(opt, msg.str());
      }
    }
}

/// 4. The channel Poisson solve alone, on the whole-blood grid, by every solver at hand.
void poisson_solvers(const Options& opt, Json& results, int repeats) {
  Json peers = table({"solver", "seconds", "iterations", "relative_residual", "max_rel_diff_vs_fourier"}, {"", "s", "", "", ""});
  const double rtol = 1e-11;
  double t_fourier = 0, t_hypre = 0;
  for (const PoissonPeer& r : compare_poisson_solvers(MacOperators(whole_blood()).scalar_box(), repeats + 2, rtol)) {
    peers["rows"].push(row({r.solver, r.seconds, r.iterations, r.relative_residual, r.max_rel_diff_vs_fourier}));
    if (r.solver.rfind("Fourier", 0) == 0) t_fourier = r.seconds;
    if (r.solver.rfind("hypre", 0) == 0) t_hypre = r.seconds;
    std::ostringstream m;
    m << "poisson 80x60x80, " << r.solver << ": " << r.seconds << " s, " << r.iterations << " iterations, residual " << r.relative_residual
      << ", vs Fourier " << r.max_rel_diff_vs_fourier;
    log(opt, m.str());
  }
  results["parameters"]["poisson_peer_rtol"] = rtol;
  results["parameters"]["hypre"] = have_hypre() ? "found (Debian's libhypre-dev)" : "not found: no PFMG row";
  results["tables"]["poisson_solvers"] = peers;
  if (t_hypre > 0) results["values"]["fourier_speedup_over_hypre_pfmg"] = t_hypre / t_fourier;
}

}  // namespace

int main(int argc, char** argv) {
  return run_main("bench_fluid", [&] {
    Options opt = parse_command_line(argc, argv, "bench_fluid", "Navier-Stokes solver timings per step and component; stencil bandwidth");
    const bool quick = opt.scale == Scale::quick;
    Json results = make_results(opt);
    Json& par = results["parameters"];
    const int repeats = 5;  // medians of 5 at both scales: the speedup goal reads them
    const double dt = 50 * units::ns;
    par["dt_s"] = dt;
    par["repeats"] = repeats;
    par["density_g_per_cm3"] = 1.0;
    par["viscosity_cP"] = 0.1;
    par["flow"] = "cubes: periodic 16 um box, Taylor-Green velocity (1 cm/s) plus a Gaussian force blob; "
                  "whole blood: Couette start-up (top wall 12 mm/s) plus the same blob";
    par["backend"] = backend_name();
    // Thread counts: 1 and all (CPU build). One thread is the figure least disturbed by other load on
    // the machine; all threads is what a run gets. The CUDA build has one pass.
    std::vector<int> thread_counts{omp_get_max_threads()};
#if !defined(RBFIB_BACKEND_CUDA)
    if (omp_get_max_threads() > 1) thread_counts.insert(thread_counts.begin(), 1);
#endif
    par["thread_counts"] = std::to_string(thread_counts.front()) + (thread_counts.size() > 1 ? ", " + std::to_string(thread_counts.back()) : "");
    std::vector<GridSpec> grids = {{"32^3", cube(32)}, {"64^3", cube(64)}};
    if (!quick) grids.push_back({"128^3", cube(128)});
    grids.push_back({"80x60x80 (whole blood)", whole_blood()});
    Json triad = table({"threads", "seconds", "bandwidth_GBps"}, {"", "s", "GB/s"});
    Json bw = table({"threads", "grid", "unknowns", "seconds", "bandwidth_GBps", "fraction_of_triad"}, {"", "", "", "s", "GB/s", ""});
    Json steps = table({"threads", "grid", "integrator", "solver", "unknowns", "seconds", "advection_seconds", "helmholtz_seconds",
                        "poisson_seconds", "projection_seconds", "other_seconds", "poisson_share", "helmholtz_iterations",
                        "poisson_iterations", "max_rel_diff_vs_multigrid"},
                       {"", "", "", "", "", "s", "s", "s", "s", "s", "s", "", "", "", ""});
    Summary sum;
    for (int threads : thread_counts) {
#if !defined(RBFIB_BACKEND_CUDA)
      omp_set_num_threads(threads);
#endif
      bandwidths(opt, threads, grids, quick, triad, bw, sum);
      solver_steps(opt, threads, threads == thread_counts.front(), grids, repeats, dt, steps, sum);
    }
    poisson_solvers(opt, results, repeats);
    Json& V = results["values"];
    V["whole_blood_fourier_speedup"] = sum.whole_blood_speedup;
    V["whole_blood_fourier_poisson_share"] = sum.whole_blood_fourier_share;
    V["max_rel_diff_fourier_vs_multigrid"] = sum.worst_agreement;
    results["tables"]["triad"] = triad;
    results["tables"]["stencil_bandwidth"] = bw;
    results["tables"]["step_times"] = steps;
    V["best_stencil_fraction_of_triad"] = sum.best_fraction;
    V["out_of_cache_stencil_fraction_of_triad"] = sum.dram_fraction;
    write_results(opt, results);
    return 0;
  });
}
