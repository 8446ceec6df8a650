// Checks the endothelium's explicit stability bound (lib/rbfib/sim/tether_stability.hpp, derived in
// docs/derivations/tether_stability) with the coupled step itself. The seed's endothelium (Sec. 2.2,
// eq. 2.10) holds its points with k = 2.5 dyn/cm and eta = 2.5e-7 dyn s/cm per point, "as large as
// possible for the chosen spatial and temporal step size" (h = 0.2 um, dt = 50 ns); the derivation
// says a flat sheet's sliding mode flips sign every step once (eta + k dt/2) G1(dt) > 1.
// The scene: a 4 x 12 x 4 um box (periodic x, z; walls at rest in y), plasma at rest (rho = 1 g/cm^3),
// a lattice of tethered points at y = 1 um with the seed's density (25 x 40: n_A = 62.5 um^-2), B3
// kernel, backward-forward Euler, the seed's coupling, eq. 5.4 off; the points start displaced by
// 1e-3 um along x with independent noise of 1e-5 um (fixed seed). Every step: d_n, the mean x
// displacement from the anchors (the sliding mode); |lambda| = the geometric mean of the ratios of
// its successive second differences over steps 10-40 (the mode that flips sign every step); the measured threshold dt* is where |lambda| crosses 1 (interpolated in log dt
// between the sweep's steps), beside the model's. Sweeps: the seed's constants at 1 and 0.1 cP,
// the spring alone, the damping alone, half the density, and h = 0.4 um (n_A = 16 um^-2).
// Then the rule (constants that follow the step at gain 0.5) in shear 1000/s for 2,000 steps at
// 200, 400 and 800 ns: the sheet's displacement and whether the mode stays put.
//
// Run:   build/studies/study_chapter5_tether_stability --scale quick --out runs/chapter5_tether_stability
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/series.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/tether_stability.hpp"

#include <chrono>
#include <cmath>
#include <random>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::row;

namespace {

const double um = units::um, ns = units::ns, cP = units::cP;

struct Case {
  std::string id;
  double h_um, mu;                 // grid spacing, viscosity (P)
  std::array<int, 2> lattice;      // points along x and z over 4 x 4 um
  double k, eta;                   // dyn/cm, dyn s/cm per point
  std::vector<double> dts_ns;      // the sweep
  bool shear = false;              // in shear 1000/s (the damping alone needs a flow to act on)
  double n_per_um2() const { return lattice[0] * lattice[1] / 16.0; }
  sim::TetherSheet sheet() const { return {h_um * um, 12 * um, 1 * um, n_per_um2() / (um * um), 1.0, mu, ib::Kernel::bspline3}; }
};

struct Member {
  double lambda = NAN;           // of the flipping mode: |ratio of d's second differences|, geometric mean over steps 10-40 (inf: blew up)
  double negative = 0;           // the fraction of steps whose ratio is negative (sign flips)
  double max_displacement = 0;   // max_k |X_k - X'_k| over the run (cm)
  double seconds_per_step = NAN;
  std::string stop;              // the numerical stop that ended the run early, if any
  int steps = 0;                 // steps taken
};

/// Steps the sheet `steps` times at dt with constants k, eta (in shear 1000/s when `shear`).
Member run_sheet(const Case& c, double dt, double k, double eta, int steps, bool shear) {
  scene::Scene sc;
  sc.name = "tether_stability";
  const int nx = int(std::lround(4 / c.h_um)), ny = int(std::lround(12 / c.h_um));
  sc.grid = make_mac_grid(3, {nx, ny, nx}, {4 * um, 12 * um, 4 * um}, {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  if (shear) sc.walls[1][1].velocity = {0, 0, 12 * units::mm}, sc.initial_shear = true;
  sc.fluid = {1, c.mu};
  sc.fluid_options.integrator = TimeIntegrator::backward_forward_euler;
  sc.fluid_options.dt = dt;
  sc.t_end = steps * dt;
  sc.ib.kernel = ib::Kernel::bspline3;
  sc.ib.stopping_condition = false;
  sim::ImmersedBoundary ib = scene::build(sc);
  sim::TetheredPoints sheet = scene::tethered_points({"endothelium", {false, 1, 1 * um, c.lattice}, k, eta}, {4 * um, 12 * um, 4 * um});
  host_vector<double> X(sheet.X.begin(), sheet.X.end());
  const std::size_t n = X.size() / 3;
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> noise(-1e-5 * um, 1e-5 * um);
  for (std::size_t i = 0; i < 3 * n; ++i) X[i] += (i < n ? 1e-3 * um : 0) + noise(random);
  sheet.X = dvec(X.begin(), X.end());
  const host_vector<double> A(sheet.anchors.begin(), sheet.anchors.end());
  ib.add(std::move(sheet));
  Member m;
  std::vector<double> d{1e-3 * um};  // d_0: the displacement given (the noise's mean is below 1e-6 of it)
  const auto t0 = std::chrono::steady_clock::now();
  int taken = 0;
  try {
    for (; taken < steps; ++taken) {
      ib.step();
      const host_vector<double> Xn(ib.points(0).X.begin(), ib.points(0).X.end());
      double mean = 0;
      for (std::size_t i = 0; i < n; ++i) {
        mean += (Xn[i] - A[i]) / double(n);
        double r2 = 0;
        for (int a = 0; a < 3; ++a) r2 += std::pow(Xn[a * n + i] - A[a * n + i], 2);
        m.max_displacement = std::max(m.max_displacement, std::sqrt(r2));
      }
      d.push_back(mean);
    }
  } catch (const NumericalError& e) {
    m.stop = e.what();  // grown past what the step accepts: the ratios up to here still count
  }
  m.steps = taken;
  m.seconds_per_step = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / std::max(1, taken);
  // The mode that flips sign every step, seen in the second differences of d (the slow physical
  // relaxation, lambda near 1, is suppressed there by (1 - lambda)^2; a flipping one is amplified by 4).
  std::vector<double> d2;
  for (std::size_t i = 1; i + 1 < d.size(); ++i) d2.push_back(d[i + 1] - 2 * d[i] + d[i - 1]);
  double logs = 0;
  int counted = 0, negative = 0;
  for (std::size_t i = 1; i < d2.size(); ++i) {
    negative += d2[i] / d2[i - 1] < 0;
    if (i >= 10 && i <= 40) logs += std::log(std::abs(d2[i] / d2[i - 1])), ++counted;
  }
  // Too few ratios before a stop: it grew past all bounds within 10 steps.
  m.lambda = counted >= 5 ? std::exp(logs / counted) : INFINITY;
  m.negative = d2.size() > 1 ? double(negative) / double(d2.size() - 1) : NAN;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_tether_stability", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_tether_stability",
                                                   "The endothelium's explicit stability bound (Sec. 2.2, eq. 2.10) against a dt sweep");
    const double k = 2.5, eta = 2.5e-7;  // the seed's constants (Sec. 2.2)
    const std::vector<Case> cases = {
        {"seed_1cP", 0.2, 1 * cP, {25, 40}, k, eta, {40, 50, 55, 60, 65, 70, 80, 100}},
        {"seed_0p1cP", 0.2, 0.1 * cP, {25, 40}, k, eta, {35, 40, 44, 46, 48, 50, 55}},
        {"spring_only_1cP", 0.2, 1 * cP, {25, 40}, k, 0, {120, 130, 136, 140, 144, 148, 160}},
        {"damping_only_1cP", 0.2, 1 * cP, {25, 40}, 0, eta, {75, 80, 85, 90, 95, 100, 110}, true},
        {"half_density_1cP", 0.2, 1 * cP, {25, 20}, k, eta, {100, 110, 115, 120, 125, 130, 140}},
        {"h0.4_1cP", 0.4, 1 * cP, {16, 16}, k, eta, {200, 240, 260, 280, 300, 340}}};
    const int steps = 60;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "4 x 12 x 4, periodic x and z, walls at rest in y; the sheet at y = 1 um";
    P["scheme"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g) (the spring at X^n), eq. 5.4 off";
    P["start"] = "points displaced 1e-3 um along x, noise 1e-5 um in every component (fixed seed); fluid at rest";
    P["steps_per_member"] = steps;

    Json sweep = st::table({"case", "dt_ns", "lambda", "negative_fraction", "steps", "model_gain", "seconds_per_step"}, {"", "ns", "", "", "", "", "s"});
    Json thresholds = st::table({"case", "n_per_um2", "mu_cP", "k", "eta", "dt_star_ns", "model_dt_star_ns", "ratio"},
                                {"", "1/um^2", "cP", "dyn/cm", "dyn s/cm", "ns", "ns", ""});
    Json& V = results["values"];
    for (const Case& c : cases) {
      std::vector<double> dts, lambdas;
      for (double dt_ns : c.dts_ns) {
        const Member m = run_sheet(c, dt_ns * ns, c.k, c.eta, steps, c.shear);
        if (!m.stop.empty()) st::log(opt, c.id + " at " + to_text(dt_ns) + " ns: stopped at step " + to_text(m.steps + 1) + ": " + m.stop);
        dts.push_back(dt_ns), lambdas.push_back(m.lambda);
        sweep["rows"].push(row({c.id, dt_ns, std::isfinite(m.lambda) ? Json(m.lambda) : Json(), m.negative, double(m.steps),
                                sim::tether_gain(c.sheet(), c.k, c.eta, dt_ns * ns, false), m.seconds_per_step}));
        if (c.id.rfind("seed_", 0) == 0 && dt_ns == 50) V["lambda_50ns_" + c.id] = m.lambda;
      }
      const double measured = rising_crossing_log(dts, lambdas, 1.0), model = sim::tether_dt_limit(c.sheet(), c.k, c.eta, false) / ns;
      thresholds["rows"].push(row({c.id, c.n_per_um2(), c.mu / cP, c.k, c.eta, measured, model, measured / model}));
      V["dt_star_over_model_" + c.id] = measured / model;
      st::log(opt, c.id + ": dt* " + to_text(measured) + " ns, model " + to_text(model) + " ns");
    }

    // The rule: constants that follow the step (gain 0.5), in shear 1000/s, the seed's sheet.
    Json rule = st::table({"dt_ns", "k", "eta", "steps", "max_displacement_um", "seconds_per_step", "seconds_per_us"},
                          {"ns", "dyn/cm", "dyn s/cm", "", "um", "s", "s"});
    const Case& seed = cases.front();
    double worst = 0, fewest = 2000;
    for (double dt_ns : {200.0, 400.0, 800.0}) {
      const sim::TetherConstants r = sim::tether_constants_for_step(seed.sheet(), dt_ns * ns, 0.5);
      const Member m = run_sheet(seed, dt_ns * ns, r.k, r.eta, 2000, true);
      worst = std::max(worst, std::isfinite(m.lambda) ? m.max_displacement / um : INFINITY);
      fewest = std::min(fewest, double(m.steps));
      if (!m.stop.empty()) st::log(opt, "rule at " + to_text(dt_ns) + " ns: " + m.stop);
      rule["rows"].push(row({dt_ns, r.k, r.eta, double(m.steps), m.max_displacement / um, m.seconds_per_step, m.seconds_per_step * 1000 / dt_ns}));
    }
    V["rule_max_displacement_um"] = worst;
    V["rule_fewest_steps"] = fewest;  // of 2,000: a run that stopped early took fewer
    results["tables"]["sweep"] = sweep;
    results["tables"]["thresholds"] = thresholds;
    results["tables"]["rule"] = rule;
    st::write_results(opt, results);
    return 0;
  });
}
