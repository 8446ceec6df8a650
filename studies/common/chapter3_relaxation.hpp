#pragma once
// The Chapter 3 studies' shared part (chapter3_dynamics, chapter3_capillary).
//
// The time update of the paper's Sec. 3.3 on the periodic Stokes solver of Sec. 3.2, for one
// elastic shell relaxing in [-L, L]^3 (the dynamic test of Sec. 4.2), with either force method:
//
//   SHVD: m interpolation sites carry the state. Each step (Sec. 3.3, steps 1-6):
//         1.-2. the spherical-harmonic interpolant of degree M through the m sites (eq. 86, LU
//               factored once) gives the jets at the n evaluation sites and the force density of
//               eq. (35) there, times the area weights dA0 (one force call, cells/batch.hpp);
//         3.    spread from the n evaluation sites (the forces F^ = F dA0, eq. 52);
//         4.    steady Stokes solve (alpha = 0: the exact inverse of the MAC operators);
//         5.    interpolate the velocity at the m interpolation sites;
//         6.    X^{k+1} = X^k + dt U^{k+1} at the m sites (eq. 87).
//   LDSM: the n triangulated evaluation sites carry the state: forces of eq. (66) on the
//         triangles (every energy in one pass), spread from the n sites, Stokes solve, velocity
//         interpolated at the same n sites (the sort of the spreading reused), eq. (87) at the n.
//
// Forces: neo-Hookean (paper eq. 68, Gs, A) plus surface tension (eq. 72, sigma), reference the
// unit sphere. Kernel: Peskin's 4-point function ("peskin4"), the paper's [25] (Sec. 3.3 step 3:
// "a 4 point discrete delta function", Peskin's Acta Numerica review, which is also the paper's
// source for the zero force integral of Sec. 2.4.1). Everything is dimensionless (mu = 1,
// moduli 1, the unit sphere), in the library's CGS slots as plain numbers.
//
// Diagnostics at each recorded time (from the evaluation sites' positions of that step):
//   d_axis  = (x_a - c_x)(t) - (x_a - c_x)(0): the x-displacement relative to the centroid c of
//             the material point (lambda, theta) = (0, 0), the rightmost point of the ellipsoid
//             (d_max of Fig. 5 at t = 3): SHVD evaluates its interpolant there; LDSM takes the site
//             there (the spirals have one) or its flat triangle's point on that ray (MD sets);
//   r_max - 1, r_min - 1: max / min over the evaluation sites of |X_i - c| minus the reference
//             radius 1 (Fig. 4);
//   c: the centroid of the enclosed volume (SHVD: the force call's quadrature; LDSM: the
//      triangulated polyhedron).
#include "rbfib/core/exec.hpp"
#include "rbfib/ib/kernels.hpp"
#include "rbfib/mechanics/energy.hpp"
#include "rbfib/surface/evaluation_sets.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <functional>
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
using surface::rightmost_site;

/// The total energy of Sec. 4.2: neo-Hookean (eq. 68) plus surface tension (eq. 72).
std::vector<mechanics::EnergyDensity> total_energy(double Gs, double A, double sigma);

struct RelaxationSpec {
  Method method = Method::shvd;
  surface::PerturbedEllipsoid shape;  ///< the initial surface (eq. 88 with B = 0, or eq. 89)
  int eta = 32;                       ///< grid cells per side
  double L = 2;                       ///< box [-L, L]^3
  double mu = 1;
  double dt = 1.0 / 64;
  int steps = 0;         ///< steps to take (t_end = steps dt)
  int record_every = 0;  ///< record the diagnostics every so many steps (0: first and last only)
  int M = 7;             ///< SHVD: harmonic degree, m = (M+1)^2 interpolation sites
  double Gs = 1, A = 1, sigma = 1;
  ib::Kernel kernel = ib::Kernel::peskin4;
  /// SHVD: measure d_axis at this evaluation site (e.g. the paper's rightmost site) instead of at
  /// the interpolant's material point (0, 0); -1: the material point.
  index_t measure_site = -1;
};

struct Sample {
  double t, d_axis, r_max, r_min, volume;
};

/// Wall time of the phases of the steps (s, summed over the steps).
struct PhaseTimes {
  double forces = 0, spread = 0, solve = 0, interpolate = 0, update = 0;
  double force_products = 0;  ///< SHVD: the dense products of the force call (part of forces)
  double total() const { return forces + spread + solve + interpolate + update; }
};

struct RelaxationResult {
  std::vector<Sample> series;
  int steps = 0;           ///< steps taken
  bool finished = false;   ///< reached its end (or stopped: failed)
  bool continued = false;  ///< restored from its checkpoint
  bool failed = false;     ///< a NumericalError stopped the run (message in `failure`)
  std::string failure;
  std::string label;           ///< the label of the sitting that began it (e.g. the commit)
  double seconds = 0;          ///< wall time of its steps, over all sittings (s)
  PhaseTimes phases;           ///< summed over the steps
  PhaseTimes median;           ///< per-step medians of each phase
  double force_integral0 = 0;  ///< |sum_i F^_i|_inf at t = 0 (quadrature error, Sec. 4.1)
  double max_force0 = 0;       ///< max_i |F^_i|_inf at t = 0
  std::vector<double> block_ends;  ///< phases.total() at each mark_block() (Table 1's lockstep blocks)
  double d_axis() const { return series.empty() ? NAN : series.back().d_axis; }
};

/// The interpolation sites of SHVD for degree M (maximal-determinant-like, built once per M).
const surface::SphereSites& interpolation_sites(int M);

/// One relaxation on the library's coupled step (steady periodic Stokes, forward Euler) stepped by
/// the library's run loop. Its records (series "samples"), per-step phase times ("phases"), the
/// quantities at t = 0 ("start") and the lockstep block ends ("blocks") are series of the run, so a
/// run kept in a checkpoint continues, or is read back when finished, with all of them.
class Relaxation {
 public:
  /// Builds the fluid, and the SHVD cell type (operators, LU of Y) or the LDSM state. checkpoint:
  /// where the run is kept (restored from there when it holds this run); empty: nowhere. label:
  /// kept with a fresh run (the commit that began it). sitting: the wall seconds advance_all()
  /// may step.
  Relaxation(const RelaxationSpec& spec, const EvaluationSet& eval, const std::string& checkpoint = "",
             const std::string& label = "", double sitting = INFINITY);
  ~Relaxation();
  /// One step (the diagnostics recorded when due). Returns false once the run is over (its end,
  /// or a NumericalError, kept in the result as `failed` / `failure`).
  bool advance();
  /// Steps to the end or the sitting's end; returns whether the run is over.
  bool advance_all();
  /// Appends phases.total() to the block ends (kept with the run).
  void mark_block();
  int step() const;
  RelaxationResult result() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Runs one relaxation to its end (kept in `checkpoint` when one is named; a finished run kept
/// there is read back without a step).
RelaxationResult relax(const RelaxationSpec& spec, const EvaluationSet& eval, const std::string& checkpoint = "",
                       const std::string& label = "", double sitting = INFINITY);

/// Runs several relaxations in lockstep, one step of each in turn, so that a change of load on a
/// shared machine falls on all of them alike (the timing runs of Table 1).
std::vector<RelaxationResult> relax_lockstep(const std::vector<std::pair<RelaxationSpec, const EvaluationSet*>>& runs);

}  // namespace rbfib::chapter3
