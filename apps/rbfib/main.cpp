// The rbfib command: check and run scenes (lib/rbfib/scene, docs/scenes.md).
//
//   rbfib check SCENE.yaml                  validate; print the resolved scene with units, the
//                                           dimensionless groups, eq. 5.4's bound, memory
//   rbfib run SCENE.yaml --out DIR [--until T]
//                                           run it (lib/rbfib/run); progress on stdout;
//                                           DIR/diagnostics.csv and DIR/checkpoint.h5 (at the
//                                           scene's interval, the end and a numerical stop)
//   rbfib restart DIR [--until T]           continue from DIR/checkpoint.h5, bit for bit (a run
//                                           that has finished or stopped says so and exits)
//   mpirun -n N rbfib run|restart ...       the same on N processes (built with RBFIB_MPI): the
//                                           fluid in slabs along z (x and z periodic: the Fourier
//                                           solvers), each process the cells whose centroid lies in
//                                           its planes; the checkpoint and the snapshots are the
//                                           ones a single process writes, so a run continues on
//                                           any number of processes
//
// Exit status: 0 done, 2 bad input (one line naming the field and the value), 3 a numerical
// failure (the run stops, the message names the step, time and cause; what was written stays).
#include "rbfib/core/error.hpp"
#include "rbfib/core/quantity.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/io/snapshot.hpp"
#include "rbfib/run/run.hpp"

#ifdef RBFIB_WITH_MPI
#include "rbfib/dist/slab_fluid.hpp"
#include "rbfib/dist/slab_interaction.hpp"
#endif

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <unistd.h>

using namespace rbfib;

namespace {

/// The processes of this run: one, or N under mpirun (built with RBFIB_MPI). Process 0 prints and
/// writes the files; every process steps its part.
struct Processes {
  int rank = 0, size = 1;
  bool writer() const { return rank == 0; }
#ifdef RBFIB_WITH_MPI
  std::unique_ptr<dist::Comm> comm;
#endif
  /// The split of the scene's fluid among the processes (null for one process). Throws InputError
  /// naming the field for a scene the split cannot run (walls across x or z: the multigrid path).
  std::shared_ptr<const FluidDecomposition> split(const scene::Scene& s) const {
    if (size == 1) return nullptr;
#ifdef RBFIB_WITH_MPI
    // Halo: a cell reaches beyond its owner's planes by its size (1.5 x its reference radius, for
    // the stretch of a sheared cell) plus the kernel's support.
    double beyond = 0;
    for (const scene::CellTypeGroups& g : scene::dimensionless_groups(s)) beyond = std::max(beyond, 1.5 * g.radius);
    const int ghosts = std::max(dist::SlabFluid::fluid_reach, dist::SlabInteraction::ghosts_needed(beyond, s.grid.h(2), s.ib.kernel));
    return std::make_shared<const dist::SlabFluid>(s.grid, *comm, ghosts);
#else
    (void)s;
    return nullptr;
#endif
  }
  /// What each process sent per step of this sitting (dist::Traffic), the largest over the
  /// processes; one line (collective; empty on one process).
  std::string traffic(const std::shared_ptr<const FluidDecomposition>& parts, long steps) const {
#ifdef RBFIB_WITH_MPI
    if (!parts || steps <= 0) return "";
    const dist::Traffic& t = dist::traffic();
    const double n = double(steps);
    std::ostringstream s;
    s << "communication per step, largest over the processes: halo " << comm->max(t.halo / n) << " bytes in "
      << comm->max(double(t.halo_exchanges) / n) << " exchanges (the fluid's " << dist::SlabFluid::fluid_reach
      << " planes a side, the cells' " << static_cast<const dist::SlabFluid&>(*parts).ghosts() << "), cells " << comm->max(t.cells / n)
      << " bytes, FFT transposes " << comm->max(t.transposes / n) << " bytes in " << comm->max(double(t.transforms) / n)
      << " transforms (from FFTW's local sizes), reductions " << comm->max(double(t.reductions) / n);
    return s.str();
#else
    (void)parts, (void)steps;
    return "";
#endif
  }
  /// Runs fn on process 0 (files) and returns when it has, on every process; its failure becomes
  /// every process's.
  template <class F>
  void on_writer(const std::shared_ptr<const FluidDecomposition>& parts, F&& fn) const {
    std::exception_ptr error;
    if (writer()) try {
        fn();
      } catch (...) {
        error = std::current_exception();
      }
    if (parts) parts->agree(error);
    else if (error) std::rethrow_exception(error);
  }
};

/// The run's snapshots (io/snapshot.hpp), one series whatever the number of processes: process 0
/// writes them. On several processes each snapshot gathers the whole run's state
/// (ImmersedBoundary::carried(), collective) into a one-process copy of the run that process 0
/// builds at the first snapshot; the writer reads that copy as it reads a one-process run. The
/// copy holds the whole run, as the checkpoint's gather does: process 0's memory bounds the run.
class Snapshots {
 public:
  Snapshots(const scene::Scene& s, std::string out, const Processes& procs, std::shared_ptr<const FluidDecomposition> parts)
      : scene_(s), out_(std::move(out)), procs_(procs), parts_(std::move(parts)) {}

  /// Writes ib's state as the next snapshot (collective on several processes).
  void write(const sim::ImmersedBoundary& ib) {
    on_whole(ib, [&](const sim::ImmersedBoundary& whole) {
      if (!writer_) writer_ = std::make_unique<io::SnapshotWriter>(out_, whole);
      writer_->write(whole);
    });
  }
  /// A continued run: the series goes on from the snapshots already written up to ib's time
  /// (collective on several processes).
  void resume(const sim::ImmersedBoundary& ib) {
    on_whole(ib, [&](const sim::ImmersedBoundary& whole) {
      writer_ = std::make_unique<io::SnapshotWriter>(out_, whole);
      writer_->resume(whole.time());
    });
  }

 private:
  /// Runs fn on process 0 with the whole run: ib itself, or on several processes the copy holding
  /// the state gathered from all (collective).
  template <class F>
  void on_whole(const sim::ImmersedBoundary& ib, F&& fn) {
    std::optional<sim::ImmersedBoundary::Carried> state;
    if (parts_) state = ib.carried();
    procs_.on_writer(parts_, [&] { fn(state ? restored(*state) : ib); });
  }
  const sim::ImmersedBoundary& restored(const sim::ImmersedBoundary::Carried& state) {
    if (!copy_) copy_ = std::make_unique<sim::ImmersedBoundary>(io::build_scene(scene_));
    copy_->restore(state);
    return *copy_;
  }
  const scene::Scene& scene_;
  std::string out_;
  const Processes& procs_;
  std::shared_ptr<const FluidDecomposition> parts_;
  std::unique_ptr<sim::ImmersedBoundary> copy_;  // process 0, several processes: the whole run
  std::unique_ptr<io::SnapshotWriter> writer_;
};

/// A rough estimate of what a scene needs (bytes): about 40 grid vectors for the fluid, the
/// operators of each cell type (six blocks of n_s (+ n_d with bending) x n_d).
struct Memory {
  double fluid = 0, cells = 0;
};
Memory memory(const scene::Scene& s) {
  Memory m;
  for (const scene::CellTypeEntry& t : s.types) {
    const double nd = double(t.spec.data_sites.size()), ns = double(t.spec.sample_sites.size());
    m.cells += 8.0 * 6.0 * (ns + (t.spec.model.bending() ? nd : 0)) * nd;
  }
  m.fluid = 8.0 * 40.0 * double(s.grid.cells[0]) * s.grid.cells[1] * s.grid.cells[2];
  return m;
}

double physical_memory() { return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)); }

/// Refuses a scene that cannot fit in this machine's memory (rather than failing an allocation
/// or being killed minutes into the build).
void check_memory(const scene::Scene& s) {
  const Memory m = memory(s);
  if (m.fluid + m.cells > physical_memory())
    throw InputError("grid and cell_types", to_text((m.fluid + m.cells) / 1073741824) + " GiB estimated",
                     "more than this machine's " + to_text(physical_memory() / 1073741824) + " GiB of memory");
}

/// A rough time per step on this machine (s): the fluid measured (three steps of the scene's
/// grid, solvers and walls, median), the cell forces from the flops of their dense products
/// (cells::product_flops) at a fraction of a
/// DGEMM measured now that grows with the cells of a type, min(0.6, max(0.05, 0.08 N)) (what the
/// products reach here with 6N columns: 9% of DGEMM for one red cell, 56% for eight,
/// reports/bench_cells), over 0.8 (the site kernels). Interpolation and spreading, a few percent
/// of a step, are left out.
struct StepEstimate {
  double fluid = 0, forces = 0;
};
StepEstimate estimate_step(const scene::Scene& s) {
  StepEstimate e;
  NavierStokesSolver ns(s.grid, s.fluid, s.fluid_options, scene::boundary_velocity(s));
  FluidState state = ns.zero_state(0.0);
  ns.step(state);  // first step: workspace
  std::vector<double> t;
  for (int k = 0; k < 3; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ns.step(state);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  e.fluid = t[1];
  double work = 0;  // flops over the fraction of DGEMM they reach
  for (const scene::CellTypeEntry& type : s.types) {
    const double N = double(std::count_if(s.cells.begin(), s.cells.end(), [&](const scene::CellEntry& c) { return c.type == type.spec.name; }));
    work += cells::product_flops(type.spec, index_t(N)).total() / std::clamp(0.08 * N, 0.05, 0.6);
  }
  if (work > 0) {
    const index_t n = 1000;
    std::vector<double> h(static_cast<std::size_t>(n * n), 0.5);
    const linalg::DeviceMatrix A = linalg::DeviceMatrix::from_host(n, n, h.data());
    linalg::DeviceMatrix C(n, n);
    linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0, A.view(), A.view(), 0.0, C.view());
    const auto t0 = std::chrono::steady_clock::now();
    linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0, A.view(), A.view(), 0.0, C.view());
    synchronize();
    const double rate = 2.0 * double(n) * n * n / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.forces = work / rate / 0.8;
  }
  return e;
}

void print_check(const scene::Scene& s) {
  std::cout << scene::describe(s);
  const std::optional<scene::StartingState> start =
      s.start.checkpoint.empty() ? std::nullopt : std::optional<scene::StartingState>(io::read_starting_state(s));
  const std::vector<std::string> near = scene::check_contacts(s, start ? &*start : nullptr);  // throws InputError for overlaps
  std::cout << "contacts: no cell overlaps another cell, a wall or a point set; "
            << (near.empty() ? "every pair is at least 2h apart\n" : "closer than 2h:\n");
  for (const std::string& line : near) std::cout << "  " << line << "\n";
  const double rho = s.fluid.density, gdot = scene::shear_rate(s);
  const double h = std::min({s.grid.h(0), s.grid.h(1), s.grid.h(2)}), dt = s.fluid_options.dt;
  std::cout << "dimensionless groups (shear rate " << gdot << " 1/s between the walls):\n";
  for (const scene::CellTypeGroups& g : scene::dimensionless_groups(s)) {
    std::cout << "  '" << g.type << "': radius " << g.radius / units::um << " um, Reynolds rho gdot R^2 / mu = " << g.reynolds;
    if (g.shear_modulus > 0)
      std::cout << ", capillary mu gdot R / G_s (G_s = " << g.shear_modulus << " dyn/cm, the " << g.modulus << ") = " << g.capillary;
    std::cout << "\n";
  }
  // Eq. 5.4: dt <= (1/4) sqrt(h rho / ||f||_inf), i.e. ||f||_inf <= h rho / (16 dt^2).
  std::cout << "stopping condition (eq. 5.4) at dt = " << dt / units::ns << " ns: the run stops when the spread force density exceeds "
            << h * rho / (16 * dt * dt) << " dyn/cm^3\n";
  const StepEstimate e = estimate_step(s);
  const double steps = std::ceil(s.t_end / s.fluid_options.dt * (1 - 1e-12));
  std::cout << "time per step on this machine, roughly: " << e.fluid + e.forces << " s (fluid " << e.fluid
            << " s, measured on this grid; cell forces " << e.forces << " s, from their flops and a DGEMM measured now; "
            << "interpolation and spreading add a few percent); to the end at dt: " << steps << " steps, about "
            << steps * (e.fluid + e.forces) << " s\n";
  const Memory m = memory(s);
  std::cout << "memory, roughly: fluid " << m.fluid / 1048576 << " MiB (about 40 grid vectors), cell operators "
            << m.cells / 1048576 << " MiB; this machine has " << physical_memory() / 1073741824 << " GiB\n";
}

/// The diagnostics table's columns for the step's batches.
std::vector<std::string> csv_columns(const sim::ImmersedBoundary& ib) {
  std::vector<std::string> c = {"step", "t_s", "dt_s", "max_velocity_cm_s", "kinetic_energy_erg", "elastic_energy_erg",
                                "max_force_density_dyn_cm3", "dt_bound_s", "seconds_interpolation", "seconds_forces",
                                "seconds_spreading", "seconds_fluid", "refused", "refused_by_guard", "oscillation_growth",
                                "oscillation_cosine", "peak_set"};
  for (index_t b = 0; b < ib.batches(); ++b)
    for (index_t k = 0; k < ib.cells_in_run(b); ++k) c.push_back("volume_" + ib.batch(b).type().name() + "_" + std::to_string(k) + "_um3");
  return c;
}

/// One line of the diagnostics table (the step as an integer).
std::string csv_line(const std::vector<double>& row) {
  std::ostringstream s;
  for (std::size_t k = 0; k < row.size(); ++k) {
    if (k == 0) s << std::llround(row[k]);
    else s << "," << row[k];
  }
  return s.str() + "\n";
}

/// Steps the scene from its start or its checkpoint (DIR/checkpoint.h5) to min(until, its end):
/// the run loop (run/run.hpp) with the scene's cadences; DIR/diagnostics.csv is the series
/// "diagnostics" (kept in the checkpoint), rewritten from it when a run continues.
int advance(const scene::Scene& s, const std::string& out, double until, const Processes& procs,
            std::shared_ptr<const FluidDecomposition> parts) {
  const bool terminal = isatty(STDOUT_FILENO), writer = procs.writer();
  const std::string checkpoint = out + "/checkpoint.h5", csv_path = out + "/diagnostics.csv";
  run::Options o;
  o.t_end = s.t_end;
  o.until = until > 0 ? until : s.t_end;
  o.checkpoint = checkpoint;
  o.checkpoint_every = {0, s.checkpoint_every, 0};
  o.sample_every = {s.diagnostics_every, 0, 0};
  o.snapshot_every = {0, s.snapshot_every, 0};
  o.progress_every = {0, 0, terminal ? 0.5 : 5.0};
  o.parts = parts;
  std::ofstream csv;
  Snapshots snapshots(s, out, procs, parts);
  run::Hooks h;
  h.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& series) {
    if (!r) return;  // the table starts after the first step
    run::Series& d = series["diagnostics"];
    if (d.columns.empty()) d.columns = csv_columns(ib);
    std::vector<double> row = {double(ib.step_count()), ib.time(), r->dt, r->max_velocity, r->kinetic_energy, r->elastic_energy,
                               r->max_force_density, r->dt_bound, r->seconds_interpolation, r->seconds_forces,
                               r->seconds_spreading, r->seconds_fluid, double(r->refused), double(r->refused_by_guard),
                               r->oscillation_growth, r->oscillation_cosine, double(r->peak_set)};
    for (index_t b = 0; b < ib.batches(); ++b)  // every cell of the run, in the order of their indices
      for (double v : ib.run_cell_values(b, ib.diagnostics(b).volume)) row.push_back(v / (units::um * units::um * units::um));
    if (row.size() != d.columns.size()) row.resize(d.columns.size(), NAN);  // a run begun with fewer columns keeps them
    if (writer) csv << csv_line(row);
    d.rows.push_back(std::move(row));
  };
  h.checkpointed = [&](const run::SeriesSet&) { csv.flush(); };
  if (s.snapshot_every > 0) h.snapshot = [&](const sim::ImmersedBoundary& ib) { snapshots.write(ib); };
  h.progress = [&](const run::Progress& p) {
    if (writer) std::cout << (terminal ? "\r" : "") << p.describe() << (terminal ? "" : "\n") << std::flush;
  };
  if (writer) {
    std::cout << scene::describe(s);
    if (procs.size > 1) std::cout << "processes: " << procs.size << " (the fluid in slabs along z, each process the cells whose centroid lies in its planes)\n";
    std::cout << "building the cell types and the solver ..." << std::endl;
  }
  run::Run run(s, o, h);
  if (run.continued() && s.snapshot_every > 0) snapshots.resume(run.ib());
  if (!writer) {
    const run::Progress p = run.evolve();
    procs.traffic(parts, p.sitting_steps);
    return p.status == run::RunStatus::stopped ? 3 : 0;
  }
  // The table as the run has it: its header and every row the checkpoint kept.
  csv.open(csv_path, std::ios::trunc);
  const std::vector<std::string> columns = csv_columns(run.ib());
  for (std::size_t k = 0; k < columns.size(); ++k) csv << (k ? "," : "") << columns[k];
  csv << "\n";
  if (const auto it = run.series().find("diagnostics"); it != run.series().end())
    for (const std::vector<double>& row : it->second.rows) csv << csv_line(row);
  if (run.continued())
    std::cout << "restarting at step " << run.ib().step_count() << ", t = " << run.ib().time() / units::us << " us" << std::endl;
  const run::Progress p = run.evolve();
  csv.flush();
  if (terminal) std::cout << "\n";
  if (const std::string line = procs.traffic(parts, p.sitting_steps); !line.empty()) std::cout << line << std::endl;
  if (p.status == run::RunStatus::stopped) {
    std::cout << "rbfib: stopped: " << p.stop_message << "; the last good state is in " << checkpoint << std::endl;
    return 3;
  }
  std::cout << "done: " << p.sitting_steps << " steps in " << p.sitting_seconds << " s to t = " << p.clock.t / units::us << " us"
            << (p.status == run::RunStatus::finished ? " (the scene's end)" : "") << "; " << csv_path << ", " << checkpoint << std::endl;
  return 0;
}

int run_scene(const scene::Scene& s, const std::string& out, double until, const Processes& procs) {
  check_memory(s);
  const std::shared_ptr<const FluidDecomposition> parts = procs.split(s);
  procs.on_writer(parts, [&] {
    std::filesystem::create_directories(out);
    std::ofstream(out + "/scene.yaml") << s.source;
    std::filesystem::remove(out + "/checkpoint.h5");  // a run starts afresh; `restart` continues
  });
  return advance(s, out, until > 0 ? std::min(until, s.t_end) : s.t_end, procs, parts);
}

int restart(const std::string& out, double until, const Processes& procs) {
  const io::Checkpoint k = io::read_checkpoint(out + "/checkpoint.h5");
  const scene::Scene s = scene::parse_scene(k.scene_yaml, out + "/checkpoint.h5");
  return advance(s, out, until, procs, procs.split(s));
}

}  // namespace

int main(int argc, char** argv) {
  Processes procs;
#ifdef RBFIB_WITH_MPI
  // MPI only when started by mpirun (OpenMPI names the world's size): a plain run stays one process.
  std::unique_ptr<dist::Session> session;
  if (std::getenv("OMPI_COMM_WORLD_SIZE")) {
    session = std::make_unique<dist::Session>(argc, argv);
    procs.comm = std::make_unique<dist::Comm>();
    procs.rank = procs.comm->rank();
    procs.size = procs.comm->size();
  }
#endif
  // Messages from process 0 only (every process meets the same error: the scene is the same, and
  // a step's failure is agreed by all).
  static std::ostream silent(nullptr);
  std::ostream& err = procs.writer() ? std::cerr : silent;
  CLI::App app{"rbfib: immersed-boundary simulations of red cells, platelets and endothelium in plasma (scenes in YAML)"};
  app.require_subcommand(1);
  std::string scene_path, out, until_text;
  CLI::App* check = app.add_subcommand("check", "validate a scene and print it resolved, with units and dimensionless groups");
  check->add_option("scene", scene_path, "the scene file (YAML)")->required();
  CLI::App* runc = app.add_subcommand("run", "run a scene; progress on stdout, per-step diagnostics in OUT/diagnostics.csv");
  runc->add_option("scene", scene_path, "the scene file (YAML)")->required();
  runc->add_option("--out", out, "the output directory")->required();
  runc->add_option("--until", until_text, "stop at this simulated time (with its unit, e.g. '10 us'); default: the scene's end");
  CLI::App* restartc = app.add_subcommand("restart", "continue a run from the newest checkpoint in its output directory");
  restartc->add_option("out", out, "the run's output directory")->required();
  restartc->add_option("--until", until_text, "stop at this simulated time (with its unit); default: the scene's end");
  std::vector<std::string> slim_paths;
  CLI::App* slimc = app.add_subcommand("slim", "rewrite the checkpoints of runs that have ended without their fluid (cells, series and clock kept; "
                                                "about a fiftieth of the file); a running run's is refused");
  slimc->add_option("checkpoints", slim_paths, "checkpoint files (HDF5)")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    const double until = until_text.empty() ? 0.0 : parse_quantity(until_text, "s", "--until");
    if (!until_text.empty() && !(until > 0)) throw InputError("--until", until_text, "must be positive");
    if (*restartc) return restart(out, until, procs);
    if (*slimc) {
      for (const std::string& path : slim_paths) {
        if (!std::filesystem::is_regular_file(path)) throw InputError("checkpoint", path, "does not exist");
        const auto before = std::filesystem::file_size(path);
        const bool done = io::slim_checkpoint(path);
        std::cout << path << ": " << (done ? "" : "already ") << "without its fluid, " << before / 1000 << " -> "
                  << std::filesystem::file_size(path) / 1000 << " kB" << std::endl;
      }
      return 0;
    }
    const scene::Scene s = scene::load_scene(scene_path);
    if (*check) {
      if (!procs.writer()) return 0;
      check_memory(s);
      print_check(s);
      return 0;
    }
    return run_scene(s, out, until, procs);
  } catch (const InputError& e) {
    err << "rbfib: " << e.what() << std::endl;
    return 2;
  } catch (const NumericalError& e) {
    err << "rbfib: " << e.what() << std::endl;
    return 3;
  } catch (const std::exception& e) {
    err << "rbfib: " << e.what() << std::endl;
    return 1;
  }
}
