// Chapter 3 dynamic test (the JCP 2018 paper, Sec. 4.2, with the time update of Sec. 3.3): the
// ellipsoid of eq. (88) and the perturbed ellipsoid of eq. (89) relaxing to the unit sphere in
// periodic Stokes flow, SHVD against LDSM (common/chapter3_relaxation.hpp). Dimensionless.
//
// Reproduces:
//   Fig. 4  both shapes on eta = 32 with m = 225: max_i |X_i - c| - 1 (and the min) against time;
//   Fig. 5  d_max at t = 3 (x-displacement of the rightmost point relative to the centroid) of
//           the ellipsoid, dt = 1/(2 eta), n = 2 eta^2 + 1, m = 64; error against the same method
//           on a grid 1.5 times finer; power-law orders. Also with the paper's d_max point (the
//           rightmost site of even spirals), the time step's and the grid's shares of the error,
//           the quadrature error of every evaluation set (Sec. 4.1's 1e-5), and the stored
//           maximal-determinant sets with the weights of eq. (45) against our spirals.
// Table 1 (the wall-time ratios) is study chapter3_table1.
//
// Scales. Quick: Fig. 5 on eta = 16, 24, 32; Fig. 4 with n = 4,609 to t = 4. Full: eta = 32, 48,
// 64; Fig. 4 with n = 8,281 to t = 15. Full scale (or --resumable) keeps each run in the run
// directory (run_<label>.h5): a run the sitting (--sitting) leaves unfinished continues there.
//
// Run:  build/studies/study_chapter3_dynamics --scale quick --out runs/chapter3_dynamics/quick
#include "common/chapter3_relaxation.hpp"
#include "fig5.hpp"

using namespace rbfib;
using namespace rbfib::chapter3;
namespace st = rbfib::study;
using st::Json, st::number, st::row;

namespace {

/// Fig. 4: both shapes on eta = 32 with m = 225, SHVD, LDSM and SHVD on the grid 1.5 times finer
/// (the IB discretization error the paper names as the reason both methods agree); and the
/// quadrature error of every evaluation set, |sum_i F^_i|_inf of the SHVD forces at t = 0 (Sec. 4.1).
void fig4(const Setup& S, Relaxations& runs, Json& T) {
  Json t4 = st::table({"series", "shape", "method", "eta", "t", "r_max", "r_min", "d_axis"},
                      {"", "", "", "", "1", "1", "1", "1"});
  Json agree = st::table({"shape", "method_diff", "grid_diff_SHVD", "diff_over_grid_diff", "initial_r_max",
                          "volume_change_SHVD", "volume_change_LDSM"},
                         {"", "1", "1", "", "1", "1", "1"});
  Json quad = st::table({"use", "shape", "n", "m", "force_integral", "max_force", "paper_criterion"},
                        {"", "", "", "", "1", "1", "1"});
  // largest difference of r_max and r_min over the common times; relative change of the volume
  auto max_diff = [](const RelaxationResult& a, const RelaxationResult& b) {
    if (a.failed || b.failed || a.series.empty() || a.series.size() != b.series.size()) return double(NAN);
    double d = 0;
    for (std::size_t i = 0; i < a.series.size(); ++i)
      d = std::max({d, std::abs(a.series[i].r_max - b.series[i].r_max), std::abs(a.series[i].r_min - b.series[i].r_min)});
    return d;
  };
  auto volume_change = [](const RelaxationResult& r) {
    return r.series.empty() ? Json() : number(r.series.back().volume / r.series.front().volume - 1);
  };
  runs.group("fig4");
  for (const std::string name : {"ellipsoid", "perturbed"}) {
    auto run = [&](Method m, int eta) {
      RelaxationSpec s = dynamic_test(m, eta, S.fig4_t, 14, int(std::lround(S.fig4_t * 8)));  // every 1/8
      s.n = S.fig4_n;
      if (name == "perturbed") s.shape = surface::paper_perturbed_ellipsoid(), s.shape_name = name;
      return &runs.get(s);
    };
    const RelaxationResult *shvd = run(Method::shvd, S.fig4_eta), *ldsm = run(Method::ldsm, S.fig4_eta),
                           *finer = run(Method::shvd, S.fig4_eta * 3 / 2);
    for (const auto& [label, r] : std::initializer_list<std::pair<std::string, const RelaxationResult*>>{
             {"SHVD", shvd}, {"LDSM", ldsm}, {"SHVD eta = 48", finer}})
      for (const Sample& x : r->series)
        t4["rows"].push(row({name + " " + label, name, label.substr(0, 4),
                             r == finer ? S.fig4_eta * 3 / 2 : S.fig4_eta, x.t, x.r_max, x.r_min, x.d_axis}));
    const double dm = max_diff(*shvd, *ldsm), dg = max_diff(*shvd, *finer);
    agree["rows"].push(row({name, number(dm), number(dg), number(dm / dg),
                            shvd->series.empty() ? Json() : Json(shvd->series.front().r_max), volume_change(*shvd),
                            volume_change(*ldsm)}));
    quad["rows"].push(row({"Fig. 4", name, double(S.fig4_n), 225, shvd->force_integral0, shvd->max_force0, 1e-5}));
  }
  T["fig4"] = t4;
  T["fig4_agreement"] = agree;
  runs.group("fig5");
  std::set<int> grids;
  for (int eta : S.fig5_etas) grids.insert({eta, eta * 3 / 2});
  for (int k : grids) {
    const RelaxationResult& shvd = runs.get(fig5_run(Method::shvd, k));
    quad["rows"].push(row({"Fig. 5", "ellipsoid", double(spiral_sites(k)), 64, shvd.force_integral0, shvd.max_force0, 1e-5}));
  }
  T["quadrature"] = quad;
}

/// d_max at t = 3 on the stored MD sets with eq. (45) weights (n = 2025; full also 4624) against
/// the spirals of the same grid, beside that grid's error in Fig. 5.
void sites(const Setup& S, Relaxations& runs, Json& T) {
  runs.group("sites");
  Json t = st::table({"method", "eta", "n_MD", "eq45_residual", "d_max_MD", "n_spiral", "d_max_spiral", "sites_diff",
                      "err_grid", "diff_over_err"},
                     {"", "", "", "", "1", "", "1", "1", "1", ""});
  for (const auto& [eta, N] : S.full ? std::vector<std::pair<int, int>>{{32, 44}, {48, 67}} : std::vector<std::pair<int, int>>{{32, 44}})
    for (Method m : methods) {
      const RelaxationResult &a = runs.get(md_run(m, eta, N)), &b = runs.get(fig5_run(m, eta)),
                             &c = runs.get(fig5_run(m, eta * 3 / 2));
      t["rows"].push(row({to_string(m), eta, double((N + 1) * (N + 1)), runs.md_sites(N).eq45_residual, number(dmax(a)),
                          double(spiral_sites(eta)), number(dmax(b)), number(err(a, b)), number(err(b, c)),
                          number(err(a, b) / err(b, c))}));
    }
  T["sites"] = t;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_dynamics", [&] {
    // ---- 1. Parameters ---------------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_dynamics", "Chapter 3 dynamic test: SHVD vs LDSM shells relaxing in periodic Stokes flow (Figs. 4-5)");
    const Setup S{opt.scale == st::Scale::full};
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    describe_dynamic_test(P);
    P["perturbed_ellipsoid"] = "eq. (89), a = 0.1, b = c = 0.2, B = 0.25, Vf = " + to_text(surface::paper_perturbed_ellipsoid().Vf);
    P["fig4"] = "eta = " + to_text(S.fig4_eta) + ", n = " + to_text(S.fig4_n) + ", m = 225, dt = 1/64, t = 0.." + to_text(S.fig4_t);
    P["fig5"] = "eta = " + to_text(S.fig5_etas.front()) + ".." + to_text(S.fig5_etas.back()) +
                " (references 1.5 eta), n = 2 eta^2 + 1, m = 64, dt = 1/(2 eta), t = 3";
    P["timing"] = "wall time of the steps' phases (the diagnostics excluded), one thread";
    Json& T = results["tables"];
    Json& V = results["values"];
    Relaxations runs(opt);

    // ---- 2. Fig. 5, with the paper's d_max point, and the time and space parts of its error -------
    runs.group("fig5");
    fig5(S, runs, Point::material, T, V);
    runs.group("fig5_rightmost");
    fig5(S, runs, Point::rightmost, T, V);
    rightmost_extras(S, runs, T, V);
    runs.group("fig5_time_space");
    time_and_space(S, runs, T, V);
    // ---- 3. Fig. 4, the quadrature error of the sites, the paper's sites --------------------------
    fig4(S, runs, T);
    sites(S, runs, T);

    runs.record(results);
    st::write_results(opt, results);
    return 0;
  });
}
