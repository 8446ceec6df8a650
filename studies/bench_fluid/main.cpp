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
#include "common/study.hpp"
#include "poisson_peers.hpp"

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


using rbfib::study::table;

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

}  // namespace

int main(int argc, char** argv) {
  return run_main("bench_fluid", [&] {
    Options opt = parse_command_line(argc, argv, "bench_fluid",
                                     "Navier-Stokes solver timings per step and component; stencil bandwidth");
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
    Json steps = table({"threads", "grid", "integrator", "solver", "unknowns", "seconds", "advection_seconds",
                        "helmholtz_seconds", "poisson_seconds", "projection_seconds", "other_seconds", "poisson_share",
                        "helmholtz_iterations", "poisson_iterations", "max_rel_diff_vs_multigrid"},
                       {"", "", "", "", "", "s", "s", "s", "s", "s", "s", "", "", "", ""});
    double whole_blood_speedup = 0.0, whole_blood_fourier_share = 1.0, worst_agreement = 0.0;
    double best_fraction = 0.0, dram_fraction = 0.0;
    for (int threads : thread_counts) {
#if !defined(RBFIB_BACKEND_CUDA)
    omp_set_num_threads(threads);
#endif
    // 1. triad
    const index_t nt = index_t(1) << 24;
    const double t_triad = triad_seconds(nt);
    const double bw_triad = 3.0 * 8.0 * double(nt) / t_triad;
    triad["rows"].push(row({threads, t_triad, bw_triad / 1e9}));
    log(opt, "threads " + std::to_string(threads) + ": triad " + std::to_string(bw_triad / 1e9) + " GB/s");

    // 2. stencil bandwidth, on the solver grids and on 256^3 (134 MB per array: out of every cache,
    // like the triad's arrays)
    std::vector<GridSpec> bw_grids = grids;
    if (quick) bw_grids.push_back({"128^3", cube(128)});
    bw_grids.push_back({"256^3", cube(256)});
    for (const GridSpec& g : bw_grids) {
      const Box box = g.grid.component(1);
      StaggeredLaplacian L(box, Correction::appendix_a);
      dvec u(box.size(), 1.0), out(box.size());
      L.apply(u, out, 1.0, -0.5);
      const int reps = std::max(5, int(2e7 / double(box.size())));
      const double t = best_seconds(reps, [&] { L.apply(u, out, 1.0, -0.5); });
      const double bwl = 2.0 * 8.0 * double(box.size()) / t;
      best_fraction = std::max(best_fraction, bwl / bw_triad);
      if (g.name == "256^3") dram_fraction = std::max(dram_fraction, bwl / bw_triad);
      bw["rows"].push(row({threads, g.name, double(box.size()), t, bwl / 1e9, bwl / bw_triad}));
      log(opt, "laplacian apply " + g.name + ": " + std::to_string(bwl / 1e9) + " GB/s (" +
                   std::to_string(100 * bwl / bw_triad) + "% of triad)");
    }

    // 3. solver steps: the multigrid path and the direct Fourier path (x and z periodic: every grid
    // here) from the same state, the same steps; the velocities they reach are compared.
    for (const GridSpec& g : grids)
      for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
        const bool channel = !g.grid.periodic(1);
        const double U = 12 * units::mm / units::s;
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
          const double L = 16 * units::um, k = 2 * 3.14159265358979323846 / L;
          VectorField f;
          for (int a = 0; a < 3; ++a) {
            const Box box = ns.operators().component_box(a);
            s.u[a] = sample(box, [&](double x, double y, double) {
              if (channel) return a == 0 ? U * y / (12 * units::um) : 0.0;
              return a == 0 ? std::sin(k * x) * std::cos(k * y) : a == 1 ? -std::cos(k * x) * std::sin(k * y) : 0.0;
            });
            f[a] = sample(box, [&](double x, double y, double z) {
              const double r2 = std::pow(x - 8 * units::um, 2) + std::pow(y - 0.5 * g.grid.length[1], 2) + std::pow(z - 8 * units::um, 2);
              return a == 0 ? 1e5 * std::exp(-r2 / (units::um * units::um)) : 0.0;
            });
          }
          ns.step(s, &f);  // warm-up
          std::vector<double> tot, adv, hel, poi, pro, oth, hit, pit;
          for (int r = 0; r < repeats; ++r) {
            StepStats st;
            tot.push_back(median_seconds(1, [&] { st = ns.step(s, &f); }));
            adv.push_back(st.seconds_advection);
            hel.push_back(st.seconds_helmholtz);
            poi.push_back(st.seconds_poisson);
            pro.push_back(st.seconds_projection);
            oth.push_back(st.seconds_other);
            double h = 0, p = 0;
            for (int k2 = 0; k2 < st.stages; ++k2) {
              for (int a = 0; a < 3; ++a) h += st.helmholtz_iterations[k2][a];
              p += st.poisson_iterations[k2];
            }
            hit.push_back(h / (3 * st.stages));
            pit.push_back(p / st.stages);
          }
          const double T = median(tot), P = median(poi);
          // Agreement of the two paths after the same steps: max |u_F - u_MG| / max |u_MG|.
          double diff = 0.0;
          if (solvers == FluidSolvers::multigrid) {
            T_multigrid = T;
            u_multigrid = s.u;
          } else {
            double num = 0.0, den = 0.0;
            for (int a = 0; a < 3; ++a) {
              dvec d = s.u[a];
              blas::axpy(-1.0, u_multigrid[a], d);
              num = std::max(num, blas::norm_inf(d));
              den = std::max(den, blas::norm_inf(u_multigrid[a]));
            }
            diff = num / den;
            worst_agreement = std::max(worst_agreement, diff);
            if (channel && ti == TimeIntegrator::backward_forward_euler && threads == thread_counts.front()) {
              whole_blood_speedup = T_multigrid / T;
              whole_blood_fourier_share = P / T;
            }
          }
          steps["rows"].push(row({threads, g.name, iname, to_string(solvers), double(g.grid.cells[0]) * g.grid.cells[1] * g.grid.cells[2],
                                  T, median(adv), median(hel), P, median(pro), median(oth), P / T, median(hit), median(pit),
                                  solvers == FluidSolvers::multigrid ? Json() : Json(diff)}));
          std::ostringstream m;
          m << "threads " << threads << ", " << g.name << " " << iname << ", " << to_string(solvers) << ": " << T
            << " s/step (advection " << median(adv) << ", helmholtz " << median(hel) << ", poisson " << P << " = "
            << 100 * P / T << "%, projection " << median(pro) << ")";
          if (solvers != FluidSolvers::multigrid) m << "; velocity vs multigrid " << diff;
          log(opt, m.str());
        }
      }
    }
    // 4. The channel Poisson solve alone, on the whole-blood grid, by every solver at hand.
    {
      Json peers = table({"solver", "seconds", "iterations", "relative_residual", "max_rel_diff_vs_fourier"}, {"", "s", "", "", ""});
      const Box box = MacOperators(whole_blood()).scalar_box();
      const double rtol = 1e-11;
      double t_fourier = 0, t_hypre = 0;
      for (const PoissonPeer& r : compare_poisson_solvers(box, repeats + 2, rtol)) {
        peers["rows"].push(row({r.solver, r.seconds, r.iterations, r.relative_residual, r.max_rel_diff_vs_fourier}));
        if (r.solver.rfind("Fourier", 0) == 0) t_fourier = r.seconds;
        if (r.solver.rfind("hypre", 0) == 0) t_hypre = r.seconds;
        std::ostringstream m;
        m << "poisson 80x60x80, " << r.solver << ": " << r.seconds << " s, " << r.iterations << " iterations, residual "
          << r.relative_residual << ", vs Fourier " << r.max_rel_diff_vs_fourier;
        log(opt, m.str());
      }
      par["poisson_peer_rtol"] = rtol;
      par["hypre"] = have_hypre() ? "found (Debian's libhypre-dev)" : "not found: no PFMG row";
      results["tables"]["poisson_solvers"] = peers;
      if (t_hypre > 0) results["values"]["fourier_speedup_over_hypre_pfmg"] = t_hypre / t_fourier;
    }
    results["values"]["whole_blood_fourier_speedup"] = whole_blood_speedup;
    results["values"]["whole_blood_fourier_poisson_share"] = whole_blood_fourier_share;
    results["values"]["max_rel_diff_fourier_vs_multigrid"] = worst_agreement;
    results["tables"]["triad"] = triad;
    results["tables"]["stencil_bandwidth"] = bw;
    results["tables"]["step_times"] = steps;
    results["values"]["best_stencil_fraction_of_triad"] = best_fraction;
    results["values"]["out_of_cache_stencil_fraction_of_triad"] = dram_fraction;
    write_results(opt, results);
    return 0;
  });
}
