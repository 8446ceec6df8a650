#pragma once
// Contact tests between closed surfaces given by points and a triangulation (the placed data sites
// of cells and their sphere triangulation, triangulation.hpp): is a point inside a surface, and how
// close do two point sets come. Used to refuse scenes whose cells overlap before a run (Sec. 5.2.1
// keeps 2h between cells; overlapping cells give forces with no meaning).
// Points: n x 3 column-major, X[d n + i] (docs/math.md), in cm.
#include "rbfib/surface/triangulation.hpp"

#include <array>
#include <vector>

namespace rbfib::surface {

/// The winding number of the closed triangulated surface (X, tris) about p: the sum of the solid
/// angles of its triangles seen from p over 4 pi (Van Oosterom and Strackee 1983). 1 inside a
/// surface whose triangles are outward (counter-clockwise seen from outside), 0 outside; p on the
/// surface gives a value in between.
double winding_number(const std::vector<double>& X, index_t n, const std::vector<Triangle>& tris, const std::array<double, 3>& p);

/// The smallest distance between points of A (na) and points of B (nb), B shifted by `shift`;
/// also the indices of the closest pair. Brute force, O(na nb).
struct Closest {
  double distance = 0;
  index_t a = 0, b = 0;
};
Closest closest_points(const std::vector<double>& A, index_t na, const std::vector<double>& B, index_t nb,
                       const std::array<double, 3>& shift = {0, 0, 0});

/// A box's periodicity: its lengths (cm) and which axes are periodic.
struct PeriodicBox {
  std::array<double, 3> length{0, 0, 0};
  std::array<bool, 3> periodic{false, false, false};
};

/// The shift of b, a whole number of box lengths along each periodic axis, that brings b nearest a:
/// L round((a - b) / L) per periodic axis, 0 on the others.
std::array<double, 3> nearest_image_shift(const std::array<double, 3>& a, const std::array<double, 3>& b, const PeriodicBox& box);

}  // namespace rbfib::surface
