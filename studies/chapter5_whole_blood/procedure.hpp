#pragma once
// chapter5_whole_blood's procedure (Sec. 5.2.1) as runs: per endothelium the init run (the red
// cells and the endothelium, the top wall turning) to the last starting time, its state kept at
// each; from each starting state the platelets placed against the red cells and a run with them
// (and over the bumpy wall one without the red cells); the runs' measures (measures.hpp) and the
// time to solution.
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "measures.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/scene/packing.hpp"

#include <string>
#include <vector>

namespace rbfib::whole_blood {

using namespace rbfib::scene;
namespace st = rbfib::study;
using study::row;
inline const double Lx = 16 * units::um, Ly = 12 * units::um, Lz = 16 * units::um;
inline const unsigned long long seed = 5021;  // the procedure's random numbers

struct Wall {
  std::string name;
  double y0, bump;  // eq. 5.5
};
inline const Wall flat{"flat", 1 * units::um, 0}, bumpy{"bumpy", 0.75 * units::um, 1 * units::um};

struct Setup {
  double h, dt;
  int rbc_nd, rbc_ns, plt_n;
  long endothelium;
  double turn, settle, mean_gap, window, flat_window;  // s; the runs' length over the bumpy and the flat wall
  int starts;
  std::vector<Wall> walls;
  int every;  // steps of dt between samples (with the ladder: that much simulated time)
  // > 0: the seed's adaptive step, dt = 2^k dt for k = 0..ladder by eq. 5.4, with the endothelium's
  // k and eta following the step by the seed's rule at this gain (sim/tether_stability.hpp).
  int ladder = 0;
  double tether_gain = 0;
  run::Cadence samples() const { return ladder > 0 ? run::Cadence{0, every * dt} : run::Cadence{every}; }
};

/// The study: its tables, and what the runs add up to. A value over a kind of run is written once
/// every run of that kind has finished (NaN before).
struct WholeBlood {
  const st::Options& opt;
  const Setup& s;
  Json& results;
  const st::Sitting sitting{opt};  // full scale: this sitting's wall time
  Json runs = st::table({"run", "t_start_ms", "t_end_ms", "steps", "seconds_per_step", "shear_platelet_layer_1_s", "couette_deviation_start",
                         "couette_deviation", "no_slip_height_um", "closest_red_cells_over_h", "closest_platelet_red_over_h",
                         "platelet_headroom_um", "unicycling_fraction", "longest_unicycling_ms", "max_distance_um", "max_aspect_change",
                         "tank_treading_period_ms", "volume_change"},
                        {"", "ms", "ms", "", "s", "1/s", "", "", "um", "", "", "um", "", "ms", "um", "", "ms", ""});
  Json procedure = st::table({"wall", "moved", "draws", "closest_um", "platelet_draws", "attempts_platelet_1", "attempts_platelet_2",
                              "refused_red_cells", "refused_surface_or_box", "gap1_um", "gap2_um", "starting_times_ms"},
                             {"", "", "", "um", "", "", "", "", "", "um", "um", "ms"});
  Json cost = st::table({"run", "h_um", "dt_ns", "steps_done", "steps_needed", "seconds_per_step", "hours_to_solution", "priced_from"},
                        {"", "um", "ns", "", "", "s", "h", ""});
  ReferenceSites rbc = reference_sites(cells::red_cell_spec(s.rbc_nd, s.rbc_ns)), plt = reference_sites(cells::platelet_spec(s.plt_n, s.plt_n));
  Measures measures{s.h};
  Finished done{};
  double hours_left = 0;  // the time to solution at the measured rates (h)
  int refused_red = 0, refused_surface = 0;
  std::vector<double> attempts{};  // points drawn per platelet placed

  /// A row of the cost table: the run's steps to go at its seconds per step; `from` says where its
  /// seconds per step and steps needed come from (its own steps, or another run's for one not begun).
  void add_cost(const std::string& run, double steps_done, double needed, double seconds_per_step, const std::string& from) {
    const double hours = (needed - steps_done) * seconds_per_step / 3600;
    hours_left += hours;
    cost["rows"].push(row({run, s.h / units::um, s.dt / units::ns, steps_done, needed, seconds_per_step, hours, from}));
  }
  void wall(const Wall& w, std::size_t wi);
  void run_from(const Wall& w, const Domain& box, std::size_t k, bool with_red, double t_start, const std::string& start_file,
                const io::Checkpoint& start, const std::vector<cells::Placement>& platelets, const std::vector<index_t>& tracked);
  void summarize();
};

}  // namespace rbfib::whole_blood
