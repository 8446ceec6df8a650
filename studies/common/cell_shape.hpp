#pragma once
// Shape and orientation of one cell from its data sites (material points), and the rigid-body
// reference for a spheroid in shear (Jeffery 1922), for the studies of cells in shear flow
// (dissertation Secs. 5.1.2 and 5.2: tumbling, tank-treading, wobbling platelets).
//
// Orientation: the second-moment tensor M = (1/n) sum_i (X_i - c)(X_i - c)^T of the data sites
// about their mean c; its eigenvectors are the cell's principal axes, the one of the smallest
// eigenvalue the short (symmetry) axis of a disc-like cell. Extents: max - min of the sites'
// projections on each axis (the cell's thickness and diameters, cm).
#include <array>
#include <vector>

namespace rbfib::study {

using Vec3 = std::array<double, 3>;

struct CellShape {
  Vec3 center{};                ///< mean of the data sites (cm)
  std::array<Vec3, 3> axes{};   ///< principal axes, unit, by increasing second moment (axes[0]: short axis)
  Vec3 extent{};                ///< extent along each axis (cm)
};

/// The shape of cell c of a batch from its data-site positions (n x 3N column-major, the
/// layout of cells::Batch::positions_host(): X[(d N + c) n + i]).
CellShape cell_shape(const std::vector<double>& X, long n, long N, long c);

/// Symmetric 3 x 3 eigenproblem by cyclic Jacobi rotations: eigenvalues ascending, eigenvectors
/// (unit) in the same order.
void symmetric_eigen3(const std::array<Vec3, 3>& A, Vec3& values, std::array<Vec3, 3>& vectors);

/// The symmetry axis p(t) of a rigid spheroid of aspect ratio r (axis along p over the transverse
/// diameter; r < 1 oblate) in the simple shear u = gdot x_g e_f (flow along axis f, gradient
/// along axis g), from p(0) = p0 (Jeffery 1922):
///   dp/dt = W p + B (E p - (p.E p) p),  B = (r^2 - 1) / (r^2 + 1),
/// W and E the antisymmetric and symmetric parts of grad u. Classical RK4 with steps of at most
/// 1e-3 / gdot, renormalized; returns p at each of `times` (ascending, from t = 0).
std::vector<Vec3> jeffery_axis(const Vec3& p0, double r, double gdot, int f, int g, const std::vector<double>& times);

/// Angle between two axes, sign-blind (rad, in [0, pi/2]).
double axis_angle(const Vec3& a, const Vec3& b);

/// Continues a sequence of angles (rad) across the jumps of `period` (2 pi for a direction,
/// pi for an axis) so that it varies continuously.
std::vector<double> unwrap(const std::vector<double>& angles, double period);

}  // namespace rbfib::study
