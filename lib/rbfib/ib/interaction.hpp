#pragma once
// Interpolation and spreading between Lagrangian points and the three components of a staggered
// (MAC) velocity/force grid (seed Chapter 4, Algs. 4.1-4.6), with the Peskin convention
//
//   interpolation:  U_c(X_k) = sum_x u_c(x) delta_h(x - X_k) h^3                (I u, values),
//   spreading:      f_c(x)   = sum_k F_c,k delta_h(x - X_k)                     (S F, densities),
//
// delta_h(x) = prod_a h^{-1} phi(x_a / h) (eq. 4.4), phi the kernel chosen by name (kernels.hpp).
// Spreading takes values F (a force, e.g. a force density times its area element, dyn) and
// produces a density on the grid (dyn/cm^3): the sum over the grid of f h^3 equals sum_k F_k away
// from walls, and S is the adjoint of I: sum_x h^3 (S F)(x) u(x) = sum_k F_k (I u)(X_k).
//
// Layout: points X are structure-of-arrays, X[d n + k] = coordinate d of point k (internal length
// units, cm), likewise F and U; grid component c is one vector indexed as its Box (x fastest).
// Points may lie anywhere along a periodic axis (they wrap); along a wall axis they must lie in
// [origin, origin + L]; support points outside the domain or on a wall contribute nothing.
//
// Algorithms (all give the same result up to the order of summation):
//   Interpolation::serial        Alg. 4.3 on one thread (the serial reference)
//   Interpolation::parallel      Alg. 4.3, one thread per point
//   Interpolation::binned        Alg. 4.3 on points sorted by grid cell, with separable weights
//   Spreading::serial            Alg. 4.2
//   Spreading::sort_reduce       Alg. 4.4 (key sort + one segmented reduce per shift; the runs of
//                                equal sorted keys are found once per call and each segment is
//                                summed by one thread)
//   Spreading::preallocated      Alg. 4.5 (buffer of sz vectors owned by this object)
//   Spreading::on_the_fly        Alg. 4.6 (buffer allocated and freed in each call)
//   Spreading::binned            points sorted by grid cell (counting sort of (z, y) cell rows,
//                                then by x cell within each row),
//                                z-slabs of at least s + 1 planes spread in two colours so that no
//                                two concurrent slabs touch the same unknown; separable weights.
//                                Not in the seed: a CPU-oriented variant, equal to Alg. 4.2.
#include "rbfib/core/exec.hpp"
#include "rbfib/grid/box.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/kernels.hpp"

#include <array>
#include <string>
#include <vector>

namespace rbfib::ib {

enum class Interpolation { serial, parallel, binned };
enum class Spreading { serial, sort_reduce, preallocated, on_the_fly, binned };

const char* to_string(Interpolation a);
const char* to_string(Spreading a);
/// The seed's algorithm number ("4.3", "4.2", ...) or "binned".
const char* algorithm_number(Interpolation a);
const char* algorithm_number(Spreading a);
std::vector<Interpolation> all_interpolations();
std::vector<Spreading> all_spreadings();

/// Number of shifts processed per sweep by Algs. 4.5 and 4.6 (the seed's sz; it used sz = 8).
inline constexpr int buffer_width = 8;

class Interaction;

/// Points sorted once by grid cell (the order of the binned algorithms) with the sorted copy of
/// their positions: every interpolation or spreading at the same positions reuses the sort (the
/// coupled step interpolates twice at X^n). Filled by Interaction::sort; valid for that
/// Interaction until the positions change.
class SortedPoints {
 public:
  index_t size() const { return n_; }

 private:
  friend class Interaction;
  index_t n_ = 0;
  device_vector<int> perm_, slab_start_;
  dvec x_;
};

/// One kernel and one MAC grid. Calls reuse workspace held by the object (sort keys, the Alg. 4.5
/// buffer), so one object must not be used by two threads at once; the algorithms themselves
/// run in parallel on the execution device.
class Interaction {
 public:
  /// components: the three component boxes (e.g. mac_boxes(...)), sharing cells, lengths, origins
  /// and boundary kinds per axis.
  Interaction(const std::array<Box, 3>& components, Kernel kernel);

  Kernel kernel() const { return kernel_; }
  int support() const { return support_; }
  const ComponentGrid& grid(int c) const { return grids_[c]; }
  /// h^3 of the cells (the grid's volume element).
  double cell_volume() const;

  /// U = I u for all three components; U is resized to 3n.
  void interpolate(const dvec& X, const std::array<dvec, 3>& u, dvec& U, Interpolation alg = Interpolation::binned);
  /// f = S F for all three components (f is overwritten; each f[c] is resized to its grid).
  void spread(const dvec& X, const dvec& F, std::array<dvec, 3>& f, Spreading alg = Spreading::binned);

  /// Sorts n points by grid cell into s (reusing its storage), after check_points. X points to 3n
  /// values on the execution device, X[d n + k]: a block of a larger array (a batch's state) is
  /// read in place.
  void sort(const double* X, index_t n, SortedPoints& s);
  /// U = I u at sorted points (binned algorithm); U points to 3 s.size() values, original order.
  void interpolate(const SortedPoints& s, const std::array<dvec, 3>& u, double* U);
  /// f = S F from sorted points (binned algorithm); F points to 3 s.size() values, original order.
  /// add: f += S F instead (f must already have each component's size), so that several point
  /// sets spread into one field without a zeroing and a sum per set.
  void spread(const SortedPoints& s, const double* F, std::array<dvec, 3>& f, bool add = false);

  /// Makes periodic axis d a window of a longer periodic axis of `period` cells (a process's slab
  /// of a split grid, with its ghost planes): each point is then used at its image nearest the
  /// window's middle, and check_points refuses points whose support leaves the window.
  void set_window(int d, int period);

  /// Throws InputError naming the point and axis if some coordinate is not finite, or lies outside
  /// [origin, origin + L] along a wall axis (or its support outside a window). Called by
  /// interpolate, spread and sort.
  void check_points(const dvec& X) const;
  void check_points(const double* X, index_t n) const;

 private:
  template <class K>
  void interpolate_impl(const dvec& X, const std::array<dvec, 3>& u, dvec& U, Interpolation alg);
  template <class K>
  void spread_impl(const dvec& X, const dvec& F, std::array<dvec, 3>& f, Spreading alg);
  template <class K>
  void spread_sort_reduce(int c, index_t n, const dvec& X, const double* L, dvec& out);
  template <class K>
  void spread_buffered(int c, index_t n, const dvec& X, const double* L, dvec& out, dvec& buffer);
  void sort_keys(int c, int support, index_t n, const dvec& X);
  void bin_points(const double* X, index_t n, SortedPoints& s);
  void check_fields(const std::array<dvec, 3>& u) const;
  template <class K>
  void interpolate_sorted(const SortedPoints& s, const std::array<dvec, 3>& u, double* U);
  template <class K>
  void spread_sorted(const SortedPoints& s, const double* F, std::array<dvec, 3>& f, bool add);

  Kernel kernel_;
  int support_ = 0;
  std::array<ComponentGrid, 3> grids_;
  dvec buffer_;  // Alg. 4.5: buffer_width vectors of the largest component, zero between calls
  // workspace, reused between calls
  device_vector<key_t> keys_, keys_reduced_;
  device_vector<int> perm_, bins_, xcell_, sorted_xcell_, counts_, segments_;
  index_t segment_count_ = 0;
  dvec values_, values_reduced_, sorted_f_;
  SortedPoints sorted_;  // the sort of the dvec calls
  int slabs_ = 1;
};

}  // namespace rbfib::ib
