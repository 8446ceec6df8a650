#include "setup.hpp"

#include "common/tables.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/net_force.hpp"
#include "rbfib/surface/quadrature.hpp"

#include <algorithm>

namespace rbfib::forces {

using study::row;

void describe(const Setup& S, Json& P) {
  P["ellipsoid_a"] = 1.1;
  P["ellipsoid_b_c"] = 1 / std::sqrt(1.1);
  P["perturbed_a_b_c_B"] = "0.1, 0.2, 0.2, 0.25";
  P["perturbed_Vf"] = S.pert.Vf;
  P["sigma_K_A_Gs"] = "1 (dimensionless, as the paper)";
  P["reference"] = "unit sphere";
  P["evaluation_sites"] =
      "MD: maximal-determinant-like (reference/point_sets), n = 529, 2025, 4624; "
      "spiral: Bauer spiral (diss. eq. 5.1), n = 529, 2025, 4624 (, 8281 full)";
  P["evaluation_weights"] = "MD: eq. (45) (square system, nonnegative); spiral: eq. (2.22) with phi = r^3";
  P["interpolation_sites"] = "(M+1)^2 sites maximizing |det Y| (gradient ascent from the Bauer spiral)";
  P["shvd_rbf_evaluation"] = "MD, n = " + to_text(S.n_shvd);
  P["rbf_basis"] = "PHS r^7 + real harmonics of degree <= 5";
  P["timing_repeats"] = S.repeats;
}

std::vector<double> exact_forces(const PerturbedEllipsoid& s, const EvaluationSet& e, const EnergyDensity& W) {
  return forces_from_density(elastic_force_density("exact", s.jets(e.sites), unit_sphere_jets(e.sites), W), e.w);
}

namespace {

/// One evaluation set: "MD" (stored sites, eq. 45 weights), "MD_rbf_weights" (the same sites with
/// the weights of eq. 2.22, phi = r^3) or "spiral" (Bauer spiral, eq. 2.22 weights).
EvaluationSet make_set(const study::Options& opt, const Setup& S, const std::string& points, index_t n) {
  if (points == "spiral") return make_evaluation_set(n);
  const int N = int(std::lround(std::sqrt(double(n)))) - 1;
  if (points == "MD")
    return make_md_evaluation_set(study::source_path(opt, "reference/point_sets/max_determinant_N" + to_text(N) + ".txt"),
                                  N);
  EvaluationSet e = S.sets.at({"MD", n});
  const RbfWeights q = rbf_sphere_weights(e.sites, 3);
  e.family = points;
  e.w = q.w;
  e.rcond = q.rcond;
  return e;
}

}  // namespace

Json evaluation_sets(const study::Options& opt, Setup& S) {
  Json t = study::table({"points", "n", "sqrt_n", "min_weight_n_over_4pi", "max_weight_n_over_4pi", "eq45_residual",
                      "rbf_rcond", "force_integral_ellipsoid", "force_integral_perturbed", "seconds"});
  for (const auto& [points, ns] : S.point_sets)
    for (index_t n : ns) {
      EvaluationSet e;
      const double secs = study::median_seconds(1, [&] { e = make_set(opt, S, points, n); });
      double qi[2] = {0, 0};
      for (int k = 0; k < 2; ++k)
        for (const Energy& en : S.energies)
          qi[k] = std::max(qi[k], net_force_inf(exact_forces(k ? S.pert : S.ell, e, en.W)));
      const double scale = double(n) / (4 * pi), wmin = *std::min_element(e.w.begin(), e.w.end()) * scale,
                   wmax = *std::max_element(e.w.begin(), e.w.end()) * scale;
      t["rows"].push(row({points, double(n), std::sqrt(double(n)), wmin, wmax, study::number(e.eq45_residual),
                          points == "MD" ? Json() : Json(e.rcond), qi[0], qi[1], secs}));
      study::log(opt, points + " n = " + to_text(n) + ": force integral " + to_text(qi[0]) + " / " + to_text(qi[1]));
      S.sets.emplace(std::make_pair(points, n), std::move(e));
    }
  return t;
}

}  // namespace rbfib::forces
