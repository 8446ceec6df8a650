#pragma once
// Pointwise kernels of the MAC-grid operators (Section 2.1): the centred difference D_a and average
// A_a on staggered fields, the divergence, the gradient, and the conservative advection of eq. 2.5
// (Morinishi's Div.-S2). A kernel's at(p, i) takes one grid index p and its indices i; for_each_point
// launches it over a box (mac_operators.cpp).
//
// Advection reads a padded copy of each velocity component: one extra layer on both ends of every
// axis (index -1 and n), filled by periodic wrap, by the boundary value (normal component, g = 1:
// the layer is the wall itself) or by the ghost extrapolation of eq. A.7 (tangential components).
#include "rbfib/grid/box.hpp"

namespace rbfib::kernels {

/// One launch index per row of x: the row's points in order, their indices counted rather than
/// divided out of p (two 64-bit divisions per point cost more than these kernels' arithmetic), in
/// a loop the host compiler can vectorize.
template <class K>
struct RowsOf {
  BoxShape s;
  K k;
  RBFIB_HD void operator()(index_t row) const {
    int i[3] = {0, int(row % s.n[1]), int(row / s.n[1])};
    const index_t base = row * s.n[0];
    for (int i0 = 0; i0 < s.n[0]; ++i0) {
      i[0] = i0;
      k.at(base + i0, i);
    }
  }
};

/// One launch index per point.
template <class K>
struct PointsOf {
  BoxShape s;
  K k;
  RBFIB_HD void operator()(index_t p) const {
    int i[3];
    s.split(p, i);
    k.at(p, i);
  }
};

/// Runs k.at(p, i) at every point of box s: by rows on the CPU backend (a row is a cache-friendly
/// unit of work), by points on the CUDA backend (one thread each, coalesced).
template <class K>
void for_each_point(const BoxShape& s, const K& k) {
  const index_t n = index_t(s.n[0]) * s.n[1] * s.n[2];
#if defined(RBFIB_BACKEND_CUDA)
  for_each_index(n, PointsOf<K>{s, k});
#else
  for_each_index(n / s.n[0], RowsOf<K>{s, k});
#endif
}

/// A box with one ghost layer on both ends of each of its dims axes.
struct PaddedShape {
  int dims = 3;
  int n[3] = {1, 1, 1};         ///< unknowns per axis (not counting ghosts)
  index_t stride[3] = {1, 1, 1};  ///< strides of the padded array
  index_t size = 1;

  /// Padded position of unknown (i, j, k); each index may be -1 or n on padded axes.
  RBFIB_HD index_t at(int i, int j, int k) const {
    return index_t(i + 1) * stride[0] + index_t(dims > 1 ? j + 1 : 0) * stride[1] + index_t(dims > 2 ? k + 1 : 0) * stride[2];
  }
  RBFIB_HD int extent(int d) const { return d < dims ? n[d] + 2 : 1; }
};

inline PaddedShape padded_of(const BoxShape& s) {
  PaddedShape p;
  p.dims = s.dims;
  for (int d = 0; d < 3; ++d) p.n[d] = s.n[d];
  p.stride[0] = 1;
  p.stride[1] = p.extent(0);
  p.stride[2] = p.stride[1] * p.extent(1);
  p.size = p.stride[2] * p.extent(2);
  return p;
}

/// Other axes of d, lower first (the face index order of BoundaryData).
RBFIB_HD inline void other_axes(int d, int& a, int& b) {
  a = d == 0 ? 1 : 0;
  b = d == 2 ? 1 : 2;
}

/// padded[interior] = u
struct PadInterior {
  PaddedShape ps;
  const double* u;
  double* out;
  RBFIB_HD void at(index_t p, const int i[3]) const { out[ps.at(i[0], i[1], i[2])] = u[p]; }
};

/// Ghost layer of a wall axis d on one side: u_ghost = ghost * u_adjacent + data * gamma (eq. A.7).
/// Runs over the face's unknowns (other axes' interior indices).
struct PadWall {
  PaddedShape ps;
  int d, side;
  AxisEnd end;
  const double* gamma;  ///< null: homogeneous data
  double* out;
  RBFIB_HD void operator()(index_t f) const {
    int a, b;
    other_axes(d, a, b);
    int i[3];
    i[a] = int(f % ps.n[a]);
    i[b] = int(f / ps.n[a]);
    i[d] = side ? ps.n[d] - 1 : 0;
    const double adj = out[ps.at(i[0], i[1], i[2])];
    i[d] = side ? ps.n[d] : -1;
    out[ps.at(i[0], i[1], i[2])] = end.ghost * adj + (gamma ? end.data * gamma[f] : 0.0);
  }
};

/// Ghost layers of a periodic axis d, over the whole padded extent of the other axes (so that
/// edges and corners next to already-filled layers are consistent).
struct PadPeriodic {
  PaddedShape ps;
  int d;
  double* out;
  RBFIB_HD void operator()(index_t f) const {
    int a, b;
    other_axes(d, a, b);
    const int ea = ps.extent(a);
    const index_t base = index_t(f % ea) * ps.stride[a] + index_t(f / ea) * ps.stride[b];
    const index_t st = ps.stride[d];
    const int n = ps.n[d];
    out[base] = out[base + index_t(n) * st];                  // index -1 <- n - 1
    out[base + index_t(n + 1) * st] = out[base + st];         // index n  <- 0
  }
};

/// Conservative advection of component a, eq. 2.5 (Div.-S2):
///   N_a = sum_b D_b[(A_a u_b)(A_b u_a)],
/// the products formed where u_a and u_b are collocated by averaging (cell centres for b = a,
/// cell edges otherwise). Reads padded components; writes N_a at the unknowns of component a.
struct Advection {
  BoxShape s;               ///< box of component a
  PaddedShape pad[3];       ///< padded shapes of all components
  const double* u[3];       ///< padded components
  double inv_h[3];
  int a;
  double* out;
  RBFIB_HD void at(index_t p, const int i[3]) const {
    const PaddedShape& pa = pad[a];
    const double* ua = u[a];
    const index_t c = pa.at(i[0], i[1], i[2]);
    double sum = 0.0;
    for (int b = 0; b < s.dims; ++b) {
      const index_t sb = pa.stride[b];
      if (b == a) {
        // (A_a u_a)^2 at the cell centres p +- h/2 e_a.
        const double up = 0.5 * (ua[c] + ua[c + sb]), dn = 0.5 * (ua[c - sb] + ua[c]);
        sum += (up * up - dn * dn) * inv_h[b];
      } else {
        // u_b at p + h/2 e_b - h/2 e_a has the index of p (along a and b); +h/2 e_a: a-index + 1.
        const PaddedShape& pb = pad[b];
        const double* ub = u[b];
        const index_t q = pb.at(i[0], i[1], i[2]);
        const index_t qa = pb.stride[a], qb = pb.stride[b];
        const double ub_up = 0.5 * (ub[q] + ub[q + qa]);             // A_a u_b at p + h/2 e_b
        const double ub_dn = 0.5 * (ub[q - qb] + ub[q - qb + qa]);   // A_a u_b at p - h/2 e_b
        const double ua_up = 0.5 * (ua[c] + ua[c + sb]);             // A_b u_a at p + h/2 e_b
        const double ua_dn = 0.5 * (ua[c - sb] + ua[c]);             // A_b u_a at p - h/2 e_b
        sum += (ub_up * ua_up - ub_dn * ua_dn) * inv_h[b];
      }
    }
    out[p] = sum;
  }
};

/// Discrete divergence at cell centres: sum_a D_a u_a, the faces on walls taken from the normal
/// boundary data (null: zero).
struct Divergence {
  BoxShape s;                 ///< scalar (cell-centred) box
  BoxShape comp[3];           ///< velocity component boxes
  bool periodic[3];
  const double* u[3];
  const double* normal_lo[3];  ///< normal velocity on the lower wall of axis a, face-indexed (or null)
  const double* normal_hi[3];
  double inv_h[3];
  double* out;
  RBFIB_HD void at(index_t p, const int i[3]) const {
    double div = 0.0;
    for (int a = 0; a < s.dims; ++a) {
      const BoxShape& ca = comp[a];
      const index_t base = i[0] * ca.stride[0] + i[1] * ca.stride[1] + i[2] * ca.stride[2] - i[a] * ca.stride[a];
      const int n = s.n[a];  // cells along a
      int o, q;
      other_axes(a, o, q);
      const index_t f = i[o] + index_t(s.n[o]) * i[q];
      double hi, lo;
      // upper face of cell i is unknown i of u_a (g = 1); on a wall axis the last one is the wall.
      if (periodic[a]) {
        hi = u[a][base + index_t(i[a]) * ca.stride[a]];
        lo = u[a][base + index_t(i[a] == 0 ? n - 1 : i[a] - 1) * ca.stride[a]];
      } else {
        hi = i[a] == n - 1 ? (normal_hi[a] ? normal_hi[a][f] : 0.0) : u[a][base + index_t(i[a]) * ca.stride[a]];
        lo = i[a] == 0 ? (normal_lo[a] ? normal_lo[a][f] : 0.0) : u[a][base + index_t(i[a] - 1) * ca.stride[a]];
      }
      div += (hi - lo) * inv_h[a];
    }
    out[p] = div;
  }
};

/// Component a of the discrete gradient of the cell-centred q (scalar box sc) at unknown i of u_a:
/// (q(x + h/2 e_a) - q(x - h/2 e_a)) / h_a; unknown i lies between cells i and i + 1 (wrapping on a
/// periodic axis).
RBFIB_HD inline double gradient_at(const BoxShape& sc, int a, double inv_h, const double* q, const int i[3]) {
  const index_t c = i[0] * sc.stride[0] + i[1] * sc.stride[1] + i[2] * sc.stride[2];
  const int up = i[a] + 1 == sc.n[a] ? -i[a] : 1;
  return (q[c + index_t(up) * sc.stride[a]] - q[c]) * inv_h;
}

/// Component a of the discrete gradient at its unknowns.
struct Gradient {
  BoxShape sc;  ///< scalar box
  int a;
  double inv_h;
  const double* q;
  double* out;
  RBFIB_HD void at(index_t p, const int i[3]) const {
    out[p] = gradient_at(sc, a, inv_h, q, i);
  }
};

/// gamma[f] += (G q)_c at p(f), p(f) the unknown of component c's box s adjacent to face (d, side):
/// the gradient only where the wall data take it, not over the whole box.
struct AddFaceGradient {
  BoxShape s;   ///< box of component c
  BoxShape sc;  ///< scalar box
  int c, d, side;
  double inv_h;  ///< 1 / h_c
  const double* q;
  double* gamma;
  RBFIB_HD void operator()(index_t f) const {
    int a, b;
    other_axes(d, a, b);
    int i[3];
    i[a] = int(f % s.n[a]);
    i[b] = int(f / s.n[a]);
    i[d] = side ? s.n[d] - 1 : 0;
    gamma[f] += gradient_at(sc, c, inv_h, q, i);
  }
};

}  // namespace rbfib::kernels
