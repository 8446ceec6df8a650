// Chapter 3 capillary flow (the JCP 2018 paper, Sec. 5.1, Figs. 6-9): a red cell (eq. 92) carried
// through a tethered capillary (eqs. 93-95) by a background force, in steady Stokes flow on a
// periodic 24 um box, forces by SHVD (m = 400 and 625 interpolation sites, n evaluation sites) or
// LDSM; bending k_bend = 0, 0.1, 1 pN um (eq. 79). The model and the time update: capillary_run.hpp.
//
// Reproduces (and measures what the paper only shows):
//   empty capillary  the peak flow speed (paper: 750 um/s, Sec. 5.1.1), against the Poiseuille
//                    value f R^2 / (4 mu), for two readings of "inside the capillary" and on three
//                    grids (table capillary_flow, figure profile);
//   Fig. 6   side views of the cell at several times: LDSM, SHVD m = 625 and m = 400 (k_bend = 0);
//   Fig. 7   |force density| on the front, side and back at t = 0.05 s, LDSM and SHVD m = 400;
//   Fig. 8   H seen from the front for k_bend = 0, 0.1, 1 (SHVD m = 400), and the variability of H
//            on the front (its spread std(H), std/|mean|, the fraction with H > 0);
//   Fig. 9   cross-sections y = 0 at t = 0.005, 0.025, 0.05 s for the three k_bend;
//   also     the cell's steady velocity, the area change (paper: below 1% with A = 50), the
//            non-axisymmetric deviation of the shape and its count of bumps (m = 400 vs 625, LDSM),
//            the time per step and the time to solution of each run.
// Every run is also written as ParaView snapshots (DIR/paraview/<run>.xmf with HDF5 files).
//
// Scales. Quick (CI): eta = 48 (h = 0.5 um), n = 2,049 evaluation sites (spacing ~h/2 on the
// cell), t = 0.05 s (500 steps). Full: the paper's n = 8,281 on eta = 64 (h = 0.375 um; spacing
// h/3; the paper does not state its grid), t = 0.05 s, and the k_bend = 0 runs again on eta = 96
// (spacing h/2), where dt = 1e-4 s loses every run near t = 7 ms and dt = 5e-5 s does not (table
// runs_eta96; the reference's conventions: grid). At full scale each run keeps a checkpoint
// DIR/run_<label>_eta<eta>.h5 (the library's run loop: every 5 minutes of wall time, at the
// sitting's end and at its end, with its records as series) and continues from it when the
// command is run again; --sitting SECONDS bounds this sitting's wall time: runs left
// unfinished are reported with their time per step and projected time to solution. --resumable
// keeps checkpoints at quick scale too (to test resuming).
//
// Run:  build/studies/study_chapter3_capillary --scale quick --out runs/chapter3_capillary/quick
//       (or python3 -m harness run chapter3_capillary --scale quick)
#include "capillary_run.hpp"
#include "rbfib/core/constants.hpp"
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/io/hdf5.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

using namespace rbfib;
using namespace rbfib::capillary;
namespace st = rbfib::study;
using st::Json;

namespace {

constexpr double um = 1e-4;      // cm
constexpr double pN_um = 1e-11;  // erg (1 pN um = 1e-18 J = 1e-11 erg)

using rbfib::study::row;
Json num(double x) { return std::isfinite(x) ? Json(x) : Json(); }

/// The scale's parameters.
struct Setup {
  const st::Options& opt;
  bool full;
  bool keep;  ///< keep checkpoints (full scale, or --resumable to test them)
  int eta;
  index_t n;
  std::vector<int> flow_etas;  ///< grids of the empty-capillary study
  explicit Setup(const st::Options& o)
      : opt(o),
        full(o.scale == st::Scale::full),
        keep(o.keeps_runs()),
        eta(full ? 64 : 48),
        n(full ? 8281 : 2049),
        flow_etas(full ? std::vector<int>{64, 96, 128} : std::vector<int>{32, 48, 64}) {}
  Model base() const {
    Model m;
    m.eta = eta;
    return m;
  }
};

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

/// Full scale: the k_bend = 0 runs of Fig. 6 on two other choices the paper's bumps might depend on
/// (reference conventions: bump_variants): the stored maximal-determinant sites of n = 4,624 (the
/// paper's kind of evaluation set, with the weights of eq. 45) for the three methods, and SHVD
/// with more interpolation sites than 625 on the study's sites ("When the number of interpolation
/// points is greater than 625, we observe even more bumps", Sec. 5.1.2).
std::vector<CellCase> variant_cases() {
  return {{"LDSM_kb0_MD4624", chapter3::Method::ldsm, 19, 0.0, 67},
          {"SHVD_m625_kb0_MD4624", chapter3::Method::shvd, 24, 0.0, 67},
          {"SHVD_m400_kb0_MD4624", chapter3::Method::shvd, 19, 0.0, 67},
          {"SHVD_m900_kb0", chapter3::Method::shvd, 29, 0.0},
          {"SHVD_m1024_kb0", chapter3::Method::shvd, 31, 0.0}};
}

/// results["runs"][id] for one run (harness/FORMAT.md): a check that measures it waits for its end.
void record(Json& results, const std::string& id, const Run& run) {
  st::RunProgress p;
  p.finished = run.done();
  p.t = run.step() * run.model().dt;
  p.t_end = run.model().steps * run.model().dt;
  p.steps = run.step();
  p.seconds_per_step = run.steps_timed() > 0 ? run.phases().total() / run.steps_timed() : NAN;
  p.stopped = run.failure();
  st::record_run(results, id, p);
}

/// Runs (or resumes, or reads back) one run; at full scale keeps its checkpoint.
class Runner {
 public:
  explicit Runner(const Setup& S) : S_(S), sitting_(S.opt) {}
  double elapsed() const { return sitting_.elapsed(); }

  /// The run of model m labelled `label`, advanced to its end (or to the sitting's budget).
  std::unique_ptr<Run> go(const Model& m, const chapter3::EvaluationSet* eval, const std::string& label) {
    const std::string path = S_.opt.out_dir + "/run_" + label +
                             (label.find("_eta") == std::string::npos ? "_eta" + to_text(m.eta) : "") + ".h5";
    auto run = std::make_unique<Run>(m, eval, S_.keep ? path : std::string(), std::max(0.0, sitting_.remaining()));
    if (run->continued()) st::log(S_.opt, label + ": resumed from " + path + " at step " + to_text(run->step()));
    run->advance();
    st::log(S_.opt, label + ": step " + to_text(run->step()) + " of " + to_text(m.steps) + ", " + to_text(per_step(*run)) +
                        " s per step" + (run->failure().empty() ? std::string() : ", STOPPED: " + run->failure()));
    return run;
  }
  static double per_step(const Run& r) { return r.steps_timed() > 0 ? r.phases().total() / r.steps_timed() : NAN; }

 private:
  const Setup& S_;
  const st::Sitting sitting_;  // full scale: this sitting's wall time (--sitting)
};

// ---- shape measures ------------------------------------------------------------------------------

/// Centroid of the view's sites (for the projections; the volume centroid is in the series).
std::array<double, 3> mean_point(const View& v) {
  const std::size_t n = v.X.size() / 3;
  std::array<double, 3> c{0, 0, 0};
  for (int d = 0; d < 3; ++d) {
    for (std::size_t i = 0; i < n; ++i) c[d] += v.X[d * n + i];
    c[d] /= double(n);
  }
  return c;
}

/// H on the front: the sites facing the flow (outward normal within 45 degrees of +x) ahead of the
/// centroid. cv = std(H) / |mean(H)|; pos = the fraction of those sites with H > 0 (the library's
/// sign: H = -1/r on a sphere, so a convex front has H < 0).
struct FrontH {
  double mean = NAN, std = NAN, cv = NAN, pos = NAN;
  int sites = 0;
};
FrontH front_curvature(const View& v, const double c[3]) {
  FrontH r;
  const std::size_t n = v.X.size() / 3;
  double s = 0, s2 = 0;
  int npos = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(v.normal[i] > std::cos(pi / 4)) || !(v.X[i] > c[0]) || !std::isfinite(v.H[i])) continue;
    s += v.H[i];
    s2 += v.H[i] * v.H[i];
    npos += v.H[i] > 0;
    ++r.sites;
  }
  if (r.sites < 2) return r;
  r.mean = s / r.sites;
  r.std = std::sqrt(std::max(0.0, s2 / r.sites - r.mean * r.mean));
  r.cv = r.std / std::abs(r.mean);
  r.pos = double(npos) / r.sites;
  return r;
}

/// Deviation from axisymmetry about the axis through c parallel to x. The reference cell (eq. 92)
/// and the flow are symmetric about that axis, so material points on one reference ring (equal
/// alpha, the angle of the site from the +x axis on the sphere) would stay on one ring. Per band
/// of alpha (15-165 degrees), x and rho = |(y, z) - c| are fitted linearly in alpha; the signed
/// normal deviation d_i = (dx, drho) . (n_x, n_rho) from the fit is non-axisymmetric. rms: its RMS
/// (cm); bumps: sites where d is largest among their triangle neighbours and exceeds `tau`.
struct Asymmetry {
  double rms = NAN, max = NAN;
  int bumps = 0;
};
Asymmetry asymmetry(const View& v, const surface::SphereSites& sites, const std::vector<surface::Triangle>& tris,
                    const double c[3], double tau) {
  Asymmetry a;
  const std::size_t n = v.X.size() / 3;
  const int bands = std::max(8, int(std::lround(std::sqrt(double(n)) / 2.5)));
  const double lo = 15 * pi / 180, hi = 165 * pi / 180;
  std::vector<double> alpha(n), rho(n), nrho(n), dev(n, NAN);
  std::vector<int> band(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const double xs = std::cos(sites.lambda[i]) * std::cos(sites.theta[i]);
    alpha[i] = std::acos(std::max(-1.0, std::min(1.0, xs)));
    const double dy = v.X[n + i] - c[1], dz = v.X[2 * n + i] - c[2];
    rho[i] = std::sqrt(dy * dy + dz * dz);
    nrho[i] = rho[i] > 0 ? (v.normal[n + i] * dy + v.normal[2 * n + i] * dz) / rho[i] : 0;
    if (alpha[i] >= lo && alpha[i] <= hi) band[i] = std::min(bands - 1, int((alpha[i] - lo) / (hi - lo) * bands));
  }
  std::vector<std::vector<std::size_t>> members(bands);
  for (std::size_t i = 0; i < n; ++i)
    if (band[i] >= 0) members[band[i]].push_back(i);
  double s2 = 0;
  std::size_t count = 0;
  a.max = 0;
  for (const auto& mem : members) {
    if (mem.size() < 4) continue;
    // least-squares lines x(alpha), rho(alpha) over the band
    double sa = 0, saa = 0, sx = 0, sax = 0, sr = 0, sar = 0;
    for (std::size_t i : mem) {
      sa += alpha[i];
      saa += alpha[i] * alpha[i];
      sx += v.X[i];
      sax += alpha[i] * v.X[i];
      sr += rho[i];
      sar += alpha[i] * rho[i];
    }
    const double N = double(mem.size()), det = N * saa - sa * sa;
    const double bx = (N * sax - sa * sx) / det, ax = (sx - bx * sa) / N;
    const double br = (N * sar - sa * sr) / det, ar = (sr - br * sa) / N;
    for (std::size_t i : mem) {
      const double dx = v.X[i] - (ax + bx * alpha[i]), dr = rho[i] - (ar + br * alpha[i]);
      dev[i] = dx * v.normal[i] + dr * nrho[i];
      s2 += dev[i] * dev[i];
      a.max = std::max(a.max, std::abs(dev[i]));
      ++count;
    }
  }
  a.rms = count ? std::sqrt(s2 / double(count)) : NAN;
  // local maxima over the triangle neighbours
  std::vector<std::vector<index_t>> nb(n);
  for (const auto& t : tris)
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        if (p != q) nb[t[p]].push_back(t[q]);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(dev[i]) || !(dev[i] > tau)) continue;
    bool top = true;
    for (index_t j : nb[i]) top = top && !(std::isfinite(dev[j]) && dev[j] > dev[i]);
    a.bumps += top;
  }
  return a;
}

/// |force density| on the surface: its mean over the sites, its roughness (mean over the triangle
/// edges of ||f|_i - |f|_j|, over the mean: the site-to-site noise of Fig. 7) and its mean on the
/// back (sites behind the centroid whose normal is within 45 degrees of -x), dyn/cm^2.
struct ForceMeasures {
  double mean = NAN, roughness = NAN, back = NAN, noise = NAN;
};
/// The part of a scalar field on the cell that is not axisymmetric: per band of the reference
/// angle alpha from +x (15-165 degrees), the residual of a least-squares line in alpha; its RMS.
double nonaxisymmetric_rms(const std::vector<double>& q, const surface::SphereSites& sites) {
  const std::size_t n = q.size();
  const int bands = std::max(8, int(std::lround(std::sqrt(double(n)) / 2.5)));
  const double lo = 15 * pi / 180, hi = 165 * pi / 180;
  std::vector<std::vector<std::size_t>> members(bands);
  std::vector<double> alpha(n);
  for (std::size_t i = 0; i < n; ++i) {
    alpha[i] = std::acos(std::max(-1.0, std::min(1.0, std::cos(sites.lambda[i]) * std::cos(sites.theta[i]))));
    if (alpha[i] >= lo && alpha[i] <= hi) members[std::min(bands - 1, int((alpha[i] - lo) / (hi - lo) * bands))].push_back(i);
  }
  double s2 = 0;
  std::size_t count = 0;
  for (const auto& mem : members) {
    if (mem.size() < 4) continue;
    double sa = 0, saa = 0, sq = 0, saq = 0;
    for (std::size_t i : mem) {
      sa += alpha[i];
      saa += alpha[i] * alpha[i];
      sq += q[i];
      saq += alpha[i] * q[i];
    }
    const double N = double(mem.size()), b = (N * saq - sa * sq) / (N * saa - sa * sa), a = (sq - b * sa) / N;
    for (std::size_t i : mem) {
      const double d = q[i] - (a + b * alpha[i]);
      s2 += d * d;
      ++count;
    }
  }
  return count ? std::sqrt(s2 / double(count)) : NAN;
}
ForceMeasures force_measures(const View& v, const std::vector<surface::Triangle>& tris,
                             const surface::SphereSites& sites, const double c[3]) {
  ForceMeasures r;
  const std::size_t n = v.f.size();
  if (n == 0) return r;
  double s = 0, sb = 0, se = 0;
  int nb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    s += v.f[i];
    if (v.normal[i] < -std::cos(pi / 4) && v.X[i] < c[0]) {
      sb += v.f[i];
      ++nb;
    }
  }
  for (const auto& t : tris)
    for (int p = 0; p < 3; ++p) se += std::abs(v.f[t[p]] - v.f[t[(p + 1) % 3]]);
  r.mean = s / double(n);
  r.roughness = tris.empty() ? NAN : se / (3.0 * double(tris.size())) / r.mean;
  r.back = nb ? sb / nb : NAN;
  r.noise = nonaxisymmetric_rms(v.f, sites) / r.mean;
  return r;
}

// ---- figure rows ----------------------------------------------------------------------------------

/// Projects the sites facing the viewer (normal . toward > 0) onto screen axes e1, e2 (um), shifted
/// so that `centre` lands at (ox, oy) (absolute positions when centre is null), at most `cap` sites.
struct FigRow {
  std::string panel, label;
  double a, b;
};
/// Appends the rows to a figure table, ordered by label (so that the legend lists bins in order).
void push_sorted(Json& table, std::vector<FigRow> rows) {
  std::stable_sort(rows.begin(), rows.end(), [](const FigRow& p, const FigRow& q) { return p.label < q.label; });
  for (const FigRow& r : rows) table["rows"].push(row({r.panel, r.label, r.a, r.b}));
}

template <class Label>
void project(std::vector<FigRow>& table, const std::string& panel, const View& v, const double toward[3], const double e1[3],
             const double e2[3], const double* centre, double ox, double oy, int cap, Label label) {
  const std::size_t n = v.X.size() / 3;
  std::vector<std::size_t> vis;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = v.normal[i] * toward[0] + v.normal[n + i] * toward[1] + v.normal[2 * n + i] * toward[2];
    if (d > 0) vis.push_back(i);
  }
  // at most `cap` of them, picked by a fixed hash of the index (a stride along the spiral would draw
  // its own stripes)
  if (vis.size() > std::size_t(cap)) {
    auto hash = [](std::size_t i) { return (std::uint64_t(i) * 2654435761u) % 4294967296u; };
    std::sort(vis.begin(), vis.end(), [&](std::size_t a, std::size_t b) { return hash(a) < hash(b); });
    vis.resize(std::size_t(cap));
  }
  for (std::size_t i : vis) {
    double p[3] = {v.X[i], v.X[n + i], v.X[2 * n + i]};
    if (centre)
      for (int d = 0; d < 3; ++d) p[d] -= centre[d];
    const double a = (p[0] * e1[0] + p[1] * e1[1] + p[2] * e1[2]) / um + ox;
    const double b = (p[0] * e2[0] + p[1] * e2[1] + p[2] * e2[2]) / um + oy;
    table.push_back(FigRow{panel, label(i), a, b});
  }
}

/// Bin label of x among ascending edges, with units, led by the bin's number (so that the labels
/// sort in the order of the bins).
std::string bin(double x, const std::vector<double>& edges, const std::string& name, const std::string& unit) {
  std::ostringstream s;
  s.precision(3);
  if (!std::isfinite(x)) return name + " n/a";
  if (x < edges.front()) {
    s << "0: " << name << " < " << edges.front() << " " << unit;
    return s.str();
  }
  for (std::size_t k = 0; k + 1 < edges.size(); ++k)
    if (x < edges[k + 1]) {
      s << k + 1 << ": " << name << " " << edges[k] << " to " << edges[k + 1] << " " << unit;
      return s.str();
    }
  s << edges.size() << ": " << name << " >= " << edges.back() << " " << unit;
  return s.str();
}

/// The capillary wall's trace in the plane y = 0: z = +-R for x in [x0, x1] (um), shifted.
void wall_rows(std::vector<FigRow>& t, const std::string& panel, const Model& m, double ox, double oy,
               const std::string& label) {
  for (int s : {-1, 1})
    for (int i = 0; i <= 64; ++i)
      t.push_back(FigRow{panel, label, (m.x0_cap + (m.x1_cap - m.x0_cap) * i / 64) / um + ox, s * m.R_cap / um + oy});
}

/// What the checks need from a finished cell run (CGS).
struct Summary {
  double v_cell, cv, std, rms, bumps, roughness, back, noise;
};

const View* view_at(const Run& r, double t) {
  const View* best = nullptr;
  for (const View& v : r.views())
    if (!best || std::abs(v.t - t) < std::abs(best->t - t)) best = &v;
  return best;
}

// ---- ParaView snapshots ---------------------------------------------------------------------------

/// DIR/paraview/<label>.xmf with one HDF5 file per kept surface state (cell: points, triangles,
/// |force density|, H) and the capillary's nodes and triangles (its reference; it moves by less
/// than the largest displacement in table runs).
void write_snapshots(const std::string& dir, const std::string& label, const Run& run) {
  namespace h5 = rbfib::io::h5;
  std::filesystem::create_directories(dir);
  const std::vector<double>& Z = run.capillary_reference();
  const index_t nc = index_t(Z.size() / 3);
  const int na = run.capillary_around(), nl = run.capillary_along();
  const std::string capfile = "capillary_eta" + to_text(run.model().eta) + ".h5";
  long long ncap_tris = 0;
  {
    std::vector<double> P(3 * nc);
    for (index_t q = 0; q < nc; ++q)
      for (int d = 0; d < 3; ++d) P[3 * q + d] = Z[d * nc + q] / um;
    std::vector<long long> T;
    for (int j = 0; j + 1 < nl; ++j)
      for (int i = 0; i < na; ++i) {
        const long long a = j * na + i, b = j * na + (i + 1) % na, c = (j + 1) * na + i, d = (j + 1) * na + (i + 1) % na;
        T.insert(T.end(), {a, b, c, b, d, c});
      }
    ncap_tris = (long long)(T.size() / 3);
    h5::Id f = h5::create_file(dir + "/" + capfile);
    h5::Id g = h5::create_group(f, "capillary");
    h5::write(g, "points", P.data(), {hsize_t(nc), 3}, "um");
    h5::write(g, "triangles", T.data(), {hsize_t(ncap_tris), 3});
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"" << label << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const auto& tris = run.triangles();
  for (std::size_t s = 0; s < run.views().size(); ++s) {
    const View& v = run.views()[s];
    const index_t n = index_t(v.X.size() / 3);
    const std::string file = label + "_" + to_text(s) + ".h5";
    {
      std::vector<double> P(3 * n), f(n), H(n);
      for (index_t i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d) P[3 * i + d] = v.X[d * n + i] / um;
        f[i] = v.f[i] * 1e-3;
        H[i] = v.H[i] * um;
      }
      std::vector<long long> T;
      for (const auto& t : tris) T.insert(T.end(), {(long long)t[0], (long long)t[1], (long long)t[2]});
      h5::Id fh = h5::create_file(dir + "/" + file);
      h5::attribute(fh, "t", v.t);
      h5::Id g = h5::create_group(fh, "cell");
      h5::write(g, "points", P.data(), {hsize_t(n), 3}, "um");
      h5::write(g, "triangles", T.data(), {hsize_t(tris.size()), 3});
      h5::write(g, "force_density", f.data(), {hsize_t(n)}, "pN/um^2");
      h5::write(g, "mean_curvature", H.data(), {hsize_t(n)}, "1/um");
    }
    auto item = [](const std::string& dims, const std::string& type, const std::string& path) {
      return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type + "\" Precision=\"8\" Format=\"HDF\">" + path +
             "</DataItem>";
    };
    x << "   <Grid Name=\"t" << s << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "    <Time Value=\"" << v.t << "\"/>\n"
      << "    <Grid Name=\"cell\" GridType=\"Uniform\">\n"
      << "     <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << tris.size() << "\">"
      << item(to_text(tris.size()) + " 3", "Int", file + ":/cell/triangles") << "</Topology>\n"
      << "     <Geometry GeometryType=\"XYZ\">" << item(to_text(n) + " 3", "Float", file + ":/cell/points")
      << "</Geometry>\n"
      << "     <Attribute Name=\"force_density_pN_per_um2\" AttributeType=\"Scalar\" Center=\"Node\">"
      << item(to_text(n), "Float", file + ":/cell/force_density") << "</Attribute>\n"
      << "     <Attribute Name=\"mean_curvature_per_um\" AttributeType=\"Scalar\" Center=\"Node\">"
      << item(to_text(n), "Float", file + ":/cell/mean_curvature") << "</Attribute>\n"
      << "    </Grid>\n"
      << "    <Grid Name=\"capillary\" GridType=\"Uniform\">\n"
      << "     <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << ncap_tris << "\">"
      << item(to_text(ncap_tris) + " 3", "Int", capfile + ":/capillary/triangles") << "</Topology>\n"
      << "     <Geometry GeometryType=\"XYZ\">" << item(to_text(nc) + " 3", "Float", capfile + ":/capillary/points")
      << "</Geometry>\n"
      << "    </Grid>\n"
      << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  std::ofstream(dir + "/" + label + ".xmf") << x.str();
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_capillary", [&] {
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_capillary",
        "Chapter 3 Sec. 5.1: a red cell through a tethered capillary, SHVD vs LDSM (Figs. 6-9)");
    const Setup S(opt);
    Runner runner(S);
    const Model base = S.base();

    // ---- 1. Parameters ---------------------------------------------------------------------------
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["units"] = "tables in um, s, pN (1 pN/um = 1e-3 dyn/cm, 1 pN um = 1e-11 erg); computed in CGS";
    P["box_um"] = "[-12, 12]^3, periodic; steady Stokes (alpha = 0), exact inverse of the MAC operators";
    P["eta"] = S.eta;
    P["h_um"] = base.h() / um;
    P["mu_cP"] = base.mu * 100;
    P["background_force_pN_per_um3"] = base.f_in * 1e-5;  // 1 dyn/cm^3 = 1e-5 pN/um^3
    P["capillary"] = "tethered nodes on r = 5 um, x in [-8, 8] um, k_teth = 2.45 pN/um per node (eq. 93), node "
                     "spacing h/2; eqs. (94)-(95) for the constant velocity";
    P["cell"] = "eq. (92), R = 3.91 um, centred at (-8, 0, 0) um; neo-Hookean eq. (68) Gs = 2.5 pN/um, A = 50; "
                "bending eq. (79) k_bend = 0, 0.1, 1 pN um";
    P["n_evaluation_sites"] = double(S.n);
    P["evaluation_sites"] = "Bauer spiral with the weights of diss. eq. (2.22), phi = r^3 (as chapter3_dynamics)";
    P["interpolation_sites"] = "maximal-determinant-like (M+1)^2 sites, M = 19 (m = 400) and 24 (m = 625)";
    P["dt_s"] = base.dt;
    P["t_end_s"] = base.dt * base.steps;
    P["kernel"] = "peskin4";
    Json& T = results["tables"];
    Json& V = results["values"];
    const double poiseuille = base.f_in * base.R_cap * base.R_cap / (4 * base.mu);  // cm/s
    V["poiseuille_um_s"] = poiseuille / um;

    // ---- 2. The empty capillary ------------------------------------------------------------------
    // Two frames: the capillary's (u_c of eq. 95 added, the wall at rest) and the solver's (the
    // periodic solution with zero mean velocity, before u_c is added).
    Json flow = st::table({"region", "eta", "h_um", "capillary_nodes", "u_max_um_s", "u_max_zero_mean_um_s",
                           "u_axis_x0_um_s", "u_max_change_last_half", "poiseuille_um_s", "paper_um_s",
                           "rel_diff_paper", "rel_diff_paper_zero_mean", "cap_disp_um", "seconds"},
                          {"", "", "um", "", "um/s", "um/s", "um/s", "", "um/s", "um/s", "", "", "um", "s"});
    Json profile = st::table({"series", "z_um", "u_um_s"}, {"", "um", "um/s"});
    double u_max_empty = NAN;  // um/s, the capillary's frame
    std::vector<std::pair<Region, int>> flow_cases;
    for (int e : S.flow_etas) flow_cases.emplace_back(Region::core, e);
    flow_cases.emplace_back(Region::segment, S.eta);
    for (const auto& [region, eta] : flow_cases) {
      Model m = base;
      m.with_cell = false;
      m.region = region;
      m.eta = eta;
      m.steps = 100;  // the flow is steady within a few steps (column u_max_change_last_half)
      m.record_every = 10;
      m.view_every = m.steps;
      const std::string label = std::string("empty_") + to_string(region) + "_eta" + to_text(eta);
      const std::unique_ptr<Run> ran = runner.go(m, nullptr, label);
      const Run& run = *ran;
      const bool over = run.done();
      // the study's grid under the id the checks name at both scales
      record(results, region == Region::core && eta == S.eta ? std::string("empty_core") : label, run);
      const auto& ser = run.series();
      // the peak of the last step, and of the step at half the run
      double umax = NAN, uraw = NAN, uhalf = NAN;
      for (const Sample& q : ser)
        if (std::isfinite(q.u_max)) {
          if (q.t <= 0.5 * m.dt * m.steps + 1e-12) uhalf = q.u_max;
          umax = q.u_max;
          uraw = q.u_max - q.uc[0];
        }
      if (!over || !run.failure().empty()) umax = uraw = NAN;
      double u_axis = NAN, best = 1e300;
      const std::vector<std::array<double, 2>> prof = run.profile_x(0.0);
      for (const auto& zu : prof)
        if (std::abs(zu[0]) < best) {
          best = std::abs(zu[0]);
          u_axis = zu[1];
        }
      flow["rows"].push(row({to_string(region), eta, m.h() / um, double(run.capillary_reference().size() / 3),
                             num(umax / um), num(uraw / um), num(u_axis / um), num(std::abs(umax - uhalf) / umax),
                             poiseuille / um, 750, num((umax / um - 750) / 750), num((uraw / um - 750) / 750),
                             ser.empty() ? Json() : num(ser.back().cap_disp / um), run.phases().total()}));
      for (const auto& zu : prof)
        profile["rows"].push(row({std::string(to_string(region)) + " eta = " + to_text(eta), zu[0] / um, zu[1] / um}));
      if (region == Region::core && eta == S.eta) {
        u_max_empty = umax / um;
        V["u_max_empty_um_s"] = num(umax / um);
        V["u_max_empty_zero_mean_um_s"] = num(uraw / um);
        V["u_axis_empty_um_s"] = num(u_axis / um);
        V["u_max_over_poiseuille"] = num(umax / poiseuille);
        V["u_max_rel_diff_paper"] = num((umax / um - 750) / 750);
        V["u_max_zero_mean_rel_diff_paper"] = num((uraw / um - 750) / 750);
        V["empty_seconds"] = run.phases().total();
      }
      st::log(opt, label + ": u_max " + to_text(umax / um) + " um/s with the wall at rest, " + to_text(uraw / um) +
                       " um/s in the zero-mean frame (Poiseuille " + to_text(poiseuille / um) + ", paper 750)");
    }
    for (double z = -5; z <= 5.0001; z += 0.125)
      profile["rows"].push(row({"Poiseuille f R^2/(4 mu) (1 - r^2/R^2)", z, poiseuille / um * (1 - z * z / 25)}));
    T["capillary_flow"] = flow;
    T["profile"] = profile;

    // ---- 3. The cell runs --------------------------------------------------------------------------
    const chapter3::EvaluationSet eval = chapter3::make_evaluation_set(S.n);
    st::log(opt, "evaluation set n = " + to_text(S.n) + " in " + to_text(eval.seconds) + " s");
    std::map<int, chapter3::EvaluationSet> md_sets;  // the stored MD sets of the variants, by degree
    auto sites_of = [&](const CellCase& cc) -> const chapter3::EvaluationSet& {
      if (cc.md_degree < 0) return eval;
      auto it = md_sets.find(cc.md_degree);
      if (it == md_sets.end()) {
        const std::string file =
            st::source_path(opt, "reference/point_sets/max_determinant_N" + to_text(cc.md_degree) + ".txt");
        it = md_sets.emplace(cc.md_degree, chapter3::make_md_evaluation_set(file, cc.md_degree)).first;
        st::log(opt, "MD evaluation set N = " + to_text(cc.md_degree) + " (eq. 45 weights) in " +
                         to_text(it->second.seconds) + " s");
      }
      return it->second;
    };
    Json runs_t = st::table({"run", "eta", "dt", "method", "m", "k_bend_pN_um", "status", "steps_done", "steps_needed",
                             "seconds", "seconds_per_step", "time_to_solution_s", "area_change_max",
                             "volume_change", "v_cell_um_s", "v_over_u_max", "front_H_cv", "front_H_std_per_um",
                             "front_H_positive_fraction", "nonaxisymmetric_rms_um", "nonaxisymmetric_max_um",
                             "bumps", "f_mean_pN_um2", "f_roughness", "f_noise", "f_back_mean_pN_um2", "cap_disp_um", "failed",
                             "sites", "n"},
                            {"", "", "s", "", "", "pN um", "", "", "", "s", "s", "s", "", "", "um/s", "", "", "1/um", "", "um",
                             "um", "", "pN/um^2", "", "", "pN/um^2", "um", "", "", ""});
    Json series_t = st::table({"run", "t", "cx_um", "area_change", "volume_change", "v_cell_um_s", "uc_x_um_s",
                               "max_force_density_pN_um2"},
                              {"", "s", "um", "", "", "um/s", "um/s", "pN/um^2"});
    std::map<std::string, std::unique_ptr<Run>> done;
    std::map<std::string, Summary> summary;
    const double tau = 0.1 * um;  // bump height threshold (see the reference's conventions)
    // One cell run on grid eta: its row in `table`; the study's own grid (main) also gives the series,
    // the values of the checks, the figures and the snapshots.
    auto run_case = [&](const CellCase& cc, int eta, Json& table, bool main, double dt) {
      Model m = base;
      m.eta = eta;
      if (dt != base.dt) {  // the same times (t = 0.05 s, records every 2.5 ms, views every 5 ms)
        m.dt = dt;
        m.steps = int(std::lround(base.steps * base.dt / dt));
        m.record_every = int(std::lround(base.record_every * base.dt / dt));
        m.view_every = int(std::lround(base.view_every * base.dt / dt));
      }
      std::ostringstream dts;
      dts << dt;
      const std::string label =
          main ? cc.label : cc.label + "_eta" + to_text(eta) + (dt != base.dt ? "_dt" + dts.str() : std::string());
      m.method = cc.method;
      m.M = cc.M;
      m.k_bend = cc.k_bend_pN_um * pN_um;
      const chapter3::EvaluationSet& e = sites_of(cc);
      std::unique_ptr<Run> run = runner.go(m, &e, label);
      const bool over = run->done();
      record(results, label, *run);
      const int mm = (cc.M + 1) * (cc.M + 1);
      const double per = Runner::per_step(*run);
      const auto& ser = run->series();
      double dA = 0, dV = NAN, v_cell = NAN, disp = NAN;
      if (!ser.empty()) {
        const Sample& s0 = ser.front();
        for (const Sample& s : ser) {
          dA = std::max(dA, std::abs(s.area / s0.area - 1));
          double v = NAN;
          for (const Sample& q : ser)
            if (std::abs(q.t - (s.t - 0.005)) < 1e-9) v = (s.c[0] - q.c[0]) / 0.005;
          if (main)
            series_t["rows"].push(row({cc.label, s.t, s.c[0] / um, s.area / s0.area - 1, s.volume / s0.volume - 1,
                                     num(v / um), num(s.uc[0] / um), num(s.max_density * 1e-3)}));
          if (std::isfinite(v)) v_cell = v;
        }
        dV = ser.back().volume / s0.volume - 1;
        disp = ser.back().cap_disp;
      }
      const bool ok = over && run->failure().empty();
      FrontH fh;
      Asymmetry as;
      ForceMeasures fm;
      if (ok) {
        const View& vf = run->views().back();
        const double c[3] = {ser.back().c[0], ser.back().c[1], ser.back().c[2]};
        if (cc.method == chapter3::Method::shvd) fh = front_curvature(vf, c);
        as = asymmetry(vf, e.sites, e.tris, c, tau);
        fm = force_measures(vf, e.tris, e.sites, c);
      }
      const std::string status = !over ? (run->step() > 0 ? "partial" : "not started")
                                       : (run->failure().empty() ? "finished" : "stopped: " + run->failure());
      table["rows"].push(row({cc.label, eta, m.dt, chapter3::to_string(cc.method), cc.method == chapter3::Method::shvd ? Json(mm) : Json(),
                               cc.k_bend_pN_um, status, run->step(), m.steps, run->phases().total(), num(per),
                               num(per * m.steps), ok ? num(dA) : Json(), ok ? num(dV) : Json(),
                               ok ? num(v_cell / um) : Json(), ok ? num(v_cell / um / u_max_empty) : Json(), num(fh.cv),
                               num(fh.std * um), num(fh.pos), num(as.rms / um), num(as.max / um),
                               ok ? Json(as.bumps) : Json(), num(fm.mean * 1e-3), num(fm.roughness),
                               num(fm.noise), num(fm.back * 1e-3), num(disp / um), run->failure().empty() ? 0 : 1,
                               e.family + " " + to_text(e.size()), double(e.size())}));
      st::log(opt, label + ": " + status + ", area change " + to_text(dA) + ", v_cell " + to_text(v_cell / um) +
                       " um/s, front H cv " + to_text(fh.cv) + ", asymmetry rms " + to_text(as.rms / um) +
                       " um, bumps " + to_text(as.bumps));
      if (!run->views().empty()) write_snapshots(opt.out_dir + "/paraview", label, *run);
      if (ok) summary[label] = Summary{v_cell, fh.cv, fh.std, as.rms, double(as.bumps), fm.roughness, fm.back, fm.noise};
      if (!main) return;
      done[cc.label] = std::move(run);
    };
    Json runs96 = runs_t, variants = runs_t;  // (empty: the same columns)
    for (const CellCase& cc : cell_cases()) run_case(cc, S.eta, runs_t, true, base.dt);
    // Full scale: the variants of the k_bend = 0 runs on the study's grid (table runs_variants).
    if (S.full)
      for (const CellCase& cc : variant_cases()) run_case(cc, S.eta, variants, false, base.dt);
    // Full scale: the k_bend = 0 runs again on eta = 96 (sites h/2 apart), where the bumps and LDSM's
    // stability differ (reference conventions: grid).
    // There every run loses its surface near t = 7 ms with dt = 1e-4 s; LDSM and SHVD m = 400 again
    // with dt = 5e-5 s tell whether the time step is the cause.
    if (S.full) {
      for (const CellCase& cc : cell_cases())
        if (cc.k_bend_pN_um == 0) run_case(cc, 96, runs96, false, base.dt);
      for (const CellCase& cc : cell_cases())
        if (cc.label == "LDSM_kb0" || cc.label == "SHVD_m400_kb0") run_case(cc, 96, runs96, false, base.dt / 2);
    }
    T["runs"] = runs_t;
    if (S.full) T["runs_eta96"] = runs96;
    if (S.full) T["runs_variants"] = variants;
    T["series"] = series_t;

    // ---- 4. Values for the checks -----------------------------------------------------------------
    auto get = [&](const std::string& label, double Summary::*field) {
      auto it = summary.find(label);
      return it == summary.end() ? NAN : it->second.*field;
    };
    V["v_cell_um_s"] = num(get("SHVD_m400_kb0.1", &Summary::v_cell) / um);
    V["v_cell_over_u_max"] = num(get("SHVD_m400_kb0.1", &Summary::v_cell) / um / u_max_empty);
    V["front_H_std_ratio_kb0.1_over_kb0"] =
        num(get("SHVD_m400_kb0.1", &Summary::std) / get("SHVD_m400_kb0", &Summary::std));
    V["front_H_std_ratio_kb1_over_kb0.1"] =
        num(get("SHVD_m400_kb1", &Summary::std) / get("SHVD_m400_kb0.1", &Summary::std));
    V["front_H_cv_ratio_kb0.1_over_kb0"] = num(get("SHVD_m400_kb0.1", &Summary::cv) / get("SHVD_m400_kb0", &Summary::cv));
    V["front_H_cv_ratio_kb1_over_kb0.1"] = num(get("SHVD_m400_kb1", &Summary::cv) / get("SHVD_m400_kb0.1", &Summary::cv));
    V["bumps_m625_minus_m400"] = num(get("SHVD_m625_kb0", &Summary::bumps) - get("SHVD_m400_kb0", &Summary::bumps));
    V["nonaxisymmetric_rms_ratio_m625_over_m400"] =
        num(get("SHVD_m625_kb0", &Summary::rms) / get("SHVD_m400_kb0", &Summary::rms));
    V["nonaxisymmetric_rms_ratio_LDSM_over_m400"] = num(get("LDSM_kb0", &Summary::rms) / get("SHVD_m400_kb0", &Summary::rms));
    // the variants (full scale): more interpolation sites than 625 against m = 625 (Sec. 5.1.2: "even
    // more bumps"), and the three methods on the stored MD sites
    for (const std::string m : {"m900", "m1024"}) {
      const std::string lab = "SHVD_" + m + "_kb0_eta" + to_text(S.eta);
      V["nonaxisymmetric_rms_ratio_" + m + "_over_m625"] = num(get(lab, &Summary::rms) / get("SHVD_m625_kb0", &Summary::rms));
      V["bumps_" + m + "_minus_m625"] = num(get(lab, &Summary::bumps) - get("SHVD_m625_kb0", &Summary::bumps));
    }
    {
      const std::string md = "_kb0_MD4624_eta" + to_text(S.eta);
      V["nonaxisymmetric_rms_ratio_m625_over_m400_MD4624"] =
          num(get("SHVD_m625" + md, &Summary::rms) / get("SHVD_m400" + md, &Summary::rms));
      V["nonaxisymmetric_rms_ratio_LDSM_over_m400_MD4624"] =
          num(get("LDSM" + md, &Summary::rms) / get("SHVD_m400" + md, &Summary::rms));
      V["bumps_m625_minus_m400_MD4624"] = num(get("SHVD_m625" + md, &Summary::bumps) - get("SHVD_m400" + md, &Summary::bumps));
    }
    V["f_roughness_ratio_LDSM_over_m400"] =
        num(get("LDSM_kb0", &Summary::roughness) / get("SHVD_m400_kb0", &Summary::roughness));
    V["f_noise_ratio_LDSM_over_m400"] = num(get("LDSM_kb0", &Summary::noise) / get("SHVD_m400_kb0", &Summary::noise));
    V["f_back_ratio_LDSM_over_m400"] = num(get("LDSM_kb0", &Summary::back) / get("SHVD_m400_kb0", &Summary::back));
    V["wall_seconds"] = runner.elapsed();

    // ---- 5. Figures' rows ---------------------------------------------------------------------------
    const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1}, mx[3] = {-1, 0, 0}, my[3] = {0, -1, 0};
    const int cap = S.full ? 900 : 700;  // sites per panel (results.json stays about 1 MB)
    // Fig. 6: side views (from -y) at several times, absolute x; the capillary's wall.
    {
      std::vector<FigRow> rows;
      const std::vector<double> times = {0.0, 0.01, 0.025, 0.05};
      int p = 0;
      for (const std::string lab : {"LDSM_kb0", "SHVD_m625_kb0", "SHVD_m400_kb0"}) {
        const Run& r = *done[lab];
        const double oy = -14.0 * p++;
        wall_rows(rows, lab, r.model(), 0, oy, "capillary wall");
        for (double t : times) {
          const View* v = view_at(r, t);
          if (!v || std::abs(v->t - t) > 1e-9) continue;
          std::ostringstream l;
          l << "t = " << t << " s";
          project(rows, lab, *v, my, ex, ez, nullptr, 0, oy, cap / 2, [&](std::size_t) { return l.str(); });
        }
      }
      Json t = st::table({"panel", "label", "x_um", "z_um"}, {"", "", "um", "um"});
      push_sorted(t, rows);
      T["fig6"] = t;
    }
    // Fig. 7: |force density| on the front (from +x), side (from -y), back (from -x) at the end.
    {
      std::vector<double> all, edges;
      for (const std::string lab : {"LDSM_kb0", "SHVD_m400_kb0"})
        if (!done[lab]->views().empty())
          all.insert(all.end(), done[lab]->views().back().f.begin(), done[lab]->views().back().f.end());
      std::sort(all.begin(), all.end());
      const double top = all.empty() ? 1 : all[std::size_t(0.95 * double(all.size() - 1))] * 1e-3;
      const double step = std::max(1e-3, std::round(top / 5 * 1000) / 1000);
      for (int k = 0; k <= 5; ++k) edges.push_back(k * step);
      std::vector<FigRow> rows;
      int p = 0;
      for (const std::string lab : {"LDSM_kb0", "SHVD_m400_kb0"}) {
        const Run& r = *done[lab];
        if (r.views().empty()) continue;
        const View& v = r.views().back();
        const std::array<double, 3> c = mean_point(v);
        const double oy = -12.0 * p++;
        auto lf = [&](std::size_t i) { return bin(v.f[i] * 1e-3, edges, "|f|", "pN/um^2"); };
        project(rows, lab + " front", v, ex, ey, ez, c.data(), 0, oy, cap, lf);
        project(rows, lab + " side", v, my, ex, ez, c.data(), 11, oy, cap, lf);
        project(rows, lab + " back", v, mx, my, ez, c.data(), 22, oy, cap, lf);
      }
      Json t = st::table({"panel", "label", "x_um", "z_um"}, {"", "", "um", "um"});
      push_sorted(t, rows);
      T["fig7"] = t;
    }
    // Fig. 8: H from the front for k_bend = 0, 0.1, 1.
    {
      const std::vector<double> edges = {-0.6, -0.45, -0.3, -0.15, 0.0, 0.15};
      std::vector<FigRow> rows;
      int p = 0;
      for (const std::string lab : {"SHVD_m400_kb0", "SHVD_m400_kb0.1", "SHVD_m400_kb1"}) {
        const Run& r = *done[lab];
        if (r.views().empty()) continue;
        const View& v = r.views().back();
        const std::array<double, 3> c = mean_point(v);
        project(rows, lab, v, ex, ey, ez, c.data(), 11.0 * p++, 0, cap,
                [&](std::size_t i) { return bin(v.H[i] * um, edges, "H", "1/um"); });
      }
      Json t = st::table({"panel", "label", "y_um", "z_um"}, {"", "", "um", "um"});
      push_sorted(t, rows);
      T["fig8"] = t;
    }
    // Fig. 9: cross-sections y = 0 at t = 0.005, 0.025, 0.05 s, one panel per k_bend (stacked).
    {
      std::vector<FigRow> rows;
      const double slab = 0.6 * std::sqrt(135.0 / double(S.n)) * um;  // ~0.6 site spacings
      int p = 0;
      for (const std::string lab : {"SHVD_m400_kb0", "SHVD_m400_kb0.1", "SHVD_m400_kb1"}) {
        const Run& r = *done[lab];
        const double oy = -13.0 * p++;
        wall_rows(rows, lab, r.model(), 0, oy, "capillary wall");
        for (double t : {0.005, 0.025, 0.05}) {
          const View* v = view_at(r, t);
          if (!v || std::abs(v->t - t) > 1e-9) continue;
          const std::size_t n = v->X.size() / 3;
          std::ostringstream l;
          l << "t = " << t << " s";
          for (std::size_t i = 0; i < n; ++i)
            if (std::abs(v->X[n + i]) < slab) rows.push_back(FigRow{lab, l.str(), v->X[i] / um, v->X[2 * n + i] / um + oy});
        }
      }
      Json t = st::table({"panel", "label", "x_um", "z_um"}, {"", "", "um", "um"});
      push_sorted(t, rows);
      T["fig9"] = t;
    }

    st::write_results(opt, results);
    return 0;
  });
}
