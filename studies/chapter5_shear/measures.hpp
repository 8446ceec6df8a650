#pragma once
// chapter5_shear's measures (Sec. 5.1.2, Fig. 5.2): a sample of the cell's shape, orientation and
// tracked material point, and their analysis: the short axis beside Jeffery's orbit, rotation
// rates over the second half, the material point's revolution (Fig. 5.2's period), inclination,
// Taylor deformation, volume and the growth of ||f||_inf; each case's rows of the tables (Fig. 5.2's
// angles, the summary, the outlines) and the dt scan's.
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace rbfib::shear {

inline constexpr double deg = 180 / pi;

/// A sample (a row of the run's series): t, the volume at the last step's force positions (0 before
/// a step), the inclination and Taylor deformation of the y-z profile (Fig. 5.2's view: z right, y up),
/// ||f||_inf of the last step, the shape (cells::CellShape: centre, axes, extents), the tracked
/// data site (cm), the last step's dt (s; 0 before a step).
enum Column : std::size_t { kT, kVolume, kInclination, kTaylor, kForce, kCenter, kAxes = 8, kExtent = 17, kMaterial = 20, kDt = 23 };

std::vector<double> sample(const sim::ImmersedBoundary& ib, long material, const sim::IbStepReport* rep);

struct Analysis {
  double aspect = 0;  // thickness / diameter at t = 0 (Jeffery's r)
  // Angles in the view of Fig. 5.2 (counterclockwise from e_z), unwrapped, per sample (rad): the
  // short axis, Jeffery's short axis from the same start, the profile's long axis, the material point.
  std::vector<double> t, strain, axis, jeffery, inclination, material, taylor, force;
  double body_rate = 0, jeffery_rate = 0, material_rate = 0;  // -d(angle)/dt / gdot over the second half
  double volume_change = NAN;     // largest |V - V0| / V0, V0 at the first step (NaN before two steps)
  double force_growth = NAN;      // max ||f|| over the last quarter / max over the second quarter
  double jeffery_period = 0;      // Jeffery's full period 2 pi (r + 1/r) as a strain
  double material_turn = 0;       // how far the material point turned over the window (rad, clockwise positive)
  double period = NAN;            // strain of one full revolution of the material point from the first panel
  double inclination_mean = NAN;  // mean long-axis inclination after the first panel, in (-pi/2, pi/2]
};

/// The analysis of a run's samples at shear rate `rate` (1/s); the period counted from the strain `first_panel`.
Analysis analyse(const std::vector<std::vector<double>>& samples, double rate, double first_panel);

using study::Json;

struct Case {
  std::string id;  // the run's name in results["runs"] and the suffix of its values
  double rate, mu, dt, t_end;  // dt: the fixed step, or with the ladder its lowest rung dt_min
  double first_panel;  // Fig. 5.2's first panel (gdot t)
  int ladder = 0;      // > 0: the seed's adaptive step, dt = 2^k dt for k = 0..ladder by eq. 5.4
};

struct Run {
  Case c;
  study::SceneRun run;              // its samples and series, steps, eq. 5.4's stop
  std::vector<double> snapshot;  // the data sites at t_snapshot (empty when not asked or not reached)
  study::RunProgress progress() const {  // the time reached: steps of the fixed dt (samples are sparser), or the last sample's
    return c.ladder > 0 ? run.progress(c.t_end) : study::RunProgress{run.finished, double(run.steps) * c.dt, c.t_end, run.steps, run.seconds_per_step(), run.stopped};
  }
};

struct Tables {
  Json orientation = study::table({"rate_1_s", "mu_cP", "t_ms", "strain", "axis_deg", "jeffery_axis_deg", "inclination_deg", "material_deg",
                                "taylor_D", "force_density"},
                               {"1/s", "cP", "ms", "", "deg", "deg", "deg", "deg", "", "dyn/cm^3"});
  Json summary = study::table({"rate_1_s", "mu_cP", "capillary", "dt_us", "dt_top_us", "dt_mean_us", "t_end_ms", "steps", "seconds_per_step", "aspect_ratio",
                            "body_rate_over_gdot", "jeffery_rate_over_gdot", "body_over_jeffery", "material_rate_over_gdot", "material_turn_deg",
                            "first_panel_strain", "period_strain", "period_rate_over_gdot", "jeffery_period_strain", "inclination_end_deg",
                            "inclination_mean_deg", "taylor_D_end", "volume_change_rel", "force_growth", "stopped_ms"},
                           {"1/s", "cP", "", "us", "us", "us", "ms", "", "s", "", "", "", "", "", "deg", "", "", "", "", "deg", "deg", "", "", "", "ms"});
  Json outlines = study::table({"rate_1_s", "mu_cP", "t_ms", "z_um", "y_um"}, {"1/s", "cP", "ms", "um", "um"});
};

/// One case's rows (its angles, summary and outlines as in Fig. 5.2) and values.
void tabulate(Json& results, Tables& T, const Run& r, const study::Options& opt);

/// The dt scan at 1000/s, 1 cP; members: the steps above the run's to 3 ms, the run itself (at
/// `own`), half its step to 1 ms. Stable: the window finished (eq. 5.4 did not stop it) and
/// ||f||_inf did not double between its second and last quarters (an instability grows
/// exponentially). Differences at 1 ms between successive steps dt and dt/2: first order in dt.
void dt_scan(Json& results, const std::vector<Run>& members, std::size_t own, double h, double run_dt, double t_diff);

}  // namespace rbfib::shear
