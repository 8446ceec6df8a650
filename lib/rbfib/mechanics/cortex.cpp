#include "rbfib/mechanics/cortex.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/ldsm.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::mechanics {

CortexLattice cortex_lattice(const std::vector<surface::Triangle>& tris, const std::vector<double>& Z, double k) {
  require(std::isfinite(k) && k >= 0, "cortex stiffness k (dyn/cm)", k, "must be finite and >= 0");
  require(Z.size() % 3 == 0 && Z.size() >= 9, "cortex reference size", Z.size(), "must be 3n with n >= 3");
  CortexLattice L;
  L.n = index_t(Z.size() / 3);
  for (const surface::Triangle& t : tris)
    for (int a = 0; a < 3; ++a) {
      require(t[a] >= 0 && t[a] < L.n, "cortex triangle vertex", t[a], "must lie in [0, " + to_text(L.n) + ")");
      const index_t i = t[a], j = t[(a + 1) % 3];
      L.edges.push_back({std::min(i, j), std::max(i, j)});
    }
  std::sort(L.edges.begin(), L.edges.end());
  L.edges.erase(std::unique(L.edges.begin(), L.edges.end()), L.edges.end());
  L.dA = ldsm_area_weights(tris, Z);
  const std::size_t n = std::size_t(L.n);
  for (const auto& e : L.edges) {
    double l2 = 0;
    for (int d = 0; d < 3; ++d) {
      const double r = Z[d * n + e[0]] - Z[d * n + e[1]];
      l2 += r * r;
    }
    const double dl = std::sqrt(l2);
    require(dl > 0, "cortex edge " + to_text(e[0]) + "-" + to_text(e[1]) + " reference length (cm)", dl, "must be > 0");
    L.length.push_back(dl);
    L.kappa.push_back(8 * k / (3 * dl) * 0.5 * (L.dA[e[0]] + L.dA[e[1]]));  // eq. (100)
  }
  return L;
}

PointForces cortex_forces(const CortexLattice& L, const std::vector<double>& X) {
  require(X.size() == 3 * std::size_t(L.n), "cortex positions size", X.size(), "must be 3 n = " + to_text(3 * L.n));
  const std::size_t n = std::size_t(L.n);
  PointForces out{std::vector<double>(X.size(), 0.0), 0.0};
  for (std::size_t s = 0; s < L.edges.size(); ++s) {
    const std::size_t i = std::size_t(L.edges[s][0]), j = std::size_t(L.edges[s][1]);
    const double c = L.kappa[s] / L.length[s];  // eq. (99): kappa |r| / dl along r / |r|
    double r2 = 0;
    for (int d = 0; d < 3; ++d) {
      const double r = X[d * n + i] - X[d * n + j];
      out.F[d * n + i] -= c * r;
      out.F[d * n + j] += c * r;
      r2 += r * r;
    }
    out.energy += 0.5 * c * r2;
  }
  return out;
}

AdhesionForces adhesion_forces(const std::vector<double>& Xm, const std::vector<double>& Xc, const std::vector<double>& dA,
                               double k_adh, const std::vector<char>& attached) {
  const std::size_t n = dA.size();
  require(std::isfinite(k_adh) && k_adh >= 0, "adhesion stiffness k_adh (dyn/cm^3)", k_adh, "must be finite and >= 0");
  require(Xc.size() == 3 * n, "cortex positions size", Xc.size(), "must be 3 n = " + to_text(3 * n));
  require(Xm.size() == 3 * n, "membrane sites size", Xm.size(), "must equal the cortex's (one link per site): " + to_text(3 * n));
  require(attached.size() == n, "adhesion links size", attached.size(), "must be n = " + to_text(n));
  AdhesionForces out{std::vector<double>(3 * n, 0.0), std::vector<double>(3 * n, 0.0), 0.0};
  for (std::size_t i = 0; i < n; ++i) {
    if (!attached[i]) continue;
    const double c = k_adh * dA[i];
    for (int d = 0; d < 3; ++d) {
      const double r = Xm[d * n + i] - Xc[d * n + i];  // eq. (101): d = X_mem - X_cortex
      out.on_cortex[d * n + i] = c * r;
      out.on_membrane[d * n + i] = -c * r;
      out.energy += 0.5 * c * r * r;
    }
  }
  return out;
}

}  // namespace rbfib::mechanics
