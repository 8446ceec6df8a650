#pragma once
// chapter5_collision's measures (Sec. 5.1.3, Fig. 5.3): the runs' series (the gap between the
// cells' sample sites, their approach along d, volumes, max |u|, eq. 5.4's ratio; outlines seen
// from above the plane x = z and each cell's depth over width at the figure's moments) and the
// tables they make.
#include "common/study.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/core/rotation.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/surface/contact.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace rbfib::collision {

using study::Json;
inline const double kBox = 16 * units::um;             // the box, periodic in x and z
inline const Vec3 kLine = {1 / std::sqrt(2.0), 0, 1 / std::sqrt(2.0)};   // d = (e1 + e3)/sqrt 2
inline const Vec3 kView = {1 / std::sqrt(2.0), 0, -1 / std::sqrt(2.0)};  // the normal of the plane x = z
inline const surface::PeriodicBox kPeriodic{{kBox, kBox, kBox}, {true, false, true}};

using Pose = AxisAngle;  // a cell's rotation as the scene takes it
struct Orientation {
  std::string id, what;
  std::array<Pose, 2> pose;
  double t_figure_ms;  // the time of the seed's right-hand panel
};

struct Setup {
  std::string label;    // names its runs (<label>_<orientation>) and their directory
  double h, dt, t_end;  // cm, s, s (dt: the fixed step, or with the ladder its lowest rung)
  double mu;            // P
  int n_data, n_sample;
  int measure_every, checkpoint_every;  // steps (checkpoints: 0 = none, a run that is not resumable)
  int ladder = 0;  // > 0: the seed's adaptive step, dt = 2^k dt for k = 0..ladder by eq. 5.4
};

// ---- Measurements: the run's series, kept in its checkpoint --------------------------------------
// "samples" [step, t, min_gap, separation, volume 1, volume 2, max |u|, eq54_ratio] (CGS), "outlines"
// [t, kind, cell, s, y] (um), "shapes" [t, moment, cell, depth, width_y, width_across] (cm),
// "reference" [V0, A0 of the quadrature].
enum Column { kStep, kT, kGap, kSeparation, kVolume, kMaxVelocity = 6, kEq54 };
inline constexpr int kStart = 0, kMid = 1, kFigure = 2, kEnd = 3;  // moments
inline const char* kKinds[2] = {"section", "silhouette"};
inline const char* kMoments[4] = {"start", "mid", "figure", "end"};

struct Sites {  // the two cells' sample sites (n x 3 each), volumes and volume centroids
  std::array<std::vector<double>, 2> X;
  index_t n = 0;
  cells::CellDiagnostics diag;
};

Sites sites(const sim::ImmersedBoundary& ib);

/// The minimum distance between the cells' sample sites (cell 2 at the periodic image nearest cell 1
/// by their centroids), the centroids' distance along d, the volumes, and the last step's max |u|
/// and dt over eq. 5.4's bound (1 stops the run).
std::vector<double> sample(const sim::ImmersedBoundary& ib, const Sites& at, const sim::IbStepReport& last);

/// The outlines seen from above the plane x = z in s = X.d - 8 sqrt 2 um and y (the sites within
/// h/2 of the plane, and the silhouette in 72 angular bins), and each cell's extents along d, e2
/// and the line of sight (e1 - e3)/sqrt 2 about its centroid.
void record_state(run::SeriesSet& series, double t, const Sites& at, int moment, double h);

/// The series as CSV beside the run (a view: the checkpoint holds them).
void write_csv(const std::string& dir, const run::SeriesSet& series);

/// "done", "eq. 5.4", "stopped" or "running".
std::string status(const run::Progress& p);

struct Outcome {
  run::Progress progress;
  run::SeriesSet series;  // empty: not begun (no sitting has reached it)
};

// ---- Results tables -----------------------------------------------------------------------------
struct Tables {
  Json runs = study::table({"run", "setup", "orientation", "h_um", "mu_cP", "n_sample", "dt_ns", "dt_top_ns", "dt_mean_ns", "status", "steps", "t_us", "t_stop_us", "t_figure_us",
                         "t_stop_over_t_figure", "stopped_by_eq54", "initial_gap_over_h", "min_gap_um", "min_gap_over_h", "t_min_gap_us",
                         "approach_um", "approach_over_h", "max_volume_change_rel", "seconds", "seconds_per_step", "steps_to_go", "hours_to_go"},
                        {"", "", "", "um", "cP", "", "ns", "ns", "ns", "", "", "us", "us", "us", "", "", "", "um", "", "us", "um", "", "", "s", "s", "", "h"});
  Json gap_series = study::table({"setup", "orientation", "h_um", "t_us", "min_gap_um", "gap_over_h", "separation_um", "volume_change_1",
                               "volume_change_2", "max_velocity_mm_s", "eq54_ratio"},
                              {"", "", "um", "us", "um", "", "um", "", "", "mm/s", ""});
  Json outlines = study::table({"setup", "orientation", "h_um", "kind", "t_us", "cell", "s_um", "y_um"}, {"", "", "um", "", "us", "", "um", "um"});
  Json shapes = study::table({"run", "setup", "orientation", "moment", "t_us", "cell", "depth_um", "width_y_um", "width_across_um",
                           "depth_over_width", "depth_over_width_across"},
                          {"", "", "", "", "us", "", "um", "um", "um", "", ""});
  std::vector<Json::Array> fig_rows;  // Fig. 5.3, per orientation; each setup appends its columns
  double ended = 0, peak54 = 0, hours_to_go = 0;
  std::vector<double> per_step;  // s per step at the scale's own resolution
  Json fig53(const std::vector<Setup>& setups) const {
    std::vector<std::string> columns = {"orientation", "panels", "t_figure_ms"}, units = {"", "", "ms"};
    for (const Setup& s : setups) {
      for (const char* c : {"status_", "t_reached_ms_", "t_stop_ms_", "t_stop_over_t_figure_", "depth_over_width_"}) columns.push_back(c + s.label);
      units.insert(units.end(), {"", "ms", "ms", "", ""});
    }
    Json fig = study::table(columns, units);
    for (const Json::Array& r : fig_rows) fig["rows"].push(Json(r));
    return fig;
  }
};

/// One run's rows: its gap series, outlines and shapes, its row of runs and its columns of Fig. 5.3.
void tabulate(Tables& T, Json& results, const Setup& s, const Orientation& o, std::size_t k, const Outcome& r, bool full, bool own);

}  // namespace rbfib::collision
