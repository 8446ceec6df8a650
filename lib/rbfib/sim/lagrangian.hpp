#pragma once
// The Lagrangian side of the coupled step (Sec. 2.4): a set of points that moves with the fluid
// and pushes on it. A coupling (ib_step.hpp) is a short function of the verbs below, the same for
// every kind of set; a new kind of set (a wall held by a solve, the cortex of a blebbing cell)
// implements them and joins the step without a new coupling.
//
// One step of a set, in the seed's order:
//   save()                  keep X^n (and what else the set carries) for a retake or a failure
//   interpolate_start(u)    (a) U^n = I u^n at X^n (X^n sorted by grid cell once for the step)
//   predict(c)              (b) the positions forces are computed at, X* = X^n + c U^n
//   compute_force()         (c) F at X* (the set's own law), returns its elastic energy (erg)
//   spread(f)               (d) f += S F from where F acts
//   interpolate_end(u)      (f) U = I u at X^n (the midpoint coupling: at X*)
//   update(dt)              (g) X^{n+1} = X^n + dt U
//   restore()               put back what save() kept (the step was refused or failed)
// Units (CGS): positions cm, velocities cm/s, forces dyn, force densities dyn/cm^3.
#include "rbfib/cells/batch.hpp"
#include "rbfib/grid/mac.hpp"
#include "rbfib/ib/interaction.hpp"

#include <string>

namespace rbfib::sim {

class LagrangianSet {
 public:
  virtual ~LagrangianSet() = default;
  /// The set in messages: "cell type 'rbc'", "tethered points 'endothelium'".
  virtual std::string name() const = 0;
  virtual void save() = 0;
  virtual void restore() = 0;
  virtual void interpolate_start(ib::Interaction& ib, const VectorField& u) = 0;
  virtual void predict(double c) = 0;
  virtual double compute_force() = 0;
  /// Adds S F into f; `binned` adds straight into f, another algorithm spreads into scratch first.
  virtual void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) = 0;
  /// at_predicted: interpolate at X* (sorted anew) rather than at X^n.
  virtual void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) = 0;
  virtual void update(double dt) = 0;
};

/// U = I u at sorted points; throws NumericalError (non-finite) naming `who` when U is not finite.
void interpolate_at(ib::Interaction& ib, const ib::SortedPoints& s, const VectorField& u, dvec& U, const std::string& who);

/// Adds S F from the points X into f (binned: sorted into `sorted` and added in place; another
/// algorithm spreads into scratch, then adds).
void spread_into(ib::Interaction& ib, ib::Spreading algorithm, const dvec& X, const dvec& F, ib::SortedPoints& sorted,
                 VectorField& f, VectorField& scratch);

/// A batch of cells of one type (cells/batch.hpp): data sites X carried, forces computed at the
/// sample sites reconstructed from X* and spread from there (eq. 2.24), velocities interpolated
/// at the data sites (eq. 2.23). The batch's state holds X* and U^n between (b) and (g).
class CellBatchSet final : public LagrangianSet {
 public:
  explicit CellBatchSet(cells::Batch batch) : batch_(std::move(batch)) {}
  std::string name() const override { return "cell type '" + batch_.type().name() + "'"; }
  void save() override;
  void restore() override;
  void interpolate_start(ib::Interaction& ib, const VectorField& u) override;
  void predict(double c) override { advance(c); }
  double compute_force() override;
  void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) override;
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double dt) override { advance(dt); }

  cells::Batch& batch() { return batch_; }
  const cells::Batch& batch() const { return batch_; }
  const cells::CellForces& forces() const { return forces_; }

 private:
  /// X = X^n + c U, X^n from the saved state; written into the batch's state with U.
  void advance(double c);
  cells::Batch batch_;
  cells::CellForces forces_;
  dvec saved_;               // the whole state (X^n and U) at the start of a step
  ib::SortedPoints start_;   // X^n sorted once by grid cell: (a) and (f) interpolate there
  ib::SortedPoints sample_;  // the sample sites the forces are spread from
  dvec X_, U_;               // the positions being used, the interpolated velocities
};

/// Bare Lagrangian points held by damped springs to anchors (dissertation eq. 2.10, the
/// endothelium of Sec. 5.2): the force on point k is F_k = -k_s (X_k - X'_k) - eta (U_k - U'_k),
/// U' = 0, in dyn per point (k_s in dyn/cm, eta in dyn s/cm: the seed's k = 2.5 dyn/cm and
/// eta = 2.5e-7 dyn s/cm are per point, as its units say). Forces are spread from the points and
/// velocities interpolated at them; no surface is reconstructed.
struct TetheredPoints {
  std::string name;
  dvec X;        ///< positions, 3n, X[d n + k] (cm)
  dvec anchors;  ///< X', 3n (cm)
  double k = 0;    ///< spring constant (dyn/cm)
  double eta = 0;  ///< damping (dyn s/cm)
};

/// Tethered points as a Lagrangian set. `predicted`: whether the coupling evaluates the spring at
/// X* (the midpoint coupling) or at X^n (the seed's coupling: the points are not predicted, their
/// force is spread from X^n, sorted once for (a), (d) and (f); see ib_step.hpp for why).
class TetheredPointSet final : public LagrangianSet {
 public:
  /// Throws InputError naming the field for mismatched sizes, non-finite values or negative constants.
  TetheredPointSet(TetheredPoints points, bool predicted);
  std::string name() const override { return "tethered points '" + points_.name + "'"; }
  void save() override { X0_ = points_.X; }
  void restore() override { points_.X = X0_; }
  void interpolate_start(ib::Interaction& ib, const VectorField& u) override;
  void predict(double c) override;
  double compute_force() override;
  void spread(ib::Interaction& ib, ib::Spreading algorithm, VectorField& f, VectorField& scratch) override;
  void interpolate_end(ib::Interaction& ib, const VectorField& u, bool at_predicted) override;
  void update(double dt) override;

  const TetheredPoints& points() const { return points_; }
  TetheredPoints& points() { return points_; }

 private:
  TetheredPoints points_;
  bool predicted_;
  ib::SortedPoints start_, spread_;
  dvec X0_, U_, F_;  // X^n (also what a failure restores), velocities, spring forces
};

}  // namespace rbfib::sim
