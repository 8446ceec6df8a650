// Quadrature on the sphere: the RBF weights of dissertation Chapter 2, Sec. 2.3.3 (eq. 2.22), and
// the nonnegative weights of the paper's eq. (45) on maximal-determinant-like sites (Chapter 3,
// Sec. 2.4.1), the quadratures that turn force densities into forces.
//   eq. (2.22)  [Phi 1; 1^T 0][w; I_phi] = [0; 4 pi], Phi_ij = |chi_i - chi_j|^p on Bauer spirals
//               (diss. eq. 5.1): 3rd order for phi = r, invertible for r^(2k+1), k = 1..4, and -I_phi
//               approximating the constant integral of phi over S^2;
//   eq. (45)    Y^T w = sqrt(4 pi) e_1 on (M+1)^2 sites maximizing |det Y| (L-BFGS from the spiral):
//               an exact nonnegative solution, which the plain spiral lacks from M = 6.
// Errors are those of exp(a . x), exact 4 pi sinh|a| / |a| (surface/sphere_integrals.hpp).
//
// Run:  build/studies/study_chapter2_rbf --scale quick --out runs/chapter2_rbf/quick
//       (quick: n <= 1600; full adds n = 3200)
#include <algorithm>
#include <cmath>

#include "common/study.hpp"
#include "common/tables.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/sphere_integrals.hpp"

using namespace rbfib;
using namespace rbfib::surface;
namespace st = rbfib::study;
using st::Json;
using st::row;

namespace {

/// Eq. (2.22) on spirals of n sites for phi = r^p: the worst error over four directions a, the
/// smallest weight, the conditioning, -I_phi against its exact value, and the time of the solve.
void rbf_quadrature(const st::Options& opt, const std::vector<index_t>& ns, Json& results) {
  Json t = st::table({"power", "n", "sqrt_n", "quad_err", "min_weight", "rcond", "I_phi", "I_phi_rel_err"});
  Json speed = st::table({"power", "n", "seconds", "quad_err"});
  const std::array<double, 3> dirs[4] = {{1, 0, 0}, {0, 0, 1}, {0.6, 0.6, 0.52915026221291817}, {0.3, -0.8, 0.5}};
  bool all_invertible = true;
  std::vector<double> fit_x, fit_e;
  for (int p : {1, 3, 5, 7, 9})
    for (index_t n : ns) {
      const SphereSites s = bauer_spiral(n);
      double err = NAN, wmin = NAN, rc = 0, Iphi = NAN, secs = NAN;
      try {
        RbfWeights q;
        secs = st::median_seconds(1, [&] { q = rbf_sphere_weights(s, p); });
        err = 0;
        for (const auto& a : dirs) err = std::max(err, exp_quadrature_error(s, q.w, a));
        wmin = *std::min_element(q.w.begin(), q.w.end());
        rc = q.rcond;
        Iphi = q.I_phi;
      } catch (const NumericalError& ex) {
        if (p > 1) all_invertible = false;
        st::log(opt, "r^" + to_text(p) + ", n = " + to_text(n) + ": " + ex.what());
      }
      if (p == 1 && !std::isnan(err)) {
        fit_x.push_back(std::sqrt(double(n)));
        fit_e.push_back(err);
      }
      const double exact = sphere_integral_distance_power(p);
      t["rows"].push(row({double(p), double(n), std::sqrt(double(n)), st::number(err), st::number(wmin), rc,
                          st::number(Iphi), st::number(std::abs(-Iphi - exact) / exact)}));
      speed["rows"].push(row({double(p), double(n), st::number(secs), st::number(err)}));
    }
  results["tables"]["rbf_quadrature"] = t;
  results["tables"]["speed_vs_error"] = speed;
  results["values"]["rbf_quadrature_invertible_k1_to_4"] = all_invertible ? 1.0 : 0.0;
  results["values"]["rbf_quadrature_fit_order_phi_r"] = st::power_law_order(fit_x, fit_e);
}

/// Eq. (45) on the spiral and on maximal-determinant-like sites of degree M: log|det Y| before and
/// after, the NNLS residuals, the smallest weight and the error for exp(x).
Json interpolation_sites(const std::vector<int>& Ms) {
  Json t = st::table({"M", "m", "log_det_spiral", "log_det_optimized", "iterations", "nnls_residual_spiral",
                      "nnls_residual_md", "min_weight_md", "quad_err_md", "seconds"});
  for (int M : Ms) {
    MaxDetResult r;
    const double secs = st::median_seconds(1, [&] { r = max_determinant_points(M); });
    const NnlsWeights qs = nnls_sh_weights(bauer_spiral(sh_count(M)), M), qm = nnls_sh_weights(r.sites, M);
    t["rows"].push(
        row({double(M), double(sh_count(M)), r.log_det_start, r.log_det, double(r.iterations), qs.residual, qm.residual,
             *std::min_element(qm.w.begin(), qm.w.end()), exp_quadrature_error(r.sites, qm.w, {1, 0, 0}), secs}));
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter2_rbf", [&] {
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter2_rbf",
        "Quadrature on the sphere: RBF weights (eq. 2.22) on spirals, NNLS weights (eq. 45) on MD sites");

    // 1. Parameters.
    const std::vector<index_t> ns = opt.scale == st::Scale::full ? std::vector<index_t>{100, 200, 400, 800, 1600, 3200}
                                                                 : std::vector<index_t>{100, 200, 400, 800, 1600};
    const std::vector<int> Ms = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14};  // m = 4 .. 225
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["rbf_quadrature_sites"] = "Bauer spiral (diss. eq. 5.1), n = 100 .. 1600 (3200 full)";
    P["rbf_quadrature_powers"] = "phi = r^p, p = 1, 3, 5, 7, 9";
    P["test_functions"] = "exp(a . x), a = (1,0,0), (0,0,1), (0.6,0.6,0.529), (0.3,-0.8,0.5); exact 4 pi sinh|a|/|a|";
    P["interpolation_sites"] = "(M+1)^2 sites maximizing |det Y| (gradient ascent from the Bauer spiral), M = 1..14";

    // 2. Run and measure.
    rbf_quadrature(opt, ns, results);
    st::log(opt, "RBF quadrature done");
    results["tables"]["interpolation_sites"] = interpolation_sites(Ms);
    st::log(opt, "maximal-determinant sites built for M = 1.." + to_text(Ms.back()));
    st::write_results(opt, results);
    return 0;
  });
}
