#include "rbfib/sim/lagrangian.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <thrust/copy.h>
#include <thrust/device_ptr.h>
#include <thrust/find.h>

namespace rbfib::sim {

namespace {
/// Index of the first of n entries (device memory) that is NaN or Inf, or -1.
index_t first_non_finite(const double* x, index_t n) {
  const auto begin = thrust::device_pointer_cast(x);
  const auto bad = thrust::find_if(begin, begin + n, [] RBFIB_HD (double v) { return !((v - v) == 0.0); });
  return bad == begin + n ? -1 : index_t(bad - begin);
}
index_t first_non_finite(const dvec& x) { return first_non_finite(ptr(x), index_t(x.size())); }
}  // namespace

void interpolate_at(ib::Interaction& ib, const ib::SortedPoints& s, const VectorField& u, dvec& U, const std::string& who) {
  U.resize(static_cast<std::size_t>(3 * s.size()));
  ib.interpolate(s, u, ptr(U));
  if (!blas::all_finite(U)) throw NumericalError(Cause::non_finite, who + ": non-finite interpolated velocity");
}

void spread_into(ib::Interaction& ib, ib::Spreading algorithm, const dvec& X, const dvec& F, ib::SortedPoints& sorted,
                 VectorField& f, VectorField& scratch) {
  if (algorithm == ib::Spreading::binned) {
    ib.sort(ptr(X), index_t(X.size()) / 3, sorted);
    ib.spread(sorted, ptr(F), f, true);
    return;
  }
  ib.spread(X, F, scratch, algorithm);
  for (int a = 0; a < 3; ++a) blas::axpy(1.0, scratch[a], f[a]);
}

// ---- cell batches ---------------------------------------------------------------------------

void CellBatchSet::save() { saved_ = batch_.state().storage(); }

void CellBatchSet::restore() { batch_.state().storage() = saved_; }

void CellBatchSet::interpolate_start(ib::Interaction& ib, const VectorField& u) {
  // X^n, read in place from the state, checked finite, then sorted once.
  const index_t nd = batch_.type().n_data(), N = batch_.size(), n = N * nd;
  const double* X = ptr(batch_.state().storage());
  const index_t k = first_non_finite(X, 3 * n);
  if (k >= 0)
    throw NumericalError(Cause::non_finite, name() + ", cell " + to_text((k % n) / nd) + ": non-finite position at data site " +
                                               to_text(k % nd) + " (coordinate " + "xyz"[k / n] + ")");
  ib.sort(X, n, start_);
  interpolate_at(ib, start_, u, U_, name());
}

double CellBatchSet::compute_force() {
  cells::compute_forces(batch_, forces_);
  return forces_.energy;
}

void CellBatchSet::spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  spread_into(ib, algorithm, forces_.positions.storage(), forces_.force.storage(), sample_, f, scratch);
}

void CellBatchSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) {
  if (at_predicted) ib.sort(ptr(X_), index_t(X_.size()) / 3, start_);
  interpolate_at(ib, start_, u, U_, name());
}

void CellBatchSet::advance(double c) {
  const auto n = static_cast<std::ptrdiff_t>(U_.size());
  X_.resize(U_.size());
  thrust::copy(saved_.begin(), saved_.begin() + n, X_.begin());  // X^n
  blas::axpy(c, U_, X_);
  auto state = batch_.state().storage().begin();
  thrust::copy(X_.begin(), X_.end(), state);
  thrust::copy(U_.begin(), U_.end(), state + n);  // the velocity block
}

// ---- tethered points ------------------------------------------------------------------------

TetheredPointSet::TetheredPointSet(TetheredPoints p, bool predicted) : points_(std::move(p)), predicted_(predicted) {
  const std::string field = name();
  require(points_.X.size() % 3 == 0 && !points_.X.empty(), field + ": positions size", points_.X.size(), "must be a positive multiple of 3");
  require(points_.anchors.size() == points_.X.size(), field + ": anchors size", points_.anchors.size(), "must equal the positions' size");
  require(std::isfinite(points_.k) && points_.k >= 0, field + ": spring constant k (dyn/cm)", points_.k, "must be finite and >= 0");
  require(std::isfinite(points_.eta) && points_.eta >= 0, field + ": damping eta (dyn s/cm)", points_.eta, "must be finite and >= 0");
  require(first_non_finite(points_.X) < 0 && first_non_finite(points_.anchors) < 0, field + ": positions and anchors", "NaN or Inf",
          "must be finite");
}

void TetheredPointSet::interpolate_start(ib::Interaction& ib, const VectorField& u) {
  ib.sort(ptr(X0_), index_t(X0_.size()) / 3, start_);
  interpolate_at(ib, start_, u, U_, name());
}

void TetheredPointSet::predict(double c) {
  if (predicted_) blas::axpy(c, U_, points_.X);
}

double TetheredPointSet::compute_force() {
  // Eq. 2.10 at X (X^n, or X* when predicted): F = -k (X - X') - eta U^n, per point.
  F_ = points_.X;
  blas::axpy(-1.0, points_.anchors, F_);
  blas::scale(-points_.k, F_);
  blas::axpy(-points_.eta, U_, F_);
  return 0;
}

void TetheredPointSet::spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  if (!predicted_ && algorithm == ib::Spreading::binned)
    ib.spread(start_, ptr(F_), f, true);  // from X^n, sorted once for (a), (d) and (f)
  else
    spread_into(ib, algorithm, points_.X, F_, spread_, f, scratch);
}

void TetheredPointSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) {
  if (at_predicted) ib.sort(ptr(points_.X), index_t(points_.X.size()) / 3, start_);
  interpolate_at(ib, start_, u, U_, name());
}

void TetheredPointSet::update(double dt) {
  points_.X = X0_;
  blas::axpy(dt, U_, points_.X);
}

}  // namespace rbfib::sim
