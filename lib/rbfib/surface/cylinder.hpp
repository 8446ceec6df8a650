#pragma once
// Points on a cylinder about the x axis at the centres of equal patches, ring after ring, alternate
// rings turned by half a spacing: the nodes of the tethered capillary of the seed's Chapter 3
// (Sec. 5.1, eq. 93), and the triangles that join consecutive rings (for pictures).
#include "rbfib/surface/triangulation.hpp"

#include <vector>

namespace rbfib::surface {

struct CylinderPoints {
  std::vector<double> X;  ///< 3n column-major (X[d n + q]), q = j around + i for ring j, point i
  int around = 0;         ///< points per ring
  int along = 0;          ///< rings
  index_t size() const { return index_t(around) * along; }
};

/// Radius R, x in [x0, x1], about `spacing` apart: around = max(8, round(2 pi R / spacing)) points
/// per ring at angles 2 pi (i + j/2 mod 1) / around, along = max(2, round((x1 - x0) / spacing))
/// rings at x0 + (x1 - x0) (j + 1/2) / along.
CylinderPoints cylinder_points(double R, double x0, double x1, double spacing);

/// Two triangles per patch between rings j and j + 1 (the ring closed around), 0-based:
/// 2 around (along - 1) triangles.
std::vector<Triangle> cylinder_triangles(const CylinderPoints& c);

}  // namespace rbfib::surface
