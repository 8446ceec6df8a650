#include "rbfib/cells/measure.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::cells {

namespace {
double dot(const double* x, const Vec3& e) { return x[0] * e[0] + x[1] * e[1] + x[2] * e[2]; }
double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

std::vector<double> cell_points(const std::vector<double>& X, index_t n, index_t N, index_t c) {
  require(n > 0 && c >= 0 && c < N && index_t(X.size()) == 3 * N * n, "cell_points cell", c,
          "expected a cell below N = " + to_text(N) + " and 3 N n = " + to_text(3 * N * n) + " values, got " + to_text(X.size()));
  std::vector<double> P;
  for (int d = 0; d < 3; ++d) P.insert(P.end(), X.begin() + (d * N + c) * n, X.begin() + (d * N + c + 1) * n);
  return P;
}

std::vector<double> extents(const std::vector<double>& X, index_t n, const Vec3& centre, const std::vector<Vec3>& directions,
                            const surface::PeriodicBox& box) {
  std::vector<double> lo(directions.size(), 1e300), hi(directions.size(), -1e300);
  for (index_t i = 0; i < n; ++i) {
    double r[3];
    for (int d = 0; d < 3; ++d) {
      r[d] = X[std::size_t(d * n + i)] - centre[d];
      if (box.periodic[d]) r[d] = r[d] - box.length[d] * std::round(r[d] / box.length[d]);
    }
    for (std::size_t k = 0; k < directions.size(); ++k) {
      const double q = dot(r, directions[k]);
      lo[k] = std::min(lo[k], q), hi[k] = std::max(hi[k], q);
    }
  }
  for (std::size_t k = 0; k < directions.size(); ++k) hi[k] -= lo[k];
  return hi;
}

Outline outline(const std::vector<double>& X, index_t n, const Vec3& u, const Vec3& v, const Vec3& w, const std::array<double, 2>& origin,
                double w0, double half_width, int bins) {
  Outline out;
  std::vector<double> S(static_cast<std::size_t>(n)), Y(static_cast<std::size_t>(n));
  double sc = 0, yc = 0;
  for (index_t i = 0; i < n; ++i) {
    const double x[3] = {X[std::size_t(i)], X[std::size_t(n + i)], X[std::size_t(2 * n + i)]};
    S[i] = dot(x, u) - origin[0];
    Y[i] = dot(x, v) - origin[1];
    sc += S[i] / n;
    yc += Y[i] / n;
    if (std::abs(dot(x, w) - w0) < half_width) out.section.push_back({S[i], Y[i]});
  }
  std::vector<double> far(std::size_t(bins), -1);
  std::vector<index_t> who(std::size_t(bins), -1);
  for (index_t i = 0; i < n; ++i) {
    const double a = std::atan2(Y[i] - yc, S[i] - sc), r = std::hypot(Y[i] - yc, S[i] - sc);
    const int b = std::min(bins - 1, int((a + pi) / (2 * pi) * bins));
    if (r > far[b]) far[b] = r, who[b] = i;
  }
  for (int b = 0; b < bins; ++b)
    if (who[b] >= 0) out.silhouette.push_back({S[who[b]], Y[who[b]]});
  return out;
}

Profile profile(const std::vector<double>& X, index_t n, const Vec3& centre, int a, int b) {
  auto p = [&](int d, index_t i) { return X[std::size_t(d * n + i)] - centre[d]; };
  double maa = 0, mab = 0, mbb = 0;
  for (index_t i = 0; i < n; ++i) maa += p(a, i) * p(a, i), mab += p(a, i) * p(b, i), mbb += p(b, i) * p(b, i);
  Profile pr;
  pr.inclination = 0.5 * std::atan2(2 * mab, maa - mbb);
  const double c = std::cos(pr.inclination), s = std::sin(pr.inclination);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (index_t i = 0; i < n; ++i) {
    const double q[2] = {c * p(a, i) + s * p(b, i), -s * p(a, i) + c * p(b, i)};
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  }
  pr.length = hi[0] - lo[0];
  pr.breadth = hi[1] - lo[1];
  return pr;
}

index_t farthest_along(const std::vector<double>& X, index_t n, const Vec3& centre, const Vec3& direction) {
  index_t best_i = 0;
  double best = -1e300;
  for (index_t i = 0; i < n; ++i) {
    const double r[3] = {X[std::size_t(i)] - centre[0], X[std::size_t(n + i)] - centre[1], X[std::size_t(2 * n + i)] - centre[2]};
    const double q = dot(r, direction);
    if (q > best) best = q, best_i = i;
  }
  return best_i;
}

double revolution_strain(const std::vector<double>& s, const std::vector<double>& angle, double s0) {
  if (s.size() < 2 || s0 < s.front() || s0 > s.back()) return NAN;
  std::size_t i0 = 0;
  while (s[i0] < s0) ++i0;
  const double a0 = i0 == 0 ? angle[0] : angle[i0 - 1] + (angle[i0] - angle[i0 - 1]) * (s0 - s[i0 - 1]) / (s[i0] - s[i0 - 1]);
  const double target = a0 - 2 * pi;
  for (std::size_t i = i0 + 1; i < s.size(); ++i)
    if (angle[i] <= target) return s[i - 1] + (s[i] - s[i - 1]) * (angle[i - 1] - target) / (angle[i - 1] - angle[i]) - s0;
  return NAN;
}

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

CellShape cell_shape(const std::vector<double>& X, index_t n, index_t N, index_t c) {
  require(n > 0 && N > 0 && long(X.size()) == 3 * N * n, "cell_shape positions", X.size(),
          "expected 3 N n = " + to_text(3 * N * n) + " values (N = " + to_text(N) + " cells of n = " + to_text(n) + " sites)");
  require(c >= 0 && c < N, "cell_shape cell", c, "expected a cell index below " + to_text(N));
  auto x = [&](int d, index_t i) { return X[std::size_t((d * N + c) * n + i)]; };
  CellShape s;
  for (int d = 0; d < 3; ++d) {
    double sum = 0;
    for (index_t i = 0; i < n; ++i) sum += x(d, i);
    s.center[d] = sum / double(n);
  }
  std::array<Vec3, 3> M{};
  for (index_t i = 0; i < n; ++i) {
    const Vec3 r{x(0, i) - s.center[0], x(1, i) - s.center[1], x(2, i) - s.center[2]};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) M[a][b] += r[a] * r[b] / double(n);
  }
  Vec3 values;
  symmetric_eigen3(M, values, s.axes);
  for (int a = 0; a < 3; ++a) {
    double lo = 1e300, hi = -1e300;
    for (index_t i = 0; i < n; ++i) {
      const double q = (x(0, i) - s.center[0]) * s.axes[a][0] + (x(1, i) - s.center[1]) * s.axes[a][1] +
                       (x(2, i) - s.center[2]) * s.axes[a][2];
      lo = std::min(lo, q);
      hi = std::max(hi, q);
    }
    s.extent[a] = hi - lo;
  }
  return s;
}

double angle_between_axes(const Vec3& a, const Vec3& b) {
  const double c = std::abs(dot3(a, b)) / std::sqrt(dot3(a, a) * dot3(b, b));
  return std::acos(std::min(1.0, c));
}

}  // namespace rbfib::cells
