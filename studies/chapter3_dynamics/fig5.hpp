#pragma once
// chapter3_dynamics' Fig. 5 (the JCP 2018 paper, Sec. 4.2): d_max at t = 3 against a grid 1.5 times
// finer, by method, at the material point and at the paper's rightmost site, and the time step's
// and the grid's shares of its error; and what the study's figures share (its scale's parameters,
// Fig. 5's run).
#include "common/chapter3_relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rbfib::chapter3 {

using study::Json;

inline const Method methods[] = {Method::shvd, Method::ldsm};

/// The scale's parameters (see the header); Fig. 5's grids each with a reference 1.5 times finer.
struct Setup {
  bool full;
  std::vector<int> fig5_etas = full ? std::vector<int>{32, 48, 64} : std::vector<int>{16, 24, 32};
  int fig4_eta = 32;
  index_t fig4_n = full ? 8281 : spiral_sites(48);
  double fig4_t = full ? 15 : 4;
};

/// Fig. 5's run: t = 3, m = 64, 12 records, read at `point`; on n spiral sites (default 2 eta^2 +
/// 1) or on the stored MD set of degree N.
inline RelaxationSpec fig5_run(Method m, int eta, Point point = Point::material, index_t n = 0, int N = -1) {
  RelaxationSpec s = dynamic_test(m, eta, 3, 7, 12);
  s.point = point;
  s.md_degree = N;
  if (N >= 0) s.n = index_t(N + 1) * (N + 1);
  if (n > 0) s.n = n;
  return s;
}
inline RelaxationSpec md_run(Method m, int eta, int N, Point point = Point::material) { return fig5_run(m, eta, point, 0, N); }

inline double dmax(const RelaxationResult& r) { return r.failed ? NAN : r.d_axis(); }
inline double err(const RelaxationResult& a, const RelaxationResult& b) { return std::abs(dmax(a) - dmax(b)); }

/// The angle of the rightmost site of a set from the x axis (rad).
inline double rightmost_offset(const surface::SphereSites& sites) {
  const index_t i = surface::rightmost_site(sites);
  return std::acos(std::min(1.0, std::cos(sites.theta[i]) * std::cos(sites.lambda[i])));
}

/// Fig. 5: d_max at t = 3 against a grid 1.5 times finer, by method; with `point` = rightmost each
/// run on its own even spiral of 2 eta^2 sites (Sec. 4.2's "rightmost point"). Orders into V.
void fig5(const Setup& S, Relaxations& runs, Point point, Json& T, Json& V);

/// SHVD read at the odd spiral's site (0, 0) against its interpolant at the material point (0, 0):
/// the same run, measured two ways. Full scale: the paper's own sets of eta = 32 and of its
/// reference (MD, n = 2025 and 4624), read at their rightmost sites.
void rightmost_extras(const Setup& S, Relaxations& runs, Json& T, Json& V);

/// The time step's and the grid's shares of the Fig. 5 error on its coarsest grid: d_max with dt,
/// dt/2, dt/4 (forward Euler, eq. 87, is first order in dt; 2 |d(dt) - d(dt/2)| estimates the time
/// error); and the grids eta, 1.5 eta, 2.25 eta with the finest one's dt (the spatial error alone).
void time_and_space(const Setup& S, Relaxations& runs, Json& T, Json& V);

}  // namespace rbfib::chapter3
