#include "rbfib/sim/circulant_mobility.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace rbfib::sim {

namespace {

/// The lattice index along one in-plane axis of each marker: coordinates relative to marker 0's,
/// modulo the box, on multiples of length / n; n from the number of distinct offsets. Nothing
/// when they are not a regular lattice commensurate with the cells.
std::optional<std::vector<index_t>> axis_indices(const double* x, index_t n_markers, double length, double h, index_t& n) {
  const double tol = 1e-9 * h;
  std::vector<double> r(static_cast<std::size_t>(n_markers));
  for (index_t k = 0; k < n_markers; ++k) {
    double v = std::fmod(x[k] - x[0], length);
    if (v < 0) v += length;
    if (v > length - tol) v = 0;  // the box's end is its start
    r[std::size_t(k)] = v;
  }
  std::vector<double> distinct(r);
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end(), [tol](double a, double b) { return b - a <= tol; }), distinct.end());
  n = index_t(distinct.size());
  const double spacing = length / double(n), cells = spacing / h;
  if (std::abs(cells - std::round(cells)) > 1e-9 * cells) return std::nullopt;  // not a whole number of cells
  for (index_t i = 0; i < n; ++i)
    if (std::abs(distinct[std::size_t(i)] - double(i) * spacing) > tol) return std::nullopt;  // not regular
  std::vector<index_t> index(r.size());
  for (std::size_t k = 0; k < r.size(); ++k) index[k] = index_t(std::lround(r[k] / spacing)) % n;
  return index;
}

}  // namespace

std::optional<MarkerLattice> commensurate_lattice(const std::vector<double>& X, const MacGrid& grid) {
  const index_t n = index_t(X.size() / 3);
  if (n == 0 || X.size() % 3 != 0) return std::nullopt;
  for (int normal = 0; normal < 3; ++normal) {
    const int a = normal == 0 ? 1 : 0, b = normal == 2 ? 1 : 2;
    if (!grid.periodic(a) || !grid.periodic(b)) continue;
    const double* y = X.data() + normal * n;
    const auto [lo, hi] = std::minmax_element(y, y + n);
    if (*hi - *lo > 1e-9 * grid.h(normal)) continue;  // not one plane normal to this axis
    MarkerLattice L;
    L.normal = normal, L.axes = {a, b};
    const auto ia = axis_indices(X.data() + a * n, n, grid.length[a], grid.h(a), L.n[0]);
    const auto ib = axis_indices(X.data() + b * n, n, grid.length[b], grid.h(b), L.n[1]);
    if (!ia || !ib || L.size() != n) return std::nullopt;
    L.marker.assign(std::size_t(n), -1);
    for (index_t k = 0; k < n; ++k) {
      index_t& slot = L.marker[std::size_t((*ia)[std::size_t(k)] + L.n[0] * (*ib)[std::size_t(k)])];
      if (slot >= 0) return std::nullopt;  // two markers on one lattice point
      slot = k;
    }
    return L;
  }
  return std::nullopt;
}

CirculantMobility::CirculantMobility(MarkerLattice lattice, const std::array<std::vector<double>, 3>& response) : lattice_(std::move(lattice)) {
  const index_t n = lattice_.size();
  for (int c = 0; c < 3; ++c)
    require(index_t(response[std::size_t(c)].size()) == 3 * n, "circulant mobility: response " + std::to_string(c) + " size",
            response[std::size_t(c)].size(), "must be 3 x the markers");
  for (int a = 0; a < 2; ++a) {
    const index_t m = lattice_.n[std::size_t(a)];
    roots_[std::size_t(a)].resize(std::size_t(m));
    for (index_t k = 0; k < m; ++k) roots_[std::size_t(a)][std::size_t(k)] = std::polar(1.0, -2 * pi * double(k) / double(m));
  }
  // The symbol m^(p)_{ec}: the transform over the lattice offsets d of the response along e to a
  // force along c at (0, 0), which is m_{ec}(d).
  std::array<std::array<std::vector<cplx>, 3>, 3> symbol;
  for (int c = 0; c < 3; ++c)
    for (int e = 0; e < 3; ++e) {
      std::vector<cplx>& s = symbol[std::size_t(e)][std::size_t(c)];
      s.resize(std::size_t(n));
      for (index_t d = 0; d < n; ++d) s[std::size_t(d)] = response[std::size_t(c)][std::size_t(e * n + lattice_.marker[std::size_t(d)])];
      transform(s, -1);
    }
  // The pseudo-inverse per wavenumber; singular values below 1e-10 of the largest anywhere are zero.
  std::vector<Eigen::JacobiSVD<Eigen::Matrix3cd>> svd(static_cast<std::size_t>(n));
  double largest = 0;
  for (index_t p = 0; p < n; ++p) {
    Eigen::Matrix3cd A;
    for (int e = 0; e < 3; ++e)
      for (int c = 0; c < 3; ++c) A(e, c) = symbol[std::size_t(e)][std::size_t(c)][std::size_t(p)];
    svd[std::size_t(p)].compute(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    largest = std::max(largest, svd[std::size_t(p)].singularValues()(0));
  }
  require(std::isfinite(largest) && largest > 0, "circulant mobility: largest singular value", largest, "must be finite and positive");
  inverse_.resize(std::size_t(9 * n));
  for (index_t p = 0; p < n; ++p) {
    const auto& s = svd[std::size_t(p)];
    Eigen::Vector3d inv_sigma;
    for (int k = 0; k < 3; ++k) {
      const double sigma = s.singularValues()(k);
      inv_sigma(k) = sigma > 1e-10 * largest ? 1 / sigma : 0;
      singular_ += sigma > 1e-10 * largest ? 0 : 1;
    }
    const Eigen::Matrix3cd P = s.matrixV() * inv_sigma.cast<cplx>().asDiagonal() * s.matrixU().adjoint();
    for (int c = 0; c < 3; ++c)
      for (int e = 0; e < 3; ++e) inverse_[std::size_t(9 * p + 3 * c + e)] = P(c, e);
  }
}

void CirculantMobility::transform(std::vector<cplx>& a, int sign) const {
  const index_t n0 = lattice_.n[0], n1 = lattice_.n[1];
  const auto root = [&](int axis, index_t k) {
    const cplx w = roots_[std::size_t(axis)][std::size_t(k % lattice_.n[std::size_t(axis)])];
    return sign < 0 ? w : std::conj(w);
  };
  std::vector<cplx> line(static_cast<std::size_t>(std::max(n0, n1)));
  for (index_t j = 0; j < n1; ++j) {  // along axis 0
    for (index_t p = 0; p < n0; ++p) {
      cplx sum = 0;
      for (index_t i = 0; i < n0; ++i) sum += a[std::size_t(i + n0 * j)] * root(0, p * i);
      line[std::size_t(p)] = sum;
    }
    std::copy_n(line.begin(), n0, a.begin() + n0 * j);
  }
  for (index_t i = 0; i < n0; ++i) {  // along axis 1
    for (index_t q = 0; q < n1; ++q) {
      cplx sum = 0;
      for (index_t j = 0; j < n1; ++j) sum += a[std::size_t(i + n0 * j)] * root(1, q * j);
      line[std::size_t(q)] = sum;
    }
    for (index_t q = 0; q < n1; ++q) a[std::size_t(i + n0 * q)] = line[std::size_t(q)];
  }
}

void CirculantMobility::solve(std::vector<double>& b) const {
  const index_t n = lattice_.size();
  require(index_t(b.size()) == 3 * n, "circulant mobility: right-hand side size", b.size(), "must be 3 x the markers");
  std::array<std::vector<cplx>, 3> B;
  for (int e = 0; e < 3; ++e) {
    B[std::size_t(e)].resize(std::size_t(n));
    for (index_t d = 0; d < n; ++d) B[std::size_t(e)][std::size_t(d)] = b[std::size_t(e * n + lattice_.marker[std::size_t(d)])];
    transform(B[std::size_t(e)], -1);
  }
  std::array<std::vector<cplx>, 3> F;
  for (int c = 0; c < 3; ++c) {
    F[std::size_t(c)].resize(std::size_t(n));
    for (index_t p = 0; p < n; ++p) {
      const cplx* P = &inverse_[std::size_t(9 * p + 3 * c)];
      F[std::size_t(c)][std::size_t(p)] = P[0] * B[0][std::size_t(p)] + P[1] * B[1][std::size_t(p)] + P[2] * B[2][std::size_t(p)];
    }
    transform(F[std::size_t(c)], +1);
    for (index_t d = 0; d < n; ++d) b[std::size_t(c * n + lattice_.marker[std::size_t(d)])] = F[std::size_t(c)][std::size_t(d)].real() / double(n);
  }
}

}  // namespace rbfib::sim
