// Chapter 3 dynamic test (the JCP 2018 paper, Sec. 4.2, with the time update of Sec. 3.3):
// elastic shells relaxing in steady Stokes flow on the periodic box [-2, 2]^3 (the exact periodic
// MAC Stokes solver of Sec. 3.2), Peskin's 4-point kernel, forward Euler X += dt U (eq. 87);
// forces neo-Hookean (eq. 68) + surface tension (eq. 72), sigma = K = A = Gs = mu = 1, reference
// the unit sphere; SHVD (m interpolation sites, forces at n evaluation sites, Sec. 3.1) against
// LDSM (n triangulated sites, eq. 66). Everything is dimensionless, as in the paper.
//
// Reproduces:
//   Fig. 4   the ellipsoid (eq. 88, a = 1.2, b = c = 1/sqrt(1.2)) and the perturbed ellipsoid
//            (eq. 89, B = 0.25, Vf for the unit sphere's volume) relaxing on eta = 32 with m = 225:
//            max_i |X_i - c| - 1 (and the min) against time, SHVD and LDSM;
//   Fig. 5   d_max at t = 3 (x-displacement of the rightmost point relative to the centroid) for
//            the ellipsoid, dt = 1/(2 eta), n ~ 2 eta^2, m = 64; error against the same method on
//            a grid 1.5 times finer; power-law orders;
//   Table 1  the SHVD / LDSM wall-time ratio of an ellipsoidal contraction (same parameters) for
//            m = 64 and 225, with each method's time split into forces, spreading, Stokes solve,
//            interpolation and update.
// Also: the time step's and the grid's shares of the Fig. 5 error (d_max with dt/2, dt/4 on one
// grid; three grids with one dt), the quadrature error of every evaluation set (Sec. 4.1's 1e-5),
// and the stored maximal-determinant sets with the weights of eq. (45) against our spirals.
//
// Scales. Quick (CI): Fig. 5 on eta = 16, 24, 32 (references 24, 36, 48); Fig. 4 with n = 4,609
// to t = 4; Table 1 on eta = 32, 48 for a 1 s contraction (the ratio is one of per-step costs).
// Full: the paper's eta = 32, 48, 64 (references 48, 72, 96); Fig. 4 with
// n = 8,281 to t = 15; Table 1 on eta = 32, 48, 64, 72 for the 15 s contraction. At full scale each
// run is kept in the run directory (run_<label>.h5, the library's run loop's checkpoint): a run the
// sitting (--sitting) leaves unfinished continues from there, and a finished one is read back, when
// the same command is run again, so the full scale can be completed over several sittings.
//
// Evaluation sites (reference/chapter3_dynamics.yaml, conventions): Bauer spirals (dissertation
// eq. 5.1) of n = 2 eta^2 + 1 sites (odd: the middle site is exactly at (1, 0, 0), the material
// point whose displacement is d_max) with the weights of dissertation eq. (2.22), phi = r^3; the
// paper's maximal-determinant sets with eq. (45) weights exist here only for n = 529, 2025, 4624.
// Interpolation sites: maximal-determinant-like (M + 1)^2 sites (surface::max_determinant_points).
//
// Run:  build/studies/study_chapter3_dynamics --scale quick --out runs/chapter3_dynamics/quick
//       (or python3 -m harness run chapter3_dynamics --scale quick)
#include "common/chapter3_relaxation.hpp"
#include "common/study.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/exec.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

using namespace rbfib;
using namespace rbfib::chapter3;
namespace st = rbfib::study;
using st::Json;

namespace {

using rbfib::study::row;
Json num(double x) { return std::isfinite(x) ? Json(x) : Json(); }


/// The angle of that site from the x axis (rad).
double rightmost_offset(const surface::SphereSites& sites) {
  const index_t i = rightmost_site(sites);
  return std::acos(std::min(1.0, std::cos(sites.theta[i]) * std::cos(sites.lambda[i])));
}


/// The runs of the study: each computed once per invocation; at full scale also kept in
/// DIR/run_<label>.h5, the library's run loop's checkpoint (the state, the records, the phase times
/// and the lockstep blocks as series, the commit that began it), so that the full scale continues
/// over several sittings (--sitting SECONDS: a run in progress stops at the sitting's end and
/// continues next time; a finished run is read back). Runs are counted in groups (group()),
/// recorded as results["runs"][group] (record()): a group is finished when every run asked of it
/// has finished; an unfinished run gives no values (its checks are not run).
class Runs {
 public:
  explicit Runs(const st::Options& opt) : opt_(opt), keep_(opt.keeps_runs()), sitting_(opt) {
    skipped_.force_integral0 = skipped_.max_force0 = NAN;
  }

  /// The group the next runs belong to.
  void group(const std::string& g) { group_ = g; }

  const EvaluationSet& evaluation_set(index_t n) {
    auto it = sets_.find(n);
    if (it == sets_.end()) {
      it = sets_.emplace(n, make_evaluation_set(n)).first;
      st::log(opt_, "evaluation set n = " + to_text(n) + ": weights and triangulation in " +
                        to_text(it->second.seconds) + " s");
    }
    return it->second;
  }

  static std::string label(const RelaxationSpec& s, index_t n, const std::string& shape_name) {
    return std::string(to_string(s.method)) + "_" + shape_name + "_eta" + to_text(s.eta) + "_n" + to_text(n) +
           (s.method == Method::shvd ? "_M" + to_text(s.M) : std::string()) + "_dt1over" +
           to_text(std::lround(1 / s.dt)) + "_steps" + to_text(s.steps) + "_every" + to_text(s.record_every);
  }

  std::string md_file(int N) const {
    return st::source_path(opt_, "reference/point_sets/max_determinant_N" + to_text(N) + ".txt");
  }

  /// The stored maximal-determinant-like set of degree N with the weights of eq. (45).
  const EvaluationSet& md_set(int N) {
    auto it = md_sets_.find(N);
    if (it == md_sets_.end()) {
      it = md_sets_.emplace(N, make_md_evaluation_set(md_file(N), N)).first;
      st::log(opt_, "MD evaluation set N = " + to_text(N) + ": eq. (45) weights and triangulation in " +
                        to_text(it->second.seconds) + " s");
    }
    return it->second;
  }

  /// The run of spec on the spiral of n sites (md_degree < 0) or on the MD set of that degree, its
  /// d_max at the material point (0, 0).
  const RelaxationResult& get(const RelaxationSpec& s, index_t n, const std::string& shape_name, int md_degree = -1) {
    return run(label(s, n, md_degree < 0 ? shape_name : shape_name + "_MD"), s, [&](const std::string& path) {
      return relax(s, md_degree < 0 ? evaluation_set(n) : md_set(md_degree), path, commit(), sitting_.remaining());
    });
  }

  /// The run of spec on the ellipsoid with d_max at the rightmost evaluation site (the paper's
  /// reading): on the even spiral of n sites (md_degree < 0) or on the MD set of that degree.
  /// LDSM measures at eval.axis_site (set to that site), SHVD at that site too (its measure_site).
  const RelaxationResult& get_rightmost(const RelaxationSpec& s, index_t n, int md_degree = -1) {
    const std::string key = md_degree < 0 ? label(s, n, "ellipsoid_rightmost")
                                          : label(s, index_t(md_degree + 1) * (md_degree + 1), "ellipsoid_MD_rightmost");
    return run(key, s, [&](const std::string& path) {
      EvaluationSet e = md_degree < 0 ? evaluation_set(n) : md_set(md_degree);
      e.axis_site = rightmost_site(e.sites);
      RelaxationSpec at = s;
      // SHVD measures d_max at the material point (0, 0) of its interpolant unless told a site; the
      // paper's d_max point is the rightmost evaluation site, off the axis on most sets.
      if (s.method == Method::shvd) at.measure_site = e.axis_site;
      return relax(at, e, path, commit(), sitting_.remaining());
    });
  }

  /// The SHVD run of spec on the odd spiral of n sites measured at its site (0, 0): the same run as
  /// get(s, n, "ellipsoid"), which measures at the interpolant's material point (0, 0); the two
  /// agree to rounding (value rightmost_loop_vs_library).
  const RelaxationResult& get_driver_loop(const RelaxationSpec& s, index_t n) {
    return run(label(s, n, "ellipsoid_driver_loop"), s, [&](const std::string& path) {
      const EvaluationSet& e = evaluation_set(n);
      RelaxationSpec at = s;
      at.measure_site = e.axis_site;
      return relax(at, e, path, commit(), sitting_.remaining());
    });
  }

  /// Runs of one ellipsoid (same n) in lockstep, one step of each in turn, so that a change of load
  /// on the shared machine falls on all of them alike; all again unless all are kept finished. The
  /// cumulative wall time of each run's steps is taken at the ends of `blocks` blocks of steps
  /// (block_seconds).
  std::vector<const RelaxationResult*> get_lockstep(const std::vector<RelaxationSpec>& specs, index_t n, int blocks) {
    std::vector<std::string> keys;
    std::vector<RelaxationResult> rs(specs.size());
    bool all = true;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      keys.push_back(label(specs[i], n, "ellipsoid_lockstep"));
      if (done_.count(keys[i])) continue;
      if (keep_ && std::filesystem::exists(path(keys[i]))) rs[i] = Relaxation(specs[i], evaluation_set(n), path(keys[i])).result();
      all = all && rs[i].finished;
    }
    if (!all && sitting_.remaining() <= 0) {
      for (std::size_t i = 0; i < specs.size(); ++i) count(keys[i], specs[i], nullptr);
      return std::vector<const RelaxationResult*>(specs.size(), &skipped_);
    }
    if (!all) {
      std::vector<std::unique_ptr<Relaxation>> runs;
      for (std::size_t i = 0; i < specs.size(); ++i) {
        if (keep_) std::filesystem::remove(path(keys[i]));  // all again, together
        runs.push_back(std::make_unique<Relaxation>(specs[i], evaluation_set(n), keep_ ? path(keys[i]) : "", commit()));
      }
      const int steps = specs.front().steps, every = std::max(1, steps / blocks);
      int last = 0;
      for (bool any = true; any;) {
        any = false;
        for (auto& r : runs) any = r->advance() || any;
        const int k = runs.front()->step();
        if (k != last && (k % every == 0 || k == steps)) {
          for (auto& r : runs) r->mark_block();
          last = k;
        }
      }
      for (std::size_t i = 0; i < specs.size(); ++i) {
        rs[i] = runs[i]->result();
        done_.erase(keys[i]);
        finished(keys[i], rs[i]);
      }
    }
    std::vector<const RelaxationResult*> out;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      auto it = done_.find(keys[i]);
      if (it == done_.end()) it = done_.emplace(keys[i], std::move(rs[i])).first;
      count(keys[i], specs[i], &it->second);
      out.push_back(&it->second);
    }
    return out;
  }

  /// The block ends of a lockstep run (cumulative wall time of its steps, s).
  const std::vector<double>& block_seconds(const RelaxationSpec& s, index_t n) const {
    static const std::vector<double> none;
    auto it = done_.find(label(s, n, "ellipsoid_lockstep"));
    return it == done_.end() ? none : it->second.block_ends;
  }

  /// results["runs"][group] for every group: finished when each run asked of it was there.
  void record(Json& results) const {
    for (const auto& [id, g] : groups_) {
      st::RunProgress p;
      p.finished = g.finished;
      p.t = g.t;
      p.t_end = g.t_end;
      p.steps = g.steps;
      p.seconds_per_step = g.steps > 0 ? g.seconds / double(g.steps) : NAN;
      p.stopped = g.stopped;
      st::record_run(results, id, p);
    }
  }

 private:
  /// Simulated time, steps and wall time of a group's runs (summed), and whether all are there.
  struct Group {
    double t = 0, t_end = 0, seconds = 0;
    long steps = 0;
    bool finished = true;
    std::string stopped;  ///< the first numerical stop among them
  };

  std::string path(const std::string& label) const { return opt_.out_dir + "/run_" + label + ".h5"; }
  std::string commit() const { return st::source_commit(opt_); }

  /// The run `key` of spec: done this invocation, or computed (kept in its checkpoint at full scale:
  /// continued, or read back when finished). A run the sitting left unfinished gives no values.
  template <class Compute>
  const RelaxationResult& run(const std::string& key, const RelaxationSpec& s, Compute compute) {
    auto it = done_.find(key);
    if (it == done_.end()) {
      RelaxationResult r = compute(keep_ ? path(key) : std::string());
      if (r.continued && r.finished && r.steps == s.steps)
        st::log(opt_, key + ": taken from " + path(key) + " (begun by " + r.label + ")");
      else if (r.finished)
        finished(key, r);
      it = done_.emplace(key, std::move(r)).first;
    }
    count(key, s, &it->second);
    return it->second.finished ? it->second : skipped_;
  }

  /// Adds run `key` to the current group once (r = nullptr or unfinished: not finished in this sitting).
  void count(const std::string& key, const RelaxationSpec& s, const RelaxationResult* r) {
    if (!counted_.insert(group_ + " " + key).second) return;
    Group& g = groups_[group_];
    g.t_end += s.steps * s.dt;
    if (!r || !r->finished) g.finished = false;
    if (!r) return;
    g.t += r->steps * s.dt;
    g.steps += r->steps;
    g.seconds += r->seconds;
    if (r->failed && g.stopped.empty()) g.stopped = r->failure;
  }

  void finished(const std::string& label, const RelaxationResult& r) {
    st::log(opt_, label + ": " + to_text(r.steps) + " steps in " + to_text(r.seconds) + " s, d_axis " +
                      to_text(r.d_axis()) + (r.failed ? " FAILED: " + r.failure : std::string()));
  }

  const st::Options& opt_;
  bool keep_;
  const st::Sitting sitting_;
  RelaxationResult skipped_;  ///< what a run not started in this sitting gives (no samples)
  std::string group_ = "runs";
  std::map<std::string, Group> groups_;
  std::set<std::string> counted_;
  std::map<index_t, EvaluationSet> sets_;
  std::map<int, EvaluationSet> md_sets_;
  std::map<std::string, RelaxationResult> done_;
};

/// Best time (of 11) of the jets' products of one SHVD force call for the degree-M interpolant
/// at the n sites: value and derivatives (6n x m) times the m x 3 coefficients as one product per
/// operator block, as the force call does (`gemm`), and as three matrix-vector products, one per
/// coordinate (`gemv`), the paper's "each derivative is a matrix-vector multiplication" (Sec. 3.1).
void product_times(const EvaluationSet& e, int M, double& t_gemm, double& t_gemv) {
  const auto ops = surface::sh_operators(interpolation_sites(M), e.sites, M);
  const index_t m = ops->value.cols(), n = ops->value.rows();
  std::vector<double> c(static_cast<std::size_t>(3 * m));
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = std::cos(double(i));  // any coefficients
  const linalg::DeviceMatrix B = linalg::DeviceMatrix::from_host(m, 3, c.data());
  linalg::DeviceMatrix V(n, 3), D(5 * n, 3);
  using linalg::Op;
  t_gemm = st::best_seconds(11, [&] {
    linalg::gemm(Op::none, Op::none, 1.0, ops->value.view(), B.view(), 0.0, V.view());
    linalg::gemm(Op::none, Op::none, 1.0, ops->derivatives.view(), B.view(), 0.0, D.view());
  });
  t_gemv = st::best_seconds(11, [&] {
    for (index_t k = 0; k < 3; ++k) {
      linalg::gemm(Op::none, Op::none, 1.0, ops->value.view(), B.view().block(0, k, m, 1), 0.0,
                   V.view().block(0, k, n, 1));
      linalg::gemm(Op::none, Op::none, 1.0, ops->derivatives.view(), B.view().block(0, k, m, 1), 0.0,
                   D.view().block(0, k, 5 * n, 1));
    }
  });
}

/// The parameters of the scale (see the header) and the run specification built from them.
struct Setup {
  const st::Options& opt;
  bool full;
  surface::PerturbedEllipsoid ellipsoid = surface::ellipsoid(1.2, 1 / std::sqrt(1.2), 1 / std::sqrt(1.2));  // eq. (88)
  surface::PerturbedEllipsoid perturbed = surface::paper_perturbed_ellipsoid();                             // eq. (89)
  // Fig. 5: the grids, each with its reference 1.5 times finer; t = 3, m = 64.
  std::vector<int> fig5_etas;
  double fig5_t = 3;
  int fig5_M = 7;
  // Fig. 4: eta = 32, m = 225; n = 8,281 (full) or the 4,609 sites of Fig. 5's eta = 48 (quick).
  int fig4_eta = 32, fig4_M = 14;
  index_t fig4_n;
  double fig4_t;
  // Table 1: m = 64 and 225.
  std::vector<int> table1_etas;
  double table1_t;
  int table1_blocks = 10;  // blocks of steps over which the timing noise of the ratio is measured

  explicit Setup(const st::Options& o)
      : opt(o),
        full(o.scale == st::Scale::full),
        fig5_etas(full ? std::vector<int>{32, 48, 64} : std::vector<int>{16, 24, 32}),
        fig4_n(full ? 8281 : n_for(48)),
        fig4_t(full ? 15 : 4),
        table1_etas(full ? std::vector<int>{32, 48, 64, 72} : std::vector<int>{32, 48}),
        table1_t(full ? 15 : 1) {}

  static index_t n_for(int eta) { return index_t(2) * eta * eta + 1; }  // n ~ 2 eta^2 (Secs. 3.2, 4.2), odd
  static double dt_for(int eta) { return 1.0 / (2 * eta); }             // Sec. 4.2

  /// The run of `m` on `shape` on the grid eta to time t (dt = 1/(2 eta)), degree M for SHVD,
  /// recording about `records` times (0: first and last only).
  RelaxationSpec spec(Method m, const surface::PerturbedEllipsoid& shape, int eta, double t, int M, int records) const {
    RelaxationSpec s;
    s.method = m;
    s.shape = shape;
    s.eta = eta;
    s.dt = dt_for(eta);
    s.steps = int(std::lround(t / s.dt));
    s.M = M;
    s.record_every = records > 0 ? std::max(1, s.steps / records) : 0;
    return s;
  }
};

/// Fig. 5: d_max at t = 3 and its error against a grid 1.5 times finer
void fig5(const Setup& S, Runs& runs, Json& T, Json& V) {
  runs.group("fig5");
  Json t5 = st::table({"method", "eta", "n", "m", "dt", "d_max", "eta_ref", "d_max_ref", "err", "seconds"},
                      {"", "", "", "", "1", "1", "", "1", "1", "s"});
  Json agree = st::table({"eta", "d_max_SHVD", "d_max_LDSM", "method_diff", "err_SHVD", "err_LDSM", "diff_over_err"},
                         {"", "1", "1", "1", "1", "1", ""});
  std::map<Method, std::vector<double>> xs, es;
  std::map<std::pair<Method, int>, double> d, e;
  for (int eta : S.fig5_etas) {
    const int ref = eta * 3 / 2;
    for (Method m : {Method::shvd, Method::ldsm}) {
      const RelaxationResult& a =
          runs.get(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), S.n_for(eta), "ellipsoid");
      const RelaxationResult& b =
          runs.get(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), S.n_for(ref), "ellipsoid");
      const bool ok = !a.failed && !b.failed;
      const double err = ok ? std::abs(a.d_axis() - b.d_axis()) : NAN;
      t5["rows"].push(
          row({to_string(m), eta, double(S.n_for(eta)), m == Method::shvd ? Json(64) : Json(), S.dt_for(eta),
               ok ? num(a.d_axis()) : Json(), ref, ok ? num(b.d_axis()) : Json(), num(err), a.phases.total()}));
      d[{m, eta}] = ok ? a.d_axis() : NAN;
      e[{m, eta}] = err;
      if (std::isfinite(err) && err > 0) {
        xs[m].push_back(eta);
        es[m].push_back(err);
      }
    }
    const double diff = std::abs(d[{Method::shvd, eta}] - d[{Method::ldsm, eta}]);
    const double err_min = std::min(e[{Method::shvd, eta}], e[{Method::ldsm, eta}]);
    agree["rows"].push(row({eta, num(d[{Method::shvd, eta}]), num(d[{Method::ldsm, eta}]), num(diff),
                            num(e[{Method::shvd, eta}]), num(e[{Method::ldsm, eta}]), num(diff / err_min)}));
  }
  // the series d(t) of the grids, for the figure
  Json ts = st::table({"method", "eta", "t", "d_axis"}, {"", "", "1", "1"});
  for (int eta : S.fig5_etas)
    for (Method m : {Method::shvd, Method::ldsm})
      for (const Sample& s :
           runs.get(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), S.n_for(eta), "ellipsoid").series)
        ts["rows"].push(row({std::string(to_string(m)) + " eta = " + to_text(eta), eta, s.t, s.d_axis}));
  T["fig5"] = t5;
  T["fig5_agreement"] = agree;
  T["fig5_series"] = ts;
  for (Method m : {Method::shvd, Method::ldsm}) {
    const bool all = xs[m].size() == S.fig5_etas.size();
    V[std::string("fig5_order_fit_") + to_string(m)] = all ? num(st::power_law_order(xs[m], es[m])) : Json();
  }
  st::log(S.opt, "Fig. 5: power-law orders SHVD " + to_text(st::power_law_order(xs[Method::shvd], es[Method::shvd])) +
                     ", LDSM " + to_text(st::power_law_order(xs[Method::ldsm], es[Method::ldsm])));
}

/// Fig. 5 with the paper's d_max point: the rightmost evaluation site
/// Sec. 4.2: "the change in distance ... of the rightmost point (the point with largest x
/// coordinate) minus the center of mass". Each grid with its own n = 2 eta^2 sites: an even Bauer
/// spiral, which has no site on the x axis (its rightmost site lies sqrt(pi/n) from it, as an MD
/// set's lies some part of a spacing away), d_max = (x_s - c_x)(3) - (x_s - c_x)(0) at that site s,
/// c the centroid as for our d_max; the error against the grid 1.5 times finer with its own set
/// and its own rightmost site. Full scale also: the paper's own sets for eta = 32 and its
/// reference, the stored MD sets of n = 2025 and 4624 with eq. (45) weights.
void fig5_rightmost(const Setup& S, Runs& runs, Json& T, Json& V) {
  runs.group("fig5_rightmost");
  auto n_even = [](int eta) { return index_t(2) * eta * eta; };
  Json t = st::table({"method", "eta", "n", "offset_rad", "d_max", "eta_ref", "n_ref", "offset_ref_rad", "d_max_ref",
                      "err", "err_axis", "err_over_err_axis", "d_max_minus_axis"},
                     {"", "", "", "rad", "1", "", "", "rad", "1", "1", "1", "", "1"});
  std::map<Method, std::vector<double>> xs, es;
  for (int eta : S.fig5_etas) {
    const int ref = eta * 3 / 2;
    for (Method m : {Method::shvd, Method::ldsm}) {
      const RelaxationResult& a = runs.get_rightmost(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), n_even(eta));
      const RelaxationResult& b = runs.get_rightmost(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), n_even(ref));
      // our d_max (the material point (0, 0) on the odd spirals), from Fig. 5's runs
      const RelaxationResult& ax =
          runs.get(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), S.n_for(eta), "ellipsoid");
      const RelaxationResult& bx =
          runs.get(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), S.n_for(ref), "ellipsoid");
      const bool ok = !a.failed && !b.failed, ok_axis = !ax.failed && !bx.failed;
      const double err = ok ? std::abs(a.d_axis() - b.d_axis()) : NAN;
      const double err_axis = ok_axis ? std::abs(ax.d_axis() - bx.d_axis()) : NAN;
      t["rows"].push(row({to_string(m), eta, double(n_even(eta)), rightmost_offset(surface::bauer_spiral(n_even(eta))),
                          ok ? num(a.d_axis()) : Json(), ref, double(n_even(ref)),
                          rightmost_offset(surface::bauer_spiral(n_even(ref))), ok ? num(b.d_axis()) : Json(), num(err),
                          num(err_axis), num(err / err_axis), num(a.d_axis() - ax.d_axis())}));
      if (std::isfinite(err) && err > 0) {
        xs[m].push_back(eta);
        es[m].push_back(err);
      }
    }
  }
  T["fig5_rightmost"] = t;
  for (Method m : {Method::shvd, Method::ldsm}) {
    const bool all = xs[m].size() == S.fig5_etas.size();
    V[std::string("fig5_rightmost_order_fit_") + to_string(m)] = all ? num(st::power_law_order(xs[m], es[m])) : Json();
  }
  // SHVD measured at the site (0, 0) against SHVD measured at the material point (0, 0) by its
  // interpolant, on the coarsest grid (the same run).
  {
    const RelaxationSpec s = S.spec(Method::shvd, S.ellipsoid, S.fig5_etas.front(), S.fig5_t, S.fig5_M, 12);
    const RelaxationResult& lib = runs.get(s, S.n_for(s.eta), "ellipsoid");
    const RelaxationResult& drv = runs.get_driver_loop(s, S.n_for(s.eta));
    V["rightmost_loop_vs_library"] =
        !lib.failed && !drv.failed ? num(std::abs(drv.d_axis() - lib.d_axis())) : Json();
  }
  st::log(S.opt, "Fig. 5, rightmost site: power-law orders SHVD " +
                     to_text(st::power_law_order(xs[Method::shvd], es[Method::shvd])) + ", LDSM " +
                     to_text(st::power_law_order(xs[Method::ldsm], es[Method::ldsm])));
  if (!S.full) return;
  // The paper's sets of eta = 32 and of its reference, eta = 48.
  Json md = st::table({"method", "eta", "n", "offset_rad", "d_max", "eta_ref", "n_ref", "offset_ref_rad", "d_max_ref",
                       "err", "err_spiral", "err_axis"},
                      {"", "", "", "rad", "1", "", "", "rad", "1", "1", "1", "1"});
  const int eta = 32, ref = 48, N = 44, N_ref = 67;  // n = 2025 and 4624 (Sec. 4.2)
  for (Method m : {Method::shvd, Method::ldsm}) {
    const RelaxationResult& a = runs.get_rightmost(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), 0, N);
    const RelaxationResult& b = runs.get_rightmost(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), 0, N_ref);
    const RelaxationResult& as = runs.get_rightmost(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), n_even(eta));
    const RelaxationResult& bs = runs.get_rightmost(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), n_even(ref));
    const RelaxationResult& ax = runs.get(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), S.n_for(eta), "ellipsoid");
    const RelaxationResult& bx = runs.get(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), S.n_for(ref), "ellipsoid");
    const bool ok = !a.failed && !b.failed;
    md["rows"].push(row({to_string(m), eta, double((N + 1) * (N + 1)),
                         rightmost_offset(surface::read_sphere_sites(runs.md_file(N))), ok ? num(a.d_axis()) : Json(), ref,
                         double((N_ref + 1) * (N_ref + 1)), rightmost_offset(surface::read_sphere_sites(runs.md_file(N_ref))),
                         ok ? num(b.d_axis()) : Json(), ok ? num(std::abs(a.d_axis() - b.d_axis())) : Json(),
                         num(std::abs(as.d_axis() - bs.d_axis())), num(std::abs(ax.d_axis() - bx.d_axis()))}));
  }
  T["fig5_rightmost_md"] = md;
}

/// The time step's share of the Fig. 5 error
/// Forward Euler (eq. 87) is first order in dt = 1/(2 eta): on one grid (the coarsest of Fig. 5)
/// d_max at t = 3 with dt, dt/2, dt/4 (SHVD, m = 64). The first-order extrapolated time error at
/// dt is 2 |d(dt) - d(dt/2)|, compared with the grid's error in Fig. 5 (space and time together).
void time_step(const Setup& S, Runs& runs, Json& T, Json& V) {
  runs.group("fig5_time_space");
  const int eta = S.fig5_etas.front();
  Json t = st::table({"eta", "dt", "steps", "d_max", "diff_to_half_dt", "order_dt"}, {"", "1", "", "1", "1", ""});
  std::vector<double> dts, ds;
  for (int q : {1, 2, 4}) {
    RelaxationSpec s = S.spec(Method::shvd, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12);
    s.dt = S.dt_for(eta) / q;
    s.steps = int(std::lround(S.fig5_t / s.dt));
    s.record_every = s.steps / 12;
    const RelaxationResult& r = runs.get(s, S.n_for(eta), "ellipsoid");
    dts.push_back(s.dt);
    ds.push_back(r.failed ? NAN : r.d_axis());
  }
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double diff = i + 1 < dts.size() ? std::abs(ds[i] - ds[i + 1]) : NAN;
    const double prev = i > 0 ? std::abs(ds[i - 1] - ds[i]) : NAN;
    t["rows"].push(row({eta, dts[i], int(std::lround(S.fig5_t / dts[i])), num(ds[i]), num(diff),
                        num(std::log(prev / diff) / std::log(2.0))}));
  }
  T["time_step"] = t;
  const RelaxationResult& ref = runs.get(S.spec(Method::shvd, S.ellipsoid, eta * 3 / 2, S.fig5_t, S.fig5_M, 12),
                                         S.n_for(eta * 3 / 2), "ellipsoid");
  const double err = std::abs(ds[0] - ref.d_axis());
  V["time_error_share_coarsest"] = num(2 * std::abs(ds[0] - ds[1]) / err);
  V["time_order_dt"] = num(std::log(std::abs(ds[0] - ds[1]) / std::abs(ds[1] - ds[2])) / std::log(2.0));
  st::log(S.opt, "time step: d_max " + to_text(ds[0]) + ", " + to_text(ds[1]) + ", " + to_text(ds[2]) +
                     "; time error share " + to_text(2 * std::abs(ds[0] - ds[1]) / err));
}

/// The spatial error alone
/// The grids eta, 1.5 eta, 2.25 eta (the coarsest of Fig. 5 and its refinements) with one dt,
/// that of the finest: the differences of d_max are then the spatial (grid and n) error alone.
void space_only(const Setup& S, Runs& runs, Json& T, Json& V) {
  runs.group("fig5_time_space");
  const int e0 = S.fig5_etas.front();
  const std::vector<int> etas = {e0, e0 * 3 / 2, e0 * 9 / 4};
  const double dt = S.dt_for(etas.back());
  Json t = st::table({"eta", "n", "dt", "d_max", "err", "order"}, {"", "", "1", "1", "1", ""});
  std::vector<double> ds;
  for (int eta : etas) {
    RelaxationSpec s = S.spec(Method::shvd, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12);
    s.dt = dt;
    s.steps = int(std::lround(S.fig5_t / dt));
    s.record_every = s.steps / 12;
    const RelaxationResult& r = runs.get(s, S.n_for(eta), "ellipsoid");
    ds.push_back(r.failed ? NAN : r.d_axis());
  }
  std::vector<double> errs;
  for (std::size_t i = 0; i < etas.size(); ++i) {
    const double err = i + 1 < etas.size() ? std::abs(ds[i] - ds[i + 1]) : NAN;
    errs.push_back(err);
    const double order = i > 0 && i + 1 < etas.size() ? std::log(errs[i - 1] / err) / std::log(1.5) : NAN;
    t["rows"].push(row({etas[i], double(S.n_for(etas[i])), dt, num(ds[i]), num(err), num(order)}));
  }
  T["space_only"] = t;
  V["space_order"] = num(std::log(errs[0] / errs[1]) / std::log(1.5));
  st::log(S.opt, "spatial error alone: order " + to_text(std::log(errs[0] / errs[1]) / std::log(1.5)));
}

/// Fig. 4: relaxation of both shapes on eta = 32, m = 225
/// Beside each pair, SHVD on a grid 1.5 times finer (eta = 48, dt = 1/96, the same n): the IB
/// discretization error that the paper names as the reason both methods agree.
void fig4(const Setup& S, Runs& runs, Json& T, Json& /*V*/) {
  runs.group("fig4");
  Json t4 = st::table({"series", "shape", "method", "eta", "t", "r_max", "r_min", "d_axis"},
                      {"", "", "", "", "1", "1", "1", "1"});
  Json t4d = st::table({"shape", "method_diff", "grid_diff_SHVD", "diff_over_grid_diff", "initial_r_max",
                        "volume_change_SHVD", "volume_change_LDSM"},
                       {"", "1", "1", "", "1", "1", "1"});
  const int records = int(std::lround(S.fig4_t * 8));  // every 1/8
  for (const auto& [name, shape] : std::vector<std::pair<std::string, const surface::PerturbedEllipsoid*>>{
           {"ellipsoid", &S.ellipsoid}, {"perturbed", &S.perturbed}}) {
    const RelaxationResult& shvd =
        runs.get(S.spec(Method::shvd, *shape, S.fig4_eta, S.fig4_t, S.fig4_M, records), S.fig4_n, name);
    const RelaxationResult& ldsm =
        runs.get(S.spec(Method::ldsm, *shape, S.fig4_eta, S.fig4_t, S.fig4_M, records), S.fig4_n, name);
    const RelaxationResult& finer =
        runs.get(S.spec(Method::shvd, *shape, S.fig4_eta * 3 / 2, S.fig4_t, S.fig4_M, records), S.fig4_n, name);
    for (const auto& [label, r] : std::vector<std::pair<std::string, const RelaxationResult*>>{
             {"SHVD", &shvd}, {"LDSM", &ldsm}, {"SHVD eta = 48", &finer}}) {
      const int eta = r == &finer ? S.fig4_eta * 3 / 2 : S.fig4_eta;
      for (const Sample& x : r->series)
        t4["rows"].push(row({name + " " + label, name, label.substr(0, 4), eta, x.t, x.r_max, x.r_min, x.d_axis}));
    }
    // largest difference over the common times of r_max and r_min (Fig. 4's quantities)
    auto max_diff = [](const RelaxationResult& a, const RelaxationResult& b) {
      if (a.failed || b.failed || a.series.empty() || a.series.size() != b.series.size()) return double(NAN);
      double d = 0;
      for (std::size_t i = 0; i < a.series.size(); ++i)
        d = std::max(
            {d, std::abs(a.series[i].r_max - b.series[i].r_max), std::abs(a.series[i].r_min - b.series[i].r_min)});
      return d;
    };
    // relative change of the enclosed volume over the run (the velocity is interpolated, not
    // exactly divergence free on the surface)
    auto volume_change = [](const RelaxationResult& r) {
      return r.series.empty() ? Json() : num(r.series.back().volume / r.series.front().volume - 1);
    };
    const double dm = max_diff(shvd, ldsm), dg = max_diff(shvd, finer);
    t4d["rows"].push(
        row({name, num(dm), num(dg), num(dm / dg), shvd.series.empty() ? Json() : Json(shvd.series.front().r_max),
             volume_change(shvd), volume_change(ldsm)}));
    if (shvd.failed || ldsm.failed || finer.failed)
      st::log(S.opt, "Fig. 4 " + name + ": " + shvd.failure + " " + ldsm.failure + " " + finer.failure);
  }
  T["fig4"] = t4;
  T["fig4_agreement"] = t4d;
  st::log(S.opt, "Fig. 4 done");
}

/// Quadrature error of the evaluation weights (Sec. 4.1: ~1e-5 or less)
/// |sum_i F^_i|_inf of the SHVD forces at t = 0 (the translation-invariant force integrates to
/// zero; LDSM's sum is zero to rounding by construction).
void quadrature(const Setup& S, Runs& runs, Json& T, Json& /*V*/) {
  runs.group("fig4");
  Json quad = st::table({"use", "shape", "n", "m", "force_integral", "max_force", "paper_criterion"},
                        {"", "", "", "", "1", "1", "1"});
  const int records = int(std::lround(S.fig4_t * 8));
  for (const auto& [name, shape] : std::vector<std::pair<std::string, const surface::PerturbedEllipsoid*>>{
           {"ellipsoid", &S.ellipsoid}, {"perturbed", &S.perturbed}}) {
    const RelaxationResult& shvd =
        runs.get(S.spec(Method::shvd, *shape, S.fig4_eta, S.fig4_t, S.fig4_M, records), S.fig4_n, name);
    quad["rows"].push(row({"Fig. 4", name, double(S.fig4_n), 225, shvd.force_integral0, shvd.max_force0, 1e-5}));
  }
  std::vector<int> grids;
  for (int eta : S.fig5_etas) grids.insert(grids.end(), {eta, eta * 3 / 2});
  std::sort(grids.begin(), grids.end());
  grids.erase(std::unique(grids.begin(), grids.end()), grids.end());
  runs.group("fig5");
  for (int k : grids) {
    const RelaxationResult& shvd =
        runs.get(S.spec(Method::shvd, S.ellipsoid, k, S.fig5_t, S.fig5_M, 12), S.n_for(k), "ellipsoid");
    quad["rows"].push(
        row({"Fig. 5", "ellipsoid", double(S.n_for(k)), 64, shvd.force_integral0, shvd.max_force0, 1e-5}));
  }
  T["quadrature"] = quad;
}

/// The evaluation sites: the paper's MD sets with eq. (45) weights, where stored
/// d_max at t = 3 on the stored MD sets (n = 2025, 4624) against the spirals of the same grid
/// (n = 2049, 4609), beside that grid's error in Fig. 5.
void sites(const Setup& S, Runs& runs, Json& T, Json& /*V*/) {
  runs.group("sites");
  Json t = st::table({"method", "eta", "n_MD", "eq45_residual", "d_max_MD", "n_spiral", "d_max_spiral", "sites_diff",
                      "err_grid", "diff_over_err"},
                     {"", "", "", "", "1", "", "1", "1", "1", ""});
  const std::vector<std::pair<int, int>> md =
      S.full ? std::vector<std::pair<int, int>>{{32, 44}, {48, 67}} : std::vector<std::pair<int, int>>{{32, 44}};
  for (const auto& [eta, N] : md) {
    const int ref = eta * 3 / 2;
    for (Method m : {Method::shvd, Method::ldsm}) {
      const RelaxationResult& a =
          runs.get(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), (N + 1) * (N + 1), "ellipsoid", N);
      const RelaxationResult& b =
          runs.get(S.spec(m, S.ellipsoid, eta, S.fig5_t, S.fig5_M, 12), S.n_for(eta), "ellipsoid");
      const RelaxationResult& c =
          runs.get(S.spec(m, S.ellipsoid, ref, S.fig5_t, S.fig5_M, 12), S.n_for(ref), "ellipsoid");
      const bool ok = !a.failed && !b.failed && !c.failed;
      const double diff = std::abs(a.d_axis() - b.d_axis()), err = std::abs(b.d_axis() - c.d_axis());
      t["rows"].push(row({to_string(m), eta, double((N + 1) * (N + 1)), runs.md_set(N).eq45_residual,
                          ok ? num(a.d_axis()) : Json(), double(S.n_for(eta)), ok ? num(b.d_axis()) : Json(),
                          ok ? num(diff) : Json(), ok ? num(err) : Json(), ok ? num(diff / err) : Json()}));
    }
  }
  T["sites"] = t;
  st::log(S.opt, "evaluation-site comparison done");
}

/// The sample standard deviation over the blocks of a lockstep run of the ratio of the wall times
/// of its steps, SHVD over LDSM, block by block (the cumulative times at the blocks' ends; NaN for
/// fewer than two blocks).
double block_ratio_std(const std::vector<double>& shvd, const std::vector<double>& ldsm) {
  if (shvd.size() != ldsm.size() || shvd.size() < 2) return NAN;
  std::vector<double> r;
  for (std::size_t j = 0; j < shvd.size(); ++j)
    r.push_back((shvd[j] - (j ? shvd[j - 1] : 0)) / (ldsm[j] - (j ? ldsm[j - 1] : 0)));
  double mean = 0, s2 = 0;
  for (double x : r) mean += x / double(r.size());
  for (double x : r) s2 += (x - mean) * (x - mean);
  return std::sqrt(s2 / double(r.size() - 1));
}

/// Table 1: SHVD / LDSM wall time, and where each method spends it
/// ratio_*: wall time of the steps (the paper's measure); ratio_*_median: from the per-step medians
/// of each phase (the three runs of a grid advance in lockstep, so both see the same load).
void table1(const Setup& S, Runs& runs, Json& T, Json& V) {
  runs.group("table1");
  Json t1 = st::table({"eta", "n", "t_contraction", "steps", "ldsm_seconds", "shvd_m64_seconds", "shvd_m225_seconds",
                       "ratio_m64", "ratio_m225", "ratio_m64_median", "ratio_m225_median", "blocks",
                       "ratio_m64_block_std", "ratio_m225_block_std"},
                      {"", "", "1", "", "s", "s", "s", "", "", "", "", "", "", ""});
  Json phases =
      st::table({"method", "eta", "n", "forces_seconds", "force_products_seconds", "spread_seconds", "solve_seconds",
                 "interpolate_seconds", "update_seconds", "step_seconds", "forces_share", "product_gflops"},
                {"", "", "", "s", "s", "s", "s", "s", "s", "s", "", "GFLOP/s"});
  Json products = st::table(
      {"eta", "n", "m", "gemm_seconds", "gemv_seconds", "gemv_over_gemm", "ratio_median", "ratio_median_with_gemv"},
      {"", "", "", "s", "s", "", "", ""});
  for (int eta : S.table1_etas) {
    const index_t n = S.n_for(eta);
    const std::vector<RelaxationSpec> specs = {S.spec(Method::ldsm, S.ellipsoid, eta, S.table1_t, 7, 0),
                                               S.spec(Method::shvd, S.ellipsoid, eta, S.table1_t, 7, 0),
                                               S.spec(Method::shvd, S.ellipsoid, eta, S.table1_t, 14, 0)};
    const std::vector<const RelaxationResult*> g = runs.get_lockstep(specs, n, S.table1_blocks);
    const RelaxationResult &L = *g[0], &S64 = *g[1], &S225 = *g[2];
    const double lt = L.phases.total(), lm = L.median.total();
    // The timing noise of the ratio in this run: the spread of the ratio over its blocks of steps.
    const std::vector<double>& bl = runs.block_seconds(specs[0], n);
    const double std64 = block_ratio_std(runs.block_seconds(specs[1], n), bl);
    const double std225 = block_ratio_std(runs.block_seconds(specs[2], n), bl);
    t1["rows"].push(row({eta, double(n), S.table1_t, L.steps, lt, S64.phases.total(), S225.phases.total(),
                         num(S64.phases.total() / lt), num(S225.phases.total() / lt), num(S64.median.total() / lm),
                         num(S225.median.total() / lm), double(bl.size()), num(std64), num(std225)}));
    for (const auto& [label, r] : std::vector<std::pair<std::string, const RelaxationResult*>>{
             {"LDSM", &L}, {"SHVD m = 64", &S64}, {"SHVD m = 225", &S225}}) {
      const PhaseTimes& p = r->median;
      // the jets' products: value and 5 derivatives (6n x m) times the m x 3 coefficients
      const double m = r == &S64 ? 64 : 225;
      const Json rate = r == &L ? Json() : num(2 * 6 * double(n) * m * 3 / p.force_products / 1e9);
      phases["rows"].push(row({label, eta, double(n), p.forces, p.force_products, p.spread, p.solve, p.interpolate,
                               p.update, p.total(), p.forces / p.total(), rate}));
    }
    // what three matrix-vector products per force call instead of one product would cost
    for (const auto& [M, r] : std::vector<std::pair<int, const RelaxationResult*>>{{7, &S64}, {14, &S225}}) {
      double t_gemm, t_gemv;
      product_times(runs.evaluation_set(n), M, t_gemm, t_gemv);
      const double with_gemv =  // the run's own products, scaled by the measured gemv / gemm
          (r->median.total() + r->median.force_products * (t_gemv / t_gemm - 1)) / lm;
      products["rows"].push(
          row({eta, double(n), (M + 1) * (M + 1), t_gemm, t_gemv, t_gemv / t_gemm, r->median.total() / lm, with_gemv}));
    }
    if (eta == S.table1_etas.back()) {
      V["table1_ratio_m64_median_largest_eta"] = num(S64.median.total() / lm);
      V["table1_ratio_m225_minus_m64_median_largest_eta"] = num((S225.median.total() - S64.median.total()) / lm);
    }
  }
  T["table1"] = t1;
  T["table1_phases"] = phases;
  T["shvd_products"] = products;
  st::log(S.opt, "Table 1 done");
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_dynamics", [&] {
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_dynamics",
        "Chapter 3 dynamic test: SHVD vs LDSM shells relaxing in periodic Stokes flow (Figs. 4-5, Table 1)");
    const Setup S(opt);

    // ---- 1. Parameters -----------------------------------------------------------------------
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["units"] = "dimensionless (mu = 1, moduli 1, reference the unit sphere), as the paper's Sec. 4";
    P["box"] = "[-2, 2]^3, periodic; steady Stokes (alpha = 0), exact inverse of the MAC operators (Sec. 3.2)";
    P["mu"] = 1.0;
    P["moduli"] =
        "neo-Hookean (eq. 68) Gs = 1, A = 1; surface tension (eq. 72) sigma = 1; total force their sum (Sec. 4.2)";
    P["kernel"] = "peskin4 (Peskin's 4-point function, the paper's [25])";
    P["time_update"] =
        "Sec. 3.3: forces at X^k, spread, Stokes solve, interpolate, X^{k+1} = X^k + dt U^{k+1} (eq. 87)";
    P["ellipsoid"] = "eq. (88), a = 1.2, b = c = 1/sqrt(1.2)";
    P["perturbed_ellipsoid"] = "eq. (89), a = 0.1, b = c = 0.2, B = 0.25, Vf = " + to_text(S.perturbed.Vf);
    P["evaluation_sites"] =
        "Bauer spiral (diss. eq. 5.1), n = 2 eta^2 + 1 (Fig. 4 full: 8281), weights diss. eq. (2.22) with "
        "phi = r^3; for comparison the stored MD sets with eq. (45) weights (table sites)";
    P["interpolation_sites"] = "(M+1)^2 maximal-determinant-like sites, M = 7 (m = 64) or 14 (m = 225)";
    P["fig4"] = "eta = " + to_text(S.fig4_eta) + ", n = " + to_text(S.fig4_n) + ", m = 225, dt = 1/64, t = 0.." +
                to_text(S.fig4_t);
    P["fig5"] = "eta = " + to_text(S.fig5_etas.front()) + ".." + to_text(S.fig5_etas.back()) +
                " (references 1.5 eta), n = 2 eta^2 + 1, m = 64, dt = 1/(2 eta), t = 3";
    P["table1"] = "eta = " + to_text(S.table1_etas.front()) + ".." + to_text(S.table1_etas.back()) +
                  ", m = 64 and 225, contraction of " + to_text(S.table1_t) + " s" +
                  (S.full ? " (the paper's 15 s)" : " (quick: shortened from the paper's 15 s; the ratio is per step)");
    P["timing"] =
        "wall time of the steps' phases (the diagnostics excluded), one thread; Table 1: the three runs of a grid "
        "(LDSM, SHVD m = 64, SHVD m = 225) advanced in lockstep, one step of each in turn; per-step phase "
        "times: the median over the steps";
    Json& T = results["tables"];
    Json& V = results["values"];
    Runs runs(opt);

    // ---- 2. Fig. 5, and the time and space parts of its error ----------------------------------
    fig5(S, runs, T, V);
    fig5_rightmost(S, runs, T, V);
    time_step(S, runs, T, V);
    space_only(S, runs, T, V);
    // ---- 3. Fig. 4, the quadrature error of the sites, the paper's sites -----------------------
    fig4(S, runs, T, V);
    quadrature(S, runs, T, V);
    sites(S, runs, T, V);
    // ---- 4. Table 1 ----------------------------------------------------------------------------
    table1(S, runs, T, V);

    runs.record(results);
    st::write_results(opt, results);
    return 0;
  });
}
