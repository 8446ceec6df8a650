#pragma once
// The mobility of a flat held wall whose markers tile a periodic plane of the grid, solved in
// Fourier space (sim/held_wall.hpp). When the markers lie on one plane normal to an axis whose
// two in-plane axes are periodic, one marker per point of a regular lattice that tiles the box,
// its spacing a whole number of grid cells, a shift by one lattice spacing maps the grid, the
// kernel's weights and the markers onto themselves. The fluid step's linear part L is translation
// invariant along periodic axes (constant coefficients), so the wall's mobility M = J L S is
// block circulant: the velocity at marker k from a force at marker l depends on k - l alone,
//     u(k) = sum_l m(k - l) Lambda(l),   m(d) a 3 x 3 block,
// and the discrete Fourier transform over the lattice turns M Lambda = b into one 3 x 3 system per
// wavenumber p, m^(p) Lambda^(p) = b^(p). m(d) is the response of every marker to a force at
// one: three fluid steps (one per component) instead of the 3n of the dense mobility, and a solve
// costs two transforms instead of a dense LU solve of order 3n.
// A mode M does not see is given zero force: a uniform force normal to the plane between walls
// moves no fluid (the pressure holds it), and the velocity it would have to cancel, the mean
// normal flow through the plane, is zero by incompressibility. Singular values of m^(p) below
// 1e-10 of the largest over all p count as zero (the trial responses are exact to about 1e-13).
// The transforms are direct and separable, O(n (n_a + n_b)) per component on the host: for the
// walls here (n up to a few thousand markers) a millisecond.
// Units: whatever the responses carry (cm/s per dyn); positions cm.
#include "rbfib/core/exec.hpp"
#include "rbfib/grid/mac.hpp"

#include <array>
#include <complex>
#include <optional>
#include <vector>

namespace rbfib::sim {

/// Markers on a lattice over a periodic plane: marker[i + n[0] j] is the marker at lattice point
/// (i, j), i along axes[0], j along axes[1]; the plane is normal to `normal`.
struct MarkerLattice {
  int normal = 1;
  std::array<int, 2> axes{{0, 2}};
  std::array<index_t, 2> n{{0, 0}};
  std::vector<index_t> marker;
  index_t size() const { return n[0] * n[1]; }
};

/// The lattice of the markers X (host, 3n, X[d n + k], cm) on `grid`, or nothing when they do not
/// lie on one plane normal to an axis with both in-plane axes periodic, one per point of a regular
/// lattice that tiles the box with a spacing of a whole number of cells (to 1e-9 of a cell).
std::optional<MarkerLattice> commensurate_lattice(const std::vector<double>& X, const MacGrid& grid);

class CirculantMobility {
 public:
  /// From response[c] (3n, u[e n + k]): the velocity at every marker for a unit force along c at
  /// the lattice point (0, 0).
  CirculantMobility(MarkerLattice lattice, const std::array<std::vector<double>, 3>& response);

  /// b (3n, b[e n + k]) -> the force Lambda with M Lambda = b, in place (the modes M does not see
  /// get zero).
  void solve(std::vector<double>& b) const;

  /// The number of (wavenumber, direction) modes taken as singular.
  index_t singular_modes() const { return singular_; }
  const MarkerLattice& lattice() const { return lattice_; }

 private:
  using cplx = std::complex<double>;
  /// The separable transform over the lattice, in place, of a[i + n0 j]: sign -1 forward,
  /// +1 backward (unscaled).
  void transform(std::vector<cplx>& a, int sign) const;

  MarkerLattice lattice_;
  std::array<std::vector<cplx>, 2> roots_;  // exp(-2 pi i k / n) per axis
  std::vector<cplx> inverse_;               // per wavenumber, the 3 x 3 pseudo-inverse of m^(p), row-major
  index_t singular_ = 0;
};

}  // namespace rbfib::sim
