// bench_scale: the coupled step on several processes (lib/rbfib/dist) through the rbfib command:
// weak scaling from one process to two, the bytes each process sends per step against a model of
// them, and the model's projection to 64 and 1,024 ranks (reference/bench_scale.yaml, conventions).
//
// The scenes: red cells between walls in y (top wall 16 mm/s along z), x and z periodic; the eight
// cells of the whole-blood box (16 x 12 x 16 um, scenes/whole_blood_bumpy.yaml) tiled along x (2x
// box, 16 cells, one process) and along x and z (4x box, 32 cells, two processes; and one process,
// for the speedup). Each run is `rbfib run` (two processes under mpiexec) for a few steps; its
// output gives the seconds per step, the largest velocity and, on two processes, the traffic line.
//
// Run:  build/studies/study_bench_scale --scale quick --out runs/bench_scale/quick
#include "common/study.hpp"
#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

using namespace rbfib;
namespace st = rbfib::study;
using st::number;
using st::row;

namespace {

struct Scale {
  double h;        // um
  int data, sample;
  int steps, repeats;
};

#if defined(RBFIB_COMMAND) && defined(RBFIB_MPIEXEC)
// The eight red cells of the whole-blood box: centre (um), rotation axis and angle (deg).
struct Placed {
  double c[3], axis[3], angle;
};
const Placed kBox[8] = {
    {{4.023521152, 6.138827504, 1.930320408}, {0.4113345735, 0.1885521296, -0.8917690077}, 8.616748617},
    {{3.974824518, 6.342616491, 5.950994469}, {0.2336787967, 0.5574604148, 0.7966380018}, 2.23026998},
    {{3.989106042, 6.075374373, 10.23170806}, {0.7261543688, -0.5786713862, -0.3712670999}, 4.340872144},
    {{4.096070485, 6.103011726, 14.01222664}, {0.6111371031, -0.7266775447, -0.3137693217}, 0.4518098765},
    {{12.09630418, 6.217769697, 4.066493879}, {-0.9114167025, 0.3408842665, 0.2304723654}, 3.69346559},
    {{11.82244446, 5.936727066, 8.018481606}, {0.5056748171, 0.2546382014, -0.8242890062}, 14.05381298},
    {{12.00867413, 6.189066145, 12.0311834}, {0.2582796887, -0.754664576, -0.603135955}, 2.553258844},
    {{12.10142044, 5.87240787, 0.002491379054}, {-0.7179587943, 0.5088304997, 0.4750017812}, 3.122351516},
};

/// The scene of tx x tz whole-blood boxes.
std::string scene_text(int tx, int tz, const Scale& s) {
  std::ostringstream y;
  y.precision(12);
  y << "name: bench_scale_" << tx << "x" << tz << "\n"
    << "domain:\n  size: [" << 16 * tx << " um, 12 um, " << 16 * tz << " um]\n  periodic: [x, z]\n"
    << "  walls:\n    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [0 mm/s, 0 mm/s, 16 mm/s]}\n"
    << "fluid: {density: 1 g/cm^3, viscosity: 1 cP}\n"
    << "grid: {h: " << s.h << " um}\n"
    << "time: {integrator: backward_forward_euler, dt: 100 ns, end: " << 0.1 * s.steps << " us}\n"
    << "ib: {kernel: bspline3}\n"
    << "cell_types:\n  - {name: red cell, preset: red_cell, data_sites: " << s.data << ", sample_sites: " << s.sample << "}\n"
    << "cells:\n";
  for (int i = 0; i < tx; ++i)
    for (int k = 0; k < tz; ++k)
      for (const Placed& p : kBox)
        y << "  - {type: red cell, center: [" << p.c[0] + 16 * i << " um, " << p.c[1] << " um, " << p.c[2] + 16 * k
          << " um], axis: [" << p.axis[0] << ", " << p.axis[1] << ", " << p.axis[2] << "], angle: " << p.angle << " deg}\n";
  y << "output: {diagnostics_every: 1}\n";
  return y.str();
}

/// What one run of the command gave.
struct Outcome {
  double seconds_per_step = NAN, max_velocity = NAN;
  double halo = NAN, halo_exchanges = NAN, ghosts = NAN, cells = NAN, transposes = NAN, transforms = NAN, reductions = NAN;
  double share_cells = NAN;  // (interpolation + forces + spreading) over the phases' sum, rank 0
};

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

double match(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return NAN;
  return std::stod(m[1].str());
}

/// The shell command that runs `rbfib run` on `processes` processes (one: without mpiexec) in dir.
std::string command_in(const std::string& scene, int processes, const std::string& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/scene.yaml") << scene;
  std::string cmd = "OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE ";
  if (processes > 1)
    cmd += "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 " +
           std::string(RBFIB_MPIEXEC) + " -n " + to_text(processes) + " ";
  return cmd + std::string(RBFIB_COMMAND) + " run " + dir + "/scene.yaml --out " + dir + "/out > " + dir + "/log.txt 2>&1";
}

/// Runs `rbfib run` on `processes` processes and reads its output; with `beside`, a second
/// one-process run of the same scene at the same time (the machine's own ceiling for two).
Outcome run_command(const std::string& scene, int processes, const std::string& dir, bool beside = false) {
  std::string cmd = command_in(scene, processes, dir);
  if (beside) cmd = "(" + cmd + ") & (" + command_in(scene, 1, dir + "_beside") + ") & wait";
  const int status = std::system(cmd.c_str());
  const std::string log = slurp(dir + "/log.txt");
  if (status != 0) throw std::runtime_error("rbfib run on " + to_text(processes) + " processes failed (" + dir + "/log.txt): " + log.substr(0, 400));
  Outcome o;
  const double steps = match(log, "done: ([0-9]+) steps in"), seconds = match(log, "steps in ([0-9.e+-]+) s");
  o.seconds_per_step = seconds / steps;
  o.halo = match(log, "halo ([0-9.e+-]+) bytes");
  o.halo_exchanges = match(log, "bytes in ([0-9.e+-]+) exchanges");
  o.ghosts = match(log, "the cells' ([0-9]+)\\)");
  o.cells = match(log, "cells ([0-9.e+-]+) bytes");
  o.transposes = match(log, "FFT transposes ([0-9.e+-]+) bytes");
  o.transforms = match(log, "bytes in ([0-9.e+-]+) transforms");
  o.reductions = match(log, "reductions ([0-9.e+-]+)");
  // The diagnostics: the last row's largest velocity; the phases' shares over the steps.
  std::ifstream csv(dir + "/out/diagnostics.csv");
  std::string line, last;
  std::getline(csv, line);  // header: step,t_s,dt_s,max_velocity_cm_s,...,seconds_interpolation,_forces,_spreading,_fluid
  double cells = 0, all = 0;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream s(line);
    for (std::string x; std::getline(s, x, ',');) v.push_back(std::stod(x));
    if (v.size() < 12) continue;
    cells += v[8] + v[9] + v[10];
    all += v[8] + v[9] + v[10] + v[11];
    o.max_velocity = v[3];
  }
  o.share_cells = all > 0 ? cells / all : NAN;
  return o;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("bench_scale", [&]() -> int {
    const st::Options opt = st::parse_command_line(argc, argv, "bench_scale",
                                                   "Several processes: weak scaling, communication, projection");
    const bool full = opt.scale == st::Scale::full;
    const Scale s = full ? Scale{0.4, 400, 1600, 40, 5} : Scale{0.5, 200, 800, 5, 1};
    st::Json results = st::make_results(opt);
    st::Json& P = results["parameters"];
    P["h_um"] = s.h;
    P["red_cell_sites"] = to_text(s.data) + " data, " + to_text(s.sample) + " sample";
    P["steps"] = s.steps;
    P["repeats"] = s.repeats;
    P["threads_per_process"] = 1;
    P["dt_ns"] = 100.0;
    P["integrator"] = "backward_forward_euler";
#if !defined(RBFIB_COMMAND) || !defined(RBFIB_MPIEXEC)
    throw std::runtime_error("bench_scale needs the rbfib command built with RBFIB_MPI (MPI and FFTW's MPI transforms)");
#else
    struct Config {
      std::string label;
      int processes, tx, tz;
      bool beside = false;
    };
    // The last: the first run twice at once, each on its own core, no communication: what two
    // processes of this machine reach when they share only its memory and caches (the ceiling).
    const std::vector<Config> configs = {{"2x box, 1 process", 1, 2, 1},
                                         {"4x box, 2 processes", 2, 2, 2},
                                         {"4x box, 1 process", 1, 2, 2},
                                         {"2x box, 1 process, two at once", 1, 2, 1, true}};
    std::vector<std::vector<Outcome>> out(configs.size());
    for (int r = 0; r < s.repeats; ++r)
      for (std::size_t c = 0; c < configs.size(); ++c) {
        const Config& k = configs[c];
        out[c].push_back(run_command(scene_text(k.tx, k.tz, s), k.processes, opt.out_dir + "/run_" + to_text(c), k.beside));
        st::log(opt, k.label + ", repeat " + to_text(r + 1) + ": " + to_text(out[c].back().seconds_per_step) + " s per step");
      }
    auto median_of = [&](std::size_t c, double Outcome::*f) {
      std::vector<double> v;
      for (const Outcome& o : out[c]) v.push_back(o.*f);
      return st::median(v);
    };
    st::Json runs = st::table({"configuration", "processes", "cells", "grid", "seconds_per_step", "seconds_per_step_min",
                               "seconds_per_step_max", "cells_share", "max_velocity_cm_s", "max_velocity_rel_diff_to_one_process"},
                              {"", "", "", "", "s", "s", "s", "", "cm/s", ""});
    const double n_y = std::round(12 / s.h);
    std::vector<double> t(configs.size());
    for (std::size_t c = 0; c < configs.size(); ++c) {
      const Config& k = configs[c];
      t[c] = median_of(c, &Outcome::seconds_per_step);
      double lo = INFINITY, hi = 0;
      for (const Outcome& o : out[c]) lo = std::min(lo, o.seconds_per_step), hi = std::max(hi, o.seconds_per_step);
      const double diff = std::abs(out[c].front().max_velocity / out[k.tz == 2 ? 2 : 0].front().max_velocity - 1);
      std::ostringstream grid;
      grid << std::lround(16 * k.tx / s.h) << " x " << n_y << " x " << std::lround(16 * k.tz / s.h);
      runs["rows"].push(row({k.label, double(k.processes), double(8 * k.tx * k.tz), grid.str(), number(t[c]), number(lo), number(hi),
                             number(median_of(c, &Outcome::share_cells)), number(out[c].front().max_velocity),
                             c == 0 || c == 2 ? st::Json() : number(diff)}));
    }
    st::Json& V = results["values"];
    V["weak_scaling_efficiency"] = number(t[0] / t[1]);
    V["two_at_once_efficiency"] = number(t[0] / t[3]);  // the machine's ceiling for two processes
    V["weak_scaling_over_ceiling"] = number(t[3] / t[1]);
    V["speedup_4x_box_one_to_two"] = number(t[2] / t[1]);
    V["max_velocity_rel_diff_two_vs_one"] = number(std::abs(out[1].front().max_velocity / out[2].front().max_velocity - 1));

    // ---- Communication: measured (two processes) against the model (conventions) -----------------
    const Outcome& two = out[1].front();
    const double nx = std::round(32 / s.h), nz = std::round(32 / s.h), G = two.ghosts, Pm = 2;
    // Backward-forward Euler, the seed's coupling: the fluid fills 8 fields on its 2 planes a side
    // (4 solutions, u, v, w, p at the stage's end); the cells' side widens u twice ((a) and (f), 3
    // components each) and sums the 3 spread components on G planes a side.
    const double E_fluid = 8, E_cells = 9, g = 2, solves = 4;
    const double halo_model = (E_fluid * g + E_cells * G) * 2 * nx * n_y * 8;
    const double modes_x = std::floor(nx / 2) + 1;  // real transforms: k_x = 0..nx/2
    const double transposes_model = solves * 2 * (nz / Pm) * modes_x * n_y * 16 * (Pm - 1) / Pm;
    st::Json comm = st::table({"kind", "measured_bytes_per_step", "model_bytes_per_step", "measured_over_model", "messages_per_step"},
                              {"", "B", "B", "", ""});
    comm["rows"].push(row({"halo", number(two.halo), number(halo_model), number(two.halo / halo_model), number(2 * two.halo_exchanges)}));
    comm["rows"].push(row({"FFT transposes (from FFTW's local sizes)", number(two.transposes), number(transposes_model),
                           number(two.transposes / transposes_model), number(two.transforms)}));
    comm["rows"].push(row({"cells (owners, diagnostics)", number(two.cells), st::Json(), st::Json(), st::Json()}));
    comm["rows"].push(row({"reductions (8-byte allreduces)", number(8 * two.reductions), st::Json(), st::Json(), number(two.reductions)}));
    V["halo_measured_over_model"] = number(two.halo / halo_model);
    V["transposes_measured_over_model"] = number(two.transposes / transposes_model);
    V["ghost_planes"] = G;
    V["owned_planes_per_process"] = nz / Pm;

    // ---- Projection: weak scaling along z to P processes on a stated network ----------------------
    const double alpha = 2e-6, beta = 12.5e9;  // s, bytes/s per process (100 Gb/s InfiniBand)
    const double lambda = 16;                  // cells per process
    const double share = median_of(1, &Outcome::share_cells), t2 = t[1];
    auto largest = [&](double p) { return lambda + std::sqrt(2 * lambda * std::log(p)); };
    const double local_transposed = (nz / Pm) * modes_x * n_y * 16;  // bytes of one transform's half spectrum per process
    st::Json proj = st::table({"processes", "seconds_fluid", "seconds_cells", "seconds_halo", "seconds_transposes", "seconds_reductions",
                               "seconds_per_step", "efficiency", "largest_term"},
                              {"", "s", "s", "s", "s", "s", "s", "", ""});
    for (double p : {2.0, 64.0, 1024.0}) {
      const double fluid = t2 * (1 - share), cells = t2 * share * largest(p) / largest(2);
      const double halo = (E_fluid + E_cells) * 2 * alpha + halo_model / beta;
      const double trans = solves * 2 * ((p - 1) * alpha + local_transposed * (p - 1) / p / beta);
      const double red = two.reductions * 2 * std::log2(p) * alpha;
      const double total = fluid + cells + halo + trans + red;
      const std::vector<std::pair<std::string, double>> terms = {
          {"cells (imbalance)", cells - t2 * share}, {"halo", halo}, {"transposes", trans}, {"reductions", red}};
      const auto top = std::max_element(terms.begin(), terms.end(), [](auto& a, auto& b) { return a.second < b.second; });
      proj["rows"].push(row({p, number(fluid), number(cells), number(halo), number(trans), number(red), number(total),
                             number(t[0] / total), top->first}));
    }
    V["network"] = "alpha = 2 us, 12.5 GB/s per process, full bisection";
    st::Json& T = results["tables"];
    T["runs"] = runs;
    T["communication"] = comm;
    T["projection"] = proj;
    st::write_results(opt, results);
    return 0;
#endif
  });
}
