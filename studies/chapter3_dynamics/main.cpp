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

using namespace rbfib;
using namespace rbfib::chapter3;
namespace st = rbfib::study;
using st::Json, st::number, st::row;

namespace {

const Method methods[] = {Method::shvd, Method::ldsm};

/// The scale's parameters (see the header); Fig. 5's grids each with a reference 1.5 times finer.
struct Setup {
  bool full;
  std::vector<int> fig5_etas = full ? std::vector<int>{32, 48, 64} : std::vector<int>{16, 24, 32};
  int fig4_eta = 32;
  index_t fig4_n = full ? 8281 : spiral_sites(48);
  double fig4_t = full ? 15 : 4;
};

/// Fig. 5's run: t = 3, m = 64, 12 records, read at `point`; on n spiral sites (default 2 eta^2 +
/// 1) or on the stored MD set of degree N.
RelaxationSpec fig5_run(Method m, int eta, Point point = Point::material, index_t n = 0, int N = -1) {
  RelaxationSpec s = dynamic_test(m, eta, 3, 7, 12);
  s.point = point;
  s.md_degree = N;
  if (N >= 0) s.n = index_t(N + 1) * (N + 1);
  if (n > 0) s.n = n;
  return s;
}
RelaxationSpec md_run(Method m, int eta, int N, Point point = Point::material) { return fig5_run(m, eta, point, 0, N); }

double dmax(const RelaxationResult& r) { return r.failed ? NAN : r.d_axis(); }
double err(const RelaxationResult& a, const RelaxationResult& b) { return std::abs(dmax(a) - dmax(b)); }

/// The angle of the rightmost site of a set from the x axis (rad).
double rightmost_offset(const surface::SphereSites& sites) {
  const index_t i = surface::rightmost_site(sites);
  return std::acos(std::min(1.0, std::cos(sites.theta[i]) * std::cos(sites.lambda[i])));
}

/// Fig. 5: d_max at t = 3 against a grid 1.5 times finer, by method; with `point` = rightmost each
/// run on its own even spiral of 2 eta^2 sites (Sec. 4.2's "rightmost point"). Orders into V.
void fig5(const Setup& S, Relaxations& runs, Point point, Json& T, Json& V) {
  const bool at_site = point == Point::rightmost;
  auto n_even = [](int eta) { return index_t(2) * eta * eta; };
  Json t = at_site ? st::table({"method", "eta", "n", "offset_rad", "d_max", "eta_ref", "n_ref", "offset_ref_rad",
                                "d_max_ref", "err", "err_axis", "err_over_err_axis", "d_max_minus_axis"},
                               {"", "", "", "rad", "1", "", "", "rad", "1", "1", "1", "", "1"})
                   : st::table({"method", "eta", "n", "m", "dt", "d_max", "eta_ref", "d_max_ref", "err", "seconds"},
                               {"", "", "", "", "1", "1", "", "1", "1", "s"});
  Json agree = st::table({"eta", "d_max_SHVD", "d_max_LDSM", "method_diff", "err_SHVD", "err_LDSM", "diff_over_err"},
                         {"", "1", "1", "1", "1", "1", ""});
  Json series = st::table({"method", "eta", "t", "d_axis"}, {"", "", "1", "1"});
  std::map<Method, std::vector<double>> xs, es;
  for (int eta : S.fig5_etas) {
    const int ref = eta * 3 / 2;
    double d[2], e[2];
    for (Method m : methods) {
      const RelaxationResult& a = runs.get(at_site ? fig5_run(m, eta, point, n_even(eta)) : fig5_run(m, eta));
      const RelaxationResult& b = runs.get(at_site ? fig5_run(m, ref, point, n_even(ref)) : fig5_run(m, ref));
      const RelaxationResult& ax = runs.get(fig5_run(m, eta)), &bx = runs.get(fig5_run(m, ref));
      d[int(m)] = dmax(a);
      e[int(m)] = err(a, b);
      if (at_site)
        t["rows"].push(row({to_string(m), eta, double(n_even(eta)), rightmost_offset(surface::bauer_spiral(n_even(eta))),
                            number(dmax(a)), ref, double(n_even(ref)), rightmost_offset(surface::bauer_spiral(n_even(ref))),
                            number(dmax(b)), number(e[int(m)]), number(err(ax, bx)), number(e[int(m)] / err(ax, bx)),
                            number(a.d_axis() - ax.d_axis())}));
      else
        t["rows"].push(row({to_string(m), eta, double(spiral_sites(eta)), m == Method::shvd ? Json(64) : Json(),
                            1.0 / (2 * eta), number(dmax(a)), ref, number(dmax(b)), number(e[int(m)]), a.phases.total()}));
      if (std::isfinite(e[int(m)]) && e[int(m)] > 0) xs[m].push_back(eta), es[m].push_back(e[int(m)]);
      for (const Sample& s : a.series)
        series["rows"].push(row({std::string(to_string(m)) + " eta = " + to_text(eta), eta, s.t, s.d_axis}));
    }
    agree["rows"].push(row({eta, number(d[0]), number(d[1]), number(std::abs(d[0] - d[1])), number(e[0]), number(e[1]),
                            number(std::abs(d[0] - d[1]) / std::min(e[0], e[1]))}));
  }
  const std::string name = at_site ? "fig5_rightmost" : "fig5";
  T[name] = t;
  if (!at_site) T["fig5_agreement"] = agree, T["fig5_series"] = series;
  for (Method m : methods)
    V[name + "_order_fit_" + to_string(m)] =
        xs[m].size() == S.fig5_etas.size() ? number(st::power_law_order(xs[m], es[m])) : Json();
}

/// SHVD read at the odd spiral's site (0, 0) against its interpolant at the material point (0, 0):
/// the same run, measured two ways. Full scale: the paper's own sets of eta = 32 and of its
/// reference (MD, n = 2025 and 4624), read at their rightmost sites.
void rightmost_extras(const Setup& S, Relaxations& runs, Json& T, Json& V) {
  const RelaxationResult& lib = runs.get(fig5_run(Method::shvd, S.fig5_etas.front()));
  const RelaxationResult& drv = runs.get(fig5_run(Method::shvd, S.fig5_etas.front(), Point::axis_site));
  V["rightmost_loop_vs_library"] = number(err(drv, lib));
  if (!S.full) return;
  Json md = st::table({"method", "eta", "n", "offset_rad", "d_max", "eta_ref", "n_ref", "offset_ref_rad", "d_max_ref",
                       "err", "err_spiral", "err_axis"},
                      {"", "", "", "rad", "1", "", "", "rad", "1", "1", "1", "1"});
  const int eta = 32, ref = 48, N = 44, N_ref = 67;
  const Point at = Point::rightmost;
  for (Method m : methods) {
    const RelaxationResult &a = runs.get(md_run(m, eta, N, at)), &b = runs.get(md_run(m, ref, N_ref, at));
    const RelaxationResult &as = runs.get(fig5_run(m, eta, at, 2 * eta * eta)),
                           &bs = runs.get(fig5_run(m, ref, at, 2 * ref * ref));
    const RelaxationResult &ax = runs.get(fig5_run(m, eta)), &bx = runs.get(fig5_run(m, ref));
    md["rows"].push(row({to_string(m), eta, double((N + 1) * (N + 1)),
                         rightmost_offset(surface::read_sphere_sites(runs.md_file(N))), number(dmax(a)), ref,
                         double((N_ref + 1) * (N_ref + 1)), rightmost_offset(surface::read_sphere_sites(runs.md_file(N_ref))),
                         number(dmax(b)), number(err(a, b)), number(err(as, bs)), number(err(ax, bx))}));
  }
  T["fig5_rightmost_md"] = md;
}

/// The time step's and the grid's shares of the Fig. 5 error on its coarsest grid: d_max with dt,
/// dt/2, dt/4 (forward Euler, eq. 87, is first order in dt; 2 |d(dt) - d(dt/2)| estimates the time
/// error); and the grids eta, 1.5 eta, 2.25 eta with the finest one's dt (the spatial error alone).
void time_and_space(const Setup& S, Relaxations& runs, Json& T, Json& V) {
  const int e0 = S.fig5_etas.front();
  auto d_at = [&](int eta, double dt) {
    RelaxationSpec s = fig5_run(Method::shvd, eta);
    s.dt = dt;
    s.steps = int(std::lround(3 / dt));
    s.record_every = s.steps / 12;
    return dmax(runs.get(s));
  };
  Json t = st::table({"eta", "dt", "steps", "d_max", "diff_to_half_dt", "order_dt"}, {"", "1", "", "1", "1", ""});
  std::vector<double> ds;
  for (int q : {1, 2, 4}) ds.push_back(d_at(e0, 1.0 / (2 * e0) / q));
  for (std::size_t i = 0; i < 3; ++i) {
    const double diff = i < 2 ? std::abs(ds[i] - ds[i + 1]) : NAN, prev = i > 0 ? std::abs(ds[i - 1] - ds[i]) : NAN;
    const double dt = 1.0 / (2 * e0) / (1 << i);
    t["rows"].push(row({e0, dt, int(std::lround(3 / dt)), number(ds[i]), number(diff), number(std::log(prev / diff) / std::log(2.0))}));
  }
  T["time_step"] = t;
  const double grid_err = std::abs(ds[0] - runs.get(fig5_run(Method::shvd, e0 * 3 / 2)).d_axis());
  V["time_error_share_coarsest"] = number(2 * std::abs(ds[0] - ds[1]) / grid_err);
  V["time_order_dt"] = number(std::log(std::abs(ds[0] - ds[1]) / std::abs(ds[1] - ds[2])) / std::log(2.0));

  const std::vector<int> etas = {e0, e0 * 3 / 2, e0 * 9 / 4};
  const double dt = 1.0 / (2 * etas.back());
  Json u = st::table({"eta", "n", "dt", "d_max", "err", "order"}, {"", "", "1", "1", "1", ""});
  std::vector<double> d, e;
  for (int eta : etas) d.push_back(d_at(eta, dt));
  for (std::size_t i = 0; i < 3; ++i) {
    e.push_back(i < 2 ? std::abs(d[i] - d[i + 1]) : NAN);
    const double order = i == 1 ? std::log(e[0] / e[1]) / std::log(1.5) : NAN;
    u["rows"].push(row({etas[i], double(spiral_sites(etas[i])), dt, number(d[i]), number(e[i]), number(order)}));
  }
  T["space_only"] = u;
  V["space_order"] = number(std::log(e[0] / e[1]) / std::log(1.5));
}

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
