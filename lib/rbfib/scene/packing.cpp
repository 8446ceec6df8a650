#include "rbfib/scene/packing.hpp"
#include "rbfib/cells/measure.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/surface/contact.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rbfib::scene {

namespace {

/// A rotation as a unit quaternion (w, x, y, z).
struct Quaternion {
  double w = 1, x = 0, y = 0, z = 0;
  static Quaternion about(const Vec3& axis, double angle) {
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double s = std::sin(angle / 2) / n;
    return {std::cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s};
  }
  Quaternion operator*(const Quaternion& q) const {  // this after q
    return {w * q.w - x * q.x - y * q.y - z * q.z, w * q.x + x * q.w + y * q.z - z * q.y, w * q.y - x * q.z + y * q.w + z * q.x,
            w * q.z + x * q.y - y * q.x + z * q.w};
  }
  Vec3 rotate(const Vec3& v) const {
    const Quaternion p = *this * Quaternion{0, v[0], v[1], v[2]} * Quaternion{w, -x, -y, -z};
    return {p.x, p.y, p.z};
  }
  /// The placement's axis and angle (the identity: axis z, angle 0).
  void to(cells::Placement& p) const {
    const double s = std::sqrt(x * x + y * y + z * z);
    if (s < 1e-15) {
      p.axis = {0, 0, 1}, p.angle = 0;
      return;
    }
    p.axis = {x / s, y / s, z / s};
    p.angle = 2 * std::atan2(s, w);
  }
  static Quaternion from(const cells::Placement& p) { return about(p.axis, p.angle); }
};

Vec3 cross(const Vec3& a, const Vec3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// A direction uniform on the unit sphere.
Vec3 random_direction(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1), a(0, 2 * pi);
  const double z = u(rng), phi = a(rng), r = std::sqrt(1 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Sites of a cell (n x 3): the lowest clearance above the endothelium and below the top wall.
void clearances(const std::vector<double>& X, index_t n, const Domain& box, double& above, double& below_top) {
  above = below_top = INFINITY;
  for (index_t i = 0; i < n; ++i) {
    const double x = X[std::size_t(i)], y = X[std::size_t(n + i)], z = X[std::size_t(2 * n + i)];
    above = std::min(above, y - box.endothelium.height(x, z));
    below_top = std::min(below_top, box.Ly - y);
  }
}

}  // namespace

double distance_to_red_cells(const std::vector<double>& X, index_t n, const std::vector<double>& red, index_t n_red, const Domain& box,
                             double cutoff) {
  if (red.empty()) return INFINITY;
  const std::size_t N = red.size() / std::size_t(3 * n_red);
  double closest = INFINITY;
  std::vector<double> R(std::size_t(3 * n_red));
  for (std::size_t c = 0; c < N; ++c) {
    for (int d = 0; d < 3; ++d)
      std::copy_n(red.begin() + long((d * N + c) * std::size_t(n_red)), n_red, R.begin() + long(d * n_red));
    closest = std::min(closest, cell_distance(X, n, R, n_red, box, cutoff));
  }
  return closest;
}

std::vector<double> batch_layout(const ReferenceSites& r, const std::vector<cells::Placement>& placements) {
  const std::size_t n = std::size_t(r.n), N = placements.size();
  std::vector<double> X(3 * n * N);
  for (std::size_t c = 0; c < N; ++c) {
    const std::vector<double> Y = cells::placed(r.X, r.n, placements[c], "cell " + std::to_string(c));
    for (std::size_t d = 0; d < 3; ++d) std::copy_n(Y.begin() + long(d * n), n, X.begin() + long((d * N + c) * n));
  }
  return X;
}

ReferenceSites reference_sites(const cells::CellTypeSpec& spec) {
  const surface::SphereSites& z = spec.data_sites;
  ReferenceSites r;
  r.n = z.size();
  r.X.resize(std::size_t(3 * r.n));
  r.normals.resize(std::size_t(3 * r.n));
  const double e = 1e-6;  // rad: central differences of the parametrization give the tangents
  for (index_t i = 0; i < r.n; ++i) {
    double x[3], lp[3], lm[3], tp[3], tm[3];
    spec.shape.position(z.lambda[i], z.theta[i], x);
    // Near a pole the longitude tangent vanishes: step the latitude toward the equator.
    const double th = std::clamp(z.theta[i], -pi / 2 + 2 * e, pi / 2 - 2 * e);
    spec.shape.position(z.lambda[i] + e, th, lp);
    spec.shape.position(z.lambda[i] - e, th, lm);
    spec.shape.position(z.lambda[i], th + e, tp);
    spec.shape.position(z.lambda[i], th - e, tm);
    Vec3 n = cross(Vec3{lp[0] - lm[0], lp[1] - lm[1], lp[2] - lm[2]}, Vec3{tp[0] - tm[0], tp[1] - tm[1], tp[2] - tm[2]});
    double nn = std::sqrt(dot(n, n));
    if (!(nn > 0)) n = {x[0], x[1], x[2]}, nn = std::sqrt(dot(n, n));  // a pole of a shape of revolution
    if (dot(n, Vec3{x[0], x[1], x[2]}) < 0) nn = -nn;                   // outward (shapes about their centre)
    for (int d = 0; d < 3; ++d) {
      r.X[std::size_t(d * r.n + i)] = x[d];
      r.normals[std::size_t(d * r.n + i)] = n[std::size_t(d)] / nn;
    }
  }
  return r;
}

double cell_distance(const std::vector<double>& A, index_t na, const std::vector<double>& B, index_t nb, const Domain& box,
                     double cutoff) {
  // The nearest periodic image of B's centre (x and z periodic).
  Vec3 ca{0, 0, 0}, cb{0, 0, 0};
  double ra = 0, rb = 0;
  for (int d = 0; d < 3; ++d) {
    for (index_t i = 0; i < na; ++i) ca[std::size_t(d)] += A[std::size_t(d * na + i)] / double(na);
    for (index_t i = 0; i < nb; ++i) cb[std::size_t(d)] += B[std::size_t(d * nb + i)] / double(nb);
  }
  for (index_t i = 0; i < na; ++i)
    ra = std::max(ra, std::hypot(A[std::size_t(i)] - ca[0], A[std::size_t(na + i)] - ca[1], A[std::size_t(2 * na + i)] - ca[2]));
  for (index_t i = 0; i < nb; ++i)
    rb = std::max(rb, std::hypot(B[std::size_t(i)] - cb[0], B[std::size_t(nb + i)] - cb[1], B[std::size_t(2 * nb + i)] - cb[2]));
  const std::array<double, 3> shift = surface::nearest_image_shift(ca, cb, {{box.Lx, 0, box.Lz}, {true, false, true}});
  const double centres = std::hypot(ca[0] - cb[0] - shift[0], ca[1] - cb[1], ca[2] - cb[2] - shift[2]);
  if (centres - ra - rb > cutoff) return centres - ra - rb;  // a lower bound, enough to tell far cells
  return surface::closest_points(A, na, B, nb, shift).distance;
}

double closest_cells(const std::vector<double>& X, index_t n, index_t N, const Domain& box) {
  double best = INFINITY;
  for (index_t a = 0; a < N; ++a)
    for (index_t b = a + 1; b < N; ++b) best = std::min(best, cell_distance(cells::cell_points(X, n, N, a), n, cells::cell_points(X, n, N, b), n, box));
  return best;
}

double sheet_distance(const std::vector<double>& X, index_t n, const std::vector<double>& E, const Domain& box) {
  const std::size_t m = E.size() / 3;
  double best = INFINITY;
#pragma omp parallel for reduction(min : best)
  for (index_t i = 0; i < n; ++i) {
    const double x = X[std::size_t(i)], y = X[std::size_t(n + i)], z = X[std::size_t(2 * n + i)];
    for (std::size_t k = 0; k < m; ++k) {
      const double dx = std::remainder(x - E[k], box.Lx), dy = y - E[m + k], dz = std::remainder(z - E[2 * m + k], box.Lz);
      best = std::min(best, dx * dx + dy * dy + dz * dz);
    }
  }
  return std::sqrt(best);
}

Layout red_cell_layout(const ReferenceSites& red_cell, const Domain& box, const LayoutSpec& spec, std::mt19937_64& rng) {
  if (!(spec.h > 0)) throw InputError("red_cell_layout h", to_text(spec.h), "must be > 0");
  Layout L;
  // Two rows of four, concavities facing z (the reference shape's short axis is z).
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 4; ++k) {
      cells::Placement p;
      p.center = {box.Lx * (0.25 + 0.5 * row), spec.y, std::fmod(box.Lz * (0.125 + 0.25 * k) + row * spec.stagger, box.Lz)};
      L.red_cells.push_back(p);
    }
  const index_t n = red_cell.n;
  std::vector<std::vector<double>> X;
  for (const cells::Placement& p : L.red_cells) X.push_back(cells::placed(red_cell.X, n, p, "red cell"));
  auto fits = [&](std::size_t c, const std::vector<double>& Y) {
    double above, below_top;
    clearances(Y, n, box, above, below_top);
    if (above < 2 * spec.h || below_top < 2 * spec.h) return false;
    for (std::size_t o = 0; o < X.size(); ++o)
      if (o != c && cell_distance(Y, n, X[o], n, box, 2 * spec.h) < 2 * spec.h) return false;
    return true;
  };
  std::uniform_real_distribution<double> unit(-1, 1);
  for (std::size_t c = 0; c < L.red_cells.size(); ++c)
    for (int draw = 0; draw < spec.max_draws; ++draw) {
      ++L.draws;
      const double size = std::pow(spec.shrink, draw);  // smaller moves after each refusal
      cells::Placement p = L.red_cells[c];
      for (int d = 0; d < 3; ++d) p.center[std::size_t(d)] += size * spec.max_shift * unit(rng);
      const Vec3 axis = random_direction(rng);
      (Quaternion::about(axis, size * spec.max_angle * 0.5 * (1 + unit(rng))) * Quaternion::from(p)).to(p);
      std::vector<double> Y = cells::placed(red_cell.X, n, p, "red cell");
      if (!fits(c, Y)) continue;
      L.red_cells[c] = p, X[c] = std::move(Y), ++L.moved;
      break;
    }
  L.closest = INFINITY;
  for (std::size_t a = 0; a < X.size(); ++a)
    for (std::size_t b = a + 1; b < X.size(); ++b) L.closest = std::min(L.closest, cell_distance(X[a], n, X[b], n, box));
  return L;
}

std::vector<double> starting_times(double settle, double mean_gap, int count, std::mt19937_64& rng) {
  std::exponential_distribution<double> gap(1 / mean_gap);
  std::vector<double> t;
  double now = settle;
  for (int k = 0; k < count; ++k) t.push_back(now += gap(rng));
  return t;
}

PlateletPlacement place_platelets(const ReferenceSites& platelet, const Domain& box, const std::vector<double>& E,
                                  const std::vector<double>& red, index_t n_red, int count, const PlateletSpec& spec,
                                  std::mt19937_64& rng) {
  const index_t m = index_t(E.size() / 3), n = platelet.n;
  std::uniform_int_distribution<index_t> endo(0, m - 1), site(0, n - 1);
  std::uniform_real_distribution<double> gap(spec.gap_min, spec.gap_max), spin(0, 2 * pi);
  PlateletPlacement P;
  std::vector<Vec3> chosen;  // the endothelium points taken
  int attempts = 0;          // platelet points drawn for the platelet being placed
  for (int endothelium_draws = 0; int(P.platelets.size()) < count; ++endothelium_draws) {
    if (endothelium_draws > spec.max_draws)
      throw NumericalError(Cause::solver, "placing platelet " + std::to_string(P.platelets.size()) + ": no endothelium point found in " +
                           std::to_string(spec.max_draws) + " draws");
    // An endothelium point far enough from those already taken (periodic in x and z).
    const index_t k = endo(rng);
    const Vec3 e{E[std::size_t(k)], E[std::size_t(m + k)], E[std::size_t(2 * m + k)]};
    bool far = true;
    for (const Vec3& o : chosen) {
      const double dx = std::remainder(e[0] - o[0], box.Lx), dz = std::remainder(e[2] - o[2], box.Lz);
      far = far && std::hypot(dx, e[1] - o[1], dz) >= spec.min_separation;
    }
    if (!far) continue;
    const std::array<double, 3> ne = box.endothelium.normal(e[0], e[2]);  // (n_x, n_y, n_z)
    const Vec3 to{-ne[0], -ne[1], -ne[2]};
    // Platelet points for this endothelium point; after 20 refusals, another endothelium point.
    bool placed = false;
    for (int tries = 0; tries < 20 && !placed; ++tries) {
      if (++P.draws > spec.max_draws)
        throw NumericalError(Cause::solver, "placing platelet " + std::to_string(P.platelets.size()) + ": no placement in " +
                             std::to_string(spec.max_draws) + " draws (the space between the endothelium and the red cells is too small)");
      ++attempts;
      const index_t i = site(rng);
      const Vec3 xp{platelet.X[std::size_t(i)], platelet.X[std::size_t(n + i)], platelet.X[std::size_t(2 * n + i)]};
      const Vec3 np{platelet.normals[std::size_t(i)], platelet.normals[std::size_t(n + i)], platelet.normals[std::size_t(2 * n + i)]};
      // The rotation taking the platelet's normal np to -ne, then a spin about ne.
      const Vec3 v = cross(np, to);
      const double s = std::sqrt(dot(v, v)), c = dot(np, to);
      Quaternion q;
      if (s > 1e-12)
        q = Quaternion::about(v, std::atan2(s, c));
      else if (c < 0)
        q = Quaternion::about(std::abs(np[0]) < 0.9 ? cross(np, Vec3{1, 0, 0}) : cross(np, Vec3{0, 1, 0}), pi);
      q = Quaternion::about(to, spin(rng)) * q;
      const double g = gap(rng);
      const Vec3 r = q.rotate(xp);
      cells::Placement p;
      for (int d = 0; d < 3; ++d) p.center[std::size_t(d)] = e[std::size_t(d)] + g * ne[std::size_t(d)] - r[std::size_t(d)];
      q.to(p);
      const std::vector<double> Y = cells::placed(platelet.X, n, p, "platelet");
      double above, below_top;
      clearances(Y, n, box, above, below_top);
      if (!(above > 0 && below_top > 0)) {
        ++P.refused_surface;
        continue;
      }
      if (distance_to_red_cells(Y, n, red, n_red, box, spec.red_cell_clearance) < spec.red_cell_clearance) {
        ++P.refused_red_cells;
        continue;
      }
      P.platelets.push_back(p), P.gaps.push_back(g), chosen.push_back(e), P.attempts.push_back(attempts);
      attempts = 0;
      placed = true;
    }
  }
  return P;
}

}  // namespace rbfib::scene
