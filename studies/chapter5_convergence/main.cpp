// Reproduces seed Sec. 5.1.1, Tables 5.1 and 5.2: a red cell with Skalak's law only, stretched by
// 1.1 in z and compressed in x to keep its volume, relaxes in a 16 um box with walls at rest in y
// (periodic in x and z), fluid at rest initially; Roma's 3-point kernel, Peskin's two-stage
// scheme (the seed's coupling (a)-(g)); grids of 20 r cells per 16 um, h = 0.8/r um,
// dt = 180/r ns, n_d = 125 r^2, n_s = 500 r^2 (Bauer spirals, eq. 5.1), to t = 180 us; r = 1..6
// at full scale, 1..3 to t = 36 us at quick scale. Errors between successive grids:
//   u: at the centres of the r = 1 grid's 20^3 cells (interpolated there with the same kernel);
//   X: the surface at 1000 Bauer-spiral points of the sphere, evaluated from each run's data
//      sites by its own interpolant; L2 norm of eq. 5.2 with the weights omega_j / cos(phi_j) of
//      the sphere (eq. 2.22, phi = r), L_inf of eq. 5.3;
// and orders p from successive ratios by the seed's formula (core/series.hpp, successive_order).
// The seed's printed orders are this formula one index higher: its row r holds p from
// eps_{r-2} / eps_{r-1} solved with r - 1 in place of r - 2 (the columns order_*_seed_index).
// Each grid's scene is kept as DIR/scene_r<r>.yaml (`build/bin/rbfib run` reruns it); at full
// scale its run keeps DIR/checkpoint_r<r>.h5 and continues over sittings (--sitting SECONDS), and
// a finished grid keeps only what the comparison takes, DIR/grid_r<r>.h5 (a few hundred kB, where
// the finished checkpoint of r = 5 is 50 MB), which `make keep-chapter5_convergence` can commit.
//
// Run:   build/studies/study_chapter5_convergence --scale quick --out runs/chapter5_convergence
#include "common/study.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/series.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/hdf5.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::row;

namespace {

struct Run {
  int r = 0;
  dvec u_centres;          // 3 x 8000, the velocity at the r = 1 cell centres (cm/s)
  std::vector<double> X;   // the surface at the 1000 evaluation points, 1000 x 3 (cm)
  double volume_change = 0, seconds = 0;  // seconds: wall time of its steps, over all sittings
  double seconds_per_step = NAN;
  int steps = 0;
  std::string commit;  // the commit that began it
};

/// Grid r's setup as a scene (docs/scenes.md), kept beside the results, where `rbfib run` reruns it.
scene::Scene relaxation_scene(int r, double t_end) {
  scene::Scene sc;
  sc.name = "chapter5_convergence_r" + to_text(r);
  const double L = 16 * units::um;
  sc.grid = make_mac_grid(3, {20 * r, 20 * r, 20 * r}, {L, L, L}, {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  sc.fluid = {1, 1 * units::cP};  // g/cm^3, P
  sc.fluid_options.integrator = TimeIntegrator::peskin_two_stage;
  sc.fluid_options.dt = 180 * units::ns / r;
  sc.t_end = t_end;
  sc.ib.kernel = ib::Kernel::roma3;
  scene::CellTypeEntry red = scene::cell_type("red cell (Skalak only)", "red_cell", 125 * r * r, 500 * r * r);
  red.spec.model = {{mechanics::EnergyDensity::skalak(cells::seed::red_cell_E, cells::seed::red_cell_G)}};  // Skalak only
  sc.types.push_back(red);
  const double c = 8 * units::um;
  sc.cells.push_back({red.spec.name, {{c, c, c}, {0, 0, 1}, 0, {1 / 1.1, 1, 1.1}}});
  return sc;
}

/// A finished grid's comparison data (DIR/grid_r<r>.h5): the velocity at the coarse centres, the
/// surface at the evaluation points, the volume change, the run's steps and times, and the scene it
/// ran, so that a file of another scene is never taken for this one.
constexpr const char* grid_format = "rbfib chapter5_convergence grid 1";

void write_grid(const std::string& path, const std::string& scene_text, const Run& run) {
  namespace h5 = io::h5;
  const std::string tmp = path + ".tmp";
  {
    const h5::Id file = h5::create_file(tmp);
    h5::attribute(file, "format", std::string(grid_format));
    h5::write_bytes(file, "scene", scene_text);
    h5::attribute(file, "r", run.r);
    h5::attribute(file, "steps", run.steps);
    h5::attribute(file, "seconds", run.seconds);
    h5::attribute(file, "seconds_per_step", run.seconds_per_step);
    h5::attribute(file, "volume_change", run.volume_change);
    h5::attribute(file, "commit", run.commit);
    const host_vector<double> u = run.u_centres;
    h5::write(file, "u_centres", u.data(), {hsize_t(u.size())}, "cm/s");
    h5::write(file, "X", run.X.data(), {hsize_t(run.X.size())}, "cm");
    h5::flush_and_sync(file, tmp);
  }
  h5::replace(tmp, path);
}

/// Reads DIR/grid_r<r>.h5 into run; false (and a line saying why, when the file is there) unless it
/// holds grid r of this very scene.
bool read_grid(const std::string& path, const std::string& scene_text, int r, const st::Options& opt, Run& run) {
  namespace h5 = io::h5;
  if (!std::filesystem::exists(path)) return false;
  const h5::Id file = h5::open_file(path);
  std::string format, scene, commit;
  std::vector<double> u;
  bool ok = file.valid() && h5::read_attribute(file, "format", format) && format == grid_format && h5::read_bytes(file, "scene", scene) &&
            h5::read_attribute(file, "commit", commit) && h5::read(file, "u_centres", u) && h5::read(file, "X", run.X);
  int steps = 0;
  ok = ok && h5::read_attribute(file, "steps", H5T_NATIVE_INT, &steps) &&
       h5::read_attribute(file, "seconds", H5T_NATIVE_DOUBLE, &run.seconds) &&
       h5::read_attribute(file, "seconds_per_step", H5T_NATIVE_DOUBLE, &run.seconds_per_step) &&
       h5::read_attribute(file, "volume_change", H5T_NATIVE_DOUBLE, &run.volume_change);
  if (!ok || scene != scene_text) {
    st::log(opt, "r = " + to_text(r) + ": " + path + (ok ? " holds another scene" : " is malformed") + ": the grid is run again");
    return false;
  }
  run.r = r;
  run.steps = steps;
  run.commit = commit;
  run.u_centres = dvec(u.begin(), u.end());
  return true;
}

/// Grid r's run through the library's run loop (run/run.hpp). Runs kept over sittings (full
/// scale, or --resumable) keep DIR/checkpoint_r<r>.h5, written every five minutes of wall time
/// and at the sitting's end, and continue from it; a finished grid is its checkpoint marked
/// finished, from which the comparison data are taken again (quick scale always recomputes, so
/// that a code change is never hidden by old runs). Returns the run, `finished` false when the
/// sitting ended first.
Run relax(int r, double t_end, const dvec& centres, const surface::SphereSites& eval, const st::Options& opt,
          const st::Sitting& sitting, bool& finished) {
  const std::string file = "scene_r" + to_text(r) + ".yaml";
  const std::string text = scene::to_yaml(relaxation_scene(r, t_end),
                                          "chapter5_convergence: a stretched red cell (Skalak only) relaxing in a channel (Sec. 5.1.1), r = " + to_text(r));
  std::ofstream(opt.out_dir + "/" + file) << text;
  const std::string grid_file = opt.out_dir + "/grid_r" + to_text(r) + ".h5";
  if (opt.keeps_runs()) {
    Run done;
    if (read_grid(grid_file, text, r, opt, done)) {
      st::log(opt, "r = " + to_text(r) + ": finished earlier (" + grid_file + ", " + to_text(done.steps) + " steps)");
      finished = true;
      return done;
    }
  }
  run::Options o;
  o.t_end = t_end;
  o.label = st::source_commit(opt);
  if (opt.keeps_runs()) {
    o.checkpoint = opt.out_dir + "/checkpoint_r" + to_text(r) + ".h5";
    o.sitting = std::max(0.0, sitting.remaining());
  }
  o.progress_every = {0, 0, 60};
  run::Hooks h;
  h.sample = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport* report, run::SeriesSet& series) {
    if (report) return;  // the starting volume only
    cells::CellGeometry f;
    cells::measure(ib.batch(0), f);
    series["start"].columns = {"volume_cm3"};
    series["start"].rows.push_back({f.cells.volume[0]});
  };
  h.progress = [&](const run::Progress& p) { st::log(opt, "r = " + to_text(r) + ": " + p.describe()); };
  run::Run runner(text, file, o, h);
  if (runner.continued()) st::log(opt, "r = " + to_text(r) + ": continuing from " + o.checkpoint + " at t = " + to_text(runner.ib().time() / units::us) + " us");
  const run::Progress p = runner.evolve();
  if (p.status == run::RunStatus::stopped) throw NumericalError(*p.stop_cause, "grid r = " + to_text(r) + ": " + p.stop_message);
  Run run;
  run.r = r;
  run.steps = int(p.clock.step);
  run.seconds = p.wall_seconds;
  run.seconds_per_step = p.seconds_per_step();
  run.commit = runner.label();
  finished = p.status == run::RunStatus::finished;
  if (!finished) return run;
  const sim::ImmersedBoundary& ib = runner.ib();
  const cells::CellTypeSpec& spec = ib.batch(0).type().spec();
  cells::CellGeometry f;
  cells::measure(ib.batch(0), f);
  const double v0 = runner.series("start").rows.at(0).at(0);
  run.volume_change = (f.cells.volume[0] - v0) / v0;
  // u at the coarse cell centres, interpolated with the run's kernel.
  ib::Interaction probe({ib.fluid().operators().component_box(0), ib.fluid().operators().component_box(1),
                         ib.fluid().operators().component_box(2)}, runner.scene().ib.kernel);
  probe.interpolate(centres, ib.fluid_state().u, run.u_centres);
  // The surface at the evaluation points, from the run's own interpolant of its data sites.
  const auto ops = surface::rbf_operators(spec.data_sites, eval, spec.basis);
  const std::vector<surface::Jet> J = surface::jets_from_operators(*ops, ib.batch(0).positions_host());
  run.X.resize(3 * J.size());
  for (std::size_t i = 0; i < J.size(); ++i)
    for (int d = 0; d < 3; ++d) run.X[d * J.size() + i] = J[i].x[d];
  st::log(opt, "r = " + to_text(r) + ": " + to_text(run.steps) + " steps in " + to_text(run.seconds) + " s, volume change " +
                   to_text(run.volume_change));
  if (opt.keeps_runs()) {  // what the comparison takes replaces the finished checkpoint (a whole grid)
    write_grid(grid_file, text, run);
    std::filesystem::remove(o.checkpoint);
  }
  return run;
}

/// The centres of the r = 1 grid's 20^3 cells (3 x 8000, cm), where the velocities are compared.
dvec coarse_centres() {
  const index_t nc = 20 * 20 * 20;
  host_vector<double> ch(3 * nc);
  for (index_t q = 0; q < nc; ++q)
    for (int d = 0; d < 3; ++d) ch[d * nc + q] = (double(d == 0 ? q % 20 : d == 1 ? q / 20 % 20 : q / 400) + 0.5) * 0.8 * units::um;
  return ch;
}

/// The L2 (eq. 5.2) and L_inf (eq. 5.3) differences between two grids' runs: of the velocity at the
/// coarse cell centres (the root mean square over the centres), and of the surface at the
/// evaluation points (weights omega_j / cos(phi_j) of the sphere, eq. 2.22; um).
struct Errors {
  double u2 = 0, uinf = 0, x2 = 0, xinf = 0;
};
Errors errors(const Run& ra, const Run& rb, const surface::SphereSites& eval, const std::vector<double>& w) {
  Errors e;
  const host_vector<double> a = ra.u_centres, b = rb.u_centres;
  const std::size_t nc = a.size() / 3, n = w.size();
  for (std::size_t q = 0; q < nc; ++q) {
    double e2 = 0;
    for (std::size_t d = 0; d < 3; ++d) e2 += std::pow(a[d * nc + q] - b[d * nc + q], 2);
    e.u2 += e2 / double(index_t(nc)), e.uinf = std::max(e.uinf, std::sqrt(e2));
  }
  for (std::size_t i = 0; i < n; ++i) {
    double e2 = 0;
    for (std::size_t d = 0; d < 3; ++d) e2 += std::pow((ra.X[d * n + i] - rb.X[d * n + i]) / units::um, 2);
    e.x2 += w[i] / std::cos(eval.theta[i]) * e2, e.xinf = std::max(e.xinf, std::sqrt(e2));
  }
  e.u2 = std::sqrt(e.u2), e.x2 = std::sqrt(e.x2);
  return e;
}

/// Tables 5.1 and 5.2 from the finished grids, each grid recorded as a run (grid_r<r>, finished once
/// its state at t_end is in hand; `unfinished` the one this sitting ended in), written to results.json.
void write(const st::Options& opt, Json results, const std::vector<Run>& runs, const Run& unfinished, int r_max, double t_end,
           const surface::SphereSites& eval, const std::vector<double>& w) {
  Json tu = st::table({"r", "u_err_2", "order_2", "u_err_inf", "order_inf", "order_2_seed_index", "order_inf_seed_index", "seconds"},
                      {"", "cm/s", "", "cm/s", "", "", "", "s"});
  Json tx = st::table({"r", "X_err_2", "order_2", "X_err_inf", "order_inf", "order_2_seed_index", "order_inf_seed_index", "seconds"},
                      {"", "um", "", "um", "", "", "", "s"});
  std::vector<double> eu2, euinf, ex2, exinf;
  for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
    const Errors e = errors(runs[k], runs[k + 1], eval, w);
    eu2.push_back(e.u2), euinf.push_back(e.uinf), ex2.push_back(e.x2), exinf.push_back(e.xinf);
  }
  Json& V = results["values"];
  for (std::size_t k = 0; k < eu2.size(); ++k) {
    const int r = int(k) + 1;
    // As the formula is written: eps_{r-1} / eps_r with r - 1; as the seed's tables print it: eps_{r-2} / eps_{r-1} with r - 1.
    auto order = [&](const std::vector<double>& e) { return k >= 1 ? Json(successive_order(e[k - 1] / e[k], r - 1)) : Json(); };
    auto printed = [&](const std::vector<double>& e) { return k >= 2 ? Json(successive_order(e[k - 2] / e[k - 1], r - 1)) : Json(); };
    tu["rows"].push(row({r, eu2[k], order(eu2), euinf[k], order(euinf), printed(eu2), printed(euinf), runs[k].seconds}));
    tx["rows"].push(row({r, ex2[k], order(ex2), exinf[k], order(exinf), printed(ex2), printed(exinf), runs[k].seconds}));
    if (k >= 1)
      for (auto [name, e] : {std::pair{"u_2", &eu2}, {"u_inf", &euinf}, {"X_2", &ex2}, {"X_inf", &exinf}})
        V[std::string("last_order_") + name] = successive_order((*e)[k - 1] / (*e)[k], r - 1);
  }
  double worst_volume = 0;
  for (const Run& run : runs) worst_volume = std::max(worst_volume, std::abs(run.volume_change));
  V["max_volume_change_rel"] = worst_volume;
  Json tr = st::table({"r", "h_um", "dt_ns", "steps", "seconds", "seconds_per_step", "volume_change_rel", "commit"}, {"", "um", "ns", "", "s", "s", "", ""});
  for (const Run& run : runs)
    tr["rows"].push(row({run.r, 0.8 / run.r, 180.0 / run.r, run.steps, run.seconds, run.seconds / run.steps, run.volume_change, run.commit}));
  results["tables"]["runs"] = tr;
  results["tables"]["table51_velocity"] = tu;
  results["tables"]["table52_positions"] = tx;
  V["grids_completed"] = double(runs.size());
  for (int r = 1; r <= r_max; ++r) {
    st::RunProgress p;
    p.t_end = t_end;
    for (const Run& run : runs)
      if (run.r == r) p = {true, t_end, t_end, long(run.steps), run.seconds_per_step, ""};
    if (unfinished.r == r)  // how far this sitting took it
      p = {false, unfinished.steps * 180 * units::ns / r, t_end, long(unfinished.steps), unfinished.seconds_per_step, ""};
    st::record_run(results, "grid_r" + to_text(r), p);
  }
  st::write_results(opt, results);
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_convergence", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_convergence",
                                                   "Sec. 5.1.1, Tables 5.1-5.2: a stretched red cell relaxing on grids r = 1.. (h = 0.8/r um)");
    const bool full = opt.scale == st::Scale::full;
    const int r_max = full ? 6 : 3;
    // Quick scale stops at 36 us (a fifth of the seed's 180 us): r = 3 alone takes 5 minutes here
    // for 180 us. Full scale runs the seed's time.
    const double t_end = (full ? 180 : 36) * units::us;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 16 x 16; walls at rest in y, periodic in x and z; fluid at rest initially";
    P["cell"] = "Evans-Fung red cell (R0 = 3.91 um), Skalak E = 2.5e-3, G = 2.5e-1 dyn/cm only; stretch 1.1 in z, 1/1.1 in x";
    P["kernel_integrator"] = "Roma 3-point kernel, Peskin's two-stage scheme, the seed's coupling (a)-(g)";
    P["grids"] = "20 r cells per 16 um, h = 0.8/r um, dt = 180/r ns, n_d = 125 r^2, n_s = 500 r^2, r = 1.." + to_text(r_max);
    P["t_end_us"] = t_end / units::us;
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's public code; Sec. 2.1 prints 0.1 cP while saying plasma behaves like water)";
    const dvec centres = coarse_centres();
    const surface::SphereSites eval = surface::bauer_spiral(1000);
    const std::vector<double> w = surface::rbf_sphere_weights(eval, 1).w;  // eq. 2.22, phi = r

    // The grids in turn; at full scale the tables are written after every finished grid (a run
    // stopped before r = 6 leaves those of the grids it has), and at the end.
    std::vector<Run> runs;
    Run unfinished;  // the grid this sitting ended in, if one
    const st::Sitting sitting(opt);  // full scale: the wall time of this sitting, over the grids
    for (int r = 1; r <= r_max; ++r) {
      bool finished = false;
      Run run = relax(r, t_end, centres, eval, opt, sitting, finished);
      if (!finished) {
        st::log(opt, "sitting over at grid r = " + to_text(r) + " (step " + to_text(run.steps) + "): the grids r >= " + to_text(r) +
                         " are left for the next one");
        unfinished = run;
        break;
      }
      runs.push_back(std::move(run));
      if (full && runs.size() >= 2) write(opt, results, runs, unfinished, r_max, t_end, eval, w);
    }
    write(opt, results, runs, unfinished, r_max, t_end, eval, w);
    return 0;
  });
}
