#include "rbfib/grid/periodic_spline.hpp"

#include <cstddef>

namespace rbfib {

std::vector<double> periodic_spline_midpoints(const std::vector<double>& y, double h) {
  const int n = int(y.size());
  std::vector<double> r(n), M(n), mid(n);
  for (int i = 0; i < n; ++i) r[i] = 6 * (y[(i + n - 1) % n] - 2 * y[i] + y[(i + 1) % n]) / (h * h);
  // Cyclic tridiagonal (1, 4, 1): A = T + u v^T with T's corner-corrected diagonal.
  auto thomas = [n](std::vector<double> d, std::vector<double> b) {  // sub = super = 1
    std::vector<double> c(n);
    c[0] = 1 / d[0];
    b[0] /= d[0];
    for (int i = 1; i < n; ++i) {
      const double den = d[i] - c[i - 1];
      c[i] = 1 / den;
      b[i] = (b[i] - b[i - 1]) / den;
    }
    for (int i = n - 2; i >= 0; --i) b[i] -= c[i] * b[i + 1];
    return b;
  };
  const double gamma = -4;
  std::vector<double> d(n, 4.0), u(n, 0.0);
  d[0] = 4 - gamma;
  d[n - 1] = 4 - 1.0 / gamma;
  u[0] = gamma;
  u[n - 1] = 1;
  const std::vector<double> x = thomas(d, r), z = thomas(d, u);
  const double fact = (x[0] + x[n - 1] / gamma) / (1 + z[0] + z[n - 1] / gamma);
  for (int i = 0; i < n; ++i) M[i] = x[i] - fact * z[i];
  for (int i = 0; i < n; ++i) mid[i] = 0.5 * (y[i] + y[(i + 1) % n]) - h * h * (M[i] + M[(i + 1) % n]) / 16;
  return mid;
}

std::vector<double> restrict_mac_component(const std::vector<double>& fine, int nf, double hf, int a) {
  const int nc = nf / 2;
  std::vector<double> cur = fine;
  int n[3] = {nf, nf, nf};
  for (int d = 0; d < 3; ++d) {  // line by line along d
    const int m[3] = {d == 0 ? nc : n[0], d == 1 ? nc : n[1], d == 2 ? nc : n[2]};
    std::vector<double> next(std::size_t(m[0]) * m[1] * m[2]);
    const int s[3] = {1, n[0], n[0] * n[1]};
    const int t[3] = {1, m[0], m[0] * m[1]};
    const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
    for (int q2 = 0; q2 < n[e2]; ++q2)
      for (int q1 = 0; q1 < n[e1]; ++q1) {
        std::vector<double> line(n[d]);
        for (int p = 0; p < n[d]; ++p) line[p] = cur[std::size_t(p) * s[d] + std::size_t(q1) * s[e1] + std::size_t(q2) * s[e2]];
        std::vector<double> out(nc);
        if (d == a) {
          for (int i = 0; i < nc; ++i) out[i] = line[2 * i + 1];
        } else {
          const std::vector<double> mid = periodic_spline_midpoints(line, hf);
          for (int i = 0; i < nc; ++i) out[i] = mid[2 * i];
        }
        for (int i = 0; i < nc; ++i) next[std::size_t(i) * t[d] + std::size_t(q1) * t[e1] + std::size_t(q2) * t[e2]] = out[i];
      }
    cur.swap(next);
    n[d] = nc;
  }
  return cur;
}

}  // namespace rbfib
