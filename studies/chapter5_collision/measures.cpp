#include "measures.hpp"

#include "rbfib/cells/measure.hpp"

#include <algorithm>
#include <fstream>

namespace rbfib::collision {

using study::row;

Sites sites(const sim::ImmersedBoundary& ib) {
  cells::CellGeometry g;
  cells::measure(ib.batch(0), g);
  const std::vector<double> P = g.positions.to_host();
  const index_t n = ib.batch(0).type().n_sample();
  return {{cells::cell_points(P, n, 2, 0), cells::cell_points(P, n, 2, 1)}, n, g.cells};
}

std::vector<double> sample(const sim::ImmersedBoundary& ib, const Sites& at, const sim::IbStepReport& last) {
  const auto& c = at.diag.centroid;
  auto wrap = [](double d) { return d - kBox * std::round(d / kBox); };
  return {double(ib.step_count()), ib.time(),
          surface::closest_points(at.X[0], at.n, at.X[1], at.n, surface::nearest_image_shift(c[0], c[1], kPeriodic)).distance,
          wrap(c[1][0] - c[0][0]) * kLine[0] + wrap(c[1][2] - c[0][2]) * kLine[2], at.diag.volume[0], at.diag.volume[1],
          last.max_velocity, last.dt_bound > 0 && std::isfinite(last.dt_bound) ? last.dt / last.dt_bound : 0};
}

void record_state(run::SeriesSet& series, double t, const Sites& at, int moment, double h) {
  for (int c = 0; c < 2; ++c) {
    const cells::Outline o = cells::outline(at.X[c], at.n, kLine, {0, 1, 0}, kView, {kBox / 2 * std::sqrt(2.0), 0}, 0, h / 2);
    for (int kind = 0; kind < 2; ++kind)
      for (const auto& q : kind == 0 ? o.section : o.silhouette)
        series["outlines"].rows.push_back({t, double(kind), c + 1.0, q[0] / units::um, q[1] / units::um});
  }
  for (int c = 0; c < 2; ++c) {
    const std::vector<double> e = cells::extents(at.X[c], at.n, at.diag.centroid[c], {kLine, {0, 1, 0}, kView}, kPeriodic);
    series["shapes"].rows.push_back({t, double(moment), c + 1.0, e[0], e[1], e[2]});
  }
}

void write_csv(const std::string& dir, const run::SeriesSet& series) {
  auto write = [&](const char* file, const char* name, const char* header, int precision, const char* const* names) {
    std::ofstream f(dir + "/" + file);
    f.precision(precision);
    f << header << "\n";
    if (series.count(name))
      for (const std::vector<double>& r : series.at(name).rows)
        for (std::size_t k = 0; k < r.size(); ++k) {
          if (k == 1 && names) f << names[int(r[k])];
          else f << r[k];
          f << (k + 1 < r.size() ? "," : "\n");
        }
  };
  write("series.csv", "samples", "step,t_s,min_gap_cm,separation_cm,volume0_cm3,volume1_cm3,max_velocity_cm_s,eq54_ratio", 17, nullptr);
  write("outlines.csv", "outlines", "t_s,kind,cell,s_um,y_um", 10, kKinds);
  write("shapes.csv", "shapes", "t_s,moment,cell,depth_cm,width_y_cm,width_across_cm", 17, kMoments);
}

std::string status(const run::Progress& p) {
  if (p.status == run::RunStatus::finished) return "done";
  if (p.status == run::RunStatus::stopped) return *p.stop_cause == Cause::stopping_condition ? "eq. 5.4" : "stopped";
  return "running";
}

void tabulate(Tables& T, Json& results, const Setup& s, const Orientation& o, std::size_t k, const Outcome& r, bool full, bool own) {
  const std::string id = s.label + "_" + o.id;
  const double h_um = s.h / units::um, t_figure = o.t_figure_ms * units::ms;
  if (r.series.empty()) {  // not begun: nothing measured
    Json::Array cols{Json(id), Json(s.label), Json(o.id), Json(h_um), Json(s.mu / units::cP), Json(s.n_sample), Json(s.dt / units::ns),
                     Json(s.dt * double(1 << s.ladder) / units::ns), Json(), Json("not begun")};
    cols.resize(27);
    T.runs["rows"].push(Json(cols));
    T.fig_rows[k].insert(T.fig_rows[k].end(), {Json("not begun"), Json(), Json(), Json(), Json()});
    study::record_run(results, id, study::RunProgress{false, 0, s.t_end, 0, NAN, ""});
    return;
  }
  const std::vector<std::vector<double>>& samples = r.series.at("samples").rows;
  const double v0 = r.series.at("reference").rows.back().at(0);
  double gmin = 1e300, tmin = 0, vmax = 0, closest = samples.front()[kSeparation];
  for (const std::vector<double>& m : samples) {
    if (m[kGap] < gmin) gmin = m[kGap], tmin = m[kT];
    T.peak54 = std::max(T.peak54, m[kEq54]);
    for (int c = 0; c < 2; ++c) vmax = std::max(vmax, std::abs(m[kVolume + c] - v0) / v0);
    closest = std::min(closest, std::abs(m[kSeparation]));  // before any sliding past
    T.gap_series["rows"].push(row({s.label, o.id, h_um, m[kT] / units::us, m[kGap] / units::um, m[kGap] / s.h, m[kSeparation] / units::um,
                                   (m[kVolume] - v0) / v0, (m[kVolume + 1] - v0) / v0, m[kMaxVelocity] / units::mm,
                                   m[kStep] > 0 ? Json(m[kEq54]) : Json()}));
  }
  for (const std::vector<double>& q : r.series.at("outlines").rows)
    T.outlines["rows"].push(row({s.label, o.id, h_um, kKinds[int(q[1])], std::round(q[0] / units::ns) / 1e3, q[2], q[3], q[4]}));
  bool at_figure = false;  // full scale: a run that ended before the figure's time has no shapes there
  double figure_ratio = 0;
  for (const std::vector<double>& c : r.series.at("shapes").rows) {
    at_figure = at_figure || c[1] == kFigure;
    if (c[1] == kFigure) figure_ratio += c[3] / c[4] / 2;
    T.shapes["rows"].push(row({id, s.label, o.id, kMoments[int(c[1])], c[0] / units::us, c[2], c[3] / units::um, c[4] / units::um,
                               c[5] / units::um, c[3] / c[4], c[3] / c[5]}));
  }
  const run::Progress& q = r.progress;
  if (full && q.ended() && !at_figure)
    for (int c = 1; c <= 2; ++c) T.shapes["rows"].push(row({id, s.label, o.id, "figure", t_figure / units::us, c, Json(), Json(), Json(), Json(), Json()}));
  const std::string how = status(q);
  const bool stopped = q.status == run::RunStatus::stopped;
  const long steps = q.clock.step;
  const double t = q.clock.t, approach = samples.front()[kSeparation] - closest;
  // The time per step: this sitting's if it stepped, else every sitting's.
  const double sps = q.sitting_steps > 0 ? q.sitting_seconds / q.sitting_steps : (steps > 0 ? q.wall_seconds / steps : NAN);
  const double mean_dt = steps > 0 ? t / double(steps) : s.dt;  // the ladder's mean step so far
  const long to_go = q.ended() ? 0 : std::lround((s.t_end - t) / mean_dt);
  const double hours = to_go * sps / 3600;
  T.hours_to_go += std::isfinite(hours) ? hours : 0;
  if (std::isfinite(sps) && own) T.per_step.push_back(sps);
  const Json ratio = stopped ? Json(t / t_figure) : Json();
  T.runs["rows"].push(row({id, s.label, o.id, h_um, s.mu / units::cP, s.n_sample, s.dt / units::ns, s.dt * double(1 << s.ladder) / units::ns,
                           steps > 0 ? Json(mean_dt / units::ns) : Json(), how, double(steps), t / units::us,
                           stopped ? Json(t / units::us) : Json(), t_figure / units::us, ratio, q.ended() ? Json(how == "eq. 5.4" ? 1.0 : 0.0) : Json(),
                           samples.front()[kGap] / s.h, gmin / units::um, gmin / s.h, tmin / units::us, approach / units::um, approach / s.h, vmax,
                           q.wall_seconds, sps, double(to_go), hours}));
  T.fig_rows[k].insert(T.fig_rows[k].end(), {Json(how), Json(t / units::ms), stopped ? Json(t / units::ms) : Json(), ratio,
                                             at_figure ? Json(figure_ratio) : Json()});
  T.ended += q.ended();
  if (!q.stop_message.empty()) results["parameters"]["stop_" + id] = q.stop_message;
  study::record_run(results, id, study::RunProgress{q.ended(), t, s.t_end, steps, sps, q.stop_message});
}

}  // namespace rbfib::collision
