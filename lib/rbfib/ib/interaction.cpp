#include "rbfib/ib/interaction.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/ib/interaction_kernels.hpp"
#include "rbfib/ib/kernels.hpp"

#include <thrust/copy.h>
#include <thrust/device_ptr.h>
#include <thrust/fill.h>
#include <thrust/iterator/permutation_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include <algorithm>
#include <cmath>

namespace rbfib::ib {

static_assert(sizeof(detail::Pack) == buffer_width * sizeof(double), "Algs. 4.5/4.6 reduce packs of buffer_width values");

const char* to_string(Interpolation a) {
  switch (a) {
    case Interpolation::serial: return "serial";
    case Interpolation::parallel: return "parallel";
    case Interpolation::binned: return "binned";
  }
  return "?";
}
const char* to_string(Spreading a) {
  switch (a) {
    case Spreading::serial: return "serial";
    case Spreading::sort_reduce: return "sort_reduce";
    case Spreading::preallocated: return "preallocated";
    case Spreading::on_the_fly: return "on_the_fly";
    case Spreading::binned: return "binned";
  }
  return "?";
}
const char* algorithm_number(Interpolation a) {
  switch (a) {
    case Interpolation::serial: return "4.3 (1 thread)";
    case Interpolation::parallel: return "4.3";
    case Interpolation::binned: return "binned";
  }
  return "?";
}
const char* algorithm_number(Spreading a) {
  switch (a) {
    case Spreading::serial: return "4.2";
    case Spreading::sort_reduce: return "4.4";
    case Spreading::preallocated: return "4.5";
    case Spreading::on_the_fly: return "4.6";
    case Spreading::binned: return "binned";
  }
  return "?";
}
std::vector<Interpolation> all_interpolations() { return {Interpolation::serial, Interpolation::parallel, Interpolation::binned}; }
std::vector<Spreading> all_spreadings() {
  return {Spreading::serial, Spreading::sort_reduce, Spreading::preallocated, Spreading::on_the_fly, Spreading::binned};
}

const char* to_string(Kernel k) {
  switch (k) {
    case Kernel::roma3: return Roma3::name;
    case Kernel::bspline3: return BSpline3::name;
    case Kernel::cosine4: return Cosine4::name;
    case Kernel::peskin4: return Peskin4::name;
  }
  return "unknown";
}

std::vector<Kernel> all_kernels() { return {Kernel::roma3, Kernel::bspline3, Kernel::cosine4, Kernel::peskin4}; }

std::vector<std::string> kernel_names() {
  std::vector<std::string> names;
  for (Kernel k : all_kernels()) names.push_back(to_string(k));
  return names;
}

Kernel kernel_named(const std::string& name, const std::string& field) {
  std::string all;
  for (Kernel k : all_kernels()) {
    if (name == to_string(k)) return k;
    all += std::string(all.empty() ? "" : ", ") + to_string(k);
  }
  throw InputError(field, name, "is not a known IB kernel (one of: " + all + ")");
}

int kernel_support(Kernel kernel) {
  int s = 0;
  with_kernel(kernel, [&](auto k) { s = decltype(k)::support; });
  return s;
}

Interaction::Interaction(const std::array<Box, 3>& components, Kernel kernel)
    : kernel_(kernel), support_(kernel_support(kernel)) {
  static const char* axis_names[3] = {"x", "y", "z"};
  for (int c = 0; c < 3; ++c) grids_[c] = make_component_grid(components[c], support_);
  for (int c = 1; c < 3; ++c)
    for (int a = 0; a < 3; ++a) {
      const GridAxis &p = grids_[0].axis[a], &q = grids_[c].axis[a];
      const std::string f = std::string("components[") + std::to_string(c) + "]." + axis_names[a];
      require(q.cells == p.cells, f + ".cells", q.cells, "all components must share the cells of component 0");
      require(q.length == p.length, f + ".length", q.length, "all components must share the length of component 0");
      require(q.origin == p.origin, f + ".origin", q.origin, "all components must share the origin of component 0");
      require(q.periodic == p.periodic, f + ".periodic", q.periodic, "all components must share the boundary kind");
    }
  // z-slabs of at least s + 1 planes; an even number of them on a periodic axis so that the
  // two colours alternate around the period.
  const GridAxis& z = grids_[0].axis[2];
  int slabs = z.cells / (support_ + 1);
  if (z.periodic) slabs -= slabs % 2;
  slabs_ = std::max(slabs, 1);
}

double Interaction::cell_volume() const {
  return grids_[0].axis[0].h * grids_[0].axis[1].h * grids_[0].axis[2].h;
}

void Interaction::check_points(const dvec& X) const {
  require(X.size() % 3 == 0, "X.size", X.size(), "points are stored as 3 n coordinates (x..., y..., z...)");
  check_points(ptr(X), index_t(X.size()) / 3);
}

void Interaction::check_points(const double* X, index_t n) const {
  require(n < index_t(1) << 31, "number of points", n, "at most 2^31 - 1 points");
  if (n == 0) return;
  detail::BadCoordinate bad{{grids_[0].axis[0], grids_[0].axis[1], grids_[0].axis[2]}, X, n, support_};
  const index_t first = thrust::transform_reduce(thrust::counting_iterator<index_t>(0),
                                                 thrust::counting_iterator<index_t>(3 * n), bad, 3 * n, detail::MinIndex{});
  if (first == 3 * n) return;
  const int d = int(first / n);
  const index_t k = first % n;
  const double x = thrust::device_pointer_cast(X)[first];
  const GridAxis& a = grids_[0].axis[d];
  static const char* names[3] = {"x", "y", "z"};
  const std::string field = std::string("X[") + std::to_string(k) + "]." + names[d];
  if (!std::isfinite(x)) throw InputError(field, to_text(x), "point coordinates must be finite");
  if (a.period > 0)
    throw InputError(field, to_text(x), "lies beyond this process's slab [" + to_text(a.origin) + ", " +
                                            to_text(a.origin + a.length) + "] (its ghost planes included) less the "
                                            "kernel's support: more ghost planes are needed");
  if (a.periodic)
    throw InputError(field, to_text(x), "lies more than 2^20 periods from the periodic box [" + to_text(a.origin) +
                                            ", " + to_text(a.origin + a.length) + "]");
  throw InputError(field, to_text(x), "lies outside the domain [" + to_text(a.origin) + ", " +
                                          to_text(a.origin + a.length) + "] of a wall (non-periodic) axis");
}

void Interaction::set_window(int d, int period) {
  require(d >= 0 && d < 3, "window axis", d, "must be 0, 1 or 2");
  require(grids_[0].axis[d].periodic && period >= 2 * support_, "window period (cells)", period,
          "must belong to a periodic axis and exceed twice the kernel's support");
  for (auto& g : grids_) g.axis[d].period = period;
}

void Interaction::check_fields(const std::array<dvec, 3>& u) const {
  for (int c = 0; c < 3; ++c)
    require(index_t(u[c].size()) == grids_[c].size, "u[" + std::to_string(c) + "].size", u[c].size(),
            "must equal the number of unknowns of component " + std::to_string(c) + " (" + std::to_string(grids_[c].size) + ")");
}

void Interaction::sort(const double* X, index_t n, SortedPoints& s) {
  check_points(X, n);
  bin_points(X, n, s);
}

void Interaction::interpolate(const SortedPoints& s, const std::array<dvec, 3>& u, double* U) {
  check_fields(u);
  with_kernel(kernel_, [&](auto k) { interpolate_sorted<decltype(k)>(s, u, U); });
}

void Interaction::spread(const SortedPoints& s, const double* F, std::array<dvec, 3>& f, bool add) {
  for (int c = 0; c < 3; ++c) {
    if (add)
      require(index_t(f[c].size()) == grids_[c].size, "f[" + std::to_string(c) + "].size", f[c].size(),
              "must equal the number of unknowns of component " + std::to_string(c) + " to add to it");
    else
      f[c].resize(grids_[c].size);
  }
  with_kernel(kernel_, [&](auto k) { spread_sorted<decltype(k)>(s, F, f, add); });
}

template <class K>
void Interaction::interpolate_sorted(const SortedPoints& s, const std::array<dvec, 3>& u, double* U) {
  const index_t n = s.n_;
  for (int c = 0; c < 3; ++c)
    for_each_index(n, detail::InterpolateSorted<K>{grids_[c], ptr(s.x_), ptr(s.perm_), n, ptr(u[c]), U + c * n});
}

template <class K>
void Interaction::spread_sorted(const SortedPoints& s, const double* F, std::array<dvec, 3>& f, bool add) {
  const index_t n = s.n_;
  const index_t most = std::max({f[0].size(), f[1].size(), f[2].size()});
  if (!add)
    for_each_index(most, detail::ZeroThree{index_t(f[0].size()), index_t(f[1].size()), index_t(f[2].size()), ptr(f[0]), ptr(f[1]), ptr(f[2])});
  if (n == 0) return;
  sorted_f_.resize(3 * n);
  for_each_index(n, detail::GatherSorted{ptr(s.perm_), n, nullptr, F, nullptr, ptr(sorted_f_)});
  const double scale = 1.0 / cell_volume();
  for (int colour = 0; colour < 2; ++colour) {
    const int tasks = (slabs_ - colour + 1) / 2;
    if (tasks == 0) continue;
    detail::SpreadSlab<K> p{{{grids_[0], grids_[1], grids_[2]}}, ptr(s.x_), ptr(sorted_f_), ptr(s.slab_start_), n,
                            scale, colour, ptr(f[0]), ptr(f[1]), ptr(f[2])};
    for_each_index(tasks, p);
  }
}

void Interaction::interpolate(const dvec& X, const std::array<dvec, 3>& u, dvec& U, Interpolation alg) {
  check_points(X);
  check_fields(u);
  with_kernel(kernel_, [&](auto k) { interpolate_impl<decltype(k)>(X, u, U, alg); });
}

void Interaction::spread(const dvec& X, const dvec& F, std::array<dvec, 3>& f, Spreading alg) {
  check_points(X);
  require(F.size() == X.size(), "F.size", F.size(), "must equal X.size() = " + std::to_string(X.size()) + " (3 n values)");
  for (int c = 0; c < 3; ++c) f[c].resize(grids_[c].size);
  with_kernel(kernel_, [&](auto k) { spread_impl<decltype(k)>(X, F, f, alg); });
}

template <class K>
void Interaction::interpolate_impl(const dvec& X, const std::array<dvec, 3>& u, dvec& U, Interpolation alg) {
  const index_t n = X.size() / 3;
  U.resize(3 * n);
  if (n == 0) return;
  if (alg == Interpolation::binned) {
    bin_points(ptr(X), n, sorted_);
    interpolate_sorted<K>(sorted_, u, ptr(U));
    return;
  }
  for (int c = 0; c < 3; ++c) {
    detail::InterpolatePoint<K> f{grids_[c], ptr(X), n, ptr(u[c]), ptr(U) + c * n};
    if (alg == Interpolation::serial)
      for_each_index(1, detail::Serially<detail::InterpolatePoint<K>>{f, n});
    else
      for_each_index(n, f);
  }
}

template <class K>
void Interaction::spread_impl(const dvec& X, const dvec& F, std::array<dvec, 3>& f, Spreading alg) {
  const index_t n = X.size() / 3;
  const double scale = 1.0 / cell_volume();
  if (alg == Spreading::binned) {
    bin_points(ptr(X), n, sorted_);
    spread_sorted<K>(sorted_, ptr(F), f, false);
    return;
  }
  for (int c = 0; c < 3; ++c) {
    const double* L = ptr(F) + c * n;
    switch (alg) {
      case Spreading::serial: {
        thrust::fill(f[c].begin(), f[c].end(), 0.0);
        detail::SpreadPoint<K> p{grids_[c], ptr(X), n, L, scale, ptr(f[c])};
        for_each_index(1, detail::Serially<detail::SpreadPoint<K>>{p, n});
        break;
      }
      case Spreading::sort_reduce:
        thrust::fill(f[c].begin(), f[c].end(), 0.0);
        spread_sort_reduce<K>(c, n, X, L, f[c]);
        break;
      case Spreading::preallocated: {
        const index_t need = buffer_width * std::max({grids_[0].size, grids_[1].size, grids_[2].size});
        if (index_t(buffer_.size()) != need) buffer_.assign(need, 0.0);  // allocated once, kept zero
        spread_buffered<K>(c, n, X, L, f[c], buffer_);
        break;
      }
      case Spreading::on_the_fly: {
        dvec buffer(buffer_width * grids_[c].size, 0.0);  // Alg. 4.6: the buffer lives for this call
        spread_buffered<K>(c, n, X, L, f[c], buffer);
        break;
      }
      default: break;
    }
  }
}

void Interaction::sort_keys(int c, int support, index_t n, const dvec& X) {
  keys_.resize(n);
  perm_.resize(n);
  const ComponentGrid& g = grids_[c];
  switch (support) {
    case 3: for_each_index(n, detail::MakeKeys<3>{g, ptr(X), n, ptr(keys_), ptr(perm_)}); break;
    case 4: for_each_index(n, detail::MakeKeys<4>{g, ptr(X), n, ptr(keys_), ptr(perm_)}); break;
    default: {
      // Supports other than 3 and 4 differ only in the parity of s.
      if (support % 2) for_each_index(n, detail::MakeKeys<3>{g, ptr(X), n, ptr(keys_), ptr(perm_)});
      else for_each_index(n, detail::MakeKeys<4>{g, ptr(X), n, ptr(keys_), ptr(perm_)});
    }
  }
  thrust::sort_by_key(keys_.begin(), keys_.end(), perm_.begin());
  // The runs of equal keys (q of them, line 9 of Alg. 4.4), found once and reused for every shift.
  segments_.resize(n + 1);
  const auto end = thrust::copy_if(thrust::counting_iterator<int>(0), thrust::counting_iterator<int>(int(n)), segments_.begin(),
                                   detail::IsSegmentHead{ptr(keys_)});
  segment_count_ = end - segments_.begin();
  segments_[segment_count_] = int(n);
}

template <class K>
void Interaction::spread_sort_reduce(int c, index_t n, const dvec& X, const double* L, dvec& out) {
  constexpr int S = K::support;
  if (n == 0) return;
  const ComponentGrid& g = grids_[c];
  const double scale = 1.0 / cell_volume();
  sort_keys(c, S, n, X);
  values_.resize(n);
  values_reduced_.resize(n);
  keys_reduced_.resize(n);
  for (int j = 0; j < Shifts<S>::count; ++j) {
    for_each_index(n, detail::ShiftValues<K>{g, ptr(X), n, L, ptr(perm_), scale, j, ptr(values_)});
    const index_t q = segment_count_;
    for_each_index(q, detail::SegmentSum<double>{ptr(segments_), ptr(keys_), ptr(values_), ptr(keys_reduced_), ptr(values_reduced_)});
    for_each_index(q, detail::WriteReduced<S>{g, ptr(keys_reduced_), ptr(values_reduced_), j, ptr(out)});
  }
}

template <class K>
void Interaction::spread_buffered(int c, index_t n, const dvec& X, const double* L, dvec& out, dvec& buffer) {
  constexpr int S = K::support;
  const ComponentGrid& g = grids_[c];
  if (n > 0) {
    const double scale = 1.0 / cell_volume();
    sort_keys(c, S, n, X);
    values_.resize(8 * n);
    values_reduced_.resize(8 * n);
    keys_reduced_.resize(n);
    using detail::Pack;
    Pack* V = reinterpret_cast<Pack*>(ptr(values_));
    Pack* Vr = reinterpret_cast<Pack*>(ptr(values_reduced_));
    for (int first = 0; first < Shifts<S>::count; first += buffer_width) {
      for_each_index(n, detail::PackValues<K>{g, ptr(X), n, L, ptr(perm_), scale, first, V});
      const index_t q = segment_count_;
      for_each_index(q, detail::SegmentSum<Pack>{ptr(segments_), ptr(keys_), V, ptr(keys_reduced_), Vr});
      for_each_index(q, detail::WriteReducedPack<S>{g, ptr(keys_reduced_), Vr, first, g.size, ptr(buffer)});
    }
  }
  for_each_index(g.size, detail::SumBuffer{g.size, ptr(buffer), ptr(out)});
}

void Interaction::bin_points(const double* X, index_t n, SortedPoints& s) {
  s.n_ = n;
  s.slab_start_.resize(slabs_ + 1);
  if (n == 0) {
    thrust::fill(s.slab_start_.begin(), s.slab_start_.end(), 0);
    return;
  }
  const GridAxis &y = grids_[0].axis[1], &z = grids_[0].axis[2];
  const int rows = y.cells, planes = z.cells;
  const index_t bins = index_t(rows) * planes;
  const int chunks = int(std::clamp<index_t>(n / 4096, 1, 16));
  bins_.resize(n);
  s.perm_.resize(n);
  counts_.resize(bins * chunks);
  xcell_.resize(n);
  for_each_index(n, detail::RowBin{grids_[0].axis[0], y, z, X, n, ptr(bins_), ptr(xcell_)});
  thrust::fill(counts_.begin(), counts_.end(), 0);
  for_each_index(chunks, detail::CountChunk{ptr(bins_), n, bins, chunks, ptr(counts_)});
  // Exclusive scan in (bin, chunk) order over the chunk-major counters: a stable counting sort.
  const auto order = thrust::make_permutation_iterator(
      counts_.begin(), thrust::make_transform_iterator(thrust::counting_iterator<index_t>(0), detail::ChunkMajor{bins, chunks}));
  thrust::exclusive_scan(order, order + bins * chunks, order);
  sorted_xcell_.resize(n);
  for_each_index(chunks, detail::PlaceChunk{ptr(bins_), ptr(xcell_), n, bins, chunks, ptr(counts_), ptr(s.perm_), ptr(sorted_xcell_)});
  for_each_index(bins, detail::SortRow{ptr(counts_), bins, chunks, ptr(sorted_xcell_), ptr(s.perm_), slabs_, planes, rows,
                                       ptr(s.slab_start_)});
  s.x_.resize(3 * n);
  for_each_index(n, detail::GatherSorted{ptr(s.perm_), n, X, nullptr, ptr(s.x_), nullptr});
}

}  // namespace rbfib::ib
