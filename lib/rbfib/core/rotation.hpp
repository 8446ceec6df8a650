#pragma once
// Rotations of R^3 as 3 x 3 matrices: from an axis and an angle (Rodrigues, right-handed, as the
// placements of cells take them, cells/batch.hpp), their product, and back to an axis and angle.
#include <array>

namespace rbfib {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;  ///< rows

/// A rotation by `angle` (rad) about `axis` (any length > 0), right-handed.
struct AxisAngle {
  Vec3 axis{0, 0, 1};
  double angle = 0;
};

/// R = cos a I + sin a [k]x + (1 - cos a) k k^T, k = axis / |axis|.
Mat3 rotation_matrix(const Vec3& axis, double angle);
inline Mat3 rotation_matrix(const AxisAngle& r) { return rotation_matrix(r.axis, r.angle); }

/// The product A B.
Mat3 product(const Mat3& A, const Mat3& B);

/// The axis (unit) and angle (in (0, pi)) of a rotation matrix: cos a = (tr R - 1) / 2, the axis
/// from the antisymmetric part R - R^T = 2 sin a [k]x. Not for angles 0 or pi.
AxisAngle axis_angle(const Mat3& R);

}  // namespace rbfib
