#pragma once
// Measures of a deformed closed surface whose reference is a sphere's image (a cell), on its n
// sites (n x 3 column-major, X[d n + i]) with outward unit normals: how far it departs from
// axisymmetry about an axis parallel to x, how rough a field on it is, and the spread of a field
// over the sites facing along +x or -x (the seed's Chapter 3, Sec. 5.1.2, Figs. 6-8: bumps, the
// smoothness of the forces, the variability of the mean curvature on the cell's front).
#include "rbfib/surface/triangulation.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace rbfib::surface {

/// Area-weighted vertex normals of the triangulated surface X (outward triangles), unit length.
std::vector<double> vertex_normals(const std::vector<Triangle>& tris, const std::vector<double>& X);

/// The sites banded by their reference angle from the +x axis, alpha = acos(cos lambda cos theta):
/// max(8, round(sqrt(n) / 2.5)) equal bands over 15-165 degrees (sites nearer the poles in none).
/// The sites of one band lie near one ring of the reference, which an axisymmetric flow keeps a ring.
struct AlphaBands {
  std::vector<double> alpha;                      ///< per site (rad)
  std::vector<std::vector<std::size_t>> members;  ///< per band, its sites ascending
};
AlphaBands alpha_bands(const SphereSites& sites);

/// The residual of q about its least-squares line in alpha, per band of at least 4 sites (NaN at
/// the sites of no such band).
std::vector<double> band_residuals(const AlphaBands& bands, const std::vector<double>& q);

/// The RMS of r over the sites of the bands of at least 4 sites (NaN without any).
double band_rms(const AlphaBands& bands, const std::vector<double>& r);

/// The deviation from axisymmetry about the axis through c parallel to x: per band, x and
/// rho = |(y, z) - (c_y, c_z)| fitted linearly in alpha; d_i = (dx, drho) . (n_x, n_rho), the
/// residuals along the normal. rms and max |d| (NaN / 0 without a band); bumps: the sites where d
/// exceeds tau and no triangle neighbour's d is larger.
struct Axisymmetry {
  double rms = NAN, max = NAN;
  int bumps = 0;
};
Axisymmetry axisymmetry(const std::vector<double>& X, const std::vector<double>& normal, const AlphaBands& bands,
                        const std::vector<Triangle>& tris, const std::array<double, 3>& c, double tau);

/// The mean over the triangles' edges of |q_i - q_j| (NaN without triangles).
double edge_jump(const std::vector<double>& q, const std::vector<Triangle>& tris);

/// The sites facing along s x (s = +1 or -1): s n_x > cos 45 degrees and s x > s c_x.
std::vector<std::size_t> facing_sites(const std::vector<double>& X, const std::vector<double>& normal,
                                      const std::array<double, 3>& c, int s);

/// The spread of q over the given sites where it is finite: mean, std, std / |mean| and the fraction
/// with q > 0 (NaN below two such sites).
struct Spread {
  double mean = NAN, std = NAN, cv = NAN, positive = NAN;
  int count = 0;
};
Spread spread(const std::vector<double>& q, const std::vector<std::size_t>& sites);

}  // namespace rbfib::surface
