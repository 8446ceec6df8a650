#pragma once
// The Eulerian side of interpolation and spreading (seed Sec. 4.1): one scalar component of a
// staggered field on a Box (lib/rbfib/grid/box.hpp), unknown p = i + n_x (j + n_y k) at
// x = origin + h (i + g) per axis. On the MAC grid, component d lives on the faces normal to d:
// g = 1 along axis d (the face x = origin + h (i + 1)) and g = 1/2 along the other axes.
//
// Grid cells (Fig. 4.1): for a kernel of support s, the point X belongs to cell
//   floor(X) = floor(u) + 1       (s even),     floor(X) = floor(u + 1/2)   (s odd),
// u = (X - origin)/h - g, so that the support points are floor(X) + sigma for the shifts of
// Alg. 4.1, sigma_a in [-floor(s/2), floor((s-1)/2)], and the weight of shift sigma is
// prod_a phi(sigma_a + delta_a) with delta = floor(X) - u (delta in (0,1] for even s, (-1/2,1/2]
// for odd s).
//
// The grid indexing function # (eq. 4.5) maps a cell to its unknown, or to "none" (-1): on a
// periodic axis the cell index wraps mod N; on a wall axis, cells outside 0 <= i < unknowns (ghost
// points and points on the wall itself, e.g. the wall face of a g = 1 component) have none and
// contribute nothing. The key function kappa is injective on all cells a point can occupy,
// including those ghost cells: kappa(i) = (i_x + o_x) + E_x ((i_y + o_y) + E_y (i_z + o_z)) with
// o = 0, E = N on periodic axes and o = 1, E = N + 2 on wall axes.
#include "rbfib/core/exec.hpp"
#include "rbfib/grid/box.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace rbfib::ib {

using key_t = std::uint32_t;

/// One axis of a component grid, plain data for kernels.
struct GridAxis {
  int cells = 1;       ///< N
  int n = 1;           ///< unknowns along this axis
  bool periodic = true;
  double origin = 0.0, length = 1.0, h = 1.0, inv_h = 1.0, g = 0.5;
  int key_offset = 0, key_extent = 1;

  /// A window of a longer periodic axis (a process's slab with its ghost planes, dist/): the
  /// period of that axis in cells; 0 for an axis that is its own period or a wall.
  int period = 0;

  /// Position in index units, u = (x - origin)/h - g, wrapped into [0, N] on periodic axes; on a
  /// window, the image nearest the window's middle, u in [(N - period)/2, (N + period)/2).
  RBFIB_HD double index_position(double x) const {
    double u = (x - origin) * inv_h - g;
    if (period > 0) {
      const double c = 0.5 * (cells - period);
      if (u < c || u >= c + period) u -= period * floor((u - c) / period);
    } else if (periodic && (u < 0.0 || u >= cells)) {
      u -= cells * floor(u / cells);
    }
    return u;
  }
  /// The grid indexing function # along this axis: unknown index of cell i, or -1 for none.
  RBFIB_HD int index(int i) const {
    if (periodic) {
      // Cells and shifts stay within one period of [0, N) (N >= s); avoid the division then.
      if (i < 0) i += cells;
      else if (i >= cells) i -= cells;
      if (i < 0 || i >= cells) {
        i %= cells;
        if (i < 0) i += cells;
      }
      return i;
    }
    return (i >= 0 && i < n) ? i : -1;
  }
  /// Cell index wrapped for the key (periodic) or as is (wall).
  RBFIB_HD int key_index(int i) const { return periodic ? index(i) + key_offset : i + key_offset; }
};

/// The cell of a point along one axis for support s, and delta = cell - u.
template <int S>
RBFIB_HD inline int cell_of(const GridAxis& a, double x, double& delta) {
  const double u = a.index_position(x);
  const int i = (S % 2 == 0) ? int(floor(u)) + 1 : int(floor(u + 0.5));
  delta = i - u;
  return i;
}

/// One scalar component grid (a Box) as plain data.
struct ComponentGrid {
  GridAxis axis[3];
  index_t stride[3] = {1, 1, 1};
  index_t size = 1;

  /// Unknown index of cell (i, j, k) or -1 if it has none (eq. 4.5).
  RBFIB_HD index_t index(int i, int j, int k) const {
    const int a = axis[0].index(i), b = axis[1].index(j), c = axis[2].index(k);
    if (a < 0 || b < 0 || c < 0) return -1;
    return a + stride[1] * b + stride[2] * c;
  }
  /// kappa of the key function (Sec. 4.1.3): injective on cells points can occupy.
  RBFIB_HD key_t key(int i, int j, int k) const {
    return key_t(axis[0].key_index(i)) +
           key_t(axis[0].key_extent) * (key_t(axis[1].key_index(j)) + key_t(axis[1].key_extent) * key_t(axis[2].key_index(k)));
  }
  /// kappa^{-1}: the cell of a key (ghost cells of wall axes included).
  RBFIB_HD void cell_of_key(key_t key, int c[3]) const {
    c[0] = int(key % key_t(axis[0].key_extent)) - axis[0].key_offset;
    key /= key_t(axis[0].key_extent);
    c[1] = int(key % key_t(axis[1].key_extent)) - axis[1].key_offset;
    c[2] = int(key / key_t(axis[1].key_extent)) - axis[2].key_offset;
  }
};

/// Component grid of a 3D box for a kernel of support `support`. Throws InputError when the box is
/// not 3D, a staggering is not in (0, 1], an axis has fewer cells than the support (on a periodic
/// axis the kernel would wrap onto itself), or the number of keys does not fit in 32 bits.
ComponentGrid make_component_grid(const Box& box, int support);

/// The three boxes of a MAC grid with `cells` cells of width h = length/cells per axis, origin 0:
/// component d has g = 1 along d and 1/2 along the other axes; wall axes carry Dirichlet data.
std::array<Box, 3> mac_boxes(std::array<int, 3> cells, std::array<double, 3> length,
                             std::array<bool, 3> periodic);

}  // namespace rbfib::ib
