#pragma once
// chapter5_whole_blood's measures (Figs. 5.4-5.6): a sample's row of one run, and what the finished
// runs add up to (the velocity profile and the shear in the platelet layer, the platelets' distance,
// unicycling and shape, the red cells' tank-treading, closest approaches and volumes).
#include "common/study.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/rotation.hpp"
#include "rbfib/scene/packing.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <map>
#include <string>
#include <vector>

namespace rbfib::whole_blood {

using study::Json;
constexpr int red_count = 8;
const double wall_speed = 1.6;  // cm/s: 16 mm/s (Sec. 5.2.1)
extern const Vec3 flow_dir, vorticity_dir;  // the top wall's final direction, and the vorticity's

std::vector<double> host(const dvec& v);

/// Per red cell, the data site tracked for its tank-treading: its rim in the shear plane.
std::vector<index_t> tracked_sites(const std::vector<double>& X, index_t n, index_t N);

/// A sample's row: t; per platelet its centre, short axis and extents, its distance to the
/// endothelium, clearance, smallest surface speed, volume and headroom; the closest red cells and
/// platelet-red cell (cm), the red cells' least and largest volume (um^3); per red cell the angles
/// of its tracked site and of its short axis in the shear plane; the velocity profile along
/// flow_dir (cm/s). NaN for red cells' columns without them.
std::vector<double> sample(const sim::ImmersedBoundary& ib, bool red, const scene::Domain& box, const std::vector<index_t>& tracked);

/// Which kinds of run have finished: a value over a kind is written once all of them have (NaN before).
struct Finished {
  bool inits = true, red_runs = true, free_runs = true, flat_runs = true;
};

/// The finished runs' measures: their tables and the totals over them.
class Measures {
 public:
  explicit Measures(double h) : h(h) {}
  const double h;    // the grid's spacing (cm): closest approaches in units of h
  double v_ref = 0;  // the red cell's reference volume (um^3)
  Json profiles = study::table({"run", "y_um", "u_mm_s"}, {"", "um", "mm/s"});
  Json platelets = study::table({"run", "t_ms", "distance_um", "two_h_um", "unicycling", "min_speed_mm_s", "aspect_change"},
                                {"", "ms", "um", "um", "", "mm/s", ""});
  Json treading = study::table({"run", "cell", "material_turn_deg", "short_axis_turn_deg", "relative_turn_deg", "period_ms"},
                               {"", "", "deg", "deg", "deg", "ms"});
  Json snapshot = study::table({"cell", "z_um", "y_um"}, {"", "um", "um"});
  double closest_red = INFINITY;  // red cells' closest approach over h (the init runs' too)

  /// The measures of one finished run from its samples: the runs table's row (`out` then the
  /// measures), adding to the totals and the tables.
  Json analyse(const std::string& tag, bool flat, bool with_red, const std::vector<std::vector<double>>& rows, Json::Array out,
               const study::Options& opt);
  /// A side view (along x) of the cells and the endothelium at a run's end.
  void side_view(const std::vector<double>& E, const std::vector<std::vector<double>>& positions, index_t n_red, index_t n_platelet, double Lz);
  /// The values over the runs (those of an unfinished kind NaN).
  void values(Json& V, const Finished& done, bool has_flat) const;

 private:
  const double v_plt_ref = 4.0 / 3 * pi * 1.55 * 1.55 * 0.5;  // the platelet ellipsoid (um^3)
  std::map<std::string, double> shear{};  // per run: the platelet layer's shear rate
  double worst_volume = 0, worst_couette = 0, closest_platelet_red = INFINITY, min_platelet_endothelium = INFINITY;
  double min_headroom = INFINITY, no_slip_sum = 0, min_clearance = INFINITY, max_distance_red = 0, max_aspect = 0, longest_unicycling_flat = 0;
  int free_runs = 0;
  std::vector<double> frequencies{};  // tank-treading turns per second per red cell and run
};

}  // namespace rbfib::whole_blood
