#pragma once
// The measures of chapter3_blebbing's figures (the JCP 2018 paper, Figs. 11 and 15) from a kept
// membrane state: the section of the triangulated membrane by a plane x = const, and the mean
// curvature against the polar angle from the bleb's axis.
#include "rbfib/surface/triangulation.hpp"

#include <array>
#include <vector>

namespace rbfib::blebbing {

/// Fig. 11: where the membrane's triangles cross the plane x = x0 (X n x 3, cm): one (y, z) point
/// per crossed edge of each crossed triangle (cm).
std::vector<std::array<double, 2>> section_x(const std::vector<double>& X, const std::vector<surface::Triangle>& tris, double x0);

/// Fig. 15's LDSM curvature as the paper signs it: the edges' unsigned |H| (surface::
/// edge_mean_curvature) made negative at the vertices of the convex hull of X (the convex part;
/// the library's sign, -1/r on a sphere) and positive elsewhere (the concave part).
std::vector<double> ldsm_signed_curvature(const std::vector<double>& X, const std::vector<surface::Triangle>& tris);

/// Fig. 15: H (1/cm) in bands of the polar angle about +z through `center` (cm): per band its
/// angle (degrees, the band's middle) and the mean, least and largest H of its sites.
struct CurvatureBand {
  double angle_deg, mean, min, max;
};
std::vector<CurvatureBand> curvature_by_angle(const std::vector<double>& X, const std::vector<double>& H,
                                              const std::array<double, 3>& center, int bands);

}  // namespace rbfib::blebbing
