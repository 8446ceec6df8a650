#include "rbfib/surface/contact.hpp"
#include "rbfib/core/constants.hpp"

#include <cmath>

namespace rbfib::surface {

double winding_number(const std::vector<double>& X, index_t n, const std::vector<Triangle>& tris, const std::array<double, 3>& p) {
  double omega = 0;
  for (const Triangle& t : tris) {
    double r[3][3], len[3];
    for (int v = 0; v < 3; ++v) {
      for (int d = 0; d < 3; ++d) r[v][d] = X[std::size_t(d * n + t[v])] - p[d];
      len[v] = std::sqrt(r[v][0] * r[v][0] + r[v][1] * r[v][1] + r[v][2] * r[v][2]);
    }
    // tan(Omega / 2) = r1 . (r2 x r3) / (|r1||r2||r3| + (r1.r2)|r3| + (r1.r3)|r2| + (r2.r3)|r1|)
    const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                       r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    auto dot = [&](int a, int b) { return r[a][0] * r[b][0] + r[a][1] * r[b][1] + r[a][2] * r[b][2]; };
    const double den = len[0] * len[1] * len[2] + dot(0, 1) * len[2] + dot(0, 2) * len[1] + dot(1, 2) * len[0];
    omega += 2 * std::atan2(det, den);
  }
  return omega / (4 * pi);
}

Closest closest_points(const std::vector<double>& A, index_t na, const std::vector<double>& B, index_t nb,
                       const std::array<double, 3>& shift) {
  Closest c;
  double best = INFINITY;
  for (index_t i = 0; i < na; ++i)
    for (index_t j = 0; j < nb; ++j) {
      double s = 0;
      for (int d = 0; d < 3; ++d) {
        const double e = A[std::size_t(d * na + i)] - B[std::size_t(d * nb + j)] - shift[d];
        s += e * e;
      }
      if (s < best) best = s, c.a = i, c.b = j;
    }
  c.distance = std::sqrt(best);
  return c;
}

std::array<double, 3> nearest_image_shift(const std::array<double, 3>& a, const std::array<double, 3>& b, const PeriodicBox& box) {
  std::array<double, 3> shift{0, 0, 0};
  for (int d = 0; d < 3; ++d)
    if (box.periodic[d]) shift[d] = box.length[d] * std::round((a[d] - b[d]) / box.length[d]);
  return shift;
}

}  // namespace rbfib::surface
