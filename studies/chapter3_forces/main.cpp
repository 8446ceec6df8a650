// Chapter 3 force-accuracy study (the JCP 2018 paper, Sec. 4.1, Figs. 1-3), with the same
// experiment for the RBF reconstruction of Chapter 2 (Sec. 2.3) and the RBF quadrature claims of
// Sec. 2.3.3.
//
// Reproduces:
//   Fig. 1  the ellipsoid (eq. 88) and perturbed ellipsoid (eq. 89) with n = 529 evaluation sites;
//   Fig. 2  LDSM and SHVD force errors on the ellipsoid a = 1.1, b = c = 1/sqrt(1.1), reference the
//           unit sphere, sigma = K = A = Gs = 1: LDSM ~2nd order in sqrt(n), SHVD exact;
//   Fig. 3  the same on the perturbed ellipsoid: LDSM between 1st and 2nd order, SHVD spectral in m;
//   plus    the RBF (PHS r^7 + harmonics of degree 5) reconstruction against n_d, the RBF
//           quadrature of eq. (2.22) (3rd order for phi = r, invertible for r^(2k+1), k = 1..4),
//           maximal-determinant-like points and their NNLS weights (eq. 45), mean curvature (eq. 76)
//           against m and n_d, and force-evaluation
//           time against force error for SHVD(m), RBF(n_d) and LDSM(n).
//
// Run:  build/studies/study_chapter3_forces --scale quick --out runs/chapter3_forces/quick
//       (or python3 -m harness run chapter3_forces --scale quick). Quick scale: n <= 4624,
//       m <= 225, n_d <= 800; full scale adds n = 8281 and n_d = 1600.
//
// Conventions (see reference/chapter3_forces.yaml): the exact force is F^_E,i = F_E(X_i) dA0_i with
// F_E from eq. (35) on the exact map (88)/(89) and dA0 the evaluation sites' quadrature weights; the
// error is max_i ||F^ - F^_E||_inf (eqs. 90-91), also divided by max_i ||F^_E,i||_inf.
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/mechanics/shell.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/shapes.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

using namespace rbfib;
using namespace rbfib::surface;
using namespace rbfib::mechanics;
namespace st = rbfib::study;
using rbfib::study::Json;

namespace {
constexpr double pi = 3.14159265358979323846;

Json::Array row(std::initializer_list<Json> xs) { return Json::Array(xs); }

using rbfib::study::table;

struct ErrorNorms {
  double abs = 0;  ///< max_i ||F^_i - F^_E,i||_inf (eqs. 90-91)
  double rel = 0;  ///< abs / max_i ||F^_E,i||_inf
};

ErrorNorms force_error(const std::vector<double>& F, const std::vector<double>& Fe) {
  ErrorNorms e;
  double scale = 0;
  for (std::size_t i = 0; i < F.size(); ++i) {
    e.abs = std::max(e.abs, std::abs(F[i] - Fe[i]));
    scale = std::max(scale, std::abs(Fe[i]));
  }
  e.rel = e.abs / scale;
  return e;
}

/// |sum_i F^_i|_inf: the quadrature error of a translation-invariant force (paper Sec. 4.1).
double force_integral(const std::vector<double>& F) {
  double s[3] = {0, 0, 0};
  for (std::size_t i = 0; i < F.size(); ++i) s[i % 3] += F[i];
  return std::max({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])});
}

/// An evaluation set: Bauer spiral sites, RBF quadrature weights (eq. 2.22), triangulation.
struct EvalSet {
  index_t n = 0;
  SphereSites sites;
  std::vector<double> w;
  double min_weight = 0, rcond = 0;
  std::vector<Triangle> tris;
  std::vector<Jet> Z;
  std::vector<double> Zpts;
};

EvalSet make_eval_set(index_t n, int weight_power) {
  EvalSet e;
  e.n = n;
  e.sites = bauer_spiral(n);
  const RbfWeights q = rbf_sphere_weights(e.sites, weight_power);
  e.w = q.w;
  e.rcond = q.rcond;
  e.min_weight = *std::min_element(e.w.begin(), e.w.end());
  e.tris = sphere_triangulation(e.sites);
  e.Z = unit_sphere_jets(e.sites);
  e.Zpts = unit_sphere_points(e.sites);
  return e;
}

/// Least-squares slope p of log(err) = c - p log(x): the paper's "power-law fit" (Figs. 2-3).
double power_law_order(const std::vector<double>& x, const std::vector<double>& e) {
  const std::size_t n = x.size();
  if (n < 2) return NAN;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += std::log(x[i]) / n;
    my += std::log(e[i]) / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(e[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return -sxy / sxx;
}

struct Energy {
  std::string name;
  EnergyDensity W;
};

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_forces", [&]() {
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_forces",
        "Chapter 3 force accuracy: LDSM vs SHVD vs RBF on the ellipsoid and perturbed ellipsoid (Figs. 1-3)");
    const bool full = opt.scale == st::Scale::full;

    // ---- 1. Parameters -----------------------------------------------------------------------
    const std::vector<index_t> n_list = full ? std::vector<index_t>{529, 2025, 4624, 8281}
                                             : std::vector<index_t>{529, 2025, 4624};
    const index_t n_shvd = n_list.back();  // evaluation sites for the SHVD and RBF sweeps
    const std::vector<int> M_list = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14};  // m = 4 .. 225
    const std::vector<index_t> nd_list = full ? std::vector<index_t>{100, 200, 400, 800, 1600}
                                              : std::vector<index_t>{100, 200, 400, 800};
    const std::vector<index_t> quad_n = full ? std::vector<index_t>{100, 200, 400, 800, 1600, 3200}
                                             : std::vector<index_t>{100, 200, 400, 800, 1600};
    const int weight_power = 3;  // eq. (2.22) with phi = r^3 for the evaluation weights
    const double a_ell = 1.1, b_ell = 1 / std::sqrt(1.1);
    const PerturbedEllipsoid ell = ellipsoid(a_ell, b_ell, b_ell);
    const PerturbedEllipsoid pert = paper_perturbed_ellipsoid();
    const std::vector<Energy> energies = {{"tension", EnergyDensity::surface_tension(1.0)},
                                          {"neo-Hookean", EnergyDensity::neo_hookean_paper(1.0, 1.0)}};
    const int repeats = 11;

    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["ellipsoid_a"] = a_ell;
    P["ellipsoid_b_c"] = b_ell;
    P["perturbed_a_b_c_B"] = "0.1, 0.2, 0.2, 0.25";
    P["perturbed_Vf"] = pert.Vf;
    P["sigma_K_A_Gs"] = "1 (dimensionless, as the paper)";
    P["reference"] = "unit sphere";
    P["evaluation_sites"] = "Bauer spiral (diss. eq. 5.1), n = 529, 2025, 4624 (, 8281 full)";
    P["evaluation_weights"] = "RBF quadrature eq. (2.22) with phi = r^3";
    P["interpolation_sites"] = "(M+1)^2 sites maximizing |det Y| (gradient ascent from the Bauer spiral)";
    P["shvd_rbf_evaluation_n"] = static_cast<double>(n_shvd);
    P["rbf_basis"] = "PHS r^7 + real harmonics of degree <= 5";
    P["timing_repeats"] = repeats;
    results["values"]["perturbed_Vf"] = pert.Vf;
    st::log(opt, "Vf = " + to_text(pert.Vf) + " (paper: ~5.14); scale " + st::to_string(opt.scale));
    Json& T = results["tables"];
    Json& V = results["values"];

    // ---- 2. Evaluation sets and their quadrature error ----------------------------------------
    std::map<index_t, EvalSet> sets;
    Json weights_table = table({"n", "sqrt_n", "min_weight", "rcond", "force_integral_ellipsoid",
                                "force_integral_perturbed", "seconds"},
                               {"", "", "", "", "", "", "s"});
    std::vector<index_t> all_n = n_list;
    if (std::find(all_n.begin(), all_n.end(), n_shvd) == all_n.end()) all_n.push_back(n_shvd);
    double worst_quad = 0;
    for (index_t n : all_n) {
      const auto t0 = std::chrono::steady_clock::now();
      sets.emplace(n, make_eval_set(n, weight_power));
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const EvalSet& e = sets.at(n);
      double qi[2] = {0, 0};
      int k = 0;
      for (const PerturbedEllipsoid* s : {&ell, &pert}) {
        for (const auto& en : energies)
          qi[k] = std::max(qi[k], force_integral(forces_from_density(
                                      elastic_force_density("exact", s->jets(e.sites), e.Z, en.W), e.w)));
        ++k;
      }
      worst_quad = std::max({worst_quad, qi[0], qi[1]});
      weights_table["rows"].push(row({double(n), std::sqrt(double(n)), e.min_weight, e.rcond, qi[0], qi[1], secs}));
      st::log(opt, "eval set n = " + to_text(n) + ": min weight " + to_text(e.min_weight) + ", force integral " +
                       to_text(qi[0]) + " / " + to_text(qi[1]) + " (" + to_text(secs) + " s)");
    }
    T["evaluation_weights"] = weights_table;
    V["max_force_integral"] = worst_quad;

    // ---- 3. Fig. 1: the shapes at n = 529 -----------------------------------------------------
    {
      Json t = table({"shape", "x", "y", "z"}, {"", "", "", ""});
      const EvalSet& e = sets.at(529);
      for (const auto& [name, s] : std::vector<std::pair<std::string, const PerturbedEllipsoid*>>{
               {"ellipsoid", &ell}, {"perturbed", &pert}}) {
        const std::vector<double> X = s->points(e.sites);
        for (index_t i = 0; i < e.n; ++i) t["rows"].push(row({name, X[3 * i], X[3 * i + 1], X[3 * i + 2]}));
      }
      T["fig1_shapes"] = t;
    }

    // ---- 4. Interpolation sites (maximal determinant) and their NNLS weights (eq. 45) ---------
    std::map<int, SphereSites> md;
    {
      Json t = table({"M", "m", "log_det_spiral", "log_det_optimized", "iterations", "nnls_residual_spiral",
                      "nnls_residual_md", "min_weight_md", "quad_err_md", "seconds"},
                     {"", "", "", "", "", "", "", "", "", "s"});
      for (int M : M_list) {
        const auto t0 = std::chrono::steady_clock::now();
        const MaxDetResult r = max_determinant_points(M);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        md[M] = r.sites;
        const NnlsWeights qs = nnls_sh_weights(bauer_spiral(sh_count(M)), M);
        const NnlsWeights qm = nnls_sh_weights(r.sites, M);
        // quadrature error for f = exp(x): exact 4 pi sinh(1)
        double I = 0;
        for (index_t i = 0; i < r.sites.size(); ++i)
          I += qm.w[i] * std::exp(std::cos(r.sites.lambda[i]) * std::cos(r.sites.theta[i]));
        t["rows"].push(row({double(M), double(sh_count(M)), r.log_det_start, r.log_det, double(r.iterations),
                            qs.residual, qm.residual, *std::min_element(qm.w.begin(), qm.w.end()),
                            std::abs(I - 4 * pi * std::sinh(1.0)), secs}));
      }
      T["interpolation_sites"] = t;
      st::log(opt, "maximal-determinant sites built for M = 1.." + to_text(M_list.back()));
    }

    // ---- 5. Figs. 2-3: LDSM against n, SHVD against m -----------------------------------------
    Json speed = table({"method", "param", "seconds", "rel_err"}, {"", "", "s", ""});
    Json orders = table({"figure", "method", "energy", "fit_order", "fit_order_all_n", "fit_points"}, {"", "", "", "", "", ""});
    for (const auto& [fig, shape] : std::vector<std::pair<std::string, const PerturbedEllipsoid*>>{
             {"fig2_ellipsoid", &ell}, {"fig3_perturbed", &pert}}) {
      Json t = table({"series", "method", "energy", "n", "m", "sqrt_points", "err_inf", "rel_err", "quad_err",
                      "seconds"},
                     {"", "", "", "", "", "", "", "", "", "s"});
      for (const auto& en : energies) {
        std::vector<double> xs_all, es_all, xs_ok, es_ok;
        double rel_finest = 0;
        for (index_t n : n_list) {  // LDSM
          const EvalSet& e = sets.at(n);
          const std::vector<double> Fe =
              forces_from_density(elastic_force_density("exact", shape->jets(e.sites), e.Z, en.W), e.w);
          const std::vector<double> X = shape->points(e.sites);
          LdsmResult r;
          const double secs = st::median_seconds(repeats, [&] { r = ldsm_forces(fig, e.tris, e.Zpts, X, en.W); });
          const ErrorNorms err = force_error(r.F, Fe);
          const double quad = force_integral(Fe);
          t["rows"].push(row({"LDSM " + en.name, "LDSM", en.name, double(n), Json(), std::sqrt(double(n)), err.abs,
                              err.rel, quad, secs}));
          rel_finest = err.rel;
          xs_all.push_back(std::sqrt(double(n)));
          es_all.push_back(err.abs);
          if (quad < 0.1 * err.abs) {  // the paper's criterion: quadrature error negligible (Sec. 4.1)
            xs_ok.push_back(std::sqrt(double(n)));
            es_ok.push_back(err.abs);
          }
          if (fig == "fig3_perturbed" && en.name == "neo-Hookean")
            speed["rows"].push(row({"LDSM", "n = " + to_text(n), secs, err.rel}));
        }
        const std::string tag = (fig == "fig2_ellipsoid" ? "fig2_" : "fig3_") +
                                std::string(en.name == "tension" ? "tension" : "neo_hookean");
        V["ldsm_fit_order_all_" + tag] = power_law_order(xs_all, es_all);
        V["ldsm_fit_order_" + tag] = power_law_order(xs_ok, es_ok);
        V["ldsm_fit_points_" + tag] = double(xs_ok.size());
        orders["rows"].push(row({fig == "fig2_ellipsoid" ? "Fig. 2" : "Fig. 3(a)", "LDSM", en.name,
                                 power_law_order(xs_ok, es_ok), power_law_order(xs_all, es_all),
                                 double(xs_ok.size())}));
        V["ldsm_rel_err_finest_" + tag] = rel_finest;
        const EvalSet& e = sets.at(n_shvd);
        const std::vector<double> Fe =
            forces_from_density(elastic_force_density("exact", shape->jets(e.sites), e.Z, en.W), e.w);
        for (int M : M_list) {  // SHVD
          if (fig == "fig2_ellipsoid" && M > 4) break;  // exact from M = 1; a few m suffice
          auto ops = sh_operators(md.at(M), e.sites, M);
          const std::vector<double> Xd = shape->points(md.at(M));
          std::vector<double> F;
          const double secs = st::median_seconds(repeats, [&] {
            F = forces_from_density(elastic_force_density(fig, jets_from_operators(*ops, Xd), e.Z, en.W), e.w);
          });
          const ErrorNorms err = force_error(F, Fe);
          const double m = sh_count(M);
          t["rows"].push(row({"SHVD " + en.name, "SHVD", en.name, double(n_shvd), m, std::sqrt(m), err.abs, err.rel,
                              force_integral(Fe), secs}));
          if (M == 8) V["shvd_m81_rel_err_" + tag] = err.rel;
          if (M == 14) V["shvd_m225_rel_err_" + tag] = err.rel;
          if (M == 8) V["shvd_m81_rel_err_over_ldsm_finest_" + tag] = err.rel / rel_finest;
          if (fig == "fig3_perturbed" && en.name == "neo-Hookean")
            speed["rows"].push(row({"SHVD", "m = " + to_text(int(m)), secs, err.rel}));
        }
      }
      T[fig] = t;
      st::log(opt, fig + " done");
    }

    // ---- 6. The RBF reconstruction (Chapter 2) on the perturbed ellipsoid ---------------------
    {
      Json t = table({"series", "energy", "n_d", "sqrt_nd", "n", "err_inf", "rel_err", "rcond", "seconds",
                      "build_seconds"},
                     {"", "", "", "", "", "", "", "", "s", "s"});
      const EvalSet& e = sets.at(n_shvd);
      for (index_t nd : nd_list) {
        const SphereSites data = bauer_spiral(nd);
        const auto t0 = std::chrono::steady_clock::now();
        auto ops = rbf_operators(data, e.sites, PhsBasis{7, 5});
        const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (const PerturbedEllipsoid* shape : {&pert, &ell}) {
          const std::vector<double> Xd = shape->points(data);
          for (const auto& en : energies) {
            const std::vector<double> Fe =
                forces_from_density(elastic_force_density("exact", shape->jets(e.sites), e.Z, en.W), e.w);
            std::vector<double> F;
            const double secs = st::median_seconds(repeats, [&] {
              F = forces_from_density(elastic_force_density("rbf", jets_from_operators(*ops, Xd), e.Z, en.W), e.w);
            });
            const ErrorNorms err = force_error(F, Fe);
            const std::string sh = shape == &pert ? "perturbed" : "ellipsoid";
            t["rows"].push(row({"RBF " + sh + " " + en.name, en.name, double(nd), std::sqrt(double(nd)),
                                double(e.n), err.abs, err.rel, ops->condition_estimate, secs, build}));
            if (shape == &pert && en.name == "neo-Hookean")
              speed["rows"].push(row({"RBF", "n_d = " + to_text(nd), secs, err.rel}));
          }
        }
        st::log(opt, "RBF n_d = " + to_text(nd) + " done (operators " + to_text(build) + " s)");
      }
      T["rbf_reconstruction"] = t;
    }
    T["speed_vs_error"] = speed;
    T["ldsm_orders"] = orders;

    // ---- 7. Mean curvature (eq. 76) on the perturbed ellipsoid: SHVD(m) and RBF(n_d) ----------
    {
      Json t = table({"method", "points", "sqrt_points", "H_err_inf", "H_rel_err"}, {"", "", "", "", ""});
      const EvalSet& e = sets.at(n_shvd);
      const std::vector<PointGeometry> ge = surface_geometry(pert.jets(e.sites), "exact");
      auto push = [&](const std::string& method, double pts, const std::vector<Jet>& J) {
        const std::vector<PointGeometry> g = surface_geometry(J, method);
        double err = 0, scale = 0;
        for (std::size_t i = 0; i < g.size(); ++i) {
          err = std::max(err, std::abs(g[i].H - ge[i].H));
          scale = std::max(scale, std::abs(ge[i].H));
        }
        t["rows"].push(row({method, pts, std::sqrt(pts), err, err / scale}));
        return err / scale;
      };
      for (int M : M_list) {
        auto ops = sh_operators(md.at(M), e.sites, M);
        const double r = push("SHVD", sh_count(M), jets_from_operators(*ops, pert.points(md.at(M))));
        if (M == 14) V["shvd_m225_H_rel_err"] = r;
      }
      for (index_t nd : nd_list) {
        const SphereSites data = bauer_spiral(nd);
        auto ops = rbf_operators(data, e.sites, PhsBasis{7, 5});
        push("RBF", double(nd), jets_from_operators(*ops, pert.points(data)));
      }
      T["mean_curvature"] = t;
      st::log(opt, "mean curvature done");
    }

    // ---- 8. RBF quadrature on the sphere (eq. 2.22) -------------------------------------------
    {
      Json t = table({"power", "n", "sqrt_n", "quad_err", "min_weight", "rcond", "I_phi", "I_phi_rel_err"},
                     {"", "", "", "", "", "", "", ""});
      bool all_invertible = true;
      std::vector<double> fit_x, fit_e;
      for (int p : {1, 3, 5, 7, 9}) {
        for (index_t n : quad_n) {
          const SphereSites s = bauer_spiral(n);
          double err = NAN, wmin = NAN, rc = 0, Iphi = NAN;
          try {
            const RbfWeights q = rbf_sphere_weights(s, p);
            // worst error over f = exp(a . x) for four directions a (exact: 4 pi sinh|a| / |a|)
            const double dirs[4][3] = {{1, 0, 0}, {0, 0, 1}, {0.6, 0.6, 0.52915026221291817}, {0.3, -0.8, 0.5}};
            err = 0;
            for (const auto& a : dirs) {
              const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
              double I = 0;
              for (index_t i = 0; i < n; ++i) {
                double x[3];
                unit_sphere_point(s.lambda[i], s.theta[i], x);
                I += q.w[i] * std::exp(a[0] * x[0] + a[1] * x[1] + a[2] * x[2]);
              }
              err = std::max(err, std::abs(I - 4 * pi * std::sinh(na) / na));
            }
            wmin = *std::min_element(q.w.begin(), q.w.end());
            rc = q.rcond;
            Iphi = q.I_phi;
          } catch (const NumericalError& ex) {
            if (p > 1) all_invertible = false;
            st::log(opt, std::string("r^") + to_text(p) + ", n = " + to_text(n) + ": " + ex.what());
          }
          if (p == 1 && !std::isnan(err)) {
            fit_x.push_back(std::sqrt(double(n)));
            fit_e.push_back(err);
          }
          // exact: int_{S^2} |x - y|^p dA(x) = 2 pi int_0^2 r^(p+1) dr = 2 pi 2^(p+2) / (p+2)
          const double exact = 2 * pi * std::pow(2.0, p + 2) / (p + 2);
          t["rows"].push(row({double(p), double(n), std::sqrt(double(n)), std::isnan(err) ? Json() : Json(err),
                              std::isnan(wmin) ? Json() : Json(wmin), rc, std::isnan(Iphi) ? Json() : Json(Iphi),
                              std::isnan(Iphi) ? Json() : Json(std::abs(-Iphi - exact) / exact)}));
        }
      }
      T["rbf_quadrature"] = t;
      V["rbf_quadrature_invertible_k1_to_4"] = all_invertible ? 1.0 : 0.0;
      V["rbf_quadrature_fit_order_phi_r"] = power_law_order(fit_x, fit_e);
      st::log(opt, "RBF quadrature done");
    }

    st::write_results(opt, results);
    return 0;
  });
}
