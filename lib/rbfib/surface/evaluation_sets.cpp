#include "rbfib/surface/evaluation_sets.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/shapes.hpp"

#include <chrono>
#include <cmath>

namespace rbfib::surface {

namespace {
using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }
}  // namespace

index_t rightmost_site(const SphereSites& sites) {
  index_t best = 0;
  for (index_t i = 1; i < sites.size(); ++i)
    if (std::cos(sites.theta[i]) * std::cos(sites.lambda[i]) > std::cos(sites.theta[best]) * std::cos(sites.lambda[best]))
      best = i;
  return best;
}

EvaluationSet make_evaluation_set(index_t n) {
  require(n >= 4, "evaluation set size n", n, "must be >= 4");
  const auto t0 = clock_type::now();
  EvaluationSet e;
  e.family = "spiral";
  e.sites = bauer_spiral(n);
  if (n % 2 == 1) {
    // Site j = (n + 1)/2 (1-based) has latitude asin(0) = 0 and longitude mod(pi, 2 pi) - pi = 0.
    e.axis_site = (n + 1) / 2 - 1;
    if (e.sites.lambda[e.axis_site] != 0.0 || e.sites.theta[e.axis_site] != 0.0)
      throw NumericalError(Cause::solver, "Bauer spiral of " + to_text(n) + " sites: site " + to_text(e.axis_site) +
                           " is not at (lambda, theta) = (0, 0)");
  } else {
    e.axis_site = rightmost_site(e.sites);  // no site on the x axis (the rightmost lies sqrt(pi / n) from it)
  }
  const RbfWeights q = rbf_sphere_weights(e.sites, 3);
  e.w = q.w;
  e.rcond = q.rcond;
  e.tris = sphere_triangulation(e.sites);
  e.Z = ellipsoid(1, 1, 1).points(e.sites);
  e.seconds = since(t0);
  return e;
}

EvaluationSet make_md_evaluation_set(const std::string& file, int N) {
  const auto t0 = clock_type::now();
  EvaluationSet e;
  e.family = "MD";
  e.sites = read_sphere_sites(file);
  const index_t n = e.sites.size();
  require(n == index_t(N + 1) * (N + 1), file + ": number of sites", n,
          "must be (N+1)^2 = " + to_text((N + 1) * (N + 1)));
  const NnlsWeights q = nnls_sh_weights(e.sites, N);
  if (!(q.residual < 1e-10))
    throw NumericalError(Cause::solver, "eq. (45) weights on " + file + ": NNLS residual " + to_text(q.residual));
  e.w = q.w;
  e.eq45_residual = q.residual;
  e.tris = sphere_triangulation(e.sites);
  e.Z = ellipsoid(1, 1, 1).points(e.sites);
  // The triangle met by the ray of (1, 0, 0): e_x = a A + b B + c C with a, b, c >= 0.
  bool found = false;
  for (const Triangle& t : e.tris) {
    double P[3][3];
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d) P[v][d] = e.Z[d * n + t[v]];
    // Cramer's rule for [A B C] w = e_x.
    auto det3 = [](const double* a, const double* b, const double* c) {
      return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    };
    const double ex[3] = {1, 0, 0};
    const double D = det3(P[0], P[1], P[2]);
    const double w[3] = {det3(ex, P[1], P[2]) / D, det3(P[0], ex, P[2]) / D, det3(P[0], P[1], ex) / D};
    if (w[0] >= 0 && w[1] >= 0 && w[2] >= 0) {
      const double sum = w[0] + w[1] + w[2];
      e.axis_triangle = t;
      for (int v = 0; v < 3; ++v) e.axis_weights[v] = w[v] / sum;
      found = true;
      break;
    }
  }
  if (!found) throw NumericalError(Cause::solver, file + ": no triangle meets the ray of (1, 0, 0)");
  e.seconds = since(t0);
  return e;
}

}  // namespace rbfib::surface
