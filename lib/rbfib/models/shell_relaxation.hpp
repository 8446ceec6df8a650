#pragma once
// Chapter 3's dynamic test (the JCP 2018 paper, Sec. 4.2): one elastic shell relaxing in steady
// Stokes flow on the periodic box [-L, L]^3 with the time update of Sec. 3.3 (the library's
// coupled step with the forward-Euler coupling, eq. 87, over the periodic Stokes solver of Sec.
// 3.2, Peskin's 4-point kernel), stepped by the library's run loop: a setup no scene file
// describes (the studies' bookkeeping is studies/common/chapter3_relaxation.hpp). Forces: neo-Hookean (eq. 68)
// plus surface tension (eq. 72), reference the unit sphere, everything dimensionless (mu = 1,
// moduli 1) in the library's CGS slots as plain numbers. Two force methods:
//   SHVD: the m interpolation sites carry the state; the degree-M interpolant through them (eq.
//         86) gives the force density of eq. (35) at the n evaluation sites, spread from there;
//         the velocity is interpolated at the m sites;
//   LDSM: the n triangulated evaluation sites carry the state, forces of eq. (66).
//
// Diagnostics at each recorded time, from the evaluation sites' positions:
//   d_axis  = (x_a - c_x)(t) - (x_a - c_x)(0), x_a the x coordinate of the point where d_max is
//             read (Point) and c the centroid of the enclosed volume (SHVD: the force call's
//             quadrature; LDSM: the triangulated polyhedron): d_max of Fig. 5 at t = 3;
//   r_max - 1, r_min - 1: the radial extent about c minus the reference radius 1 (Fig. 4).
#include "rbfib/core/error.hpp"
#include "rbfib/ib/kernels.hpp"
#include "rbfib/run/phase_times.hpp"
#include "rbfib/surface/evaluation_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbfib::chapter3 {

enum class Method { shvd, ldsm };
const char* to_string(Method m);

// The evaluation sets of Sec. 4.1 (surface/evaluation_sets.hpp), by their names here.
using surface::EvaluationSet;
using surface::make_evaluation_set;
using surface::make_md_evaluation_set;

/// The interpolation sites of SHVD for degree M (maximal-determinant-like, built once per M).
const surface::SphereSites& interpolation_sites(int M);

/// Where d_max is read.
enum class Point {
  material,   ///< the material point (0, 0): SHVD's interpolant there; LDSM's site there, or the
              ///< point of its flat triangle on the ray of (1, 0, 0)
  rightmost,  ///< the rightmost evaluation site at t = 0 (the paper's reading, Sec. 4.2)
  axis_site,  ///< the set's axis site, read as a site by both methods (on the odd spirals the
              ///< material point itself: the same run as `material`, measured another way)
};

struct RelaxationSpec {
  Method method = Method::shvd;
  surface::PerturbedEllipsoid shape;  ///< the initial surface (eq. 88 with B = 0, or eq. 89)
  std::string shape_name = "ellipsoid";
  int eta = 32;  ///< grid cells per side
  double L = 2;  ///< box [-L, L]^3
  double mu = 1;
  double dt = 1.0 / 64;
  int steps = 0;         ///< steps to take (t_end = steps dt)
  int record_every = 0;  ///< record the diagnostics every so many steps (0: first and last only)
  int M = 7;             ///< SHVD: harmonic degree, m = (M+1)^2 interpolation sites
  double Gs = 1, A = 1, sigma = 1;
  ib::Kernel kernel = ib::Kernel::peskin4;
  index_t n = 0;       ///< evaluation sites: a Bauer spiral of n sites, or
  int md_degree = -1;  ///< the stored MD set of this degree (then n = (N+1)^2)
  Point point = Point::material;
  /// The run's name (its checkpoint's file name); `tag` marks runs of another kind (lockstep).
  std::string label(const std::string& tag = "") const;
};

/// Sec. 4.2's run of `method` from the ellipsoid of eq. (88) (a = 1.2, b = c = 1/sqrt(1.2)) on the
/// grid eta: dt = 1/(2 eta), n = 2 eta^2 + 1 spiral sites (odd: a site at the material point
/// (0, 0)), to time t, degree M, about `records` records (0: first and last only).
RelaxationSpec dynamic_test(Method method, int eta, double t, int M, int records);
inline index_t spiral_sites(int eta) { return index_t(2) * eta * eta + 1; }

struct Sample {
  double t, d_axis, r_max, r_min, volume;
};

using run::PhaseTimes;

struct RelaxationResult {
  std::vector<Sample> series;
  int steps = 0;           ///< steps taken
  bool finished = false;   ///< reached its end (or stopped: failed)
  bool continued = false;  ///< restored from its checkpoint
  bool failed = false;     ///< a NumericalError stopped the run (message in `failure`)
  std::string failure;
  std::string label;                 ///< the label of the sitting that began it (the commit)
  double seconds = 0;                ///< wall time of its steps, over all sittings (s)
  PhaseTimes phases;                 ///< summed over the steps
  PhaseTimes median;                 ///< per-step medians of each phase
  double force_integral0 = NAN;      ///< |sum_i F^_i|_inf at t = 0 (quadrature error, Sec. 4.1)
  double max_force0 = NAN;           ///< max_i |F^_i|_inf at t = 0
  std::vector<double> block_ends;    ///< phases.total() at each mark_block() (lockstep blocks)
  double d_axis() const { return series.empty() ? NAN : series.back().d_axis; }
};

/// One relaxation on the library's run loop. Its records (series "samples"), per-step phase times
/// ("phases"), the quantities at t = 0 ("start") and the lockstep block ends ("blocks") are series
/// of the run, so a run kept in a checkpoint continues, or is read back when finished, with them.
class Relaxation {
 public:
  /// checkpoint: where the run is kept (restored from there when it holds this run); empty:
  /// nowhere. label: kept with a fresh run. sitting: the wall seconds advance_all() may step.
  Relaxation(const RelaxationSpec& spec, const EvaluationSet& eval, const std::string& checkpoint = "",
             const std::string& label = "", double sitting = INFINITY);
  ~Relaxation();
  /// One step; false once the run is over (its end, or a NumericalError kept as `failed`).
  bool advance();
  /// Steps to the end or the sitting's end; returns whether the run is over.
  bool advance_all();
  /// Appends the wall time of the steps so far to the block ends.
  void mark_block();
  int step() const;
  RelaxationResult result() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rbfib::chapter3
