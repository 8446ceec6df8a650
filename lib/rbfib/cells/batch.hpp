#pragma once
// A batch: N cells of one type, and the force call over all of them (dissertation Secs. 2.3-2.4).
//
// State (device, docs/math.md layout): an n_d x 6N matrix, positions X (columns d N + c) then
// velocities U (columns 3N + d N + c) at the data sites, in cm and cm/s.
//
// compute_forces, for every cell at once:
//   1. bending only: the jets of X at the data sites (rows n_s .. of the type's operators), and
//      from them H - H' there;
//   2. jets at the sample sites: value and derivatives of X, two products (with U as 3N more
//      columns when the type has dissipation, and H - H' as N more with bending, so that the
//      operators are read once: with few cells the products are bound by that read); the
//      sample-site values are the positions spread from;
//   3. one launch over the N n_s sample sites: the force density of every energy of the type's
//      model (eq. 35 for W(I1, I2), eq. 84 / 2.13 for bending, eq. 2.14 for dissipation), per unit
//      reference area, the force F^ = F dA0 (eq. 52) plus each cell's body force spread in
//      proportion to dA0, and each site's contributions to energy, area, volume and centroid;
//   4. reductions per cell, and a reduction of the per-site status to the first bad site, from
//      which the host raises NumericalError naming the type, the cell, the site and the cause.
#include "rbfib/cells/cell_type.hpp"

#include <array>
#include <memory>
#include <vector>

namespace rbfib::cells {

/// Where a cell goes: X = center + R(axis, angle) diag(stretch) X_ref, with X_ref the reference
/// shape (centred at the origin) and R the rotation by `angle` (rad) about `axis`. stretch
/// deforms the cell in its own frame first (the stretch/compress initial states of Secs. 4.2.2.1
/// and 5.1.1, e.g. {1, 1/1.1, 1.1}).
struct Placement {
  std::array<double, 3> center{0, 0, 0};  ///< cm
  std::array<double, 3> axis{0, 0, 1};
  double angle = 0;                       ///< rad
  std::array<double, 3> stretch{1, 1, 1};
};

/// The placed positions center + R diag(stretch) X_ref of n reference points (component-major,
/// X_ref[d n + i]; host). Throws InputError naming `who` for a zero or non-finite axis, a
/// non-finite angle or centre, or a stretch <= 0.
std::vector<double> placed(const std::vector<double>& reference, index_t n, const Placement& p, const std::string& who);

/// Per-cell results of a force call.
struct CellDiagnostics {
  std::vector<double> energy;       ///< elastic + bending energy (erg)
  std::vector<double> dissipation;  ///< Rayleigh dissipation (erg/s)
  std::vector<double> area;         ///< cm^2
  std::vector<double> volume;       ///< cm^3
  std::vector<std::array<double, 3>> centroid;  ///< centroid of the enclosed volume (cm)
};

/// Wall time of the phases of one force call (s), measured only when asked for (it
/// synchronizes the device between phases).
struct ForceTimings {
  double jets = 0;              ///< products at the sample sites: the jets of X (and U), and of H - H' with bending
  double bending_products = 0;  ///< products: the jets of X at the data sites, for H (bending)
  double bending_kernel = 0;    ///< H - H' at the data sites and its status reduction
  double kernels = 0;           ///< the site launch: geometry, every force density, F^
  double reductions = 0;        ///< the status reduction and the per-cell sums
  double products() const { return jets + bending_products; }
  double bending() const { return bending_products + bending_kernel; }
  double total() const { return jets + bending_products + bending_kernel + kernels + reductions; }
};

/// The output of a force call, in the sample-site layout n_s x 3N (docs/math.md).
struct CellForces {
  linalg::DeviceMatrix positions;   ///< sample-site positions (cm): what is spread from
  linalg::DeviceMatrix density;     ///< force density per unit reference area (dyn/cm^2)
  linalg::DeviceMatrix force;       ///< F^ = density dA0 + body-force share (dyn)
  double energy = 0;                ///< sum over cells (erg)
  CellDiagnostics cells;
};

class Batch {
 public:
  Batch(std::shared_ptr<const CellType> type, const std::vector<Placement>& placements);
  /// A batch of `cells` cells (zero allowed: a process that owns none of the type) from their
  /// state (host, n_d x 6N column-major as state()) and body forces (3N, F[d N + c]).
  static Batch from_state(std::shared_ptr<const CellType> type, index_t cells, const std::vector<double>& state,
                          const std::vector<double>& body);

  const CellType& type() const { return *type_; }
  const std::shared_ptr<const CellType>& type_ptr() const { return type_; }
  index_t size() const { return cells_; }

  /// n_d x 6N: positions then velocities at the data sites.
  linalg::DeviceMatrix& state() { return state_; }
  const linalg::DeviceMatrix& state() const { return state_; }
  linalg::MatrixView positions() { return state_.view().block(0, 0, type_->n_data(), 3 * cells_); }
  linalg::MatrixView velocities() { return state_.view().block(0, 3 * cells_, type_->n_data(), 3 * cells_); }

  /// Places cell c (host computation, one upload of its three columns).
  void place(index_t c, const Placement& p);
  /// A constant total force on cell c (dyn), spread over its sample sites in proportion to dA0
  /// (the fictitious force of Sec. 5.1.3).
  void set_body_force(index_t c, const std::array<double, 3>& F);
  const std::vector<double>& body_force() const { return body_; }  ///< 3N, F[d N + c]
  /// The same on the device (uploaded by set_body_force, read by the force call).
  const dvec& body_force_device() const { return body_device_; }

  /// Host copy of the positions (n_d x 3N, column-major).
  std::vector<double> positions_host() const;

  /// Workspace of the force call, reused between calls (no allocation after the first).
  struct Workspace {
    linalg::DeviceMatrix values, derivatives;            // jets at the sample sites
    linalg::DeviceMatrix data_derivatives;  // derivatives of X at the data sites (bending)
    linalg::DeviceMatrix fields;                         // [X U (H - H')] at the data sites (bending)
    surface::OperatorWorkspace ops;
    device_vector<int> status, data_status;
    dvec site_sums;       // per site: 7 contributions (energy, dissipation, area, volume, 3 moments)
    dvec cell_sums;       // per cell
    dvec ones;            // n_s ones: the per-cell sums are S^T 1
  };
  Workspace& workspace() const { return work_; }

 private:
  Batch() = default;
  std::shared_ptr<const CellType> type_;
  index_t cells_ = 0;
  linalg::DeviceMatrix state_;
  std::vector<double> body_;
  dvec body_device_;
  mutable Workspace work_;
};

/// The force call over all cells of a batch (see the header comment). Throws NumericalError
/// naming the type, the cell, the site and the cause for a degenerate site, an
/// undefined energy or a non-finite force, and naming the cell for one turned inside out
/// (enclosed volume <= 0); `out` is then unspecified.
void compute_forces(const Batch& batch, CellForces& out, ForceTimings* timings = nullptr);
/// The same at another state of the batch's cells (n_d x 6N: positions then velocities at the
/// data sites, e.g. the predicted X* of the coupled step kept outside the batch).
void compute_forces(const Batch& batch, linalg::ConstMatrixView state, CellForces& out, ForceTimings* timings = nullptr);

/// The geometry of every cell of a batch, without its forces (for samples and diagnostics).
struct CellGeometry {
  linalg::DeviceMatrix positions;  ///< sample-site positions (cm), n_s x 3N
  CellDiagnostics cells;           ///< area, volume and centroid (energy and dissipation are left empty)
};

/// The sample-site positions and each cell's area, enclosed volume and centroid, by the force
/// call's quadrature (one product of the position columns only, one site launch, one reduction).
/// Throws NumericalError for a degenerate site or a cell turned inside out, as the force call does.
void measure(const Batch& batch, CellGeometry& out);

}  // namespace rbfib::cells
