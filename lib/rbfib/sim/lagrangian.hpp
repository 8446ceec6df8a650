#pragma once
// The Lagrangian side of the coupled step (Sec. 2.4): a set of points that moves with the fluid
// and pushes on it. A coupling (ib_step.hpp) is a short function of the verbs below, the same for
// every kind of set; a new kind of set (a wall held by a solve, the cortex of a blebbing cell)
// implements them and joins the step without a new coupling.
//
// One step of a set, in the seed's order:
//   save()                  keep X^n (and what else the set carries) for a retake or a failure
//   locate()                X^n checked finite and sorted by grid cell once for the step
//   interpolate_start(u)    (a) U^n = I u^n at X^n
//   predict(c)              (b) the positions forces are computed at, X* = X^n + c U^n
//   compute_force()         (c) F at X* (the set's own law), returns its elastic energy (erg)
//   spread(f)               (d) f += S F from where F acts
//   interpolate_end(u)      (f) U = I u at X^n (the midpoint coupling: at X*)
//   update(dt, u_frame)     (g) X^{n+1} = X^n + dt (U + u_frame), u_frame a uniform velocity
//                           added throughout the domain (the capillary's frame, Chapter 3 eq. 95;
//                           zero otherwise)
//   restore()               put back what save() kept (the step was refused or failed)
// Chapter 3's forward Euler (Sec. 3.3) skips (a) and (b): forces at X^n, X^{n+1} = X^n + dt U.
// Units (CGS): positions cm, velocities cm/s, forces dyn, force densities dyn/cm^3.
#include "rbfib/cells/batch.hpp"
#include "rbfib/fluid/decomposition.hpp"
#include "rbfib/grid/mac.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/mechanics/energy.hpp"
#include "rbfib/sim/tether_stability.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace rbfib::sim {

class LagrangianSet {
 public:
  virtual ~LagrangianSet() = default;
  /// The set in messages: "cell type 'rbc'", "tethered points 'endothelium'".
  virtual std::string name() const = 0;
  virtual void save() = 0;
  virtual void restore() = 0;
  virtual void locate(ib::Interaction& ib) = 0;
  virtual void interpolate_start(ib::Interaction& ib, const VectorField& u) = 0;
  virtual void predict(double c) = 0;
  virtual double compute_force() = 0;
  /// Adds S F into f; `binned` adds straight into f, another algorithm spreads into scratch first.
  virtual void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) = 0;
  /// at_predicted: interpolate at X* (sorted anew) rather than at X^n.
  virtual void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) = 0;
  virtual void update(double dt, const std::array<double, 3>& u_frame) = 0;
  /// Seconds of the last compute_force() spent in dense products (0 for a set without them).
  virtual double seconds_force_products() const { return 0; }
  /// The last compute_force()'s forces (dyn, one entry per site and component), what the step's
  /// growth guard watches; null for a set that offers none.
  virtual const dvec* force_values() const { return nullptr; }
  /// Where the last compute_force()'s forces act, n x 3 column-major (cm, a host copy): what a set
  /// linked to this one reads (the cortex's adhesion, sim/cortex.hpp). Throws InputError for a
  /// set that offers none.
  virtual std::vector<double> force_sites() const;
};

/// U = I u at sorted points; throws NumericalError (non-finite) naming `who` when U is not finite.
void interpolate_at(ib::Interaction& ib, const ib::SortedPoints& s, const VectorField& u, dvec& U, const std::string& who);

/// The entries of a point set's values (positions, velocities, forces: 3n, X[d n + k]) at the
/// points `ids`, in their order (3m).
dvec points_at(const dvec& X, const std::vector<index_t>& ids);

/// The whole set's values (3n) from each process's values X (3m) at its points `ids`
/// (collective); NaN where no process sent a point.
dvec whole_points(const FluidDecomposition& parts, const dvec& X, const std::vector<index_t>& ids, index_t n);

/// Adds S F from the points X into f (binned: sorted into `sorted` and added in place; another
/// algorithm spreads into scratch, then adds).
void spread_into(ib::Interaction& ib, ib::Spreading algorithm, const dvec& X, const dvec& F, ib::SortedPoints& sorted,
                 VectorField& f, VectorField& scratch);

/// A batch of cells of one type (cells/batch.hpp): data sites X carried, forces computed at the
/// sample sites reconstructed from X* and spread from there (eq. 2.24), velocities interpolated
/// at the data sites (eq. 2.23). The batch's state holds X^n until (g); X* (with U^n, for
/// dissipation) lives in the set's workspace, so a refused or failed step has nothing to restore.
class CellBatchSet final : public LagrangianSet {
 public:
  explicit CellBatchSet(cells::Batch batch) : batch_(std::move(batch)) {}
  std::string name() const override { return "cell type '" + batch_.type().name() + "'"; }
  void save() override {}     // the state changes only in update(), the step's last verb
  void restore() override {}  // (a failure before it leaves X^n in place)
  void locate(ib::Interaction& ib) override;
  void interpolate_start(ib::Interaction& ib, const VectorField& u) override;
  void predict(double c) override;
  double compute_force() override;
  void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) override;
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double dt, const std::array<double, 3>& u_frame) override;
  double seconds_force_products() const override { return timings_.products(); }
  const dvec* force_values() const override { return &forces_.force.storage(); }
  /// The sample sites of the last force call (every cell's, cell after cell).
  std::vector<double> force_sites() const override { return forces_.positions.to_host(); }

  cells::Batch& batch() { return batch_; }
  const cells::Batch& batch() const { return batch_; }
  const cells::CellForces& forces() const { return forces_; }
  /// Another set of cells of the type (cells moving between processes, sim/cell_owners.hpp); the
  /// last force call's results are dropped. A batch of no cells does nothing in the step.
  void replace(cells::Batch batch);

 private:
  cells::Batch batch_;
  cells::CellForces forces_;
  cells::ForceTimings timings_;
  linalg::DeviceMatrix star_;  // X* = X^n + c U^n and U^n (n_d x 6N), once predicted
  bool predicted_ = false;     // whether this step's forces act at star_ (else at X^n)
  ib::SortedPoints start_;     // X^n sorted once by grid cell: (a) and (f) interpolate there
  ib::SortedPoints sample_;    // the sample sites the forces are spread from
  dvec U_;                     // the interpolated velocities (3 n_d N)
};

/// Bare Lagrangian points held by damped springs to anchors (dissertation eq. 2.10, the
/// endothelium of Sec. 5.2): the force on point k is F_k = -k_s (X_k - X'_k) - eta (U_k - U'_k),
/// U' = 0, in dyn per point (k_s in dyn/cm, eta in dyn s/cm: the seed's k = 2.5 dyn/cm and
/// eta = 2.5e-7 dyn s/cm are per point, as its units say). Forces are spread from the points and
/// velocities interpolated at them; no surface is reconstructed.
/// Constants that follow the step (the seed's rule, sim/tether_stability.hpp): k and eta are set
/// before every step from its dt, as large as the sheet's bound allows at the given gain.
struct TetherRule {
  TetherSheet sheet;  ///< the flat sheet the points form (the model of the bound)
  double gain = 0.5;  ///< (eta + k dt/2) G1(dt), in (0, 1)
};

struct TetheredPoints {
  std::string name;
  dvec X;        ///< positions, 3n, X[d n + k] (cm)
  dvec anchors;  ///< X', 3n (cm)
  double k = 0;    ///< spring constant (dyn/cm)
  double eta = 0;  ///< damping (dyn s/cm)
  /// The points hold the frame (the capillary of Chapter 3, eqs. 94-95): after each step the
  /// uniform velocity u_c = (1 / (n dt)) sum_k (X'_k - X^_k), X^ = X^n + dt U (equal node areas),
  /// is added throughout the domain, so that the points return to their anchors on average.
  bool frame = false;
  std::optional<TetherRule> follow;  ///< set: k and eta follow the step (then set before each step)
};

/// Tethered points as a Lagrangian set. `predicted`: whether the coupling evaluates the spring at
/// X* (the midpoint coupling) or at X^n (the seed's coupling: the points are not predicted, their
/// force is spread from X^n, sorted once for (a), (d) and (f); see ib_step.hpp for why).
class TetheredPointSet final : public LagrangianSet {
 public:
  /// Throws InputError naming the field for mismatched sizes, non-finite values or negative
  /// constants, or no points (`part`: a process's part of a split set, which may have none).
  TetheredPointSet(TetheredPoints points, bool predicted, bool part = false);
  std::string name() const override { return "tethered points '" + points_.name + "'"; }
  void save() override { X0_ = points_.X; }
  void restore() override { points_.X = X0_; }
  void locate(ib::Interaction& ib) override;
  void interpolate_start(ib::Interaction& ib, const VectorField& u) override;
  void predict(double c) override;
  double compute_force() override;
  void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) override;
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double dt, const std::array<double, 3>& u_frame) override;
  const dvec* force_values() const override { return &F_; }
  /// The points (X^n: the seed's coupling spreads from there; X* when predicted), n x 3.
  std::vector<double> force_sites() const override;
  /// The frame velocity u_c of eq. (95) after (f): (1 / (n dt)) sum_k (X'_k - (X^n_k + dt U_k)) (cm/s).
  std::array<double, 3> frame_velocity(double dt) const;

  const TetheredPoints& points() const { return points_; }
  TetheredPoints& points() { return points_; }

 private:
  TetheredPoints points_;
  bool predicted_;
  ib::SortedPoints start_, spread_;
  dvec X0_, U_, F_;  // X^n (also what a failure restores), velocities, spring forces
};

/// A shell whose forces are LDSM's (Chapter 3 eq. 66, the linear-element method the paper compares
/// with): its n triangulated vertices carry the state, forces are computed on the flat triangles
/// (every energy in one pass) and spread from the vertices, velocities interpolated at them.
struct LdsmShell {
  std::string name;
  std::vector<surface::Triangle> triangles;
  std::vector<double> reference;  ///< the reference vertices Z, n x 3 column-major (cm)
  std::vector<double> X;          ///< the vertices now, n x 3 column-major (cm)
  std::vector<mechanics::EnergyDensity> energies;
};

/// An LDSM shell as a Lagrangian set. Its forces and positions live on the host (the force loop is
/// the host's); the interaction gets device copies.
class LdsmShellSet final : public LagrangianSet {
 public:
  /// Throws InputError naming the field for mismatched sizes or non-finite positions.
  explicit LdsmShellSet(LdsmShell shell);
  std::string name() const override { return "LDSM shell '" + shell_.name + "'"; }
  void save() override { X0_ = shell_.X; }
  void restore() override { shell_.X = X0_; }
  void locate(ib::Interaction& ib) override;
  void interpolate_start(ib::Interaction& ib, const VectorField& u) override;
  void predict(double c) override;
  double compute_force() override;
  void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) override;
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double dt, const std::array<double, 3>& u_frame) override;
  /// The vertices where the last forces were computed (X^n, or X* once predicted).
  std::vector<double> force_sites() const override { return shell_.X; }

  const LdsmShell& shell() const { return shell_; }
  LdsmShell& shell() { return shell_; }
  /// The forces of the last compute_force() at the vertices (dyn), n x 3.
  const std::vector<double>& force() const { return F_; }

 private:
  LdsmShell shell_;
  std::vector<double> X0_, F_, U_;  // X^n, forces, velocities (host)
  dvec Xd_, Fd_, Ud_;               // device copies for the interaction
  ib::SortedPoints at_;             // where the vertices are sorted (X^n, or X* once predicted)
  bool predicted_ = false;          // whether X holds X* (moved from X^n) in this step
};

}  // namespace rbfib::sim
