#include "measures.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::blebbing {

std::vector<std::array<double, 2>> section_x(const std::vector<double>& X, const std::vector<surface::Triangle>& tris, double x0) {
  const std::size_t n = X.size() / 3;
  std::vector<std::array<double, 2>> out;
  for (const surface::Triangle& t : tris)
    for (int a = 0; a < 3; ++a) {
      const std::size_t i = std::size_t(t[a]), j = std::size_t(t[(a + 1) % 3]);
      const double si = X[i] - x0, sj = X[j] - x0;
      if ((si < 0) == (sj < 0) || si == sj) continue;
      const double w = si / (si - sj);  // the crossing along the edge i -> j
      out.push_back({X[n + i] + w * (X[n + j] - X[n + i]), X[2 * n + i] + w * (X[2 * n + j] - X[2 * n + i])});
    }
  return out;
}

std::vector<double> ldsm_signed_curvature(const std::vector<double>& X, const std::vector<surface::Triangle>& tris) {
  const std::size_t n = X.size() / 3;
  std::vector<double> H = surface::edge_mean_curvature(tris, X), p(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) p[3 * i + d] = X[d * n + i];
  std::vector<char> on_hull(n, 0);
  for (const surface::Triangle& t : surface::convex_hull(p))
    for (index_t v : t) on_hull[std::size_t(v)] = 1;
  for (std::size_t i = 0; i < n; ++i) H[i] = on_hull[i] ? -H[i] : H[i];
  return H;
}

std::vector<CurvatureBand> curvature_by_angle(const std::vector<double>& X, const std::vector<double>& H,
                                              const std::array<double, 3>& c, int bands) {
  const std::size_t n = H.size();
  const double pi = 3.141592653589793, width = pi / bands;
  std::vector<CurvatureBand> out(std::size_t(bands), CurvatureBand{0, 0, INFINITY, -INFINITY});
  std::vector<int> count(std::size_t(bands), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = std::hypot(X[i] - c[0], X[n + i] - c[1], X[2 * n + i] - c[2]);
    const double phi = std::acos(std::clamp((X[2 * n + i] - c[2]) / r, -1.0, 1.0));
    const std::size_t b = std::min(std::size_t(phi / width), std::size_t(bands - 1));
    out[b].mean += H[i];
    out[b].min = std::min(out[b].min, H[i]);
    out[b].max = std::max(out[b].max, H[i]);
    ++count[b];
  }
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b].angle_deg = (double(b) + 0.5) * width * 180 / pi;
    out[b].mean = count[b] > 0 ? out[b].mean / count[b] : NAN;
    if (count[b] == 0) out[b].min = out[b].max = NAN;
  }
  return out;
}

}  // namespace rbfib::blebbing
