#pragma once
// The cortex of a blebbing cell as a Lagrangian set (the JCP 2018 paper, Sec. 5.2.1, eqs. 96-104),
// linked to the membrane set it adheres to. The cortex is permeable: it moves with the fluid plus
// its own force over a drag coefficient,
//   dX_cortex/dt = (1/xi) (F_elastic + F_adh) + U                                      (104)
// (forces per unit reference area, U = S* u), and the drag it feels, F_drag = -(F_elastic + F_adh)
// (eq. 97), is spread to the fluid as -S F_drag (eq. 98): the set spreads its elastic and adhesion
// forces as any other set does. Its springs (eqs. 99-100) and the adhesion links (eqs. 101-102)
// are mechanics/cortex.hpp. The membrane's share of the adhesion, -k_adh dA_i d per link, is
// spread by this set from the membrane's force sites (where the membrane set spreads its own
// forces: SHVD's evaluation sites, LDSM's vertices), so the membrane set is unchanged and the
// links balance exactly (eq. 102).
// The membrane set must come first in the step (its compute_force gives the sites this set reads),
// and the coupling is Chapter 3's forward Euler (Sec. 3.3): forces at X^n, X^{n+1} = X^n + dt (U +
// F / (xi dA)); sim::ImmersedBoundary::add checks both.
// Units (CGS): k in dyn/cm, k_adh in dyn/cm^3, xi in dyn s/cm^3, positions cm.
#include "rbfib/mechanics/cortex.hpp"
#include "rbfib/sim/lagrangian.hpp"

#include <string>
#include <vector>

namespace rbfib::sim {

struct Cortex {
  std::string name;
  std::vector<surface::Triangle> triangles;
  std::vector<double> reference;  ///< Z, n x 3 column-major (cm)
  std::vector<double> X;          ///< the sites now, n x 3 (cm)
  double k = 0;                   ///< the lattice's stiffness, eq. (100) (dyn/cm; mechanics/cortex.hpp)
  double k_adh = 0;               ///< adhesion, eq. (101) (dyn/cm^3)
  double xi = 0;                  ///< drag coefficient, eq. (104) (dyn s/cm^3)
  std::vector<char> attached;     ///< per site: its adhesion link holds (empty: every link)
};

class CortexSet final : public LagrangianSet {
 public:
  /// Throws InputError naming the field for mismatched sizes, non-finite positions, negative
  /// constants or xi <= 0. `membrane` must outlive the set (the step owns both).
  CortexSet(Cortex cortex, const LagrangianSet& membrane);
  std::string name() const override { return "cortex '" + cortex_.name + "'"; }
  void save() override { X0_ = cortex_.X; }
  void restore() override { cortex_.X = X0_; }
  void locate(ib::Interaction& ib) override;
  void interpolate_start(ib::Interaction& ib, const VectorField& u) override;
  void predict(double c) override;
  /// Eqs. (99) and (101) at X^n and the membrane's force sites; returns the springs' and links' energy.
  double compute_force() override;
  void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) override;
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double dt, const std::array<double, 3>& u_frame) override;

  const Cortex& cortex() const { return cortex_; }
  Cortex& cortex() { return cortex_; }
  const mechanics::CortexLattice& lattice() const { return lattice_; }
  /// Sets which links hold (n entries); throws InputError for another size.
  void set_attached(std::vector<char> attached);
  /// The last compute_force(): the force on each cortex site (elastic + adhesion) and the
  /// adhesion's force on each membrane site (dyn, n x 3).
  const std::vector<double>& force() const { return F_; }
  const std::vector<double>& membrane_force() const { return Fm_; }

 private:
  Cortex cortex_;
  mechanics::CortexLattice lattice_;
  const LagrangianSet& membrane_;
  std::vector<double> X0_, F_, Fm_, Xm_, U_;  // X^n, forces, membrane sites, velocities (host)
  dvec Xd_, Fd_, Ud_, Xmd_, Fmd_;             // device copies for the interaction
  ib::SortedPoints at_, membrane_at_;
};

}  // namespace rbfib::sim
