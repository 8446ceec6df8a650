// Chapter 3 force accuracy (the JCP 2018 paper, Sec. 4.1, Figs. 1-3), with the RBF reconstruction of
// Chapter 2 (Sec. 2.3) in the same experiment.
//   Fig. 1  the ellipsoid (eq. 88) and perturbed ellipsoid (eq. 89), n = 529 evaluation sites;
//   Fig. 2  LDSM and SHVD force errors on the ellipsoid a = 1.1, b = c = 1/sqrt(1.1), reference the
//           unit sphere, sigma = K = A = Gs = 1: LDSM ~2nd order in sqrt(n), SHVD exact;
//   Fig. 3  the same on the perturbed ellipsoid: LDSM between 1st and 2nd order, SHVD spectral in m;
//   plus    RBF (PHS r^7 + degree-5 harmonics) forces against n_d, mean curvature (eq. 76), and
//           force-evaluation time against error.
// Evaluation sites (surface/evaluation_sets.hpp): stored maximal-determinant (MD) sites with the
// weights of eq. (45), the same sites and Bauer spirals with those of eq. (2.22). The exact force is
// F^_E,i = F_E(X_i) dA0_i, F_E of eq. (35) on the exact map; the error is max_i ||F^ - F^_E||_inf
// (eqs. 90-91), also relative to max_i ||F^_E,i||_inf (reference/chapter3_forces.yaml).
//
// Run:  build/studies/study_chapter3_forces --scale quick --out runs/chapter3_forces/quick
//       (quick: n <= 4624, m <= 225, n_d <= 800; full adds the spiral n = 8281 and n_d = 1600)
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "common/study.hpp"
#include "setup.hpp"
#include "common/tables.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/error_norms.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/mechanics/net_force.hpp"
#include "rbfib/mechanics/shell.hpp"
#include "rbfib/surface/evaluation_sets.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/shapes.hpp"

using namespace rbfib;
using namespace rbfib::surface;
using namespace rbfib::mechanics;
namespace st = rbfib::study;
using st::Json;
using st::row;
using namespace rbfib::forces;

namespace {

/// SHVD or RBF forces from data sites X_data through ops at the evaluation sites: the median time
/// of the repeats, and the error against the exact forces Fe.
std::pair<double, MaxNormError> reconstructed_forces(const Setup& S, const std::string& cell,
                                                     const SurfaceOperators& ops, const std::vector<double>& X_data,
                                                     const EnergyDensity& W, const std::vector<double>& Fe) {
  const EvaluationSet& e = S.eval();
  std::vector<double> F;
  const double secs = st::median_seconds(S.repeats, [&] {
    F = forces_from_density(elastic_force_density(cell, jets_from_operators(ops, X_data), S.Z, W), e.w);
  });
  return {secs, max_norm_error(F, Fe)};
}

/// Figs. 2-3: LDSM against n on every evaluation set, SHVD against m on the MD set n = 4624.
Json ldsm_and_shvd(const Setup& S, const std::string& fig, const PerturbedEllipsoid& shape, Json& V, Json& speed,
                   Json& orders) {
  Json t = st::table(
      {"series", "method", "energy", "points", "n", "m", "sqrt_points", "err_inf", "rel_err", "quad_err", "seconds"});
  const bool fig3 = fig == "fig3_perturbed";
  for (const Energy& en : S.energies) {
    const std::string tag = (fig3 ? "fig3_" : "fig2_") + en.tag;
    const bool timed = fig3 && en.name == "neo-Hookean";  // the speed_vs_error series
    double rel_finest = 0;                                // LDSM on the finest MD set, for the "m >= 81" comparison
    for (const auto& [points, ns] : S.point_sets) {
      std::vector<double> xs_all, es_all, xs_ok, es_ok;
      for (index_t n : ns) {
        const EvaluationSet& e = S.sets.at({points, n});
        const std::vector<double> Fe = exact_forces(shape, e, en.W), X = shape.points(e.sites);
        LdsmResult r;
        const double secs = st::median_seconds(S.repeats, [&] { r = ldsm_forces(fig, e.tris, e.Z, X, en.W); });
        const MaxNormError err = max_norm_error(r.F, Fe);
        const double quad = net_force_inf(Fe), x = std::sqrt(double(n));
        t["rows"].push(row({"LDSM " + en.name + " " + points, "LDSM", en.name, points, double(n), Json(), x, err.abs,
                            err.rel, quad, secs}));
        if (points == "MD") rel_finest = err.rel;
        xs_all.push_back(x);
        es_all.push_back(err.abs);
        if (quad < 0.1 * err.abs) {  // the paper's criterion: quadrature error negligible (Sec. 4.1)
          xs_ok.push_back(x);
          es_ok.push_back(err.abs);
        }
        if (timed && points == "MD") speed["rows"].push(row({"LDSM", "n = " + to_text(n), secs, err.rel}));
      }
      const std::string key = (points == "MD" ? "" : points + "_") + tag;
      const double order = st::power_law_order(xs_ok, es_ok), order_all = st::power_law_order(xs_all, es_all);
      V["ldsm_fit_order_all_" + key] = order_all;
      V["ldsm_fit_order_" + key] = order;
      V["ldsm_fit_points_" + key] = double(xs_ok.size());
      orders["rows"].push(
          row({fig3 ? "Fig. 3(a)" : "Fig. 2", "LDSM", en.name, points, order, order_all, double(xs_ok.size())}));
    }
    V["ldsm_rel_err_finest_" + tag] = rel_finest;
    const EvaluationSet& e = S.eval();
    const std::vector<double> Fe = exact_forces(shape, e, en.W);
    for (int M : S.M_list) {
      if (!fig3 && M > 4) break;  // exact from M = 1: a few m suffice
      const auto [secs, err] =
          reconstructed_forces(S, fig, *sh_operators(S.md.at(M), e.sites, M), shape.points(S.md.at(M)), en.W, Fe);
      const double m = sh_count(M);
      t["rows"].push(row({"SHVD " + en.name, "SHVD", en.name, "MD", double(S.n_shvd), m, std::sqrt(m), err.abs, err.rel,
                          net_force_inf(Fe), secs}));
      if (M == 8) V["shvd_m81_rel_err_" + tag] = err.rel;
      if (M == 14) V["shvd_m225_rel_err_" + tag] = err.rel;
      if (M == 8) V["shvd_m81_rel_err_over_ldsm_finest_" + tag] = err.rel / rel_finest;
      if (timed) speed["rows"].push(row({"SHVD", "m = " + to_text(int(m)), secs, err.rel}));
    }
  }
  return t;
}

/// The RBF reconstruction of Chapter 2 (eqs. 2.15-2.19) from n_d spiral data sites.
Json rbf_reconstruction(const st::Options& opt, const Setup& S, Json& speed) {
  Json t =
      st::table({"series", "energy", "n_d", "sqrt_nd", "n", "err_inf", "rel_err", "rcond", "seconds", "build_seconds"});
  const EvaluationSet& e = S.eval();
  for (index_t nd : S.nd_list) {
    const SphereSites data = bauer_spiral(nd);
    std::shared_ptr<const SurfaceOperators> ops;
    const double build = st::median_seconds(1, [&] { ops = rbf_operators(data, e.sites, PhsBasis{7, 5}); });
    for (const auto& [sh, shape] : {std::pair{"perturbed", &S.pert}, std::pair{"ellipsoid", &S.ell}}) {
      const std::vector<double> Xd = shape->points(data);
      for (const Energy& en : S.energies) {
        const auto [secs, err] = reconstructed_forces(S, "rbf", *ops, Xd, en.W, exact_forces(*shape, e, en.W));
        t["rows"].push(row({"RBF " + std::string(sh) + " " + en.name, en.name, double(nd), std::sqrt(double(nd)),
                            double(e.size()), err.abs, err.rel, ops->condition_estimate, secs, build}));
        if (shape == &S.pert && en.name == "neo-Hookean")
          speed["rows"].push(row({"RBF", "n_d = " + to_text(nd), secs, err.rel}));
      }
    }
    st::log(opt, "RBF n_d = " + to_text(nd) + " done (operators " + to_text(build) + " s)");
  }
  return t;
}

/// Mean curvature (eq. 76) on the perturbed ellipsoid: SHVD(m) and RBF(n_d).
Json mean_curvature(const Setup& S, Json& V) {
  Json t = st::table({"method", "points", "sqrt_points", "H_err_inf", "H_rel_err"});
  const EvaluationSet& e = S.eval();
  auto H_of = [](const std::vector<Jet>& J, const std::string& cell) {
    std::vector<double> H;
    for (const PointGeometry& g : surface_geometry(J, cell)) H.push_back(g.H);
    return H;
  };
  const std::vector<double> He = H_of(S.pert.jets(e.sites), "exact");
  auto push = [&](const std::string& method, double pts, const SurfaceOperators& ops, const SphereSites& data) {
    const MaxNormError err = max_norm_error(H_of(jets_from_operators(ops, S.pert.points(data)), method), He);
    t["rows"].push(row({method, pts, std::sqrt(pts), err.abs, err.rel}));
    return err.rel;
  };
  for (int M : S.M_list)
    if (const double r = push("SHVD", sh_count(M), *sh_operators(S.md.at(M), e.sites, M), S.md.at(M)); M == 14)
      V["shvd_m225_H_rel_err"] = r;
  for (index_t nd : S.nd_list)
    push("RBF", double(nd), *rbf_operators(bauer_spiral(nd), e.sites, PhsBasis{7, 5}), bauer_spiral(nd));
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_forces", [&]() {
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_forces",
        "Chapter 3 force accuracy: LDSM vs SHVD vs RBF on the ellipsoid and perturbed ellipsoid (Figs. 1-3)");

    // 1. Parameters.
    Setup S(opt.scale == st::Scale::full);
    Json results = st::make_results(opt);
    describe(S, results["parameters"]);
    Json& V = results["values"];
    V["perturbed_Vf"] = S.pert.Vf;
    st::log(opt, "Vf = " + to_text(S.pert.Vf) + " (paper: ~5.14); scale " + st::to_string(opt.scale));

    // 2. Setup: the evaluation sets with their quadrature error, and the interpolation sites.
    Json& T = results["tables"];
    T["evaluation_weights"] = evaluation_sets(opt, S);
    S.Z = unit_sphere_jets(S.eval().sites);
    Json fig1 = st::table({"shape", "x", "y", "z"});
    const EvaluationSet& e529 = S.sets.at({"MD", 529});
    for (const auto& [name, s] : {std::pair{"ellipsoid", &S.ell}, std::pair{"perturbed", &S.pert}}) {
      const std::vector<double> X = s->points(e529.sites);
      for (index_t i = 0, n = e529.size(); i < n; ++i) fig1["rows"].push(row({name, X[i], X[n + i], X[2 * n + i]}));
    }
    T["fig1_shapes"] = fig1;                                           // Fig. 1
    for (int M : S.M_list) S.md[M] = max_determinant_points(M).sites;  // the SHVD interpolation sites

    // 3. Run and measure: Figs. 2-3, the RBF reconstruction, the mean curvature.
    Json speed = st::table({"method", "param", "seconds", "rel_err"});
    Json orders = st::table({"figure", "method", "energy", "points", "fit_order", "fit_order_all_n", "fit_points"});
    for (const auto& [fig, shape] : {std::pair{"fig2_ellipsoid", &S.ell}, std::pair{"fig3_perturbed", &S.pert}}) {
      T[fig] = ldsm_and_shvd(S, fig, *shape, V, speed, orders);
      st::log(opt, std::string(fig) + " done");
    }
    T["rbf_reconstruction"] = rbf_reconstruction(opt, S, speed);
    T["speed_vs_error"] = speed;
    T["ldsm_orders"] = orders;
    T["mean_curvature"] = mean_curvature(S, V);
    st::write_results(opt, results);
    return 0;
  });
}
