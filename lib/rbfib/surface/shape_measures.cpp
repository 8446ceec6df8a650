#include "rbfib/surface/shape_measures.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/surface/geometry_kernels.hpp"

#include <algorithm>

namespace rbfib::surface {

std::vector<double> vertex_normals(const std::vector<Triangle>& tris, const std::vector<double>& X) {
  const std::size_t n = X.size() / 3;
  std::vector<double> N(3 * n, 0.0);
  for (const Triangle& t : tris) {
    double e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = X[k * n + t[1]] - X[k * n + t[0]];
      e2[k] = X[k * n + t[2]] - X[k * n + t[0]];
    }
    cross3(e1, e2, nn);
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) N[k * n + t[v]] += nn[k];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::sqrt(N[i] * N[i] + N[n + i] * N[n + i] + N[2 * n + i] * N[2 * n + i]);
    for (int k = 0; k < 3; ++k) N[k * n + i] = s > 0 ? N[k * n + i] / s : 0.0;
  }
  return N;
}

AlphaBands alpha_bands(const SphereSites& sites) {
  const std::size_t n = sites.lambda.size();
  const int bands = std::max(8, int(std::lround(std::sqrt(double(n)) / 2.5)));
  const double lo = 15 * pi / 180, hi = 165 * pi / 180;
  AlphaBands b{std::vector<double>(n), std::vector<std::vector<std::size_t>>(bands)};
  for (std::size_t i = 0; i < n; ++i) {
    b.alpha[i] = std::acos(std::max(-1.0, std::min(1.0, std::cos(sites.lambda[i]) * std::cos(sites.theta[i]))));
    if (b.alpha[i] >= lo && b.alpha[i] <= hi)
      b.members[std::min(bands - 1, int((b.alpha[i] - lo) / (hi - lo) * bands))].push_back(i);
  }
  return b;
}

std::vector<double> band_residuals(const AlphaBands& bands, const std::vector<double>& q) {
  std::vector<double> r(q.size(), NAN);
  for (const auto& mem : bands.members) {
    if (mem.size() < 4) continue;
    double sa = 0, saa = 0, sq = 0, saq = 0;
    for (std::size_t i : mem) {
      const double a = bands.alpha[i];
      sa += a;
      saa += a * a;
      sq += q[i];
      saq += a * q[i];
    }
    const double N = double(mem.size()), b = (N * saq - sa * sq) / (N * saa - sa * sa), a = (sq - b * sa) / N;
    for (std::size_t i : mem) r[i] = q[i] - (a + b * bands.alpha[i]);
  }
  return r;
}

double band_rms(const AlphaBands& bands, const std::vector<double>& r) {
  double s2 = 0;
  std::size_t count = 0;
  for (const auto& mem : bands.members) {
    if (mem.size() < 4) continue;
    for (std::size_t i : mem) s2 += r[i] * r[i];
    count += mem.size();
  }
  return count ? std::sqrt(s2 / double(count)) : NAN;
}

Axisymmetry axisymmetry(const std::vector<double>& X, const std::vector<double>& normal, const AlphaBands& bands,
                        const std::vector<Triangle>& tris, const std::array<double, 3>& c, double tau) {
  const std::size_t n = X.size() / 3;
  std::vector<double> rho(n), nrho(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double dy = X[n + i] - c[1], dz = X[2 * n + i] - c[2];
    rho[i] = std::sqrt(dy * dy + dz * dz);
    nrho[i] = rho[i] > 0 ? (normal[n + i] * dy + normal[2 * n + i] * dz) / rho[i] : 0;
  }
  const std::vector<double> dx = band_residuals(bands, std::vector<double>(X.begin(), X.begin() + std::ptrdiff_t(n)));
  const std::vector<double> dr = band_residuals(bands, rho);
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = dx[i] * normal[i] + dr[i] * nrho[i];
  Axisymmetry a;
  a.rms = band_rms(bands, d);
  a.max = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(d[i])) a.max = std::max(a.max, std::abs(d[i]));
  std::vector<std::vector<index_t>> nb(n);
  for (const Triangle& t : tris)
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        if (p != q) nb[t[p]].push_back(t[q]);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(d[i]) || !(d[i] > tau)) continue;
    bool top = true;
    for (index_t j : nb[i]) top = top && !(std::isfinite(d[j]) && d[j] > d[i]);
    a.bumps += top;
  }
  return a;
}

double edge_jump(const std::vector<double>& q, const std::vector<Triangle>& tris) {
  double s = 0;
  for (const Triangle& t : tris)
    for (int p = 0; p < 3; ++p) s += std::abs(q[t[p]] - q[t[(p + 1) % 3]]);
  return tris.empty() ? NAN : s / (3.0 * double(tris.size()));
}

std::vector<std::size_t> facing_sites(const std::vector<double>& X, const std::vector<double>& normal,
                                      const std::array<double, 3>& c, int s) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < X.size() / 3; ++i)
    if (s * normal[i] > std::cos(pi / 4) && s * X[i] > s * c[0]) out.push_back(i);
  return out;
}

Spread spread(const std::vector<double>& q, const std::vector<std::size_t>& sites) {
  Spread r;
  double s = 0, s2 = 0;
  int npos = 0, count = 0;
  for (std::size_t i : sites) {
    if (!std::isfinite(q[i])) continue;
    s += q[i];
    s2 += q[i] * q[i];
    npos += q[i] > 0;
    ++count;
  }
  r.count = count;
  if (count < 2) return r;
  r.mean = s / count;
  r.std = std::sqrt(std::max(0.0, s2 / count - r.mean * r.mean));
  r.cv = r.std / std::abs(r.mean);
  r.positive = double(npos) / count;
  return r;
}

}  // namespace rbfib::surface
