#pragma once
// The coupled immersed-boundary time step of Sec. 2.4 over any number of cell batches and of
// tethered point sets (the endothelium of Sec. 5.2, eq. 2.10).
//
// Lagrangian side: each batch's data-site positions X and velocities U (cells/batch.hpp); forces
// are computed at the sample sites reconstructed from X and spread from there (eq. 2.24);
// velocities are interpolated at the data sites (eq. 2.23). Eulerian side: the Navier-Stokes
// solver of Sec. 2.1 (either integrator, its force evaluated at the time it asks for).
//
// Two couplings. Coupling::seed, the seed's steps (a)-(g), first order in the coupling:
//   (a) U^n     = I u^n at X^n                      (data sites; also the velocity of dissipation)
//   (b) X*      = X^n + dt U^n
//   (c) F^{n+1} = the cells' forces at X*           (sample sites, F^ = F dA0, dyn)
//   (d) f^{n+1} = S F^{n+1} from the sample sites of X*      (dyn/cm^3)
//   (e) u^{n+1} = the fluid step with f^{n+1}       (backward-forward Euler: f at t^{n+1}; Peskin's
//                                                    two-stage scheme: the same f in both stages)
//   (f) U^{n+1} = I u^{n+1} at X^n
//   (g) X^{n+1} = X^n + dt U^{n+1}
// Coupling::midpoint, formally second order, with Peskin's two-stage fluid scheme only:
//   U^n = I u^n at X^n;  X^{n+1/2} = X^n + (dt/2) U^n;  F^{n+1/2} at X^{n+1/2}, spread from there;
//   the two fluid stages with that f (giving u^{n+1/2} and u^{n+1});
//   U^{n+1/2} = I u^{n+1/2} at X^{n+1/2};  X^{n+1} = X^n + dt U^{n+1/2}.
// Coupling::forward_euler, Chapter 3's time update (Sec. 3.3, eq. 87), for Stokes flow:
//   F^n at X^n; f^n = S F^n from X^n; u^{n+1} = the fluid step with f^n; U = I u^{n+1} at X^n;
//   X^{n+1} = X^n + dt U (the capillary's frame, eqs. 94-95: + dt u_c for every set).
// Dissipation uses U^n in both (the velocity interpolated at the start of the step).
// Tethered points (eq. 2.10) are not predicted in the seed's coupling: their force
// F = -k (X^n - X') - eta U^n is spread from X^n (the midpoint coupling: from X^{n+1/2}). With
// the spring at X* = X^n + dt U^n the explicit damping would be eta + k dt, and the seed's
// endothelium (k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm, "as large as possible for the chosen
// spatial and temporal step size", h = 0.2 um, dt = 50 ns) is then unstable: a flat sheet of
// 16,000 points in shear 1000/s blows up within 20 steps, while eta alone is stable. Even at
// X^n the explicit damping's gain scales as eta / mu: in plasma of 0.1 cP (Sec. 2.1) that sheet
// grows at 50 ns; at 1 cP (the seed's code) it is stable (reference/chapter4_cells.yaml).
// Before the fluid step the stopping condition of eq. 5.4 is checked: the step is refused when
//   dt > (1/4) sqrt(h rho / ||f||_inf),
// and any failure (that condition, a degenerate or inverted cell, a non-finite force or velocity)
// raises NumericalError naming the step, the time and the cause, with every state (fluid, cells)
// left as it was before the step: the last good state survives. With the adaptive step
// (AdaptiveStep below) a refusal by eq. 5.4 instead retakes the step at once with a smaller dt.
// The Eulerian side is any FluidStep (fluid/fluid_step.hpp): Navier-Stokes, or periodic Stokes,
// steady or unsteady; its state is double-buffered, so a refused or failed step copies nothing.
// Units (CGS): positions cm, velocities cm/s, forces dyn, force densities dyn/cm^3, time s.
#include "rbfib/cells/batch.hpp"
#include "rbfib/fluid/fluid_step.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/sim/cell_owners.hpp"
#include "rbfib/sim/cortex.hpp"
#include "rbfib/sim/held_wall.hpp"
#include "rbfib/sim/lagrangian.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbfib::sim {

enum class Coupling { seed, midpoint, forward_euler };
const char* to_string(Coupling c);

/// What sets the adaptive step's rung.
enum class StepCriterion {
  /// Eq. 5.4, the seed's own code: a step whose force density makes dt exceed
  /// (1/4) sqrt(h rho / ||f||_inf) is refused and taken again at the largest rung the bound allows.
  inertial,
  /// The coupled system's explicit stability (docs/derivations/membrane_stability): the rung is
  /// capped by dt_max (the sets' own bounds) and a growth guard refuses a step whose forces carry a
  /// sign-flipping part that grows (see AdaptiveStep::guard_growth); eq. 5.4 is then the seed's
  /// stop condition only, checked at dt_min (the step the seed's runs take).
  stability,
};
const char* to_string(StepCriterion c);

/// The adaptive step: dt = ratio^k dt_min for a level k in [0, max_level] (ratio 2: the seed's own
/// code), chosen by the criterion. A refused step leaves the state as it was and is taken again at
/// once at a lower level; the level grows by one only after grow_after consecutive steps that
/// allowed the next rung. The first step is taken at the options' dt, which must be such a size.
struct AdaptiveStep {
  bool enabled = false;
  double dt_min = 0;    ///< s
  int max_level = 0;    ///< dt <= ratio^max_level dt_min
  int grow_after = 16;  ///< steps that allow the next rung before it is taken
  /// No rung above this step (s): a guard from a bound eq. 5.4 does not see, such as tethered
  /// points' explicit stability (sim/tether_stability.hpp; scene::build sets it) or, with the
  /// stability criterion, the membranes' (sim/membrane_stability.hpp; set as cells are added).
  double dt_max = INFINITY;
  StepCriterion criterion = StepCriterion::inertial;
  double ratio = 2;     ///< between rungs, in (1, 2]
  /// The stability criterion's growth guard (docs/derivations/membrane_stability, section 6). With
  /// F^n a set's forces at step n, D^n = F^n - 2 F^{n-1} + F^{n-2} is their sign-flipping part: a
  /// smooth motion gives D^n along D^{n-1}; an unstable mode of the coupling (growth factor mu < -1)
  /// gives D^n against it, |D^n| / |D^{n-1}| = |mu| (1.11-1.13 at 1.1 times the threshold step). A
  /// step of a set whose D^n has pointed against D^{n-1} (cosine < -1/2) and grown by more than
  /// guard_growth on guard_steps consecutive steps is refused, and taken again two rungs lower;
  /// the ladder is then capped one rung under the refused step for the rest of the run. The
  /// ladder climbs a rung only after the guard has watched the current one for guard_steps steps
  /// without such a pattern (and grow_after steps in all).
  double guard_growth = 1.05;
  int guard_steps = 4;
  /// The stability criterion's cap from the membranes: no rung above the step whose gain is this
  /// (sim/membrane_stability.hpp: 1 is the limit; 1/2 leaves the factor 2 the derivation's mode
  /// shapes leave open); infinite: no cap (the guard alone).
  double membrane_gain = 0.5;
};

/// Where the coupled step stands in time: the one clock of a run (the fluid's state carries t for
/// its boundary data; the step reads and sets it through here).
struct Clock {
  double t = 0;      ///< t^n (s)
  double dt = 0;     ///< the size of the next step (s)
  long step = 0;     ///< steps taken from t = 0
  int level = 0;     ///< the adaptive ladder's level: dt = ratio^level dt_min (0 without the ladder)
  int allowing = 0;  ///< consecutive steps that allowed the next rung
  /// The highest level the growth guard leaves open (stability criterion): one rung under a
  /// refused step's (s), for the rest of the run; -1 while it has not fired.
  int cap = -1;
};

struct IbOptions {
  Coupling coupling = Coupling::seed;
  ib::Kernel kernel = ib::Kernel::bspline3;
  /// How forces are spread (Algs. 4.2-4.6; binned: points sorted once per step, added in place).
  /// Interpolation always uses the sorted points (the binned algorithm).
  ib::Spreading spreading = ib::Spreading::binned;
  bool stopping_condition = true;   ///< check eq. 5.4 every step
  /// Measure each step's stability diagnostics whatever the step: the forces' sign-flipping part
  /// (AdaptiveStep's growth guard, which the stability criterion measures anyway) and the set whose
  /// force acts nearest the peak of ||f||_inf (a search over every set's force sites: a few ms per
  /// step at the seed's whole-blood sizes).
  bool watch_stability = false;
  /// A uniform body force density added to the spread force every step (dyn/cm^3), e.g. a mean
  /// pressure gradient driving a channel or a periodic box.
  std::array<double, 3> body_force{0, 0, 0};
  /// A body force density that varies in space (dyn/cm^3, one value per MAC face of each
  /// component; empty: none), added after the spread forces (e.g. the capillary's pressure
  /// gradient inside its tube and the balancing one outside, Chapter 3 Sec. 5.1).
  VectorField body_force_density;
  AdaptiveStep adaptive;
};

/// What one step did (seconds per component and the eq. 5.4 numbers).
struct IbStepReport {
  double dt = 0;                 ///< the step taken (s)
  int refused = 0;               ///< attempts refused before it (adaptive step: eq. 5.4 or the growth guard)
  int refused_by_guard = 0;      ///< of those, refused by the growth guard (stability criterion)
  /// The growth guard's measures over the sets (NaN where not measured: fewer than four steps at
  /// this rung): the largest ||D^n|| / ||D^{n-1}|| among the sets whose D^n points against D^{n-1}
  /// (cosine below -1/2), and the smallest cosine (AdaptiveStep).
  double oscillation_growth = NAN, oscillation_cosine = NAN;
  /// The set whose force acts nearest the peak of ||f||_inf (index in the order sets were added),
  /// -1 without forces or unless IbOptions::watch_stability.
  int peak_set = -1;
  double max_force_density = 0;  ///< ||f||_inf on the grid (dyn/cm^3)
  double dt_bound = 0;           ///< (1/4) sqrt(h rho / ||f||_inf) (s); infinite when f = 0
  double max_velocity = 0;       ///< max |u_a| after the step (cm/s)
  double kinetic_energy = 0;     ///< (rho / 2) sum |u|^2 h^3 after the step (erg)
  double elastic_energy = 0;     ///< the cells' energy at the forces' positions (erg)
  /// The uniform velocity added throughout the domain by a frame set (Chapter 3 eq. 95; cm/s).
  std::array<double, 3> frame_velocity{0, 0, 0};
  double seconds_interpolation = 0, seconds_forces = 0, seconds_spreading = 0, seconds_fluid = 0, seconds_update = 0;
  double seconds_force_products = 0;  ///< the cells' dense products (part of seconds_forces)
  double seconds_held = 0;  ///< a held wall's solve and second fluid step (part of seconds_fluid)
  StepStats fluid;
};

class ImmersedBoundary {
 public:
  /// The step over the Navier-Stokes solver of Sec. 2.1.
  ImmersedBoundary(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options, BoundaryVelocity boundary,
                   IbOptions ib);
  /// The step over any fluid (periodic Stokes, steady or unsteady; Navier-Stokes).
  ImmersedBoundary(std::unique_ptr<FluidStep> fluid, IbOptions ib);

  /// Adds a batch of cells; returns its index. The batch's velocities are set at the next step.
  /// On a split fluid every process adds the whole batch and keeps the cells whose centroid (the
  /// mean of their data sites) lies in its planes (none is allowed); before each step a cell whose
  /// centroid has crossed into another process's planes moves there (sim/cell_owners.hpp).
  index_t add(cells::Batch batch);
  /// The index in the whole batch of each cell this process steps (one process: 0..N-1).
  const std::vector<index_t>& cell_ids(index_t b) const { return ids_.at(b); }
  /// The cells of batch b in the whole run (on one process: batch(b).size()).
  index_t cells_in_run(index_t b) const;
  /// One value per cell of batch b, given for this process's cells (in its batch's order), for
  /// every cell of the run in the order of their indices (collective on a split fluid): per-cell
  /// diagnostics that read the same whatever the number of processes.
  std::vector<double> run_cell_values(index_t b, const std::vector<double>& mine) const;
  /// Adds a set of tethered points; returns its index. Throws InputError naming the field for
  /// mismatched sizes, non-finite values or negative constants. On a split fluid every process adds
  /// the whole set and keeps the points whose anchor lies in its planes (by position: a point stays
  /// within its spring's stretch of its anchor, far inside the Lagrangian halo, so it keeps its
  /// owner; one beyond the halo stops the step, named); a frame runs on one process only.
  index_t add(TetheredPoints points);
  /// This process's points of set p (on one process, the whole set).
  const TetheredPoints& points(index_t p) const { return points_.at(p)->points(); }
  const IbOptions& options() const { return options_; }
  index_t point_sets() const { return index_t(points_.size()); }
  /// Adds an LDSM shell; returns its index. Throws InputError naming the field for bad input.
  index_t add(LdsmShell shell);
  const LdsmShellSet& shell(index_t s) const { return *shells_.at(s); }
  index_t shells() const { return index_t(shells_.size()); }
  /// Adds the cortex of a blebbing cell linked to `membrane`, a set of this step added before it
  /// (batch_set(b) of one cell, or shell(s)); returns its index. Throws InputError naming the field
  /// for another coupling than forward_euler, a membrane not of this step or of another site
  /// count, or bad input (sim/cortex.hpp).
  index_t add(Cortex cortex, const LagrangianSet& membrane);
  const CortexSet& cortex(index_t c) const { return *cortices_.at(c); }
  CortexSet& cortex(index_t c) { return *cortices_.at(c); }
  index_t cortices() const { return index_t(cortices_.size()); }
  /// Adds a wall held exactly by a solve (sim/held_wall.hpp); returns its index. Throws InputError
  /// naming the field for a second held wall, a fluid step that is not affine in its force (Peskin's
  /// two-stage scheme advects with the half step's velocity), or bad markers.
  index_t add(HeldWall wall);
  const HeldWallSet& held_wall(index_t w) const { return *held_.at(w); }
  index_t held_walls() const { return index_t(held_.size()); }
  const CellBatchSet& batch_set(index_t b) const { return *batches_.at(b); }
  cells::Batch& batch(index_t b) { return batches_.at(b)->batch(); }
  const cells::Batch& batch(index_t b) const { return batches_.at(b)->batch(); }
  index_t batches() const { return index_t(batches_.size()); }

  FluidState& fluid_state() { return fluid_->state(); }
  const FluidState& fluid_state() const { return fluid_->state(); }
  const FluidStep& fluid() const { return *fluid_; }
  const ib::Interaction& interaction() const { return ib_; }
  ib::Interaction& interaction() { return ib_; }
  double time() const { return fluid_->state().t; }
  long step_count() const { return steps_; }
  /// t, dt, the step count and the ladder's level, read together.
  Clock clock() const { return Clock{time(), dt(), steps_, level_, allowing_, cap_}; }

  /// Everything a step carries over to the next, for checkpoints: the fluid state, each batch's
  /// data-site state (X and U), each point set's positions, each shell's vertices and the clock
  /// (its t is the fluid state's). The rest (operators, factorizations, workspaces) is rebuilt from
  /// the setup, so restoring this into an ImmersedBoundary built the same way continues the run
  /// bit for bit. On a split fluid carried() is collective and gives every process the whole
  /// run's state (the fluid gathered, each batch's cells in the order of their indices), the same
  /// as one process's; restore() takes such a state on any number of processes and keeps this
  /// process's part (the cells by centroid; their body forces those given to add()).
  struct Carried {
    FluidState fluid;
    std::vector<dvec> batches;  ///< each batch's state storage (n_d x 6N, column-major)
    std::vector<dvec> points;   ///< each point set's positions
    std::vector<std::vector<double>> shells;  ///< each LDSM shell's vertices
    std::vector<std::vector<double>> cortices;  ///< each cortex's sites
    Clock clock;
  };
  Carried carried() const;
  /// Restores a carried state; throws InputError naming what does not match this setup.
  void restore(const Carried& c);

  /// One step of the coupling. Throws NumericalError (state unchanged) as described above; with the
  /// adaptive step, eq. 5.4 stops the run only when even dt_min violates it. With the adaptive
  /// step, a rung longer than `at_most` (s; the run's end less t) is shortened to it for this step
  /// alone (the ladder keeps its level): runs compared at their end land on it.
  IbStepReport step(double at_most = INFINITY);
  /// The step size of the next step (s).
  double dt() const { return fluid_->dt(); }

  /// Per-cell diagnostics of batch b from the last step's force call, at the positions the forces
  /// were computed at (X* of (b), or X^{n+1/2}): energy, dissipation, area, volume, centroid.
  /// Empty before the first step.
  const cells::CellDiagnostics& diagnostics(index_t b) const { return batches_.at(b)->forces().cells; }

  /// The Eulerian force density of the last step (dyn/cm^3), per component.
  const VectorField& force_density() const { return f_; }

 private:
  /// Calls fn on every Lagrangian set: the cell batches, then the tethered point sets.
  template <class F>
  void for_each_set(F&& fn) {
    for (auto& s : sets_) fn(*s);
  }
  template <class T>
  index_t keep(std::unique_ptr<T> set, std::vector<T*>& kind) {
    kind.push_back(set.get());
    sets_.push_back(std::move(set));
    return index_t(kind.size()) - 1;
  }
  /// One attempt at the step with the current dt: the coupling; throws Refused (state restored)
  /// when the adaptive step is on and eq. 5.4 refuses it.
  IbStepReport attempt();
  struct Refused {
    int level;  ///< the level to take the step again at (< 0: none is left)
    std::string why;
  };
  void set_level(int level);
  /// The step of a level (s): ratio^level dt_min.
  double rung(int level) const;
  /// The level whose step is the largest at most dt (s); -1 below dt_min.
  int level_within(double dt) const;
  /// The growth guard's measures of this attempt's forces, into the report; with the stability
  /// criterion, throws Refused when they carry a growing sign-flipping part.
  bool guarded() const;
  bool watched() const;
  void guard(IbStepReport& r);
  /// Keeps this step's forces for the guard's next steps (after the step is accepted).
  void remember_forces();
  /// The set whose force acts nearest the largest |f| of the spread force density (-1 on a split
  /// fluid, or without forces).
  int peak_set(const VectorField& f) const;
  /// The index of the set whose force sites lie nearest x (cm), -1 without any.
  int nearest_set(const std::array<double, 3>& x) const;
  /// On a split fluid: the cells whose centroid left this process's planes go to their owner.
  void migrate();
  /// Keeps this process's cells of a whole batch (records with indices 0..N-1) in batch b.
  void own(index_t b, const std::vector<CellRecord>& whole);

  std::unique_ptr<FluidStep> fluid_;
  ib::Interaction ib_;
  IbOptions options_;
  std::vector<std::unique_ptr<LagrangianSet>> sets_;  // in the order added: the order of spreading
  std::vector<CellBatchSet*> batches_;
  std::vector<std::vector<index_t>> ids_;            // per batch: each cell's index in the whole batch
  std::vector<std::vector<double>> whole_body_;      // per batch, split fluid: every cell's body force (3N)
  std::vector<TetheredPointSet*> points_;
  std::vector<std::vector<index_t>> point_ids_;      // per point set, split fluid: each point's index in the whole set
  std::vector<index_t> point_counts_;                // per point set: the whole set's points
  std::vector<LdsmShellSet*> shells_;
  std::vector<CortexSet*> cortices_;
  std::vector<HeldWallSet*> held_;
  VectorField f_, scratch_;  // the force density; a scratch field for the non-binned spreadings
  VectorField u_wide_, f_wide_;  // split fluid: velocity and force on the Lagrangian grid
  long steps_ = 0;
  int level_ = 0, allowing_ = 0;  // adaptive step: current level, consecutive steps allowing the next rung
  // The growth guard's memory: every set's forces at the last two accepted steps at this rung
  // (oldest first; emptied when the rung changes or a state is restored) and ||D|| of the last.
  struct PastForces {
    dvec f1, f2;  // F^{n-1}, F^{n-2}
    dvec v;       // D^{n-1}
    dvec now;     // D^n of the attempt (scratch)
  };
  std::vector<PastForces> past_;  // per set
  int flipping_ = 0;              // consecutive accepted steps whose D flipped and grew in some set
  bool attempt_flipping_ = false; // this attempt's D flipped and grew in some set
  bool attempt_measured_ = false; // this attempt's D was measured in every set
  int quiet_ = 0;                 // consecutive accepted steps at this rung measured without flipping
  int cap_ = -1;                  // Clock::cap
};

}  // namespace rbfib::sim
