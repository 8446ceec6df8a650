#pragma once
// A wall held exactly: fixed markers whose force is solved every step so that the fluid's velocity
// interpolated at them after the step is zero (a constraint, beyond the seed, which ties its
// endothelium to anchors by damped springs, eq. 2.10). The method is the immersed-boundary
// projection of Taira and Colonius (2007) and the rigid-multiblob wall of Kallemov, Bhalla, Griffith
// and Donev (2016), written for this library's coupled step:
//   the fluid step is affine in its force, u^{n+1} = u_0 + L f, with L linear and fixed at a given
//   dt (backward-forward Euler or Stokes: the advection uses u^n only). With the cells' and the
//   other sets' force density f, the step gives u* = u_0 + L f; the wall force Lambda at the
//   markers solves
//       M Lambda = -J u*,   M = J L S   (J: interpolation at the markers, S: spreading from them),
//   and the step is taken again with f + S Lambda, so that J u^{n+1} = 0 to the rounding of the
//   solve. M, 3n x 3n for n markers, is the wall's mobility at this step size: it is built once
//   per dt (one fluid step per column, by differences from the same state: L is fixed, and the
//   trial forces are scaled so that the differences lose no digits) and kept as LU factors, one
//   per ladder level.
// A flat wall whose markers tile a periodic plane on a lattice commensurate with the grid has a
// block-circulant mobility (sim/circulant_mobility.hpp): built from 3 trial steps instead of 3n and
// solved by transforms over the lattice; the dense LU serves every other wall (a bumpy one).
// Markers about 2h apart (Kallemov et al.): closer, M is near singular (its columns overlap);
// farther, the fluid leaks between them. The held force takes no part in eq. 5.4: it is the
// solution of a constraint, not an explicit elastic force, and sets no step.
// Cost per step: a second fluid step, one interpolation and one spreading at the markers, one LU
// solve of order 3n (flat lattice: two transforms); per new dt, 3n + 1 fluid steps and one LU
// factorization (O(n^3)) (flat lattice: 4 fluid steps).
// On a fluid split among processes (fluid/decomposition.hpp) each process interpolates and spreads
// at the markers in its planes (by their coordinate along the split axis), on the Lagrangian grid;
// the velocities at all markers are gathered on every process, which each solve the same system
// (the markers are few: 3n is a few thousand) and spread their own markers' part of the force.
// Units (CGS): positions cm, forces dyn.
#include "rbfib/fluid/decomposition.hpp"
#include "rbfib/fluid/fluid_step.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/sim/circulant_mobility.hpp"
#include "rbfib/sim/lagrangian.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rbfib::sim {

struct HeldWall {
  std::string name;
  dvec X;             ///< marker positions, 3n, X[d n + k] (cm); they do not move
  bool dense = false;  ///< the dense mobility even for a commensurate flat lattice (to check the circulant one)
};

class HeldWallSet final : public LagrangianSet {
 public:
  /// Throws InputError naming the field for an empty or non-finite set of markers. On a split
  /// fluid (`parts`), this process holds the markers in its planes.
  explicit HeldWallSet(HeldWall wall, const FluidDecomposition* parts = nullptr);
  std::string name() const override { return "held wall '" + wall_.name + "'"; }
  void save() override {}  // nothing moves
  void restore() override {}
  void locate(ib::Interaction& ib) override;
  void interpolate_start(ib::Interaction&, const VectorField&) override {}
  void predict(double) override {}
  double compute_force() override { return 0; }  // its force is solved after the fluid step (hold)
  void spread(ib::Interaction&, ib::Spreading, VectorField&, VectorField&) override {}
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double, const std::array<double, 3>&) override {}

  /// After fluid.step(&f) (fluid.next() holds u*): solves M Lambda = -J u* and adds S Lambda to f;
  /// the caller then steps the fluid again with f. Builds and factors M for fluid.dt() the first
  /// time that dt is seen (stepping the fluid 3n + 1 times, then once more with f). Throws
  /// NumericalError naming the set for a singular mobility or a non-finite velocity.
  void hold(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, VectorField& f, VectorField& scratch);

  const HeldWall& wall() const { return wall_; }
  /// The wall force of the last hold() at each marker (dyn), 3n (every process: the whole wall),
  /// and its velocity after the step (interpolate_end; cm/s), the slip the solve leaves, at this
  /// process's markers (3m, in the order of markers(); one process: every marker).
  const dvec& force() const { return lambda_; }
  const dvec& velocity() const { return U_; }
  const std::vector<index_t>& markers() const { return mine_; }
  /// The mobilities factored so far (one per dt seen), and the seconds spent building them.
  std::size_t mobilities() const { return mobility_.size() + circulant_.size(); }
  /// Whether the markers tile a periodic plane commensurately (the circulant mobility; known after
  /// the first hold()).
  bool circulant() const { return lattice_.has_value(); }
  double seconds_building() const { return seconds_building_; }

 private:
  linalg::LuFactors build(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, const VectorField& shape, VectorField& scratch);
  CirculantMobility build_circulant(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, const VectorField& shape,
                                    VectorField& scratch);
  /// The velocity at every marker (3n) after one fluid step from the current state with the force
  /// `trial` on unknown `column` (component c of marker k: c n + k), minus U0 (the step without
  /// force), divided by `trial`: a column of the mobility.
  dvec response(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, index_t column, double trial, const dvec& U0,
                VectorField& g, VectorField& scratch);
  /// The base of the mobility's columns: the velocity at every marker after the step without
  /// force, from the current state (the fluid step is affine in its force).
  dvec base_velocity(ib::Interaction& ib, FluidStep& fluid);
  /// J u at every marker (3n) for a velocity u of the fluid's grid (collective on a split fluid).
  dvec velocity_at_markers(ib::Interaction& ib, const VectorField& u);
  /// Adds S F into f, a force density of the fluid's grid, for forces F at every marker (3n)
  /// (collective on a split fluid: each process spreads its markers', summed into the owners).
  void spread_forces(ib::Interaction& ib, ib::Spreading algorithm, const dvec& F, VectorField& f, VectorField& scratch);

  HeldWall wall_;
  const FluidDecomposition* parts_;  // null: one process
  std::vector<index_t> mine_;        // this process's markers
  dvec X_mine_;                      // their positions, 3m
  VectorField wide_, narrow_;        // a split fluid's Lagrangian-grid field and its owned planes
  ib::SortedPoints at_, spread_;
  dvec U_, lambda_;
  std::map<double, linalg::LuFactors> mobility_;  // by dt
  std::optional<MarkerLattice> lattice_;
  bool lattice_known_ = false;
  std::map<double, CirculantMobility> circulant_;  // by dt, for a commensurate flat lattice
  double seconds_building_ = 0;
};

}  // namespace rbfib::sim
