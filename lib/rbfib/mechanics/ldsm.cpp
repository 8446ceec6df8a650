#include "rbfib/mechanics/ldsm.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/force_kernels.hpp"

#include <cmath>

namespace rbfib::mechanics {

namespace {
/// Edge vectors of triangle t; P holds n points as P[d n + i].
void edges(const std::vector<double>& P, const surface::Triangle& t, double u[2][3]) {
  const std::size_t n = P.size() / 3;
  for (std::size_t d = 0; d < 3; ++d) {
    u[0][d] = P[d * n + t[0]] - P[d * n + t[2]];
    u[1][d] = P[d * n + t[1]] - P[d * n + t[2]];
  }
}
void gram(const double u[2][3], double G[2][2]) {
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) G[a][b] = surface::dot3(u[a], u[b]);
}
}  // namespace

LdsmResult ldsm_forces(const std::string& cell, const std::vector<surface::Triangle>& tris,
                       const std::vector<double>& Z, const std::vector<double>& X, const EnergyDensity& energy) {
  return ldsm_forces(cell, tris, Z, X, std::vector<EnergyDensity>{energy});
}

LdsmResult ldsm_forces(const std::string& cell, const std::vector<surface::Triangle>& tris,
                       const std::vector<double>& Z, const std::vector<double>& X, const std::vector<EnergyDensity>& energies) {
  require(X.size() == Z.size(), "cell '" + cell + "' current points size", X.size(),
          "must equal reference size " + to_text(Z.size()));
  LdsmResult r;
  r.F.assign(X.size(), 0.0);
  const index_t nv = static_cast<index_t>(X.size() / 3);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (index_t v : tris[t])
      if (v < 0 || v >= nv)  // (the message is built only on failure: this loop is the hot path)
        throw InputError("cell '" + cell + "' triangle " + to_text(t) + " vertex", to_text(v), "out of range");
    double u[2][3], u0[2][3], G[2][2], G0[2][2];
    edges(X, tris[t], u);
    edges(Z, tris[t], u0);
    gram(u, G);
    gram(u0, G0);
    const double det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
    const double det0 = G0[0][0] * G0[1][1] - G0[0][1] * G0[1][0];
    if (!(det > 0) || !(det0 > 0))
      throw NumericalError(Cause::degenerate_site, "cell '" + cell + "': LDSM triangle " + to_text(t) + " is degenerate (det G = " +
                           to_text(det) + ", det G0 = " + to_text(det0) + ", both must be > 0)");
    double n[3], n0[3];
    surface::cross3(u[0], u[1], n);
    surface::cross3(u0[0], u0[1], n0);
    if (!(surface::dot3(n, n0) > 0))
      throw NumericalError(Cause::inverted_cell, "cell '" + cell + "': LDSM triangle " + to_text(t) + " is inverted");
    double Gi[2][2], G0i[2][2];
    inverse2(G, det, Gi);
    inverse2(G0, det0, G0i);
    const double J2 = det / det0;
    InvariantDerivatives w{0, 0, 0, 0, 0, 0, true};
    for (const EnergyDensity& e : energies) {
      const InvariantDerivatives we = e.evaluate(trace_ab(G, G0i) - 2, J2 - 1);
      if (!we.valid)
        throw NumericalError(Cause::inverted_cell, "cell '" + cell + "': LDSM triangle " + to_text(t) + ": energy undefined (det C <= 0)");
      w.W += we.W, w.W1 += we.W1, w.W2 += we.W2;
    }
    const double A0 = 0.5 * std::sqrt(det0);
    r.energy += w.W * A0;
    double dW[2][3] = {{0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double S = 2 * w.W1 * G0i[a][b] + 2 * w.W2 * J2 * Gi[a][b];
        for (int d = 0; d < 3; ++d) dW[a][d] += S * u[b][d];
      }
    for (int d = 0; d < 3; ++d) {
      r.F[d * nv + tris[t][0]] -= A0 * dW[0][d];
      r.F[d * nv + tris[t][1]] -= A0 * dW[1][d];
      r.F[d * nv + tris[t][2]] += A0 * (dW[0][d] + dW[1][d]);
    }
  }
  for (double f : r.F)
    if (!std::isfinite(f)) throw NumericalError(Cause::non_finite, "cell '" + cell + "': non-finite LDSM force");
  return r;
}

std::vector<double> ldsm_area_weights(const std::vector<surface::Triangle>& tris, const std::vector<double>& Z) {
  std::vector<double> w(Z.size() / 3, 0.0);
  for (const auto& t : tris) {
    double u[2][3], n[3];
    edges(Z, t, u);
    surface::cross3(u[0], u[1], n);
    const double A = 0.5 * std::sqrt(surface::dot3(n, n));
    for (index_t v : t) w[v] += A / 3;
  }
  return w;
}

}  // namespace rbfib::mechanics
