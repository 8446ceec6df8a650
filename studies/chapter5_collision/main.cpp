// Reproduces seed Sec. 5.1.3, Fig. 5.3: collision tests. Two red cells (the full model of Sec. 2.2:
// Skalak, bending, dissipation; the red_cell preset) in the 16 um box with walls at rest in y
// (periodic in x and z), fluid at rest; Peskin's two-stage scheme (the seed's coupling (a)-(g)),
// the 4-point cosine kernel; centres on the line x = z, y = 8 um, the gap between the cells'
// convex hulls (concavities ignored) 4h along d = (e1 + e3)/sqrt 2; each cell pushed toward the
// other by the fictitious force density F_fict (below). Four orientations (Fig. 5.3):
//   a-b  concavities facing: both symmetry axes along d;
//   c-d  edges facing: both axes along e2 (the disks in the plane y = 8 um, seen edge-on from
//        above the plane x = z, where the profile shows the concavities);
//   e-f  the edge of cell 2 (axis e2) facing the concavity of cell 1 (axis d);
//   g-h  as c-d with cell 2 turned by pi/2 about e1 + e3 (its axis along (e1 - e3)/sqrt 2).
// Plasma: rho = 1 g/cm^3, mu = 1 cP, the viscosity every version read of the dissertation's public
// collision and whole-blood drivers passes (Sec. 2.1 writes 0.1 cP and says plasma "behaves like
// water", which is about 1 cP); at full scale a variant with the text's 0.1 cP at h = 0.5 um.
// Resolutions: the seed's, h = 0.2 um (80^3), n_d = 2,500, n_s = 10,000, dt = 50 ns; and
// h = 0.5 um (32^3), n_d = 400, n_s = 1,600 (n h^2 as the seed's: the sites' spacing in units of h
// is the same), dt = 100 ns. Quick scale: h = 0.5 um to 60 us. Full scale: each run to 10 ms (the
// end time of the seed's public driver) or until eq. 5.4 stops it, as the seed's runs all end:
// h = 0.5 um at 1 cP and at 0.1 cP, then h = 0.2 um.
//
// The fictitious force. The seed writes F_fict = +-0.1 dyn/cm (e1 + e3)/sqrt 2 and calls it a
// force density; a Lagrangian force density (eq. 2.24: f = sum_j dA_j F(X_j) delta_h) is a force
// per unit reference area, dyn/cm^2, so dyn/cm lacks a length. The dissertation's public collision
// driver supplies the convention that restores it (not the value: its coefficient is 1e-3 dyn/cm,
// and in its version at the seed's resolution the constant force is declared but left out of the
// forces it sums). There a coefficient c is an energy per area (dyn/cm); each sample site gets
// c dA0 (dA0 its reference area weight), a number of dimension energy that the solver takes as the
// site's force F_j dA_j. Its code units are 10 um, 1 ug and 1 ms: 1 dyn/cm is one unit of energy
// per area, 1e-6 cm^2 one unit of area and 1e-3 dyn one unit of force, so the site's force is
//   c [dyn/cm] * (dA0 / 1e-6 cm^2) * 1e-3 dyn = (c / 10 um) dA0,
// the missing length being the code's unit of length. With the text's c = 0.1 dyn/cm:
// F_fict = 100 dyn/cm^2 per unit reference area, uniform over the cell, a total force
// F_fict A0 = 1.3419e-4 dyn per cell (A0 = 134.19 um^2, Evans-Fung), equal and opposite on the two
// cells (no net force on the fluid). A constant total force per cell spread in proportion to dA0
// (cells::Batch::set_body_force, the scene's cells[i].force) is exactly this uniform density.
// The public coefficient (1e-3 dyn/cm: 1 dyn/cm^2, 1.3e-6 dyn per cell, F / (E R0) = 1.4) would
// move a cell about 0.2 um per ms at 1 cP and reach about 1e-4 of eq. 5.4's bound: neither the
// figure's "considerable deformation" by 1.1-1.5 ms nor the stop.
//
// Measured: every few steps the minimum distance between the two cells' sample sites (the
// nearest periodic image in x and z), the distance of their centroids along d, their volumes,
// max |u| and dt / (eq. 5.4's bound); the cells' outlines seen from above the plane x = z (the
// sample sites within h/2 of that plane, and the silhouette of all sites, in the coordinates
// s = X.d - 8 sqrt 2 um and y) and each cell's extents along d, e2 and (e1 - e3)/sqrt 2 (its
// depth along the push over its width: a hemisphere with its flat face toward the other cell
// gives 1/2) at t = 0, mid-run (full: the seed's figure time) and the end; the time and step at
// which eq. 5.4 (or another numerical failure) stops a run; wall time per step.
//
// Each run (id <setup>_<orientation>, e.g. h0.2_c-d, recorded in results["runs"]) goes through the
// library's run loop (run/run.hpp) and keeps DIR/<setup>/<orientation>/ with its scene (scene.yaml;
// `build/bin/rbfib run` reruns it) and its series as CSV (series.csv, outlines.csv, shapes.csv,
// written at the end of each sitting). Full scale is resumable: the checkpoint (checkpoint.h5,
// with the series inside and whether the run has ended) is written every 1000 steps at h = 0.5 um
// and 200 at h = 0.2 um and at the end of a sitting (--sitting SECONDS of wall time); running the
// same command again continues each unfinished run from it. Quick scale starts afresh (with
// --resumable it keeps checkpoints too).
//
// Run:   build/studies/study_chapter5_collision --scale quick --out runs/chapter5_collision/quick
//        build/studies/study_chapter5_collision --scale full --sitting 3600
//          --out runs/chapter5_collision/full   (one hour of steps, then the state of every run)
#include "common/study.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/surface/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using Vec3 = std::array<double, 3>;

namespace {

constexpr double kPi = 3.14159265358979323846;
const double R0 = 3.91 * units::um;          // Evans-Fung radius (Sec. 2.2)
const double kBox = 16 * units::um;          // the box, periodic in x and z
const double kFict = 0.1 / (1e-3 * units::cm);  // dyn/cm^2: 0.1 dyn/cm over the code's 10 um (header)
const Vec3 kLine = {1 / std::sqrt(2.0), 0, 1 / std::sqrt(2.0)};  // d = (e1 + e3)/sqrt 2
const Vec3 kView = {1 / std::sqrt(2.0), 0, -1 / std::sqrt(2.0)};  // the normal of the plane x = z

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::string fmt(double v, const char* f = "%.4g") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// ---- The reference red cell (Sec. 2.2, cells/shapes.hpp) ----------------------------------------
// X(theta, phi) = R0 [cos theta cos phi, sin theta cos phi, zeta(cos^2 phi) sin phi],
// zeta(s) = 0.105 + s - 0.56 s^2.
Vec3 evans_fung(double theta, double phi) {
  static const cells::ReferenceShape shape = cells::evans_fung_red_cell(R0);
  Vec3 x;
  shape.position(theta, phi, x.data());
  return x;
}

/// The surface area of the reference cell, 2 pi int r sqrt(r'^2 + z'^2) dphi over [-pi/2, pi/2]
/// (composite Simpson, 20,000 intervals, derivatives exact).
double reference_area() {
  const int n = 20000;
  auto integrand = [](double phi) {
    const double c = std::cos(phi), s = std::sin(phi), s2 = c * c;
    const double r = R0 * c, dr = -R0 * s;
    const double zeta = 0.105 + s2 - 0.56 * s2 * s2, dzeta = (1 - 1.12 * s2) * (-2 * c * s);
    const double dz = R0 * (dzeta * s + zeta * c);
    return 2 * kPi * r * std::sqrt(dr * dr + dz * dz);
  };
  const double a = -kPi / 2, h = kPi / n;
  double sum = integrand(a) + integrand(-a);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * integrand(a + i * h);
  return sum * h / 3;
}

/// A rotation as a matrix (Rodrigues, right-handed, as cells::placed).
using Mat3 = std::array<Vec3, 3>;
Mat3 rotation(const Vec3& axis, double angle) {
  const double n = std::sqrt(dot(axis, axis)), k[3] = {axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  const double K[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
  Mat3 R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + s * K[i][j] + (1 - c) * k[i] * k[j];
  return R;
}

Mat3 product(const Mat3& A, const Mat3& B) {
  Mat3 C{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) C[i][j] += A[i][k] * B[k][j];
  return C;
}

/// A cell's rotation (axis, angle) as the scene takes it.
struct Pose {
  Vec3 axis{0, 0, 1};
  double angle = 0;
  Mat3 matrix() const { return rotation(axis, angle); }
};

/// Axis and angle of a rotation matrix (angle in (0, pi)).
Pose pose_of(const Mat3& R) {
  const double angle = std::acos(std::clamp((R[0][0] + R[1][1] + R[2][2] - 1) / 2, -1.0, 1.0));
  const double s = 2 * std::sin(angle);
  return {{(R[2][1] - R[1][2]) / s, (R[0][2] - R[2][0]) / s, (R[1][0] - R[0][1]) / s}, angle};
}

/// The support function max_X (R X).u of the rotated reference cell (its convex hull's extent
/// along u from the centre), by a search over a 1441 x 721 (theta, phi) grid: within 1e-4 um.
double support(const Pose& p, const Vec3& u) {
  const Mat3 R = p.matrix();
  double best = -1e300;
  for (int i = 0; i <= 1440; ++i)
    for (int j = 0; j <= 720; ++j) {
      const Vec3 X = evans_fung(2 * kPi * i / 1440, -kPi / 2 + kPi * j / 720);
      double v = 0;
      for (int a = 0; a < 3; ++a) v += (R[a][0] * X[0] + R[a][1] * X[1] + R[a][2] * X[2]) * u[a];
      best = std::max(best, v);
    }
  return best;
}

// ---- The four orientations of Fig. 5.3 ----------------------------------------------------------
struct Orientation {
  std::string id, what;
  std::array<Pose, 2> pose;
  double t_figure_ms;  // the time of the seed's right-hand panel
};

std::vector<Orientation> orientations() {
  const Pose along_d{{0, 1, 0}, kPi / 4};  // e3 -> d
  const Pose along_y{{1, 0, 0}, kPi / 2};  // e3 -> -e2
  const Pose turned = pose_of(product(rotation(kLine, kPi / 2), along_y.matrix()));  // turned by pi/2 about d
  return {{"a-b", "concavities facing", {along_d, along_d}, 1.5},
          {"c-d", "edges facing", {along_y, along_y}, 1.1},
          {"e-f", "edge facing a concavity", {along_d, along_y}, 1.5},
          {"g-h", "edges facing, one turned by pi/2 about e1 + e3", {along_y, turned}, 1.1}};
}

struct Setup {
  std::string label;    // names its runs (<label>_<orientation>) and their directory
  double h, dt, t_end;  // cm, s, s
  double mu;            // P
  int n_data, n_sample;
  int measure_every, checkpoint_every;  // steps (checkpoints: 0 = none, a run that is not resumable)
};

struct Placed {
  std::array<Vec3, 2> center;
  double hull_gap;  // the gap between the convex hulls along d (cm)
};

/// Centres on the line x = z, y = 8 um with the hulls' gap 4h centred on the box centre: the
/// supporting planes of the two hulls normal to d are 4h apart. For these orientations the
/// hulls' nearest points lie on the line of centres, so this is the gap between the hulls.
Placed place(const Orientation& o, const Setup& s) {
  const double h1 = support(o.pose[0], kLine), h2 = support(o.pose[1], {-kLine[0], -kLine[1], -kLine[2]});
  const Vec3 m = {kBox / 2, kBox / 2, kBox / 2};
  Placed p;
  for (int a = 0; a < 3; ++a) {
    p.center[0][a] = m[a] - (2 * s.h + h1) * kLine[a];
    p.center[1][a] = m[a] + (2 * s.h + h2) * kLine[a];
  }
  p.hull_gap = dot(kLine, {p.center[1][0] - p.center[0][0], p.center[1][1] - p.center[0][1], p.center[1][2] - p.center[0][2]}) -
               h1 - h2;
  return p;
}

/// The run's scene (docs/scenes.md), values in CGS to 17 digits so that it reads back exactly.
std::string scene_text(const Orientation& o, const Setup& s, const Placed& p, double force) {
  auto triple = [](const Vec3& v, const std::string& unit) {
    return "[" + to_text(v[0]) + " " + unit + ", " + to_text(v[1]) + " " + unit + ", " + to_text(v[2]) + " " + unit + "]";
  };
  const std::string L = to_text(kBox) + " cm";
  std::string t = "# chapter5_collision: two red cells pushed together, Fig. 5.3 (" + o.id + ": " + o.what + ")\n"
                  "name: collision_" + o.id + "\n"
                  "domain:\n  size: [" + L + ", " + L + ", " + L + "]\n  periodic: [x, z]\n"
                  "  walls:\n    y: {lower: [0 cm/s, 0 cm/s, 0 cm/s], upper: [0 cm/s, 0 cm/s, 0 cm/s]}\n"
                  "fluid: {density: 1 g/cm^3, viscosity: " + to_text(s.mu) + " P}\n"
                  "grid: {h: " + to_text(s.h) + " cm}\n"
                  "time: {integrator: peskin_two_stage, dt: " + to_text(s.dt) + " s, end: " + to_text(s.t_end) + " s}\n"
                  "ib: {kernel: cosine4}\n"
                  "cell_types:\n  - {name: red cell, preset: red_cell, data_sites: " + to_text(s.n_data) +
                  ", sample_sites: " + to_text(s.n_sample) + "}\n"
                  "cells:\n";
  for (int c = 0; c < 2; ++c) {
    const double sign = c == 0 ? 1 : -1;  // into the gap
    const Vec3 F = {sign * force * kLine[0], 0, sign * force * kLine[2]};
    t += "  - {type: red cell, center: " + triple(p.center[c], "cm") + ", axis: [" + to_text(o.pose[c].axis[0]) + ", " +
         to_text(o.pose[c].axis[1]) + ", " + to_text(o.pose[c].axis[2]) + "], angle: " + to_text(o.pose[c].angle) +
         " rad, force: " + triple(F, "dyn") + "}\n";
  }
  return t;
}

// ---- Measurements -------------------------------------------------------------------------------
struct Sample {
  long step = 0;
  double t = 0;              // s
  double min_gap = 0;        // cm, between the cells' sample sites
  double separation = 0;     // cm, the centroids' distance along d
  std::array<double, 2> volume{0, 0};  // cm^3
  double max_velocity = 0;   // cm/s, after the last step
  double eq54_ratio = 0;     // dt / ((1/4) sqrt(h rho / ||f||_inf)) of the last step: 1 stops the run
};

/// Sample-site positions of the batch's cells (n_s x 6, column d N + c), volumes and centroids.
struct Sites {
  std::vector<double> P;
  index_t ns = 0;
  cells::CellDiagnostics diag;
};

Sites sites(const sim::ImmersedBoundary& ib) {
  cells::CellGeometry g;
  cells::measure(ib.batch(0), g);
  return {g.positions.to_host(), ib.batch(0).type().n_sample(), g.cells};
}

/// Nearest periodic image of a difference along x and z.
double wrap(double d) { return d - kBox * std::round(d / kBox); }

/// The minimum distance between the sample sites of cell 0 and cell 1, cell 1 taken at the periodic
/// image (x and z) nearest cell 0's centroid (surface::closest_points, brute force).
double min_gap(const Sites& s) {
  const index_t n = s.ns;
  std::vector<double> cell[2];
  for (int c = 0; c < 2; ++c)
    for (int d = 0; d < 3; ++d) cell[c].insert(cell[c].end(), s.P.begin() + (2 * d + c) * n, s.P.begin() + (2 * d + c + 1) * n);
  // The image nearest by the cells' volume centroids (x and z periodic).
  const surface::PeriodicBox box{{kBox, kBox, kBox}, {true, false, true}};
  return surface::closest_points(cell[0], n, cell[1], n, surface::nearest_image_shift(s.diag.centroid[0], s.diag.centroid[1], box)).distance;
}

Sample measure(const sim::ImmersedBoundary& ib, const Sites& s) {
  Sample m;
  m.step = ib.step_count();
  m.t = ib.time();
  m.min_gap = min_gap(s);
  const auto& c = s.diag.centroid;
  m.separation = wrap(c[1][0] - c[0][0]) * kLine[0] + wrap(c[1][2] - c[0][2]) * kLine[2];
  m.volume = {s.diag.volume[0], s.diag.volume[1]};
  return m;
}

/// Outline rows (kind, cell, s, y; um) seen from above the plane x = z: the sample sites within
/// h/2 of that plane (a section through both centres), and the silhouette of all sites (the
/// farthest projected site from the cell's projected centroid in each of 72 angular bins).
struct OutlinePoint {
  std::string kind;
  int cell;
  double s, y;  // um
};

std::vector<OutlinePoint> outline(const Sites& st, double h) {
  std::vector<OutlinePoint> out;
  const index_t n = st.ns;
  const double s_mid = kBox / 2 * std::sqrt(2.0);
  for (int c = 0; c < 2; ++c) {
    const double* x = &st.P[(0 + c) * n];
    const double* y = &st.P[(2 + c) * n];
    const double* z = &st.P[(4 + c) * n];
    std::vector<double> S(n), Y(n);
    double sc = 0, yc = 0;
    for (index_t i = 0; i < n; ++i) {
      S[i] = x[i] * kLine[0] + z[i] * kLine[2] - s_mid;
      Y[i] = y[i];
      sc += S[i] / n;
      yc += Y[i] / n;
      if (std::abs(x[i] * kView[0] + z[i] * kView[2]) < h / 2) out.push_back({"section", c + 1, S[i] / units::um, Y[i] / units::um});
    }
    const int bins = 72;
    std::vector<double> far(bins, -1);
    std::vector<index_t> who(bins, -1);
    for (index_t i = 0; i < n; ++i) {
      const double a = std::atan2(Y[i] - yc, S[i] - sc), r = std::hypot(Y[i] - yc, S[i] - sc);
      const int b = std::min(bins - 1, int((a + kPi) / (2 * kPi) * bins));
      if (r > far[b]) far[b] = r, who[b] = i;
    }
    for (int b = 0; b < bins; ++b)
      if (who[b] >= 0) out.push_back({"silhouette", c + 1, S[who[b]] / units::um, Y[who[b]] / units::um});
  }
  return out;
}

/// A cell's extents (cm): along the push d (its depth), along e2 and along (e1 - e3)/sqrt 2 (its
/// widths across d: e2 lies in the figure's view from above the plane x = z, (e1 - e3)/sqrt 2 is
/// the line of sight). A hemisphere with its flat face normal to d has depth / width = 1/2 both ways.
struct Shape {
  int cell;
  double depth, width_y, width_across;
};

std::vector<Shape> shapes(const Sites& st) {
  std::vector<Shape> out;
  const index_t n = st.ns;
  for (int c = 0; c < 2; ++c) {
    const auto& g = st.diag.centroid[std::size_t(c)];
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (index_t i = 0; i < n; ++i) {
      const Vec3 r = {wrap(st.P[(0 + c) * n + i] - g[0]), st.P[(2 + c) * n + i] - g[1], wrap(st.P[(4 + c) * n + i] - g[2])};
      const double along[3] = {dot(r, kLine), r[1], dot(r, kView)};
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], along[a]), hi[a] = std::max(hi[a], along[a]);
    }
    out.push_back({c + 1, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }
  return out;
}

// ---- One orientation's run, resumable ------------------------------------------------------------
struct RunResult {
  std::string status = "running";  // running, done, eq. 5.4, stopped
  std::string message;             // the NumericalError's text when stopped
  long steps = 0;
  double t = 0;                    // s, reached (the last good state when stopped)
  double v0 = 0;                   // the reference volume (cm^3)
  double seconds = 0;              // wall time of all steps (every sitting)
  double seconds_this_sitting = 0;
  long steps_this_sitting = 0;
  double area_quadrature = 0;      // sum dA0 of the built type (cm^2)
  std::vector<Sample> series;
  std::vector<std::pair<double, std::vector<OutlinePoint>>> outlines;  // (t, rows)
  struct Shapes {
    double t;
    std::string moment;  // start, mid (quick) or figure (full: the seed's figure time), end
    std::vector<Shape> cells;
  };
  std::vector<Shapes> shapes;
  bool ended() const { return status != "running"; }
};

// The run's series, kept in its checkpoint (run/run.hpp) and written out as CSV at the end of each
// sitting: "samples" [step, t, min_gap, separation, volume0, volume1, max_velocity, eq54_ratio],
// "outlines" [t, kind, cell, s, y] (kind 0 section, 1 silhouette), "shapes" [t, moment, cell,
// depth, width_y, width_across] (moment 0 start, 1 mid, 2 figure, 3 end), "reference" [v0, A0].
const char* kKinds[2] = {"section", "silhouette"};
const char* kMoments[4] = {"start", "mid", "figure", "end"};

int code(const std::string& name, const char* const* names, int n) {
  for (int k = 0; k < n; ++k)
    if (name == names[k]) return k;
  throw std::logic_error("unknown name " + name);
}

std::vector<double> sample_row(const Sample& m) {
  return {double(m.step), m.t, m.min_gap, m.separation, m.volume[0], m.volume[1], m.max_velocity, m.eq54_ratio};
}

Sample sample_of(const std::vector<double>& r) {
  Sample m;
  m.step = std::lround(r.at(0));
  m.t = r[1], m.min_gap = r[2], m.separation = r[3], m.volume = {r[4], r[5]}, m.max_velocity = r[6], m.eq54_ratio = r[7];
  return m;
}

/// The outlines and shapes of the state `at` at a moment, added to the series.
void record_state(run::SeriesSet& series, double t, const Sites& at, const std::string& moment, double h) {
  for (const OutlinePoint& q : outline(at, h)) series["outlines"].rows.push_back({t, double(code(q.kind, kKinds, 2)), double(q.cell), q.s, q.y});
  for (const Shape& c : shapes(at))
    series["shapes"].rows.push_back({t, double(code(moment, kMoments, 4)), double(c.cell), c.depth, c.width_y, c.width_across});
}

/// The run's result from its series and where it stands.
RunResult result_of(const run::SeriesSet& series, const run::Progress& p) {
  RunResult r;
  r.status = p.status == run::RunStatus::finished ? "done"
             : p.status == run::RunStatus::stopped ? (*p.stop_cause == Cause::stopping_condition ? "eq. 5.4" : "stopped")
                                                   : "running";
  r.message = p.stop_message;
  r.steps = p.clock.step;
  r.t = p.clock.t;
  r.seconds = p.wall_seconds;
  r.seconds_this_sitting = p.sitting_seconds;
  r.steps_this_sitting = p.sitting_steps;
  auto rows = [&](const char* name) {
    const auto it = series.find(name);
    return it == series.end() ? std::vector<std::vector<double>>{} : it->second.rows;
  };
  for (const auto& row : rows("reference")) r.v0 = row.at(0), r.area_quadrature = row.at(1);
  for (const auto& row : rows("samples")) r.series.push_back(sample_of(row));
  for (const auto& row : rows("outlines")) {
    if (r.outlines.empty() || r.outlines.back().first != row.at(0)) r.outlines.push_back({row[0], {}});
    r.outlines.back().second.push_back({kKinds[int(row[1])], int(row[2]), row[3], row[4]});
  }
  for (const auto& row : rows("shapes")) {
    if (r.shapes.empty() || r.shapes.back().t != row.at(0)) r.shapes.push_back({row[0], kMoments[int(row[1])], {}});
    r.shapes.back().cells.push_back({int(row[2]), row[3], row[4], row[5]});
  }
  return r;
}

/// The series as CSV files beside the run (a view: the checkpoint holds them).
void write_csv(const std::string& dir, const RunResult& r) {
  std::ofstream f(dir + "/series.csv");
  f.precision(17);
  f << "step,t_s,min_gap_cm,separation_cm,volume0_cm3,volume1_cm3,max_velocity_cm_s,eq54_ratio\n";
  for (const Sample& m : r.series)
    f << m.step << "," << m.t << "," << m.min_gap << "," << m.separation << "," << m.volume[0] << "," << m.volume[1] << ","
      << m.max_velocity << "," << m.eq54_ratio << "\n";
  std::ofstream o(dir + "/outlines.csv");
  o.precision(10);
  o << "t_s,kind,cell,s_um,y_um\n";
  for (const auto& [t, rows] : r.outlines)
    for (const OutlinePoint& q : rows) o << t << "," << q.kind << "," << q.cell << "," << q.s << "," << q.y << "\n";
  std::ofstream h(dir + "/shapes.csv");
  h.precision(17);
  h << "t_s,moment,cell,depth_cm,width_y_cm,width_across_cm\n";
  for (const auto& sh : r.shapes)
    for (const Shape& c : sh.cells) h << sh.t << "," << sh.moment << "," << c.cell << "," << c.depth << "," << c.width_y << "," << c.width_across << "\n";
}

/// One orientation's run at one setup, through the run loop. A resumable run (full scale) keeps
/// its checkpoint and steps while the sitting has wall time left.
RunResult run_orientation(const Orientation& o, const Setup& s, double figure_time, const std::string& figure_moment, const st::Options& opt,
              const st::Sitting& sitting) {
  const std::string dir = opt.out_dir + "/" + s.label + "/" + o.id;
  const bool resumable = s.checkpoint_every > 0;
  if (!resumable) std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const Placed p = place(o, s);
  const double A0 = reference_area();
  const std::string text = scene_text(o, s, p, kFict * A0), checkpoint = dir + "/checkpoint.h5";
  std::ofstream(dir + "/scene.yaml") << text;
  if (resumable && std::filesystem::exists(checkpoint)) {
    const io::Checkpoint k = io::read_checkpoint(checkpoint);
    if (k.scene_yaml != text)
      throw InputError(checkpoint, "its scene", "differs from this driver's scene for " + s.label + " " + o.id + ": remove " + dir + " to start afresh");
    // Ended in an earlier sitting, or this sitting's time is spent: the checkpoint is the result,
    // read without building the run.
    if (k.record.status != run::RunStatus::running || sitting.remaining() <= 0) {
      run::Progress q;
      q.status = k.record.status, q.clock = k.state.clock, q.t_end = s.t_end;
      q.wall_seconds = k.record.wall_seconds, q.steps_timed = k.record.steps_timed, q.stop_message = k.record.stop_message;
      if (q.status == run::RunStatus::stopped) q.stop_cause = k.record.stop_cause;
      const RunResult r = result_of(k.record.series, q);
      st::log(opt, s.label + " " + o.id + ": " + (q.ended() ? "ended in an earlier sitting (" + r.status + ")" : std::string("not stepped in this sitting (its time is spent)")) +
                       " at step " + to_text(r.steps) + ", t = " + fmt(r.t / units::us) + " us");
      return r;
    }
  }

  if (resumable && sitting.remaining() <= 0) {  // not begun: no sitting has reached it yet
    st::log(opt, s.label + " " + o.id + ": not begun (this sitting's time is spent)");
    return RunResult{};
  }
  run::Options ro;
  ro.t_end = s.t_end;
  if (resumable) {
    ro.checkpoint = checkpoint;
    ro.sitting = sitting.remaining();
  }
  ro.checkpoint_every = {s.checkpoint_every, 0, 0};
  ro.sample_every = {s.measure_every, 0, 0};
  ro.progress_every = {0, 0, 300};
  sim::IbStepReport last;  // the last step's report (max |u|, eq. 5.4's ratio)
  auto sample = [&](const sim::ImmersedBoundary& ib, const Sites& at) {
    Sample m = measure(ib, at);
    m.max_velocity = last.max_velocity;
    m.eq54_ratio = last.dt_bound > 0 && std::isfinite(last.dt_bound) ? last.dt / last.dt_bound : 0;
    return sample_row(m);
  };
  run::Hooks hk;
  hk.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* rep, run::SeriesSet& series) {
    if (rep) last = *rep;
    const Sites at = sites(ib);
    series["samples"].rows.push_back(sample(ib, at));
    if (!rep) {  // t = 0: the reference, the starting outlines and shapes
      series["reference"].rows.push_back({ib.batch(0).type().reference_volume(), ib.batch(0).type().reference_area()});
      record_state(series, ib.time(), at, "start", s.h);
    }
  };
  // The state at the figure's time (quick: mid-run); none when that time is the end (the end has its own).
  bool figure_taken = figure_time >= s.t_end * (1 - 1e-12);  // (a continued run: read from its series below)
  hk.after_step = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* rep, run::SeriesSet& series) {
    if (!rep) return;
    last = *rep;
    if (figure_taken || ib.time() < figure_time * (1 - 1e-12)) return;
    figure_taken = true;
    const Sites at = sites(ib);
    std::vector<std::vector<double>>& samples = series["samples"].rows;
    if (samples.empty() || std::lround(samples.back().at(0)) != ib.step_count()) samples.push_back(sample(ib, at));
    record_state(series, ib.time(), at, figure_moment, s.h);
  };
  hk.progress = [&](const run::Progress& q) { st::log(opt, s.label + " " + o.id + ": " + q.describe()); };
  run::Run runner(text, dir + "/scene.yaml", ro, hk);
  if (runner.continued()) {
    const std::vector<std::vector<double>>& taken = runner.series("shapes").rows;
    figure_taken = figure_taken || std::any_of(taken.begin(), taken.end(), [&](const std::vector<double>& r) {
                     return r.at(1) == code(figure_moment, kMoments, 4);
                   });
  }
  if (runner.continued())
    st::log(opt, s.label + " " + o.id + ": continuing from " + checkpoint + " at step " + to_text(runner.ib().step_count()) + ", t = " +
                     fmt(runner.ib().time() / units::us) + " us");
  else
    st::log(opt, s.label + " " + o.id + " (" + o.what + "): hull gap " + fmt(p.hull_gap / units::um) + " um = " + fmt(p.hull_gap / s.h) +
                     " h, nearest sample sites " + fmt(sample_of(runner.series("samples").rows.front()).min_gap / units::um) +
                     " um; F_fict A0 = " + fmt(kFict * A0) + " dyn per cell (A0 = " + fmt(A0 / (units::um * units::um)) + " um^2, quadrature " +
                     fmt(runner.ib().batch(0).type().reference_area() / (units::um * units::um)) + ")");
  const run::Progress q = runner.evolve();
  // The final state (the last good one when stopped): a sample, the outline and the shapes.
  if (q.ended()) {
    const sim::ImmersedBoundary& ib = runner.ib();
    const Sites at = sites(ib);
    std::vector<std::vector<double>>& samples = runner.series()["samples"].rows;
    if (samples.empty() || std::lround(samples.back().at(0)) != ib.step_count()) samples.push_back(sample(ib, at));
    record_state(runner.series(), ib.time(), at, "end", s.h);
    runner.checkpoint();
  }
  RunResult r = result_of(runner.series(), q);
  write_csv(dir, r);
  st::log(opt, s.label + " " + o.id + ": " + r.status + (r.message.empty() ? "" : " (" + r.message + ")") + " at step " + to_text(r.steps) +
                   ", t = " + fmt(r.t / units::us) + " us; " + to_text(r.steps_this_sitting) + " steps in this sitting, " +
                   fmt(r.seconds_this_sitting) + " s");
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_collision", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_collision",
                                                   "Sec. 5.1.3, Fig. 5.3: two red cells pushed together in four orientations");
    const bool full = opt.scale == st::Scale::full;

    // ---- 1. Parameters -----------------------------------------------------------------------
    // Quick: h = 0.5 um to 60 us. Full: each run to the public driver's 10 ms or until eq. 5.4
    // stops it: h = 0.5 um at 1 cP (minutes to an hour per orientation here), the text's 0.1 cP
    // at h = 0.5 um (minutes), then the seed's h = 0.2 um (days here; resumable over sittings).
    const double t_end = full ? 10 * units::ms : 60 * units::us;
    const Setup coarse{"h0.5", 0.5 * units::um, 100 * units::ns, t_end, 1 * units::cP, 400, 1600, 10, opt.keeps_runs() ? 1000 : 0};
    const Setup text_viscosity{"h0.5_mu0.1", 0.5 * units::um, 100 * units::ns, t_end, 0.1 * units::cP, 400, 1600, 10, 1000};
    const Setup seed{"h0.2", 0.2 * units::um, 50 * units::ns, t_end, 1 * units::cP, 2500, 10000, 20, 200};
    std::vector<Setup> setups = {coarse};
    if (full) setups.insert(setups.end(), {text_viscosity, seed});
    const std::string own = full ? seed.label : coarse.label;  // the scale's own resolution, for the time per step
    const double A0 = reference_area();
    const st::Sitting sitting(opt);  // full scale: the wall time of this sitting (--sitting)
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 16 x 16; walls at rest in y, periodic in x and z; fluid at rest initially";
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's public drivers; Sec. 2.1 says 0.1 cP: the variant h0.5_mu0.1 at full scale)";
    P["cells"] = "two red cells, the red_cell preset (Sec. 2.2: Skalak E = 2.5e-3, G = 2.5e-1 dyn/cm; kappa = 2e-12 erg; nu = 2.5e-7 dyn s/cm)";
    P["scheme"] = "Peskin's two-stage scheme, the seed's coupling (a)-(g), the 4-point cosine kernel, eq. 5.4 checked every step";
    for (const Setup& s : setups)
      P["setup_" + s.label] = "h = " + fmt(s.h / units::um) + " um, n_d = " + to_text(s.n_data) + ", n_s = " + to_text(s.n_sample) +
                              ", dt = " + fmt(s.dt / units::ns) + " ns, mu = " + fmt(s.mu / units::cP) + " cP, to " +
                              fmt(s.t_end / units::us) + " us or eq. 5.4; sampled every " + to_text(s.measure_every) +
                              " steps; eq. 5.4 stops a run when ||f||_inf > " + fmt(s.h * 1.0 / (16 * s.dt * s.dt), "%.3g") + " dyn/cm^3";
    P["initial_hull_gap"] = "4h along d = (e1 + e3)/sqrt 2, centres on x = z, y = 8 um, the gap centred on the box centre";
    P["fictitious_force_density_dyn_cm2"] = kFict;
    P["fictitious_force_per_cell_dyn"] = kFict * A0;
    P["reference_area_um2"] = A0 / (units::um * units::um);
    if (full && std::isfinite(sitting.remaining())) P["sitting_seconds"] = sitting.remaining();

    // ---- 2. One run per setup and orientation -------------------------------------------------
    const std::vector<std::string> run_columns = {"run", "setup", "orientation", "h_um", "mu_cP", "n_sample", "dt_ns", "status", "steps", "t_us", "t_stop_us",
                           "t_figure_us", "t_stop_over_t_figure", "stopped_by_eq54", "initial_gap_over_h", "min_gap_um", "min_gap_over_h",
                           "t_min_gap_us", "approach_um", "approach_over_h", "max_volume_change_rel", "seconds", "seconds_per_step",
                           "steps_to_go", "hours_to_go"};
    Json runs = st::table(run_columns,
                          {"", "", "", "um", "cP", "", "ns", "", "", "us", "us", "us", "", "", "", "um", "", "us", "um", "", "", "s", "s", "",
                           "h"});
    Json series = st::table({"setup", "orientation", "h_um", "t_us", "min_gap_um", "gap_over_h", "separation_um", "volume_change_1",
                             "volume_change_2", "max_velocity_mm_s", "eq54_ratio"},
                            {"", "", "um", "us", "um", "", "um", "", "", "mm/s", ""});
    Json outlines = st::table({"setup", "orientation", "h_um", "kind", "t_us", "cell", "s_um", "y_um"}, {"", "", "um", "", "us", "", "um", "um"});
    Json shape_table = st::table({"run", "setup", "orientation", "moment", "t_us", "cell", "depth_um", "width_y_um", "width_across_um",
                                  "depth_over_width", "depth_over_width_across"},
                                 {"", "", "", "", "us", "", "um", "um", "um", "", ""});
    std::vector<std::string> fc = {"orientation", "panels", "t_figure_ms"}, fu = {"", "", "ms"};
    for (const Setup& s : setups) {
      for (const char* c : {"status_", "t_reached_ms_", "t_stop_ms_", "t_stop_over_t_figure_", "depth_over_width_"}) fc.push_back(c + s.label);
      for (const char* u : {"", "ms", "ms", "", ""}) fu.push_back(u);
    }
    Json fig = st::table(fc, fu);
    std::vector<Json::Array> fig_rows;
    for (const Orientation& o : orientations()) fig_rows.push_back({Json(o.id), Json(o.what), Json(o.t_figure_ms)});
    double ended = 0, peak54 = 0, total_hours_to_go = 0;
    std::vector<double> per_step;
    for (const Setup& s : setups) {
      const double h_um = s.h / units::um;
      std::size_t k = 0;
      for (const Orientation& o : orientations()) {
        const std::string id = s.label + "_" + o.id;
        const double t_figure = o.t_figure_ms * units::ms;
        const RunResult r = full ? run_orientation(o, s, t_figure, "figure", opt, sitting) : run_orientation(o, s, s.t_end / 2, "mid", opt, sitting);
        if (r.series.empty()) {  // not begun: no sitting has reached it yet
          Json::Array row{Json(id), Json(s.label), Json(o.id), Json(h_um), Json(s.mu / units::cP), Json(s.n_sample), Json(s.dt / units::ns),
                          Json("not begun")};
          row.resize(run_columns.size());  // the rest null: nothing measured
          runs["rows"].push(Json(row));
          fig_rows[k].insert(fig_rows[k].end(), {Json("not begun"), Json(), Json(), Json(), Json()});
          ++k;
          st::record_run(results, id, st::RunProgress{false, 0, s.t_end, 0, NAN, ""});
          continue;
        }
        double gmin = 1e300, tmin = 0, vmax = 0;
        for (const Sample& m : r.series) {
          if (m.min_gap < gmin) gmin = m.min_gap, tmin = m.t;
          peak54 = std::max(peak54, m.eq54_ratio);
          for (int c = 0; c < 2; ++c) vmax = std::max(vmax, std::abs(m.volume[c] - r.v0) / r.v0);
          series["rows"].push(Json::Array{Json(s.label), Json(o.id), Json(h_um), Json(m.t / units::us), Json(m.min_gap / units::um),
                                          Json(m.min_gap / s.h), Json(m.separation / units::um), Json((m.volume[0] - r.v0) / r.v0),
                                          Json((m.volume[1] - r.v0) / r.v0), Json(m.max_velocity / units::mm),
                                          m.step > 0 ? Json(m.eq54_ratio) : Json()});
        }
        for (const auto& [t, rows] : r.outlines)
          for (const OutlinePoint& q : rows)
            outlines["rows"].push(Json::Array{Json(s.label), Json(o.id), Json(h_um), Json(q.kind), Json(std::round(t / units::ns) / 1e3),
                                              Json(q.cell), Json(q.s), Json(q.y)});
        // The cells' shapes; at full scale a run that ended before the figure's time has none there (NaN).
        bool at_figure = false;
        double figure_ratio = 0;
        for (const auto& sh : r.shapes) {
          at_figure = at_figure || sh.moment == "figure";
          for (const Shape& c : sh.cells) {
            if (sh.moment == "figure") figure_ratio += c.depth / c.width_y / 2;
            shape_table["rows"].push(Json::Array{Json(id), Json(s.label), Json(o.id), Json(sh.moment), Json(sh.t / units::us), Json(c.cell),
                                                 Json(c.depth / units::um), Json(c.width_y / units::um), Json(c.width_across / units::um),
                                                 Json(c.depth / c.width_y), Json(c.depth / c.width_across)});
          }
        }
        if (full && r.ended() && !at_figure)
          for (int c = 1; c <= 2; ++c)
            shape_table["rows"].push(Json::Array{Json(id), Json(s.label), Json(o.id), Json("figure"), Json(t_figure / units::us), Json(c), Json(),
                                                 Json(), Json(), Json(), Json()});
        const bool stopped = r.status == "eq. 5.4" || r.status == "stopped";
        // How far the centroids came toward each other along d (before any sliding past).
        double closest = r.series.front().separation;
        for (const Sample& m : r.series) closest = std::min(closest, std::abs(m.separation));
        const double approach = r.series.front().separation - closest;
        // The time per step: this sitting's if it stepped, else every sitting's.
        const double sps = r.steps_this_sitting > 0 ? r.seconds_this_sitting / r.steps_this_sitting : (r.steps > 0 ? r.seconds / r.steps : NAN);
        const long to_go = r.ended() ? 0 : std::lround((s.t_end - r.t) / s.dt);
        const double hours = to_go * sps / 3600;
        total_hours_to_go += std::isfinite(hours) ? hours : 0;
        if (std::isfinite(sps) && s.label == own) per_step.push_back(sps);
        const Json ratio = stopped ? Json(r.t / t_figure) : Json();
        runs["rows"].push(Json::Array{Json(id), Json(s.label), Json(o.id), Json(h_um), Json(s.mu / units::cP), Json(s.n_sample), Json(s.dt / units::ns),
                                      Json(r.status), Json(double(r.steps)), Json(r.t / units::us), stopped ? Json(r.t / units::us) : Json(),
                                      Json(t_figure / units::us), ratio, r.ended() ? Json(r.status == "eq. 5.4" ? 1.0 : 0.0) : Json(),
                                      Json(r.series.front().min_gap / s.h), Json(gmin / units::um), Json(gmin / s.h), Json(tmin / units::us),
                                      Json(approach / units::um), Json(approach / s.h), Json(vmax), Json(r.seconds), Json(sps),
                                      Json(double(to_go)), Json(hours)});
        fig_rows[k].insert(fig_rows[k].end(), {Json(r.status), Json(r.t / units::ms), stopped ? Json(r.t / units::ms) : Json(), ratio,
                                               at_figure ? Json(figure_ratio) : Json()});
        ++k;
        ended += r.ended();
        if (!r.message.empty()) results["parameters"]["stop_" + id] = r.message;
        st::record_run(results, id, st::RunProgress{r.ended(), r.t, s.t_end, r.steps, sps, r.message});
      }
    }
    for (auto& row : fig_rows) fig["rows"].push(Json(row));

    // ---- 3. Results -------------------------------------------------------------------------------
    // Per run: the tables runs (gaps, approach, volumes, stop) and shapes; here what spans them.
    Json& V = results["values"];
    V["max_eq54_ratio"] = peak54;                   // dt over eq. 5.4's bound: 1 stops a run
    V["runs_ended"] = ended;
    V["seconds_per_step"] = st::median(per_step);   // at the scale's own resolution (full: the seed's)
    V["hours_to_go"] = total_hours_to_go;           // to 10 ms at most; a stop by eq. 5.4 comes sooner
    results["tables"]["runs"] = runs;
    results["tables"]["gap_series"] = series;
    results["tables"]["fig53"] = fig;
    results["tables"]["outlines"] = outlines;
    results["tables"]["shapes"] = shape_table;
    st::write_results(opt, results);
    return 0;
  });
}
