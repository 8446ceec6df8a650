#include "rbfib/surface/triangulation.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/geometry_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace rbfib::surface {

namespace {
double orient(const double* a, const double* b, const double* c, const double* q) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
  return (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] + (u[0] * v[1] - u[1] * v[0]) * w[2];
}
std::uint64_t key(index_t a, index_t b) { return (std::uint64_t(a) << 32) | std::uint64_t(b); }
}  // namespace

std::vector<Triangle> convex_hull(const std::vector<double>& p, double length) {
  const index_t n = index_t(p.size() / 3);
  require(p.size() % 3 == 0 && n >= 4, "convex hull points", n, "need at least 4 points (x y z each)");
  auto P = [&](index_t i) { return &p[3 * i]; };
  const double scale = length > 0 ? length : [&] {
    double m = 0;
    for (double x : p) m = std::max(m, std::abs(x));
    return m > 0 ? m : 1.0;
  }();

  // Initial tetrahedron: site 0, the farthest from it, the farthest from that line, the farthest
  // from that plane.
  index_t i0 = 0, i1 = 0, i2 = -1, i3 = -1;
  double best = -1;
  for (index_t i = 1; i < n; ++i) {
    const double d = (p[3 * i] - p[0]) * (p[3 * i] - p[0]) + (p[3 * i + 1] - p[1]) * (p[3 * i + 1] - p[1]) +
                     (p[3 * i + 2] - p[2]) * (p[3 * i + 2] - p[2]);
    if (d > best) { best = d; i1 = i; }
  }
  best = -1;
  for (index_t i = 1; i < n; ++i) {
    if (i == i1) continue;
    const double u[3] = {P(i1)[0] - P(i0)[0], P(i1)[1] - P(i0)[1], P(i1)[2] - P(i0)[2]};
    const double w[3] = {P(i)[0] - P(i0)[0], P(i)[1] - P(i0)[1], P(i)[2] - P(i0)[2]};
    const double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double d = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    if (d > best) { best = d; i2 = i; }
  }
  best = -1;
  for (index_t i = 1; i < n; ++i) {
    if (i == i1 || i == i2) continue;
    const double d = std::abs(orient(P(i0), P(i1), P(i2), P(i)));
    if (d > best) { best = d; i3 = i; }
  }
  if (!(best > 1e-14 * scale * scale * scale))
    throw NumericalError(Cause::degenerate_site, "convex hull: the points are coplanar (no initial tetrahedron)");

  std::vector<Triangle> faces;
  std::vector<char> alive;
  std::unordered_map<std::uint64_t, index_t> edge_face;  // directed edge (a, b) -> face with a->b
  auto add_face = [&](index_t a, index_t b, index_t c) {
    const index_t f = static_cast<index_t>(faces.size());
    faces.push_back({a, b, c});
    alive.push_back(1);
    edge_face[key(a, b)] = f;
    edge_face[key(b, c)] = f;
    edge_face[key(c, a)] = f;
  };
  if (orient(P(i0), P(i1), P(i2), P(i3)) > 0) std::swap(i1, i2);  // i3 behind (i0, i1, i2)
  add_face(i0, i1, i2);
  add_face(i0, i3, i1);
  add_face(i1, i3, i2);
  add_face(i2, i3, i0);

  const double eps = 1e-13 * scale * scale * scale;
  std::vector<index_t> visible;
  for (index_t q = 0; q < n; ++q) {
    if (q == i0 || q == i1 || q == i2 || q == i3) continue;
    visible.clear();
    for (index_t f = 0; f < static_cast<index_t>(faces.size()); ++f)
      if (alive[f] && orient(P(faces[f][0]), P(faces[f][1]), P(faces[f][2]), P(q)) > eps) visible.push_back(f);
    if (visible.empty()) continue;  // inside the hull so far, hence inside the final hull
    for (index_t f : visible) alive[f] = 2;  // mark
    std::vector<std::pair<index_t, index_t>> horizon;
    for (index_t f : visible)
      for (int e = 0; e < 3; ++e) {
        const index_t a = faces[f][e], b = faces[f][(e + 1) % 3];
        auto it = edge_face.find(key(b, a));
        if (it == edge_face.end() || alive[it->second] != 2) horizon.emplace_back(a, b);
      }
    for (index_t f : visible) {
      for (int e = 0; e < 3; ++e) {
        auto it = edge_face.find(key(faces[f][e], faces[f][(e + 1) % 3]));
        if (it != edge_face.end() && it->second == f) edge_face.erase(it);
      }
      alive[f] = 0;
    }
    for (auto [a, b] : horizon) add_face(a, b, q);
  }
  std::vector<Triangle> out;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (alive[f]) out.push_back(faces[f]);
  return out;
}

std::vector<Triangle> sphere_triangulation(const SphereSites& sites) {
  const index_t n = sites.size();
  require(n >= 4, "triangulation sites", n, "need at least 4 sites");
  require_distinct(sites, "triangulation sites");
  const std::vector<Triangle> out = convex_hull(unit_sphere_points(sites), 1.0);
  std::vector<int> used(n, 0);
  for (const Triangle& t : out)
    for (index_t v : t) used[v] = 1;
  for (index_t i = 0; i < n; ++i)
    if (!used[i])
      throw NumericalError(Cause::degenerate_site, "sphere triangulation: site " + to_text(i) + " is not a vertex of the hull");
  if (static_cast<index_t>(out.size()) != 2 * n - 4)
    throw NumericalError(Cause::solver, "sphere triangulation: " + to_text(out.size()) + " triangles, expected 2n - 4 = " +
                         to_text(2 * n - 4));
  return out;
}

PolyhedronMeasures polyhedron_measures(const std::vector<Triangle>& tris, const std::vector<double>& X) {
  const std::size_t n = X.size() / 3;
  PolyhedronMeasures out;
  double m[3] = {0, 0, 0};
  for (const Triangle& t : tris) {
    double a[3], b[3], d[3], bxd[3], e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = X[k * n + t[0]];
      b[k] = X[k * n + t[1]];
      d[k] = X[k * n + t[2]];
      e1[k] = b[k] - a[k];
      e2[k] = d[k] - a[k];
    }
    cross3(b, d, bxd);
    const double v = dot3(a, bxd) / 6;  // the tetrahedron (0, a, b, d)
    out.volume += v;
    for (int k = 0; k < 3; ++k) m[k] += v * (a[k] + b[k] + d[k]) / 4;
    cross3(e1, e2, nn);
    out.area += 0.5 * std::sqrt(dot3(nn, nn));
  }
  for (int k = 0; k < 3; ++k) out.centroid[k] = m[k] / out.volume;
  return out;
}

std::vector<double> edge_mean_curvature(const std::vector<Triangle>& tris, const std::vector<double>& X) {
  const std::size_t n = X.size() / 3;
  auto at = [&](index_t v, double* x) {
    for (int k = 0; k < 3; ++k) x[k] = X[k * n + std::size_t(v)];
  };
  std::vector<std::array<double, 3>> normal(tris.size());  // unit normals
  std::vector<double> A(n, 0.0), sum(n, 0.0);
  std::unordered_map<std::uint64_t, index_t> edge_face;  // directed edge (a, b) -> its face
  for (std::size_t f = 0; f < tris.size(); ++f) {
    double a[3], b[3], c[3], e1[3], e2[3], nn[3];
    at(tris[f][0], a), at(tris[f][1], b), at(tris[f][2], c);
    for (int k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k];
    cross3(e1, e2, nn);
    const double twice = std::sqrt(dot3(nn, nn));
    require(twice > 0, "edge_mean_curvature: triangle " + to_text(f) + " area", twice, "must be > 0");
    for (int k = 0; k < 3; ++k) normal[f][k] = nn[k] / twice;
    for (index_t v : tris[f]) A[std::size_t(v)] += twice / 6;  // a third of the area
    for (int e = 0; e < 3; ++e) edge_face[key(tris[f][e], tris[f][(e + 1) % 3])] = index_t(f);
  }
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const index_t a = tris[f][e], b = tris[f][(e + 1) % 3];
      if (a > b) continue;  // each edge once, from the face where it runs a -> b with a < b
      const auto other = edge_face.find(key(b, a));
      require(other != edge_face.end(), "edge_mean_curvature: edge " + to_text(a) + "-" + to_text(b), "open",
              "the surface must be closed");
      const std::array<double, 3>& n1 = normal[f];
      const std::array<double, 3>& n2 = normal[std::size_t(other->second)];
      const double theta = std::acos(std::clamp(n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2], -1.0, 1.0));
      double xa[3], xb[3];
      at(a, xa), at(b, xb);
      const double len = std::sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) + (xa[2] - xb[2]) * (xa[2] - xb[2]));
      sum[std::size_t(a)] += theta * len;
      sum[std::size_t(b)] += theta * len;
    }
  for (std::size_t i = 0; i < n; ++i) sum[i] /= 4 * A[i];
  return sum;
}

}  // namespace rbfib::surface
