#pragma once
// Measures of placed cells from their sites (data or sample sites, cm): one cell's points out of a
// batch, extents along directions about a centre (the nearest periodic image), the outline seen
// along a direction (a section and a silhouette), the profile's inclination and Taylor deformation
// in a coordinate plane, the site farthest along a direction, the strain of one revolution of a
// tracked angle, and a cell's principal axes and extents. For the studies of cells in flow (diss. Secs. 5.1.2, 5.1.3: a cell in shear,
// two cells pushed together).
// Points of one cell: n x 3 column-major, X[d n + i]; a batch's: n x 3N, X[(d N + c) n + i].
#include "rbfib/core/exec.hpp"
#include "rbfib/core/rotation.hpp"
#include "rbfib/surface/contact.hpp"

#include <vector>

namespace rbfib::cells {

/// The points of cell c (n x 3) out of a batch's positions (n x 3N).
std::vector<double> cell_points(const std::vector<double>& X, index_t n, index_t N, index_t c);

/// Extents max - min of the projections (X_i - centre).e_k on each unit direction e_k, each
/// offset taken along the box's periodic axes at its nearest image (cm).
std::vector<double> extents(const std::vector<double>& X, index_t n, const Vec3& centre, const std::vector<Vec3>& directions,
                            const surface::PeriodicBox& box = {});

/// A cell's outline seen along w, in the plane coordinates (X.u - origin[0], X.v - origin[1]):
/// `section`, the points within `half_width` of the plane X.w = w0 (in their order), and
/// `silhouette`, in each of `bins` equal angular bins about the projected points' mean, the
/// farthest projected point (bins in order of angle from -pi; empty bins give none).
struct Outline {
  std::vector<std::array<double, 2>> section, silhouette;
};
Outline outline(const std::vector<double>& X, index_t n, const Vec3& u, const Vec3& v, const Vec3& w, const std::array<double, 2>& origin,
                double w0, double half_width, int bins = 72);

/// The profile of points in the plane of coordinates a (across) and b (up) about a centre: the
/// inclination of the major axis of its second moments, 0.5 atan2(2 M_ab, M_aa - M_bb) (rad,
/// counterclockwise from e_a toward e_b, in (-pi/2, pi/2]), and its extents along that axis
/// (length L) and across it (breadth B). Taylor's deformation D = (L - B) / (L + B).
struct Profile {
  double inclination = 0, length = 0, breadth = 0;
  double taylor() const { return (length - breadth) / (length + breadth); }
};
Profile profile(const std::vector<double>& X, index_t n, const Vec3& centre, int a, int b);

/// The index of the point farthest along `direction` from `centre` (the largest (X_i - c).d).
index_t farthest_along(const std::vector<double>& X, index_t n, const Vec3& centre, const Vec3& direction);

/// The strain (or time) from s0 until an unwrapped angle (rad, sampled at ascending s) has fallen
/// by 2 pi, one full clockwise revolution of a tracked material point, linear between samples;
/// NaN when s0 lies outside the samples or they end first. For a periodic motion, its period.
double revolution_strain(const std::vector<double>& s, const std::vector<double>& angle, double s0);

/// Shape and orientation of one cell from its data sites (material points): the second-moment
/// tensor M = (1/n) sum_i (X_i - c)(X_i - c)^T about their mean c; its eigenvectors are the cell's
/// principal axes, the one of the smallest eigenvalue the short (symmetry) axis of a disc-like
/// cell; extents max - min of the sites' projections on each axis (thickness and diameters, cm).
/// For cells in shear flow (diss. Secs. 5.1.2 and 5.2: tumbling, tank-treading, wobbling platelets).
struct CellShape {
  Vec3 center{};               ///< mean of the data sites (cm)
  std::array<Vec3, 3> axes{};  ///< principal axes, unit, by increasing second moment (axes[0]: short axis)
  Vec3 extent{};               ///< extent along each axis (cm)
};

/// The shape of cell c of a batch from its positions (n x 3N).
CellShape cell_shape(const std::vector<double>& X, index_t n, index_t N, index_t c);

/// Symmetric 3 x 3 eigenproblem by cyclic Jacobi rotations: eigenvalues ascending, eigenvectors
/// (unit) in the same order.
void symmetric_eigen3(const std::array<Vec3, 3>& A, Vec3& values, std::array<Vec3, 3>& vectors);

/// Angle between two axes, sign-blind (rad, in [0, pi/2]).
double angle_between_axes(const Vec3& a, const Vec3& b);

}  // namespace rbfib::cells
