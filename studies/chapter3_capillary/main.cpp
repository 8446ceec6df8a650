// Chapter 3 capillary flow (the JCP 2018 paper, Sec. 5.1, Figs. 6-9): a red cell (eq. 92) carried
// through a tethered capillary (eqs. 93-95) by a background force, in steady Stokes flow on a
// periodic 24 um box, forces by SHVD (m = 400 and 625 interpolation sites, n evaluation sites) or
// LDSM; bending k_bend = 0, 0.1, 1 pN um (eq. 79). The model and the time update: common/capillary.hpp;
// the empty capillary's peak speed against Poiseuille on three grids: chapter3_capillary_flow.
//
// Reproduces (and measures what the paper only shows):
//   Fig. 6   side views of the cell at several times: LDSM, SHVD m = 625 and m = 400 (k_bend = 0);
//   Fig. 7   |force density| on the front, side and back at t = 0.05 s, LDSM and SHVD m = 400;
//   Fig. 8   H seen from the front for k_bend = 0, 0.1, 1 (SHVD m = 400), and the variability of H
//            on the front (its spread std(H), std/|mean|, the fraction with H > 0);
//   Fig. 9   cross-sections y = 0 at t = 0.005, 0.025, 0.05 s for the three k_bend;
//   also     the cell's steady velocity (against the empty capillary's peak on the same grid), the
//            area change (paper: below 1% with A = 50), the non-axisymmetric deviation of the shape
//            and its count of bumps (m = 400 vs 625, LDSM), the time per step and to solution.
// Every run is also written as ParaView snapshots (DIR/paraview/<run>.xmf with HDF5 files).
//
// Scales. Quick (CI): eta = 48 (h = 0.5 um), n = 2,049 evaluation sites (spacing ~h/2 on the
// cell), t = 0.05 s (500 steps). Full: the paper's n = 8,281 on eta = 64 (h = 0.375 um; spacing
// h/3; the paper does not state its grid), the variants of the k_bend = 0 runs (table
// runs_variants), and those runs again on eta = 96, where dt = 1e-4 s loses every run near t = 7 ms
// and dt = 5e-5 s does not (table runs_eta96). At full scale each run keeps a checkpoint
// DIR/run_<label>_eta<eta>.h5 and continues from it when the command is run again; --sitting
// SECONDS bounds this sitting's wall time: runs left unfinished are reported with their time per
// step and projected time to solution. --resumable keeps checkpoints at quick scale too.
//
// Run:  build/studies/study_chapter3_capillary --scale quick --out runs/chapter3_capillary/quick
//       (or python3 -m harness run chapter3_capillary --scale quick)
#include "common/capillary.hpp"
#include "measures.hpp"
#include "rbfib/surface/shape_measures.hpp"

#include <algorithm>
#include <map>
#include <sstream>

using namespace rbfib;
using namespace rbfib::capillary;
namespace st = rbfib::study;
using st::number;
using st::row;

namespace {

/// One cell run of the study.
struct CellCase {
  std::string label;  ///< e.g. "SHVD_m400_kb0.1"
  chapter3::Method method;
  int M;
  double k_bend_pN_um;
  int md_degree = -1;  ///< evaluation sites: the scale's Bauer spiral (-1) or the stored MD set of this degree
};

std::vector<CellCase> cell_cases() {
  return {{"LDSM_kb0", chapter3::Method::ldsm, 19, 0.0},
          {"SHVD_m625_kb0", chapter3::Method::shvd, 24, 0.0},
          {"SHVD_m400_kb0", chapter3::Method::shvd, 19, 0.0},
          {"SHVD_m400_kb0.1", chapter3::Method::shvd, 19, 0.1},
          {"SHVD_m400_kb1", chapter3::Method::shvd, 19, 1.0}};
}

/// Full scale: the k_bend = 0 runs of Fig. 6 with two choices the paper's bumps might depend on
/// (reference conventions: bump_variants): the stored maximal-determinant sites of n = 4,624 (the
/// paper's kind, eq. 45 weights), and SHVD with more than 625 interpolation sites (Sec. 5.1.2).
std::vector<CellCase> variant_cases() {
  return {{"LDSM_kb0_MD4624", chapter3::Method::ldsm, 19, 0.0, 67},
          {"SHVD_m625_kb0_MD4624", chapter3::Method::shvd, 24, 0.0, 67},
          {"SHVD_m400_kb0_MD4624", chapter3::Method::shvd, 19, 0.0, 67},
          {"SHVD_m900_kb0", chapter3::Method::shvd, 29, 0.0},
          {"SHVD_m1024_kb0", chapter3::Method::shvd, 31, 0.0}};
}


/// The cell runs: each run's row of a runs table, the main runs' series, the measures the checks
/// need (front curvature, asymmetry and bumps, |f| on the back) and the figures' rows.
class CellRuns {
 public:
  CellRuns(Runner& runner, st::Json& results, const Model& base, index_t n, double u_max_empty)
      : runner_(runner), results_(results), base_(base), n_(n), u_max_empty_(u_max_empty),
        eval_(chapter3::make_evaluation_set(n)) {
    st::log(runner_.options(), "evaluation set n = " + to_text(n) + " in " + to_text(eval_.seconds) + " s");
    series = st::table({"run", "t", "cx_um", "area_change", "volume_change", "v_cell_um_s", "uc_x_um_s",
                        "max_force_density_pN_um2"},
                       {"", "s", "um", "", "", "um/s", "um/s", "pN/um^2"});
  }

  static st::Json runs_table() {
    return st::table({"run", "eta", "dt", "method", "m", "k_bend_pN_um", "status", "steps_done", "steps_needed", "seconds",
                      "seconds_per_step", "time_to_solution_s", "area_change_max", "volume_change", "v_cell_um_s",
                      "v_over_u_max", "front_H_cv", "front_H_std_per_um", "front_H_positive_fraction",
                      "nonaxisymmetric_rms_um", "nonaxisymmetric_max_um", "bumps", "f_mean_pN_um2", "f_roughness",
                      "f_noise", "f_back_mean_pN_um2", "cap_disp_um", "failed", "sites", "n"},
                     {"", "", "s", "", "", "pN um", "", "", "", "s", "s", "s", "", "", "um/s", "", "", "1/um", "", "um", "um",
                      "", "pN/um^2", "", "", "pN/um^2", "um", "", "", ""});
  }

  const chapter3::EvaluationSet& sites_of(const CellCase& cc) {
    if (cc.md_degree < 0) return eval_;
    auto it = md_sets_.find(cc.md_degree);
    if (it == md_sets_.end()) {
      const std::string file =
          st::source_path(runner_.options(), "reference/point_sets/max_determinant_N" + to_text(cc.md_degree) + ".txt");
      it = md_sets_.emplace(cc.md_degree, chapter3::make_md_evaluation_set(file, cc.md_degree)).first;
      st::log(runner_.options(), "MD evaluation set N = " + to_text(cc.md_degree) + " (eq. 45 weights) in " +
                                     to_text(it->second.seconds) + " s");
    }
    return it->second;
  }

  void run(const CellCase& cc, int eta, st::Json& table, bool main, double dt) {
    Model m = base_;
    m.eta = eta;
    if (dt != base_.dt) {  // the same times (t = 0.05 s, records every 2.5 ms, views every 5 ms)
      m.dt = dt;
      m.steps = int(std::lround(base_.steps * base_.dt / dt));
      m.record_every = int(std::lround(base_.record_every * base_.dt / dt));
      m.view_every = int(std::lround(base_.view_every * base_.dt / dt));
    }
    std::ostringstream dts;
    dts << dt;
    const std::string label =
        main ? cc.label : cc.label + "_eta" + to_text(eta) + (dt != base_.dt ? "_dt" + dts.str() : std::string());
    m.method = cc.method;
    m.M = cc.M;
    m.k_bend = cc.k_bend_pN_um * 1e-11;  // 1 pN um = 1e-11 erg
    const chapter3::EvaluationSet& e = sites_of(cc);
    std::unique_ptr<Run> run = runner_.go(m, &e, label);
    record(results_, label, *run);
    // ---- the series: area change, the velocity of the centroid over 5 ms ----
    const std::vector<Sample>& ser = run->series();
    double dA = 0, dV = NAN, v_cell = NAN, disp = NAN;
    if (!ser.empty()) {
      const Sample& s0 = ser.front();
      for (const Sample& s : ser) {
        dA = std::max(dA, std::abs(s.area / s0.area - 1));
        double v = NAN;
        for (const Sample& q : ser)
          if (std::abs(q.t - (s.t - 0.005)) < 1e-9) v = (s.c[0] - q.c[0]) / 0.005;
        if (main)
          series["rows"].push(row({cc.label, s.t, s.c[0] / um, s.area / s0.area - 1, s.volume / s0.volume - 1,
                                   number(v / um), number(s.uc[0] / um), number(s.max_density * 1e-3)}));
        if (std::isfinite(v)) v_cell = v;
      }
      dV = ser.back().volume / s0.volume - 1;
      disp = ser.back().cap_disp;
    }
    // ---- the shape at t = 0.05 s: front curvature (Fig. 8), asymmetry and bumps (Fig. 6), |f| (Fig. 7) ----
    const bool over = run->done(), ok = over && run->failure().empty();
    surface::Spread front;
    surface::Axisymmetry as;
    double f_mean = NAN, roughness = NAN, back = NAN, noise = NAN;
    if (ok) {
      const View& v = run->views().back();
      const std::array<double, 3> c{ser.back().c[0], ser.back().c[1], ser.back().c[2]};
      const surface::AlphaBands bands = surface::alpha_bands(e.sites);
      if (cc.method == chapter3::Method::shvd) front = surface::spread(v.H, surface::facing_sites(v.X, v.normal, c, +1));
      as = surface::axisymmetry(v.X, v.normal, bands, e.tris, c, 0.1 * um);  // bumps above 0.1 um
      if (!v.f.empty()) {
        double s = 0, sb = 0;
        for (double f : v.f) s += f;
        const std::vector<std::size_t> behind = surface::facing_sites(v.X, v.normal, c, -1);
        for (std::size_t i : behind) sb += v.f[i];
        f_mean = s / double(v.f.size());
        roughness = surface::edge_jump(v.f, e.tris) / f_mean;
        back = behind.empty() ? NAN : sb / double(behind.size());
        noise = surface::band_rms(bands, surface::band_residuals(bands, v.f)) / f_mean;
      }
    }
    const std::string status = !over ? (run->step() > 0 ? "partial" : "not started")
                                     : (run->failure().empty() ? "finished" : "stopped: " + run->failure());
    const double per = run->seconds_per_step();
    const bool shvd = cc.method == chapter3::Method::shvd;
    table["rows"].push(row({cc.label, eta, m.dt, chapter3::to_string(cc.method), shvd ? st::Json((cc.M + 1) * (cc.M + 1)) : st::Json(),
                            cc.k_bend_pN_um, status, run->step(), m.steps, run->seconds(), number(per), number(per * m.steps),
                            ok ? number(dA) : st::Json(), ok ? number(dV) : st::Json(), ok ? number(v_cell / um) : st::Json(),
                            ok ? number(v_cell / um / u_max_empty_) : st::Json(), number(front.cv), number(front.std * um),
                            number(front.positive), number(as.rms / um), number(as.max / um), ok ? st::Json(as.bumps) : st::Json(),
                            number(f_mean * 1e-3), number(roughness), number(noise), number(back * 1e-3), number(disp / um),
                            run->failure().empty() ? 0 : 1, e.family + " " + to_text(e.size()), double(e.size())}));
    st::log(runner_.options(), label + ": " + status + ", area change " + to_text(dA) + ", v_cell " + to_text(v_cell / um) +
                                   " um/s, front H cv " + to_text(front.cv) + ", asymmetry rms " + to_text(as.rms / um) +
                                   " um, bumps " + to_text(as.bumps));
    if (!run->views().empty()) write_snapshots(*run, runner_.options().out_dir + "/paraview", label);
    if (ok) summary_[label] = Summary{v_cell, front.cv, front.std, as.rms, double(as.bumps), roughness, back, noise};
    if (main) main_[cc.label] = std::move(run);
  }

  const std::map<std::string, Summary>& summaries() const { return summary_; }

  void figures(st::Json& T, bool full) const { capillary::figures(main_, n_, full, T); }

  st::Json series;

 private:
  Runner& runner_;
  st::Json& results_;
  Model base_;
  index_t n_;
  double u_max_empty_;
  chapter3::EvaluationSet eval_;
  std::map<int, chapter3::EvaluationSet> md_sets_;  // the stored MD sets of the variants, by degree
  std::map<std::string, std::unique_ptr<Run>> main_;
  std::map<std::string, Summary> summary_;
};


}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_capillary", [&] {
    // ---- 1. Parameters ---------------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_capillary",
        "Chapter 3 Sec. 5.1: a red cell through a tethered capillary, SHVD vs LDSM (Figs. 6-9)");
    const bool full = opt.scale == st::Scale::full;
    const index_t n = full ? 8281 : 2049;
    Runner runner(opt);
    Model base;
    base.eta = study_eta(opt);
    st::Json results = st::make_results(opt);
    st::Json& P = results["parameters"];
    write_parameters(P, base);
    P["cell"] = "eq. (92), R = 3.91 um, centred at (-8, 0, 0) um; neo-Hookean eq. (68) Gs = 2.5 pN/um, A = 50; "
                "bending eq. (79) k_bend = 0, 0.1, 1 pN um";
    P["n_evaluation_sites"] = double(n);
    P["evaluation_sites"] = "Bauer spiral with the weights of diss. eq. (2.22), phi = r^3 (as chapter3_dynamics)";
    P["interpolation_sites"] = "maximal-determinant-like (M+1)^2 sites, M = 19 (m = 400) and 24 (m = 625)";
    st::Json& T = results["tables"];
    st::Json& V = results["values"];

    // ---- 2. The empty capillary's peak speed on the study's grid (v_over_u_max) ------------------
    const double u_max_empty = empty_capillary(runner, results, base, Region::core, "empty_core").u_max / um;
    V["u_max_empty_um_s"] = number(u_max_empty);

    // ---- 3. The cell runs: the study's grid; at full scale the variants and eta = 96 --------------
    CellRuns cells(runner, results, base, n, u_max_empty);
    st::Json runs = CellRuns::runs_table(), runs96 = runs, variants = runs;
    for (const CellCase& cc : cell_cases()) cells.run(cc, base.eta, runs, true, base.dt);
    if (full) {
      for (const CellCase& cc : variant_cases()) cells.run(cc, base.eta, variants, false, base.dt);
      for (const CellCase& cc : cell_cases())
        if (cc.k_bend_pN_um == 0) cells.run(cc, 96, runs96, false, base.dt);
      for (const CellCase& cc : cell_cases())  // with dt = 5e-5 s: is the time step the cause?
        if (cc.label == "LDSM_kb0" || cc.label == "SHVD_m400_kb0") cells.run(cc, 96, runs96, false, base.dt / 2);
      T["runs_eta96"] = runs96;
      T["runs_variants"] = variants;
    }
    T["runs"] = runs;
    T["series"] = cells.series;

    // ---- 4. Values for the checks: ratios of the runs' measures ----------------------------------
    write_values(V, cells.summaries(), base.eta, u_max_empty);
    V["wall_seconds"] = runner.elapsed();

    // ---- 5. Figures' rows (Figs. 6-9) and results -------------------------------------------------
    cells.figures(T, full);
    st::write_results(opt, results);
    return 0;
  });
}
