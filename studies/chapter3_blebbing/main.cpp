// Chapter 3 cellular blebbing (the JCP 2018 paper, Sec. 5.2, eqs. 96-104, Table 2, Figs. 11-15): a
// cell whose membrane (surface tension and neo-Hookean, SHVD or LDSM) is tied by adhesion springs
// to a cortex in tension; after equilibration the links in the cap phi <= 2 pi / 25 are removed
// and the membrane bulges there. The model: rbfib/models/blebbing.hpp.
//
// Reproduces (and measures what the paper only shows):
//   Fig. 11  sections of the membrane by the plane x = 15 um at several times, LDSM and SHVD with
//            the middle m;
//   Fig. 12  the bleb ring, its diameter, and the bleb size (the top above the ring's centre, less
//            its value at the bleb's start);
//   Fig. 13  bleb size against time for LDSM and SHVD with three m (the paper: 625, 1,024, 4,761);
//   Fig. 14  the volume change (V(t) - V(0)) / V(0) in percent for the same runs;
//   Fig. 15  the mean curvature after expansion against the polar angle from the bleb's axis (SHVD:
//            the interpolant's; LDSM: from the edges, signed by the convex hull, as the paper does);
//   also     the boundary speed at the end of equilibration (the paper: about 0.01 um/s after
//            0.2 s), the time per step and to solution of each run beside the paper's 10 h (SHVD)
//            against 1 h (LDSM);
//   and      the equilibration's decay with every link attached, on our sites and on a Bauer spiral
//            of the paper's n, to the time the membrane's speed reaches the paper's 0.01 um/s.
//
// Scales. Full: the paper's box (30 um, eta = 32), n = 4,624 sites (the stored maximal-determinant
// set of degree 67; the paper's 4,761 is degree 68, not stored), m = 625, 1,024, 4,624, 0.2 s of
// equilibration and 15 s of bleb. Quick (CI): eta = 16, n = 529 (degree 22), m = 64, 121, 529
// (about the paper's ratios m / n), 0.1 s and 1 s. The m = n runs need sites that determine an
// interpolant of degree (sqrt(n) - 1): a Bauer spiral does not (reciprocal condition 1e-18 at
// n = 1,089), a maximal-determinant set does. At full scale each run keeps a checkpoint
// DIR/run_<label>.h5 and continues from it when the command is run again; --sitting SECONDS bounds
// a sitting.
//
// Run:  build/studies/study_chapter3_blebbing --scale quick --out runs/chapter3_blebbing/quick
//       (or python3 -m harness run chapter3_blebbing --scale quick)
#include "common/study.hpp"
#include "measures.hpp"
#include "rbfib/models/blebbing.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

using namespace rbfib;
using namespace rbfib::blebbing;
namespace st = rbfib::study;
using st::number;
using st::row;

namespace {

struct Case {
  std::string label;  ///< "LDSM", "SHVD_m625", ...
  chapter3::Method method;
  int M;  ///< SHVD degree (m = (M+1)^2)
};

/// The scale's runs: LDSM and SHVD with m about 13% and 21% of n (the paper's 625 and 1,024 of
/// 4,761; full scale: the paper's 625 and 1,024) and m = n.
std::vector<Case> cases(bool full) {
  const std::vector<int> M = full ? std::vector<int>{24, 31, 67} : std::vector<int>{7, 10, 22};
  std::vector<Case> c{{"LDSM", chapter3::Method::ldsm, 0}};
  for (int d : M) c.push_back({"SHVD_m" + to_text((d + 1) * (d + 1)), chapter3::Method::shvd, d});
  return c;
}

Model scale_model(bool full) {
  Model m;
  m.eta = full ? 32 : 16;
  m.dt = 2e-4;  // half the largest step the scan finds stable at both scales (4e-4 s; 8e-4 s inverts a triangle)
  m.t_equilibrate = full ? 0.2 : 0.1;
  m.t_bleb = full ? 15 : 1;
  m.record_every = full ? 250 : 50;     // every 0.05 s, 0.01 s
  m.view_every = full ? 5000 : 1250;    // every 1 s, 0.25 s
  return m;
}

/// What one run gives the checks.
struct Outcome {
  std::string label;
  double size_end = NAN, volume_change_end = NAN, speed_equilibrated = NAN, speed_rms_equilibrated = NAN, seconds = NAN, per_step = NAN;
};

class Runs {
 public:
  Runs(const st::Options& opt, st::Json& results, const Model& base, const chapter3::EvaluationSet& eval)
      : opt_(opt), sitting_(opt), results_(results), base_(base), eval_(eval) {
    runs = st::table({"run", "method", "m", "n", "dt", "status", "steps_done", "steps_needed", "seconds", "seconds_per_step",
                      "time_to_solution_h", "bleb_size_end_um", "volume_change_end_percent", "boundary_speed_equilibrated_um_s",
                      "ring_diameter_um"},
                     {"", "", "", "", "s", "", "", "", "s", "s", "h", "um", "%", "um/s", "um"});
    series = st::table({"run", "t", "bleb_size_um", "volume_change_percent", "boundary_speed_um_s", "cortex_radius_um",
                        "link_max_um"},
                       {"", "s", "um", "%", "um/s", "um", "um"});
    equilibration = st::table({"run", "t", "boundary_speed_max_um_s", "boundary_speed_rms_um_s", "volume_change_percent",
                               "cortex_radius_um", "link_max_um"},
                              {"", "s", "um/s", "um/s", "%", "um", "um"});
    sections = st::table({"run", "t", "label", "y_um", "z_um"}, {"", "s", "", "um", "um"});
    curvature = st::table({"run", "angle_deg", "H_mean_per_um", "H_min_per_um", "H_max_per_um"}, {"", "deg", "1/um", "1/um", "1/um"});
  }

  Outcome run(const Case& c, bool section) {
    Model m = base_;
    m.method = c.method;
    m.M = c.M;
    const std::string path = opt_.out_dir + "/run_" + c.label + ".h5";
    Run r(m, eval_, opt_.keeps_runs() ? path : std::string(), std::max(0.0, sitting_.remaining()),
          [&](const std::string& line) { st::log(opt_, c.label + ": " + line); });
    if (r.continued()) st::log(opt_, c.label + ": resumed from " + path + " at step " + to_text(r.step()));
    r.advance();
    st::RunProgress p{r.done(), r.step() * m.dt, m.steps() * m.dt, r.step(), r.seconds_per_step(), r.failure()};
    st::record_run(results_, c.label, p);
    Outcome o;
    o.label = c.label;
    const std::vector<Sample>& s = r.series();
    const Sample* start = nullptr;  // the record at the bleb's start
    for (const Sample& q : s)
      if (!start && q.t >= m.t_equilibrate - 1e-9) start = &q;
    for (const Sample& q : s)
      if (q.t <= m.t_equilibrate + 1e-9 && q.t > 0)
        equilibration["rows"].push(row({c.label, q.t, q.boundary_speed / um, q.boundary_speed_rms / um,
                                        100 * (q.volume / s.front().volume - 1), q.cortex_radius / um, q.link_max / um}));
    if (start) {
      o.speed_equilibrated = start->boundary_speed / um;
      o.speed_rms_equilibrated = start->boundary_speed_rms / um;
      for (const Sample& q : s) {
        if (q.t < m.t_equilibrate - 1e-9) continue;
        const double t = q.t - m.t_equilibrate;
        o.size_end = (q.bleb_size - start->bleb_size) / um;
        o.volume_change_end = 100 * (q.volume / s.front().volume - 1);
        series["rows"].push(row({c.label, t, o.size_end, o.volume_change_end, q.boundary_speed / um, q.cortex_radius / um,
                                 q.link_max / um}));
      }
    }
    if (!r.done() || !r.failure().empty()) o.size_end = o.volume_change_end = NAN;
    o.seconds = r.seconds();
    o.per_step = r.seconds_per_step();
    const std::string status = !r.done() ? (r.step() > 0 ? "partial" : "not started")
                                         : (r.failure().empty() ? "finished" : "stopped: " + r.failure());
    const double ring = s.empty() ? NAN : s.back().ring_diameter / um;
    runs["rows"].push(row({c.label, chapter3::to_string(c.method), c.method == chapter3::Method::shvd ? double((c.M + 1) * (c.M + 1)) : NAN,
                           double(eval_.size()), m.dt, status, double(r.step()), double(m.steps()), o.seconds, number(o.per_step),
                           number(o.per_step * double(m.steps()) / 3600), number(o.size_end), number(o.volume_change_end),
                           number(o.speed_equilibrated), number(ring)}));
    st::log(opt_, c.label + ": " + status + ", bleb size " + to_text(o.size_end) + " um, volume change " +
                      to_text(o.volume_change_end) + " %, " + to_text(o.per_step) + " s per step");
    views(c, r, section);
    return o;
  }

  /// The step scan: LDSM over equilibration and `window` s of bleb at step dt; a row of `scan`.
  void scan(double dt, double window) {
    Model m = base_;
    m.method = chapter3::Method::ldsm;
    m.dt = dt;
    m.t_equilibrate = std::round(base_.t_equilibrate / dt) * dt;
    m.t_bleb = window;
    m.record_every = std::max(1, int(std::lround(window / dt)));
    m.view_every = int(m.steps());
    std::ostringstream label;
    label << "scan_LDSM_dt" << dt;
    Run r(m, eval_, opt_.keeps_runs() ? opt_.out_dir + "/run_" + label.str() + ".h5" : std::string(),
          std::max(0.0, sitting_.remaining()));
    r.advance();
    st::RunProgress p{r.done(), r.step() * m.dt, m.steps() * m.dt, r.step(), r.seconds_per_step(), r.failure()};
    st::record_run(results_, label.str(), p);
    const bool ok = r.done() && r.failure().empty() && r.series().size() >= 2;
    const Sample* start = nullptr;
    for (const Sample& q : r.series())
      if (!start && q.t >= m.t_equilibrate - 1e-9) start = &q;
    const Sample& end = r.series().back();
    const std::string status = !r.done() ? "partial" : (r.failure().empty() ? "finished" : "stopped: " + r.failure());
    scan_rows["rows"].push(row({label.str(), dt, status, double(r.step()), double(m.steps()),
                                ok && start ? number((end.bleb_size - start->bleb_size) / um) : st::Json(),
                                ok ? number(100 * (end.volume / r.series().front().volume - 1)) : st::Json(),
                                ok && start ? number(start->boundary_speed / um) : st::Json(), ok ? number(end.link_max / um) : st::Json(),
                                number(r.seconds_per_step())}));
    scanned_.push_back({dt, ok && start ? (end.bleb_size - start->bleb_size) / um : NAN});
    st::log(opt_, label.str() + ": " + status);
  }

  /// The equilibration's decay: LDSM with every link attached for `T` s on the sites `sites`
  /// (labelled `family`), the membrane speed (largest and RMS over the sites) every 0.05 s; rows of
  /// `decay_rows`. Returns the first times the largest and the RMS speed reach `target` (cm/s; NaN:
  /// not within T or the run unfinished).
  std::pair<double, double> decay(const std::string& family, const chapter3::EvaluationSet& sites, double T, double target) {
    Model m = base_;
    m.method = chapter3::Method::ldsm;
    m.t_equilibrate = T;
    m.t_bleb = 0;  // no links are removed within the run
    m.record_every = std::max(1, int(std::lround(0.05 / m.dt)));
    m.view_every = int(m.steps());
    const std::string label = "decay_LDSM_" + family;
    Run r(m, sites, opt_.keeps_runs() ? opt_.out_dir + "/run_" + label + ".h5" : std::string(), std::max(0.0, sitting_.remaining()),
          [&](const std::string& line) { st::log(opt_, label + ": " + line); });
    r.advance();
    st::RunProgress p{r.done(), r.step() * m.dt, m.steps() * m.dt, r.step(), r.seconds_per_step(), r.failure()};
    st::record_run(results_, label, p);
    double t_max = NAN, t_rms = NAN;
    for (const Sample& q : r.series()) {
      if (q.t <= 0 || q.t > T + 1e-9) continue;
      decay_rows["rows"].push(row({label, double(sites.size()), q.t, q.boundary_speed / um, q.boundary_speed_rms / um}));
      if (std::isnan(t_max) && q.boundary_speed <= target) t_max = q.t;
      if (std::isnan(t_rms) && q.boundary_speed_rms <= target) t_rms = q.t;
    }
    if (!r.done() || !r.failure().empty()) t_max = t_rms = NAN;
    st::log(opt_, label + ": " + (r.done() ? (r.failure().empty() ? "finished" : "stopped: " + r.failure()) : "partial") +
                      ", largest speed at or below " + to_text(target / um) + " um/s from t = " + to_text(t_max) + " s");
    return {t_max, t_rms};
  }

  /// The cost of a step in the same conditions: each case runs `steps` steps from the start,
  /// without a checkpoint, in turn with the others, `repeats` times in this process (same threads,
  /// same load); rows of `timed_rows`. Returns each case's median seconds per step. A run's own
  /// seconds per step (table runs) average its sittings, which may have run on other thread counts
  /// or beside other work; this is the number to compare methods by.
  std::vector<double> timed(const std::vector<Case>& which, int steps, int repeats) {
    std::vector<std::vector<double>> per(which.size());
    for (int k = 0; k < repeats; ++k)
      for (std::size_t i = 0; i < which.size(); ++i) {
        Model m = base_;
        m.method = which[i].method;
        m.M = which[i].M;
        m.t_equilibrate = steps * m.dt;
        m.t_bleb = 0;
        m.record_every = m.view_every = steps;
        Run r(m, eval_);
        r.advance();
        if (!r.done() || !r.failure().empty())
          throw std::runtime_error("timed segment of " + which[i].label + " did not finish: " + r.failure());
        per[i].push_back(r.seconds_per_step());
      }
    std::vector<double> out;
    for (std::size_t i = 0; i < which.size(); ++i) {
      const auto [lo, hi] = std::minmax_element(per[i].begin(), per[i].end());
      out.push_back(st::median(per[i]));
      timed_rows["rows"].push(row({which[i].label, double(steps), double(repeats), number(out.back()), number(*lo), number(*hi)}));
      st::log(opt_, "timed segment " + which[i].label + ": " + to_text(out.back()) + " s per step (median of " +
                        to_text(repeats) + " x " + to_text(steps) + " steps)");
    }
    return out;
  }

  /// The largest step of the scan that finished with the bleb size within 1% of the smallest
  /// step's (NaN before the scan has finished).
  double largest_stable_dt() const {
    double best = NAN;
    for (const auto& [dt, size] : scanned_)
      if (std::isfinite(size) && std::abs(size / scanned_.front().second - 1) <= 0.01) best = dt;
    return best;
  }

  st::Json runs, series, equilibration, sections, curvature;
  st::Json timed_rows = st::table({"run", "steps", "repeats", "seconds_per_step_median", "seconds_per_step_min", "seconds_per_step_max"},
                                  {"", "", "", "s", "s", "s"});
  st::Json decay_rows = st::table({"run", "n", "t", "boundary_speed_max_um_s", "boundary_speed_rms_um_s"}, {"", "", "s", "um/s", "um/s"});
  st::Json scan_rows = st::table({"run", "dt", "status", "steps_done", "steps_needed", "bleb_size_um", "volume_change_percent",
                                  "boundary_speed_equilibrated_um_s", "link_max_um", "seconds_per_step"},
                                 {"", "s", "", "", "", "um", "%", "um/s", "um", "s"});

 private:
  /// Fig. 11's sections (LDSM and the middle m) at the kept times from the bleb's start, and Fig.
  /// 15's curvature bands at the last kept time of a finished run (LDSM: from the edges, signed by
  /// the convex hull).
  void views(const Case& c, const Run& r, bool section) {
    const Model& m = r.model();
    for (const View& v : r.views()) {
      if (!section || v.t < m.t_equilibrate - 1e-9) continue;
      const double t = v.t - m.t_equilibrate;
      std::ostringstream label;
      label << c.label << " t = " << std::round(t * 100) / 100 << " s";
      for (const auto& yz : section_x(v.X, eval_.tris, m.center[0]))
        sections["rows"].push(row({c.label, t, label.str(), yz[0] / um, yz[1] / um}));
    }
    if (!r.done() || r.views().empty()) return;
    const View& v = r.views().back();
    const bool ldsm = c.method == chapter3::Method::ldsm;
    for (const CurvatureBand& b : curvature_by_angle(v.X, ldsm ? ldsm_signed_curvature(v.X, eval_.tris) : v.H, m.center, 36))
      curvature["rows"].push(row({c.label, b.angle_deg, number(b.mean * um), number(b.min * um), number(b.max * um)}));
  }

  const st::Options& opt_;
  const st::Sitting sitting_;
  st::Json& results_;
  Model base_;
  const chapter3::EvaluationSet& eval_;
  std::vector<std::pair<double, double>> scanned_;  // the step scan: dt and bleb size (um; NaN: stopped)
};

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_blebbing", [&] {
    // ---- 1. Parameters ---------------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(argc, argv, "chapter3_blebbing",
                                                   "Chapter 3 Sec. 5.2: a bleb, SHVD against LDSM (Figs. 11-15)");
    const bool full = opt.scale == st::Scale::full;
    const int N = full ? 67 : 22;  // the stored maximal-determinant sets: n = (N+1)^2
    const index_t n = index_t(N + 1) * (N + 1);
    const Model base = scale_model(full);
    st::Json results = st::make_results(opt);
    st::Json& P = results["parameters"];
    P["units"] = "tables in um, s, pN; computed in CGS (1 pN/um = 1e-3 dyn/cm, 1 Pa s = 10 P)";
    P["box_um"] = base.box / um;
    P["eta"] = base.eta;
    P["h_um"] = base.h() / um;
    P["mu_Pa_s"] = base.mu / 10;
    P["membrane"] = "sphere r = 10 um: surface tension 40 pN/um (eq. 72) + neo-Hookean K = G_S = 40 pN/um (eq. 71)";
    P["cortex"] = "sphere r = 9.99 um, lattice of eqs. (99)-(100) with k = 87 pN/um, drag xi = 10 pN s/um^3 (eq. 104)";
    P["adhesion_pN_per_um3"] = base.k_adh / (pN / (um * um * um));
    P["bleb_region"] = "links removed where the polar angle phi <= 2 pi / 25";
    P["n_sites"] = double(n);
    P["sites"] = "the stored maximal-determinant set of degree " + to_text(N) + " with the weights of eq. (45); interpolation "
                 "sites: maximal-determinant-like (M+1)^2, or the n sites themselves when m = n";
    P["dt_s"] = base.dt;
    P["t_equilibrate_s"] = base.t_equilibrate;
    P["t_bleb_s"] = base.t_bleb;
    P["kernel"] = "peskin4";
    const chapter3::EvaluationSet eval = chapter3::make_md_evaluation_set(
        st::source_path(opt, "reference/point_sets/max_determinant_N" + to_text(N) + ".txt"), N);
    st::log(opt, "sites n = " + to_text(n) + " in " + to_text(eval.seconds) + " s");

    // ---- 2. The step (the paper does not state it): LDSM over equilibration and 0.1 s of bleb at
    // doubling steps; stable: no numerical stop, and the bleb size within 1% of the smallest step's.
    Runs runs(opt, results, base, eval);
    for (double dt : {1e-4, 2e-4, 4e-4, 8e-4, 1.6e-3}) runs.scan(dt, 0.1);

    // ---- 2b. The equilibration's decay (the paper: about 0.01 um/s after 0.2 s): LDSM with every
    // link attached, on our sites and on a Bauer spiral of the paper's n (full: 4,761), to the time
    // the membrane's speed reaches 0.01 um/s.
    const double T_decay = full ? 2.0 : 0.5, target = 0.01 * um;
    const index_t n_spiral = full ? 4761 : n;
    const chapter3::EvaluationSet spiral = chapter3::make_evaluation_set(n_spiral);
    const auto [md_max, md_rms] = runs.decay("MD" + to_text(n), eval, T_decay, target);
    const auto [sp_max, sp_rms] = runs.decay("spiral" + to_text(n_spiral), spiral, T_decay, target);

    // ---- 3. The runs ------------------------------------------------------------------------------
    std::vector<Case> all = cases(full);
    std::vector<Outcome> out;
    for (std::size_t i = 0; i < all.size(); ++i) out.push_back(runs.run(all[i], i == 0 || i == 2));

    // ---- 4. Values for the checks (Figs. 13-14, the cost) -----------------------------------------
    st::Json& V = results["values"];
    const Outcome &ldsm = out[0], &low = out[1], &mid = out[2], &all_m = out[3];
    V["bleb_size_ldsm_um"] = number(ldsm.size_end);
    V["bleb_size_m_low_um"] = number(low.size_end);
    V["bleb_size_m_mid_um"] = number(mid.size_end);
    V["bleb_size_m_n_um"] = number(all_m.size_end);
    V["bleb_size_m_mid_minus_low_um"] = number(mid.size_end - low.size_end);
    V["bleb_size_m_n_minus_mid_um"] = number(all_m.size_end - mid.size_end);
    V["volume_change_m_low_percent"] = number(low.volume_change_end);
    double spread = 0;
    for (const Outcome* o : {&ldsm, &mid, &all_m})
      for (const Outcome* q : {&ldsm, &mid, &all_m}) spread = std::max(spread, std::abs(o->volume_change_end - q->volume_change_end));
    V["volume_change_spread_ldsm_mid_n_percent"] = number(spread);
    double gap = INFINITY;  // the smallest distance of the low m's volume change from the other three
    for (const Outcome* o : {&ldsm, &mid, &all_m}) gap = std::min(gap, std::abs(low.volume_change_end - o->volume_change_end));
    V["volume_change_spread_over_gap_to_m_low"] = number(spread / gap);
    V["boundary_speed_equilibrated_ldsm_um_s"] = number(ldsm.speed_equilibrated);
    V["boundary_speed_rms_equilibrated_ldsm_um_s"] = number(ldsm.speed_rms_equilibrated);
    V["equilibration_time_to_0p01_um_s_md_s"] = number(md_max);
    V["equilibration_time_to_0p01_um_s_md_rms_s"] = number(md_rms);
    V["equilibration_time_to_0p01_um_s_spiral_s"] = number(sp_max);
    V["equilibration_time_to_0p01_um_s_spiral_rms_s"] = number(sp_rms);
    // The cost ratio from a timed segment of both methods in the same conditions (the runs' own
    // averages mix sittings on different thread counts and loads; both are in the tables).
    const std::vector<double> timed = runs.timed({all.front(), all.back()}, full ? 100 : 20, 3);
    V["cost_ratio_shvd_m_n_over_ldsm"] = number(timed[1] / timed[0]);
    V["cost_ratio_run_averages_shvd_m_n_over_ldsm"] = number(all_m.per_step / ldsm.per_step);
    V["dt_largest_stable_s"] = number(runs.largest_stable_dt());
    V["cost_ratio_paper"] = 10.0;  // Sec. 6: about 10 hours with SHVD against about 1 hour with LDSM
    // Speed against error: each run's time to solution against its distance from SHVD with m = n
    // (the best resolved: every site carried by the flow) in bleb size and volume change.
    st::Json cost = st::table({"run", "seconds_per_step", "time_to_solution_h", "bleb_size_difference_um", "volume_change_difference_percent"},
                              {"", "s", "h", "um", "%"});
    for (const Outcome& o : out)
      cost["rows"].push(row({o.label, number(o.per_step), number(o.per_step * double(base.steps()) / 3600),
                             number(std::abs(o.size_end - all_m.size_end)), number(std::abs(o.volume_change_end - all_m.volume_change_end))}));

    // ---- 5. Tables and results --------------------------------------------------------------------
    st::Json& T = results["tables"];
    T["runs"] = runs.runs;
    T["series"] = runs.series;
    T["equilibration"] = runs.equilibration;
    T["sections"] = runs.sections;
    T["curvature"] = runs.curvature;
    T["cost"] = cost;
    T["cost_same_conditions"] = runs.timed_rows;
    T["dt_scan"] = runs.scan_rows;
    T["equilibration_decay"] = runs.decay_rows;
    st::write_results(opt, results);
    return 0;
  });
}
