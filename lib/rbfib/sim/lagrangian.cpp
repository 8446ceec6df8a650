#include "rbfib/sim/lagrangian.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/mechanics/ldsm.hpp"

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

/// X += c over n values, on the device.
void shift_by(double* X, double c, index_t n) {
  for_each_index(n, [=] RBFIB_HD(index_t i) { X[i] += c; });
}

/// X += c U over n values, on the device.
void add_scaled(double* X, const double* U, double c, index_t n) {
  for_each_index(n, [=] RBFIB_HD(index_t i) { X[i] += c * U[i]; });
}

bool moving(const std::array<double, 3>& u_frame) { return u_frame[0] != 0 || u_frame[1] != 0 || u_frame[2] != 0; }

/// X = X0 + c (U + u_frame[d]) over 3 blocks of `block` values (component-major), on the device.
void advance_in_frame(double* X, const double* X0, const double* U, double c, const std::array<double, 3>& u_frame,
                      index_t block) {
  const double fx = u_frame[0], fy = u_frame[1], fz = u_frame[2];
  for_each_index(3 * block, [=] RBFIB_HD(index_t i) {
    const double f = i < block ? fx : (i < 2 * block ? fy : fz);
    X[i] = X0[i] + c * (U[i] + f);
  });
}
}  // namespace

std::vector<double> LagrangianSet::force_sites() const {
  throw InputError(name() + ": force sites", "requested", "this set offers none to link to");
}

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

dvec points_at(const dvec& X, const std::vector<index_t>& ids) {
  const std::vector<double> x(X.begin(), X.end());
  const std::size_t n = x.size() / 3, m = ids.size();
  std::vector<double> out(3 * m);
  for (std::size_t d = 0; d < 3; ++d)
    for (std::size_t q = 0; q < m; ++q) out[d * m + q] = x[d * n + std::size_t(ids[q])];
  return dvec(out.begin(), out.end());
}

dvec whole_points(const FluidDecomposition& parts, const dvec& X, const std::vector<index_t>& ids, index_t n) {
  const std::vector<double> x(X.begin(), X.end());
  const std::size_t m = ids.size();
  std::vector<double> mine;  // per point: its index, then its three values
  mine.reserve(4 * m);
  for (std::size_t q = 0; q < m; ++q) {
    mine.push_back(double(ids[q]));
    for (std::size_t d = 0; d < 3; ++d) mine.push_back(x[d * m + q]);
  }
  std::vector<double> whole(static_cast<std::size_t>(3 * n), NAN);
  for (const std::vector<double>& from : parts.exchange(std::vector<std::vector<double>>(std::size_t(parts.processes()), mine)))
    for (std::size_t i = 0; i + 3 < from.size(); i += 4)
      for (std::size_t d = 0; d < 3; ++d) whole[d * std::size_t(n) + std::size_t(from[i])] = from[i + 1 + d];
  return dvec(whole.begin(), whole.end());
}
// ---- cell batches ---------------------------------------------------------------------------

void CellBatchSet::replace(cells::Batch batch) {
  batch_ = std::move(batch);
  forces_ = cells::CellForces{};
  predicted_ = false;
  U_.clear();
}

void CellBatchSet::locate(ib::Interaction& ib) {
  if (batch_.size() == 0) return;
  // X^n, read in place from the state, checked finite, then sorted once.
  const index_t nd = batch_.type().n_data(), N = batch_.size(), n = N * nd;
  const double* X = ptr(batch_.state().storage());
  const index_t k = first_non_finite(X, 3 * n);
  if (k >= 0)
    throw NumericalError(Cause::non_finite, name() + ", cell " + to_text((k % n) / nd) + ": non-finite position at data site " +
                                               to_text(k % nd) + " (coordinate " + "xyz"[k / n] + ")");
  ib.sort(X, n, start_);
  predicted_ = false;
}

void CellBatchSet::interpolate_start(ib::Interaction& ib, const VectorField& u) {
  if (batch_.size() > 0) interpolate_at(ib, start_, u, U_, name());
}

void CellBatchSet::predict(double c) {
  // X* = X^n + c U^n beside the batch's state, with U^n after it (the velocities of dissipation).
  if (batch_.size() == 0) return;
  const linalg::DeviceMatrix& state = batch_.state();
  star_.resize(state.rows(), state.cols());
  const auto n = static_cast<std::ptrdiff_t>(U_.size());
  auto star = star_.storage().begin();
  thrust::copy(state.storage().begin(), state.storage().begin() + n, star);  // X^n
  thrust::copy(U_.begin(), U_.end(), star + n);                             // U^n
  add_scaled(ptr(star_.storage()), ptr(U_), c, index_t(n));
  predicted_ = true;
}

double CellBatchSet::compute_force() {
  if (batch_.size() == 0) {
    timings_ = cells::ForceTimings{};
    return 0.0;
  }
  if (predicted_)
    cells::compute_forces(batch_, star_.view(), forces_, &timings_);
  else
    cells::compute_forces(batch_, forces_, &timings_);
  return forces_.energy;
}

void CellBatchSet::spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  if (batch_.size() == 0) return;
  spread_into(ib, algorithm, forces_.positions.storage(), forces_.force.storage(), sample_, f, scratch);
}

void CellBatchSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) {
  if (batch_.size() == 0) return;
  if (at_predicted) ib.sort(ptr(star_.storage()), index_t(U_.size()) / 3, start_);  // X*, the first 3 n_d N entries
  interpolate_at(ib, start_, u, U_, name());
}

void CellBatchSet::update(double dt, const std::array<double, 3>& u_frame) {
  // X^{n+1} = X^n + dt (U + u_frame) in place, then U into the velocity block.
  if (batch_.size() == 0) return;
  const auto n = static_cast<std::ptrdiff_t>(U_.size());
  double* X = ptr(batch_.state().storage());
  if (moving(u_frame))
    advance_in_frame(X, X, ptr(U_), dt, u_frame, index_t(n / 3));
  else
    add_scaled(X, ptr(U_), dt, index_t(n));
  thrust::copy(U_.begin(), U_.end(), batch_.state().storage().begin() + n);
}

// ---- tethered points ------------------------------------------------------------------------

TetheredPointSet::TetheredPointSet(TetheredPoints p, bool predicted, bool part) : points_(std::move(p)), predicted_(predicted) {
  const std::string field = name();
  require(points_.X.size() % 3 == 0 && (part || !points_.X.empty()), field + ": positions size", points_.X.size(),
          "must be a positive multiple of 3");
  require(points_.anchors.size() == points_.X.size(), field + ": anchors size", points_.anchors.size(), "must equal the positions' size");
  require(std::isfinite(points_.k) && points_.k >= 0, field + ": spring constant k (dyn/cm)", points_.k, "must be finite and >= 0");
  require(std::isfinite(points_.eta) && points_.eta >= 0, field + ": damping eta (dyn s/cm)", points_.eta, "must be finite and >= 0");
  require(first_non_finite(points_.X) < 0 && first_non_finite(points_.anchors) < 0, field + ": positions and anchors", "NaN or Inf",
          "must be finite");
}

void TetheredPointSet::locate(ib::Interaction& ib) { ib.sort(ptr(X0_), index_t(X0_.size()) / 3, start_); }

void TetheredPointSet::interpolate_start(ib::Interaction& ib, const VectorField& u) { interpolate_at(ib, start_, u, U_, name()); }

void TetheredPointSet::predict(double c) {
  if (predicted_) blas::axpy(c, U_, points_.X);
}

std::vector<double> TetheredPointSet::force_sites() const {
  std::vector<double> X(points_.X.size());
  thrust::copy(points_.X.begin(), points_.X.end(), X.begin());
  return X;
}

double TetheredPointSet::compute_force() {
  // Eq. 2.10 at X (X^n, or X* when predicted): F = -k (X - X') - eta U^n, per point.
  F_ = points_.X;
  blas::axpy(-1.0, points_.anchors, F_);
  blas::scale(-points_.k, F_);
  if (points_.eta != 0) blas::axpy(-points_.eta, U_, F_);  // (Chapter 3's forward Euler has no U^n)
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

void TetheredPointSet::update(double dt, const std::array<double, 3>& u_frame) {
  points_.X = X0_;
  blas::axpy(dt, U_, points_.X);
  if (!moving(u_frame)) return;
  // Eqs. 94-95 as written: X^ = X^n + dt U, then X^{n+1} = X^ + dt u_c.
  const index_t n = index_t(X0_.size() / 3);
  for (int d = 0; d < 3; ++d) shift_by(ptr(points_.X) + d * n, dt * u_frame[d], n);
}

std::array<double, 3> TetheredPointSet::frame_velocity(double dt) const {
  // X^ = X^n + dt U (eq. 94), then u_c = (1 / (n dt)) sum (X' - X^) per component (eq. 95).
  const std::vector<double> X0(X0_.begin(), X0_.end()), U(U_.begin(), U_.end()), Z(points_.anchors.begin(), points_.anchors.end());
  const std::size_t n = X0.size() / 3;
  std::array<double, 3> uc{0, 0, 0};
  for (int d = 0; d < 3; ++d) {
    double sum = 0;
    for (std::size_t q = 0; q < n; ++q) {
      const std::size_t i = d * n + q;
      sum += Z[i] - (X0[i] + dt * U[i]);
    }
    uc[d] = sum / (double(n) * dt);
  }
  return uc;
}

// ---- LDSM shells ----------------------------------------------------------------------------

LdsmShellSet::LdsmShellSet(LdsmShell shell) : shell_(std::move(shell)) {
  const std::string field = name();
  const std::size_t n = shell_.reference.size() / 3;
  require(shell_.reference.size() % 3 == 0 && n >= 4, field + ": reference size", shell_.reference.size(),
          "must be 3n with n >= 4 vertices");
  require(shell_.X.size() == shell_.reference.size(), field + ": positions size", shell_.X.size(), "must equal the reference's size");
  require(!shell_.triangles.empty(), field + ": triangles", 0, "must not be empty");
  for (const surface::Triangle& t : shell_.triangles)
    for (index_t v : t) require(v >= 0 && std::size_t(v) < n, field + ": triangle vertex", v, "must lie in [0, " + to_text(n) + ")");
  require(!shell_.energies.empty(), field + ": energies", 0, "must name at least one energy");
  for (double x : shell_.X) require(std::isfinite(x), field + ": positions", x, "must be finite");
}

void LdsmShellSet::locate(ib::Interaction& ib) {
  const std::vector<double>& X = shell_.X;
  for (std::size_t i = 0; i < X.size(); ++i)
    if (!std::isfinite(X[i]))
      throw NumericalError(Cause::non_finite, name() + ": non-finite position at vertex " + to_text(i % (X.size() / 3)));
  Xd_.resize(X.size());
  thrust::copy(X.begin(), X.end(), Xd_.begin());
  ib.sort(ptr(Xd_), index_t(X.size() / 3), at_);
  predicted_ = false;
}

void LdsmShellSet::interpolate_start(ib::Interaction& ib, const VectorField& u) {
  interpolate_at(ib, at_, u, Ud_, name());
  U_.assign(Ud_.begin(), Ud_.end());
}

void LdsmShellSet::predict(double c) {
  if (c == 0) return;
  for (std::size_t i = 0; i < shell_.X.size(); ++i) shell_.X[i] = X0_[i] + c * U_[i];
  predicted_ = true;
}

double LdsmShellSet::compute_force() {
  mechanics::LdsmResult r = mechanics::ldsm_forces(shell_.name, shell_.triangles, shell_.reference, shell_.X, shell_.energies);
  F_ = std::move(r.F);
  return r.energy;
}

void LdsmShellSet::spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  Fd_.resize(F_.size());
  thrust::copy(F_.begin(), F_.end(), Fd_.begin());
  if (predicted_ || algorithm != ib::Spreading::binned) {  // predicted: spread from X*, sorted anew
    thrust::copy(shell_.X.begin(), shell_.X.end(), Xd_.begin());
    spread_into(ib, algorithm, Xd_, Fd_, at_, f, scratch);
    return;
  }
  ib.spread(at_, ptr(Fd_), f, true);  // from X^n, sorted once for the step
}

void LdsmShellSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) {
  if (at_predicted) {
    thrust::copy(shell_.X.begin(), shell_.X.end(), Xd_.begin());
    ib.sort(ptr(Xd_), index_t(shell_.X.size() / 3), at_);
  } else if (predicted_) {
    thrust::copy(X0_.begin(), X0_.end(), Xd_.begin());  // back to X^n
    ib.sort(ptr(Xd_), index_t(X0_.size() / 3), at_);
  }
  interpolate_at(ib, at_, u, Ud_, name());
  U_.assign(Ud_.begin(), Ud_.end());
}

void LdsmShellSet::update(double dt, const std::array<double, 3>& u_frame) {
  const std::size_t n = X0_.size() / 3;
  for (std::size_t i = 0; i < X0_.size(); ++i) shell_.X[i] = X0_[i] + dt * (moving(u_frame) ? U_[i] + u_frame[i / n] : U_[i]);
}

}  // namespace rbfib::sim
