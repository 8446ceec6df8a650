#include "common/cell_shape.hpp"

#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::study {

namespace {
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

void symmetric_eigen3(const std::array<Vec3, 3>& A0, Vec3& values, std::array<Vec3, 3>& vectors) {
  std::array<Vec3, 3> A = A0, V{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  // V: columns are eigenvectors
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = A[0][1] * A[0][1] + A[0][2] * A[0][2] + A[1][2] * A[1][2];
    const double diag = A[0][0] * A[0][0] + A[1][1] * A[1][1] + A[2][2] * A[2][2];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (A[p][q] == 0) continue;
        const double theta = (A[q][q] - A[p][p]) / (2 * A[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- A J
          const double akp = A[k][p], akq = A[k][q];
          A[k][p] = c * akp - s * akq;
          A[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- J^T A
          const double apk = A[p][k], aqk = A[q][k];
          A[p][k] = c * apk - s * aqk;
          A[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = V[k][p], vkq = V[k][q];
          V[k][p] = c * vkp - s * vkq;
          V[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return A[a][a] < A[b][b]; });
  for (int j = 0; j < 3; ++j) {
    values[j] = A[order[j]][order[j]];
    for (int k = 0; k < 3; ++k) vectors[j][k] = V[k][order[j]];
  }
}

CellShape cell_shape(const std::vector<double>& X, long n, long N, long c) {
  require(n > 0 && N > 0 && long(X.size()) == 3 * N * n, "cell_shape positions", X.size(),
          "expected 3 N n = " + to_text(3 * N * n) + " values (N = " + to_text(N) + " cells of n = " + to_text(n) + " sites)");
  require(c >= 0 && c < N, "cell_shape cell", c, "expected a cell index below " + to_text(N));
  auto x = [&](int d, long i) { return X[std::size_t((d * N + c) * n + i)]; };
  CellShape s;
  for (int d = 0; d < 3; ++d) {
    double sum = 0;
    for (long i = 0; i < n; ++i) sum += x(d, i);
    s.center[d] = sum / double(n);
  }
  std::array<Vec3, 3> M{};
  for (long i = 0; i < n; ++i) {
    const Vec3 r{x(0, i) - s.center[0], x(1, i) - s.center[1], x(2, i) - s.center[2]};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) M[a][b] += r[a] * r[b] / double(n);
  }
  Vec3 values;
  symmetric_eigen3(M, values, s.axes);
  for (int a = 0; a < 3; ++a) {
    double lo = 1e300, hi = -1e300;
    for (long i = 0; i < n; ++i) {
      const double q = (x(0, i) - s.center[0]) * s.axes[a][0] + (x(1, i) - s.center[1]) * s.axes[a][1] +
                       (x(2, i) - s.center[2]) * s.axes[a][2];
      lo = std::min(lo, q);
      hi = std::max(hi, q);
    }
    s.extent[a] = hi - lo;
  }
  return s;
}

std::vector<Vec3> jeffery_axis(const Vec3& p0, double r, double gdot, int f, int g, const std::vector<double>& times) {
  require(f >= 0 && f < 3 && g >= 0 && g < 3 && f != g, "jeffery_axis axes", to_text(f) + ", " + to_text(g), "expected two different axes 0..2");
  const double B = (r * r - 1) / (r * r + 1);
  // grad u = gdot e_f e_g^T: W p = (gdot/2)(p_g e_f - p_f e_g), E p = (gdot/2)(p_g e_f + p_f e_g).
  auto rhs = [&](const Vec3& p) {
    Vec3 Wp{0, 0, 0}, Ep{0, 0, 0};
    Wp[f] = 0.5 * gdot * p[g], Wp[g] = -0.5 * gdot * p[f];
    Ep[f] = 0.5 * gdot * p[g], Ep[g] = 0.5 * gdot * p[f];
    const double pEp = dot(p, Ep);
    return Vec3{Wp[0] + B * (Ep[0] - pEp * p[0]), Wp[1] + B * (Ep[1] - pEp * p[1]), Wp[2] + B * (Ep[2] - pEp * p[2])};
  };
  std::vector<Vec3> out;
  Vec3 p = p0;
  double t = 0;
  const double hmax = 1e-3 / std::abs(gdot);
  for (double target : times) {
    while (t < target) {
      const double h = std::min(hmax, target - t);
      auto add = [](const Vec3& a, const Vec3& b, double s) { return Vec3{a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; };
      const Vec3 k1 = rhs(p), k2 = rhs(add(p, k1, h / 2)), k3 = rhs(add(p, k2, h / 2)), k4 = rhs(add(p, k3, h));
      for (int d = 0; d < 3; ++d) p[d] += h / 6 * (k1[d] + 2 * k2[d] + 2 * k3[d] + k4[d]);
      const double norm = std::sqrt(dot(p, p));
      for (double& v : p) v /= norm;
      t += h;
    }
    out.push_back(p);
  }
  return out;
}

double axis_angle(const Vec3& a, const Vec3& b) {
  const double c = std::abs(dot(a, b)) / std::sqrt(dot(a, a) * dot(b, b));
  return std::acos(std::min(1.0, c));
}

std::vector<double> unwrap(const std::vector<double>& angles, double period) {
  std::vector<double> out(angles);
  for (std::size_t i = 1; i < out.size(); ++i) {
    const double step = angles[i] - angles[i - 1];
    out[i] = out[i - 1] + step - period * std::round(step / period);
  }
  return out;
}

}  // namespace rbfib::study
