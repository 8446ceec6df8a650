#include "fig5.hpp"

namespace rbfib::chapter3 {

using study::number, study::row;

void fig5(const Setup& S, Relaxations& runs, Point point, Json& T, Json& V) {
  const bool at_site = point == Point::rightmost;
  auto n_even = [](int eta) { return index_t(2) * eta * eta; };
  Json t = at_site ? study::table({"method", "eta", "n", "offset_rad", "d_max", "eta_ref", "n_ref", "offset_ref_rad",
                                "d_max_ref", "err", "err_axis", "err_over_err_axis", "d_max_minus_axis"},
                               {"", "", "", "rad", "1", "", "", "rad", "1", "1", "1", "", "1"})
                   : study::table({"method", "eta", "n", "m", "dt", "d_max", "eta_ref", "d_max_ref", "err", "seconds"},
                               {"", "", "", "", "1", "1", "", "1", "1", "s"});
  Json agree = study::table({"eta", "d_max_SHVD", "d_max_LDSM", "method_diff", "err_SHVD", "err_LDSM", "diff_over_err"},
                         {"", "1", "1", "1", "1", "1", ""});
  Json series = study::table({"method", "eta", "t", "d_axis"}, {"", "", "1", "1"});
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
        xs[m].size() == S.fig5_etas.size() ? number(study::power_law_order(xs[m], es[m])) : Json();
}

void rightmost_extras(const Setup& S, Relaxations& runs, Json& T, Json& V) {
  const RelaxationResult& lib = runs.get(fig5_run(Method::shvd, S.fig5_etas.front()));
  const RelaxationResult& drv = runs.get(fig5_run(Method::shvd, S.fig5_etas.front(), Point::axis_site));
  V["rightmost_loop_vs_library"] = number(err(drv, lib));
  if (!S.full) return;
  Json md = study::table({"method", "eta", "n", "offset_rad", "d_max", "eta_ref", "n_ref", "offset_ref_rad", "d_max_ref",
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

void time_and_space(const Setup& S, Relaxations& runs, Json& T, Json& V) {
  const int e0 = S.fig5_etas.front();
  auto d_at = [&](int eta, double dt) {
    RelaxationSpec s = fig5_run(Method::shvd, eta);
    s.dt = dt;
    s.steps = int(std::lround(3 / dt));
    s.record_every = s.steps / 12;
    return dmax(runs.get(s));
  };
  Json t = study::table({"eta", "dt", "steps", "d_max", "diff_to_half_dt", "order_dt"}, {"", "1", "", "1", "1", ""});
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
  Json u = study::table({"eta", "n", "dt", "d_max", "err", "order"}, {"", "", "1", "1", "1", ""});
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

}  // namespace rbfib::chapter3
