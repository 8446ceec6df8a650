#include "rbfib/sim/cortex.hpp"

#include "rbfib/core/error.hpp"

#include <thrust/copy.h>

#include <cmath>

namespace rbfib::sim {

namespace {
void to_device(const std::vector<double>& h, dvec& d) {
  d.resize(h.size());
  thrust::copy(h.begin(), h.end(), d.begin());
}
}  // namespace

CortexSet::CortexSet(Cortex cortex, const LagrangianSet& membrane)
    : cortex_(std::move(cortex)),
      lattice_(mechanics::cortex_lattice(cortex_.triangles, cortex_.reference, cortex_.k)),
      membrane_(membrane) {
  const std::string field = name();
  const std::size_t n = cortex_.reference.size() / 3;
  require(cortex_.X.size() == cortex_.reference.size(), field + ": positions size", cortex_.X.size(),
          "must equal the reference's size " + to_text(cortex_.reference.size()));
  for (double x : cortex_.X) require(std::isfinite(x), field + ": positions", x, "must be finite");
  require(std::isfinite(cortex_.k_adh) && cortex_.k_adh >= 0, field + ": adhesion k_adh (dyn/cm^3)", cortex_.k_adh,
          "must be finite and >= 0");
  require(std::isfinite(cortex_.xi) && cortex_.xi > 0, field + ": drag coefficient xi (dyn s/cm^3)", cortex_.xi,
          "must be finite and > 0");
  if (cortex_.attached.empty()) cortex_.attached.assign(n, 1);
  set_attached(cortex_.attached);
}

void CortexSet::set_attached(std::vector<char> attached) {
  require(attached.size() == cortex_.reference.size() / 3, name() + ": adhesion links", attached.size(),
          "must be one per site (" + to_text(cortex_.reference.size() / 3) + ")");
  cortex_.attached = std::move(attached);
}

void CortexSet::locate(ib::Interaction& ib) {
  const std::vector<double>& X = cortex_.X;
  for (std::size_t i = 0; i < X.size(); ++i)
    if (!std::isfinite(X[i]))
      throw NumericalError(Cause::non_finite, name() + ": non-finite position at site " + to_text(i % (X.size() / 3)));
  to_device(X, Xd_);
  ib.sort(ptr(Xd_), index_t(X.size() / 3), at_);
}

void CortexSet::interpolate_start(ib::Interaction& ib, const VectorField& u) {
  interpolate_at(ib, at_, u, Ud_, name());
  U_.assign(Ud_.begin(), Ud_.end());
}

void CortexSet::predict(double c) {
  require(c == 0, name() + ": predicted positions", c, "the cortex moves by Chapter 3's forward Euler only (forces at X^n)");
}

double CortexSet::compute_force() {
  // Eq. (99) at X^n, eq. (101) between the membrane's force sites (computed first) and X^n.
  Xm_ = membrane_.force_sites();
  mechanics::PointForces springs = mechanics::cortex_forces(lattice_, cortex_.X);
  mechanics::AdhesionForces links =
      mechanics::adhesion_forces(Xm_, cortex_.X, lattice_.dA, cortex_.k_adh, cortex_.attached);
  F_ = std::move(springs.F);
  for (std::size_t i = 0; i < F_.size(); ++i) F_[i] += links.on_cortex[i];
  Fm_ = std::move(links.on_membrane);
  return springs.energy + links.energy;
}

void CortexSet::spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  // Eq. (98): -S F_drag = S (F_elastic + F_adh) from the cortex sites, and the membrane's share of
  // the links from its sites (eq. 102: the two cancel link by link).
  to_device(F_, Fd_);
  if (algorithm == ib::Spreading::binned)
    ib.spread(at_, ptr(Fd_), f, true);
  else
    spread_into(ib, algorithm, Xd_, Fd_, at_, f, scratch);
  to_device(Xm_, Xmd_);
  to_device(Fm_, Fmd_);
  spread_into(ib, algorithm, Xmd_, Fmd_, membrane_at_, f, scratch);
}

void CortexSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) {
  require(!at_predicted, name() + ": interpolation at predicted positions", "requested",
          "the cortex moves by Chapter 3's forward Euler only");
  interpolate_at(ib, at_, u, Ud_, name());
  U_.assign(Ud_.begin(), Ud_.end());
}

void CortexSet::update(double dt, const std::array<double, 3>& u_frame) {
  // Eq. (104): X^{n+1} = X^n + dt (U + F / (xi dA)) (+ the frame's velocity).
  const std::size_t n = X0_.size() / 3;
  for (std::size_t i = 0; i < X0_.size(); ++i) {
    const double slip = F_[i] / (cortex_.xi * lattice_.dA[i % n]);
    cortex_.X[i] = X0_[i] + dt * (U_[i] + slip + u_frame[i / n]);
  }
}

}  // namespace rbfib::sim
