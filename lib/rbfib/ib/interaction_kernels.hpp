#pragma once
// Pointwise kernels of interpolation and spreading (one Lagrangian point, one sorted position,
// one reduced key or one grid unknown per call). The launches live in interaction.cpp.
// Notation follows seed Sec. 4.1: cell = floor(X), shifts sigma_j of Alg. 4.1, weight
// w_j = prod_a phi(sigma_j,a + delta_a), unknown # (cell + sigma_j), key kappa(cell).
#include "rbfib/core/exec.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/kernels.hpp"
#include "rbfib/ib/shifts.hpp"

// The per-point helpers below must inline into the loops that call them.
#if defined(__CUDACC__)
#define RBFIB_IB_INLINE __forceinline__
#elif defined(__GNUC__)
#define RBFIB_IB_INLINE inline __attribute__((always_inline))
#else
#define RBFIB_IB_INLINE inline
#endif

namespace rbfib::ib::detail {

/// Cell and delta of point k along all axes.
template <int S>
RBFIB_HD inline void locate(const ComponentGrid& g, const double* X, index_t n, index_t k, int cell[3], double delta[3]) {
  for (int a = 0; a < 3; ++a) cell[a] = cell_of<S>(g.axis[a], X[a * n + k], delta[a]);
}

/// delta_h(h sigma_j + Delta x) h^3 evaluated as in the seed (one product per shift).
template <class K>
RBFIB_HD inline double shift_weight(int j, const double delta[3]) {
  constexpr int S = K::support;
  return K::phi(shift_component(j, S, 0) + delta[0]) * K::phi(shift_component(j, S, 1) + delta[1]) *
         K::phi(shift_component(j, S, 2) + delta[2]);
}

template <int S>
RBFIB_HD inline index_t shift_index(const ComponentGrid& g, int j, const int cell[3]) {
  return g.index(cell[0] + shift_component(j, S, 0), cell[1] + shift_component(j, S, 1), cell[2] + shift_component(j, S, 2));
}

// ---- Alg. 4.3: interpolation, one point ------------------------------------------------------
template <class K>
struct InterpolatePoint {
  ComponentGrid g;
  const double* X;
  index_t n;
  const double* e;
  double* E;
  RBFIB_HD void operator()(index_t k) const {
    constexpr int S = K::support;
    int cell[3];
    double delta[3];
    locate<S>(g, X, n, k, cell, delta);
    double v = 0.0;
    for (int j = 0; j < Shifts<S>::count; ++j) {
      const index_t m = shift_index<S>(g, j, cell);
      if (m >= 0) v += shift_weight<K>(j, delta) * e[m];
    }
    E[k] = v;
  }
};

/// Runs a per-point functor over all points in one task (the serial algorithms).
template <class F>
struct Serially {
  F f;
  index_t n;
  RBFIB_HD void operator()(index_t) const {
    for (index_t k = 0; k < n; ++k) f(k);
  }
};

// ---- Alg. 4.2: serial spreading, one point ---------------------------------------------------
template <class K>
struct SpreadPoint {
  ComponentGrid g;
  const double* X;
  index_t n;
  const double* L;
  double scale;  // h^{-3}
  double* l;
  RBFIB_HD void operator()(index_t k) const {
    constexpr int S = K::support;
    int cell[3];
    double delta[3];
    locate<S>(g, X, n, k, cell, delta);
    const double Lk = L[k] * scale;
    for (int j = 0; j < Shifts<S>::count; ++j) {
      const index_t m = shift_index<S>(g, j, cell);
      if (m >= 0) l[m] += shift_weight<K>(j, delta) * Lk;
    }
  }
};

// ---- Algs. 4.4-4.6 ---------------------------------------------------------------------------
/// Lines 4-7: K_i = kappa(floor(X_i)), P_i = i.
template <int S>
struct MakeKeys {
  ComponentGrid g;
  const double* X;
  index_t n;
  key_t* K;
  int* P;
  RBFIB_HD void operator()(index_t i) const {
    int cell[3];
    double delta[3];
    locate<S>(g, X, n, i, cell, delta);
    K[i] = g.key(cell[0], cell[1], cell[2]);
    P[i] = int(i);
  }
};

/// Lines 12-18 of Alg. 4.4: V_i = w_j(X_{P_i}) L_{P_i}.
template <class K>
struct ShiftValues {
  ComponentGrid g;
  const double* X;
  index_t n;
  const double* L;
  const int* P;
  double scale;
  int j;
  double* V;
  RBFIB_HD void operator()(index_t i) const {
    int cell[3];
    double delta[3];
    const index_t p = P[i];
    locate<K::support>(g, X, n, p, cell, delta);
    V[i] = shift_weight<K>(j, delta) * L[p] * scale;
  }
};

/// Whether sorted position p starts a run of equal keys.
struct IsSegmentHead {
  const key_t* K;
  RBFIB_HD bool operator()(index_t p) const { return p == 0 || K[p] != K[p - 1]; }
};

/// Segmented reduce (line 19 of Alg. 4.4, line 22 of Alg. 4.5): V'_i = sum of V over segment i
/// of the sorted keys, and K'_i its key. The segments are the same for every shift.
template <class T>
struct SegmentSum {
  const int* start;  // q + 1 offsets
  const key_t* K;
  const T* V;
  key_t* Kr;
  T* Vr;
  RBFIB_HD void operator()(index_t i) const {
    const int b = start[i], e = start[i + 1];
    T v = V[b];
    for (int p = b + 1; p < e; ++p) v = add(v, V[p]);
    Vr[i] = v;
    Kr[i] = K[b];
  }
  RBFIB_HD static double add(double a, double b) { return a + b; }
  template <class P>
  RBFIB_HD static P add(const P& a, const P& b) {
    P c;
    for (int k = 0; k < 8; ++k) c.v[k] = a.v[k] + b.v[k];
    return c;
  }
};

/// Lines 20-26 of Alg. 4.4: l_m += V'_i for m = #(kappa^{-1}(K'_i) + sigma_j).
template <int S>
struct WriteReduced {
  ComponentGrid g;
  const key_t* K;
  const double* V;
  int j;
  double* l;
  RBFIB_HD void operator()(index_t i) const {
    int cell[3];
    g.cell_of_key(K[i], cell);
    const index_t m = shift_index<S>(g, j, cell);
    if (m >= 0) l[m] += V[i];
  }
};

/// sz values reduced together in Algs. 4.5/4.6.
struct Pack {
  double v[8];
};

/// Lines 13-21 of Alg. 4.5: V_ik = w_{sz b + k}(X_{P_i}) L_{P_i}.
template <class K>
struct PackValues {
  ComponentGrid g;
  const double* X;
  index_t n;
  const double* L;
  const int* P;
  double scale;
  int first;  // sz b
  Pack* V;
  RBFIB_HD void operator()(index_t i) const {
    constexpr int S = K::support;
    int cell[3];
    double delta[3];
    const index_t p = P[i];
    locate<S>(g, X, n, p, cell, delta);
    const double Lp = L[p] * scale;
    Pack v;
    for (int k = 0; k < 8; ++k) {
      const int j = first + k;
      v.v[k] = j < Shifts<S>::count ? shift_weight<K>(j, delta) * Lp : 0.0;
    }
    V[i] = v;
  }
};

/// Lines 23-31 of Alg. 4.5: l_{m,k} += V'_ik into buffer vector k.
template <int S>
struct WriteReducedPack {
  ComponentGrid g;
  const key_t* K;
  const Pack* V;
  int first;
  index_t stride;  // length of one buffer vector
  double* buffer;
  RBFIB_HD void operator()(index_t i) const {
    int cell[3];
    g.cell_of_key(K[i], cell);
    const Pack v = V[i];
    for (int k = 0; k < 8; ++k) {
      const int j = first + k;
      if (j >= Shifts<S>::count) break;
      const index_t m = shift_index<S>(g, j, cell);
      if (m >= 0) buffer[k * stride + m] += v.v[k];
    }
  }
};

/// Line 34 of Alg. 4.5: l = sum_k l_k; the buffer is left zero for the next call.
struct SumBuffer {
  index_t stride;
  double* buffer;
  double* l;
  RBFIB_HD void operator()(index_t m) const {
    double s = 0.0;
    for (int k = 0; k < 8; ++k) {
      s += buffer[k * stride + m];
      buffer[k * stride + m] = 0.0;
    }
    l[m] = s;
  }
};

// ---- binned variants -------------------------------------------------------------------------
/// Cell-centred cell of a coordinate along an axis, in [0, N).
RBFIB_HD inline int plain_cell(const GridAxis& a, double x) {
  double u = (x - a.origin) * a.inv_h;
  if (a.periodic) u -= a.cells * floor(u / a.cells);
  int c = int(floor(u));
  if (c >= a.cells) c = a.periodic ? c - a.cells : a.cells - 1;
  if (c < 0) c = a.periodic ? c + a.cells : 0;
  return c;
}

/// bin = (z cell) N_y + (y cell): rows of cells, z slowest.
struct RowBin {
  GridAxis x, y, z;
  const double* X;
  index_t n;
  int* bin;
  int* xcell;
  RBFIB_HD void operator()(index_t i) const {
    bin[i] = plain_cell(z, X[2 * n + i]) * y.cells + plain_cell(y, X[n + i]);
    xcell[i] = plain_cell(x, X[i]);
  }
};

/// Counting sort, pass 1: chunk c counts its points per bin into counts[c B + bin] (chunk-major,
/// so that concurrent chunks never share a cache line of counters).
struct CountChunk {
  const int* bin;
  index_t n, bins;
  int chunks;
  int* counts;
  RBFIB_HD void operator()(index_t c) const {
    const index_t lo = n * c / chunks, hi = n * (c + 1) / chunks;
    int* mine = counts + c * bins;
    for (index_t i = lo; i < hi; ++i) ++mine[bin[i]];
  }
};

/// Storage position of the (bin-major, chunk-minor) scan index i = bin C + c.
struct ChunkMajor {
  index_t bins;
  int chunks;
  RBFIB_HD index_t operator()(index_t i) const { return (i % chunks) * bins + i / chunks; }
};

/// Counting sort, pass 2 (after an exclusive scan of counts): stable placement.
struct PlaceChunk {
  const int* bin;
  const int* xcell;
  index_t n, bins;
  int chunks;
  int* offsets;
  int* perm;
  int* sorted_xcell;
  RBFIB_HD void operator()(index_t c) const {
    const index_t lo = n * c / chunks, hi = n * (c + 1) / chunks;
    int* mine = offsets + c * bins;
    for (index_t i = lo; i < hi; ++i) {
      const int p = mine[bin[i]]++;
      perm[p] = int(i);
      sorted_xcell[p] = xcell[i];
    }
  }
};

/// After placement: sorts the points of each (z, y) row by their x cell (stable insertion sort
/// on the keys in sorted order), so that the order is by cell (z, y, x) and deterministic. Rows
/// with more than max_row points keep their placement order (locality only; no quadratic cost).
/// Also records the first sorted position of each z-slab (slab s covers the planes
/// [s N_z / slabs, (s+1) N_z / slabs)), start[slabs] = n.
struct SortRow {
  static constexpr int max_row = 64;
  const int* ends;  // offsets after placement: ends[(C - 1) B + b] is the end of row b
  index_t bins;
  int chunks;
  int* key;         // x cells in sorted order
  int* perm;
  int slabs, planes, rows;
  int* start;
  RBFIB_HD void operator()(index_t b) const {
    const int* last = ends + index_t(chunks - 1) * bins;
    const int lo = b == 0 ? 0 : last[b - 1];
    const int hi = last[b];
    if (b % rows == 0) {
      const index_t plane = b / rows;
      for (int s = 0; s < slabs; ++s)
        if (index_t(s) * planes / slabs == plane) start[s] = lo;
    }
    if (b == bins - 1) start[slabs] = hi;
    if (hi - lo > max_row) return;
    for (int p = lo + 1; p < hi; ++p) {
      const int k = perm[p], kk = key[p];
      int q = p - 1;
      while (q >= lo && key[q] > kk) {
        perm[q + 1] = perm[q];
        key[q + 1] = key[q];
        --q;
      }
      perm[q + 1] = k;
      key[q + 1] = kk;
    }
  }
};

/// Zeroes the three output components of spreading (one launch for all three).
struct ZeroThree {
  index_t n0, n1, n2;
  double* l0;
  double* l1;
  double* l2;
  RBFIB_HD void operator()(index_t m) const {
    if (m < n0) l0[m] = 0.0;
    if (m < n1) l1[m] = 0.0;
    if (m < n2) l2[m] = 0.0;
  }
};

/// Gathers coordinates (and optionally values) in sorted order.
struct GatherSorted {
  const int* perm;
  index_t n;
  const double* X;  // may be null (F alone)
  const double* F;  // may be null (X alone)
  double* Xs;
  double* Fs;
  RBFIB_HD void operator()(index_t p) const {
    const index_t k = perm[p];
    if (X)
      for (int d = 0; d < 3; ++d) Xs[d * n + p] = X[d * n + k];
    if (F)
      for (int d = 0; d < 3; ++d) Fs[d * n + p] = F[d * n + k];
  }
};

/// The support of one point in one component: unknown offsets of the s rows along y and z and
/// of the s points along x (-1: none), and whether the x points are contiguous (the usual case).
template <int S>
struct Stencil {
  index_t ix[S], iy[S], iz[S];
  bool contiguous_x;
  RBFIB_HD void build(const ComponentGrid& g, const int first[3]) {
    contiguous_x = true;
    for (int t = 0; t < S; ++t) {
      const int a = g.axis[0].index(first[0] + t), b = g.axis[1].index(first[1] + t), c = g.axis[2].index(first[2] + t);
      ix[t] = a;
      iy[t] = b < 0 ? -1 : b * g.stride[1];
      iz[t] = c < 0 ? -1 : c * g.stride[2];
      if (a != ix[0] + t || a < 0) contiguous_x = false;
    }
  }
};

/// Whether the support lies inside the grid without wrapping along any axis: then the unknowns
/// are first + (tx, ty, tz) . stride and no index needs checking.
RBFIB_HD RBFIB_IB_INLINE bool interior(const ComponentGrid& g, const int first[3], int S) {
  for (int a = 0; a < 3; ++a)
    if (first[a] < 0 || first[a] + S > g.axis[a].n) return false;
  return true;
}

/// (v0 + v1) + (v2 + v3) + ...: a short dependency chain.
template <int S>
RBFIB_HD RBFIB_IB_INLINE double pairwise_sum(const double* v) {
  if constexpr (S == 1) {
    return v[0];
  } else {
    return pairwise_sum<S / 2>(v) + pairwise_sum<S - S / 2>(v + S / 2);
  }
}

/// sum over the support of w_x w_y w_z e (tensor-product order: x, then y, then z).
template <int S>
RBFIB_HD RBFIB_IB_INLINE double gather(const ComponentGrid& g, const int first[3], const double* const w[3], const double* e) {
  if (interior(g, first, S)) {
    // All s^2 row sums are independent (their loads overlap); then pairwise sums along y and z.
    const double* base = e + first[0] + g.stride[1] * first[1] + g.stride[2] * first[2];
    double vz[S];
    for (int tz = 0; tz < S; ++tz) {
      double vy[S];
      for (int ty = 0; ty < S; ++ty) {
        const double* row = base + tz * g.stride[2] + ty * g.stride[1];
        double xs[S];
        for (int tx = 0; tx < S; ++tx) xs[tx] = w[0][tx] * row[tx];
        vy[ty] = w[1][ty] * pairwise_sum<S>(xs);
      }
      vz[tz] = w[2][tz] * pairwise_sum<S>(vy);
    }
    return pairwise_sum<S>(vz);
  }
  Stencil<S> st;
  st.build(g, first);
  double v = 0.0;
  for (int tz = 0; tz < S; ++tz) {
    if (st.iz[tz] < 0) continue;
    double vz = 0.0;
    for (int ty = 0; ty < S; ++ty) {
      if (st.iy[ty] < 0) continue;
      const double* row = e + st.iz[tz] + st.iy[ty];
      double vy = 0.0;
      for (int tx = 0; tx < S; ++tx)
        if (st.ix[tx] >= 0) vy += w[0][tx] * row[st.ix[tx]];
      vz += w[1][ty] * vy;
    }
    v += w[2][tz] * vz;
  }
  return v;
}

/// l += w_x w_y w_z F over the support.
template <int S>
RBFIB_HD RBFIB_IB_INLINE void scatter(const ComponentGrid& g, const int first[3], const double* const w[3], double F, double* l) {
  if (interior(g, first, S)) {
    double* base = l + first[0] + g.stride[1] * first[1] + g.stride[2] * first[2];
    for (int tz = 0; tz < S; ++tz) {
      const double fz = w[2][tz] * F;
      for (int ty = 0; ty < S; ++ty) {
        double* row = base + tz * g.stride[2] + ty * g.stride[1];
        const double fy = w[1][ty] * fz;
        for (int tx = 0; tx < S; ++tx) row[tx] += w[0][tx] * fy;
      }
    }
    return;
  }
  Stencil<S> st;
  st.build(g, first);
  for (int tz = 0; tz < S; ++tz) {
    if (st.iz[tz] < 0) continue;
    const double fz = w[2][tz] * F;
    for (int ty = 0; ty < S; ++ty) {
      if (st.iy[ty] < 0) continue;
      double* row = l + st.iz[tz] + st.iy[ty];
      const double fy = w[1][ty] * fz;
      for (int tx = 0; tx < S; ++tx)
        if (st.ix[tx] >= 0) row[st.ix[tx]] += w[0][tx] * fy;
    }
  }
}

struct ThreeGrids {
  ComponentGrid g[3];
};

/// Separable weights of one point for one component: w[a][t] = phi(t - s/2 + delta_a) and the
/// first support cell along each axis.
template <class K>
RBFIB_HD RBFIB_IB_INLINE void component_weights(const ComponentGrid& g, const double x[3], int first[3], double w[3][K::support]) {
  constexpr int S = K::support;
  for (int a = 0; a < 3; ++a) {
    double delta;
    first[a] = cell_of<S>(g.axis[a], x[a], delta) - S / 2;
    axis_weights<K>(delta, w[a]);
  }
}

/// Interpolation of one component at sorted position p (points sorted by bin_points). One pass
/// per component keeps the working set of the grid small (one component's rows).
template <class K>
struct InterpolateSorted {
  ComponentGrid g;
  const double* Xs;
  const int* perm;
  index_t n;
  const double* e;
  double* E;
  RBFIB_HD void operator()(index_t p) const {
    constexpr int S = K::support;
    const double x[3] = {Xs[p], Xs[n + p], Xs[2 * n + p]};
    int first[3];
    double w[3][S];
    component_weights<K>(g, x, first, w);
    const double* wp[3] = {w[0], w[1], w[2]};
    E[perm[p]] = gather<S>(g, first, wp, e);
  }
};

/// Spreading of all sorted points of one z-slab of the given colour (slab 2t + colour), one
/// component after the other.
template <class K>
struct SpreadSlab {
  ThreeGrids grids;
  const double* Xs;
  const double* Fs;
  const int* start;
  index_t n;
  double scale;
  int colour;
  double* l0;
  double* l1;
  double* l2;
  RBFIB_HD void operator()(index_t t) const {
    constexpr int S = K::support;
    const index_t s = 2 * t + colour;
    double* l[3] = {l0, l1, l2};
    for (int c = 0; c < 3; ++c) {
      const ComponentGrid& g = grids.g[c];
      for (index_t p = start[s]; p < start[s + 1]; ++p) {
        const double x[3] = {Xs[p], Xs[n + p], Xs[2 * n + p]};
        int first[3];
        double w[3][S];
        component_weights<K>(g, x, first, w);
        const double* wp[3] = {w[0], w[1], w[2]};
        scatter<S>(g, first, wp, Fs[c * n + p] * scale, l[c]);
      }
    }
  }
};

/// How many periods away from the box a point on a periodic axis may lie (wrapping further away
/// would lose the position to rounding).
inline constexpr double periodic_reach = 1048576.0;

/// Index of the first bad coordinate (not finite, or outside a wall axis), or 3n if none.
struct BadCoordinate {
  GridAxis axis[3];
  const double* X;
  index_t n;
  int support;
  RBFIB_HD index_t operator()(index_t e) const {
    const int d = int(e / n);
    const double x = X[e];
    const GridAxis& a = axis[d];
    const bool finite = x == x && x - x == 0.0;
    // On a window the support must stay inside it: cells floor(u) - s/2 + 1 .. floor(u) + s/2 for
    // an even support, round(u) -+ (s - 1)/2 for an odd one.
    const int half = support / 2;
    const double u = a.period > 0 && finite ? a.index_position(x) : 0.0;
    const bool inside =
        a.period > 0 ? (finite && u >= half && u <= a.cells - half - 1)
        : a.periodic ? (x - a.origin <= periodic_reach * a.length && a.origin - x <= periodic_reach * a.length)
                     : (x >= a.origin && x <= a.origin + a.length);
    return (finite && inside) ? 3 * n : e;
  }
};

struct MinIndex {
  RBFIB_HD index_t operator()(index_t a, index_t b) const { return a < b ? a : b; }
};

}  // namespace rbfib::ib::detail
