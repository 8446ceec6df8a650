#pragma once
// A scene: the box, the flow, the cells and the point sets of a run, read from YAML with every
// physical quantity carrying its unit ("16 um", "1 cP", "50 ns", "2.5e-3 dyn/cm"; see
// core/quantity.hpp), converted once here to CGS, and built into a coupled IB step (sim/).
//
// Both ways: a driver may fill a Scene in C++ (cell_type(), the entries below) and write it with
// to_yaml(), the text that is kept beside its results and reads back to an equal scene.
//
// Reading is strict: an unknown key, a missing required key, a value of the wrong type or
// dimension, or a value out of range is an InputError naming the field (its path in the file,
// e.g. "cells[2].center[1]"), the value and what was expected; nothing is silently defaulted
// except the optional keys documented in docs/scenes.md with their defaults.
#include "rbfib/cells/presets.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <array>
#include <string>
#include <vector>

namespace rbfib::scene {

/// A cell type: a preset of cells/presets.hpp with its arguments, and the spec they give.
struct CellTypeEntry {
  cells::CellTypeSpec spec;
  std::string preset;         ///< red_cell, platelet, skalak_sphere or chapter3_red_cell
  double radius = 0;          ///< skalak_sphere: the sphere's radius (cm)
  int degree = 19;            ///< chapter3_red_cell: the spherical-harmonic degree
};

/// The cell type `name` from a preset: its data and sample site counts (0: the preset's default,
/// docs/scenes.md), the sphere's radius (skalak_sphere, cm) or the degree (chapter3_red_cell).
/// Throws InputError for an unknown preset.
CellTypeEntry cell_type(const std::string& name, const std::string& preset, index_t data_sites = 0, index_t sample_sites = 0,
                        double radius = 0, int degree = 19);

struct CellEntry {
  std::string type;  ///< a name in Scene::types
  cells::Placement placement;
  std::array<double, 3> force{0, 0, 0};  ///< constant total force on the cell (dyn)
};

/// The motion of one wall: a constant velocity, or (Sec. 5.2.1) a constant speed whose direction
/// in the wall's plane turns from one angle to another over a time and then stays:
/// direction = cos(alpha) e_q + sin(alpha) e_p, with p < q the wall's two tangential axes (for a
/// wall across y: alpha from e3 toward e1, the seed's 16 mm/s (sin alpha e1 + cos alpha e3)).
struct WallMotion {
  std::array<double, 3> velocity{0, 0, 0};  ///< cm/s (constant motion)
  bool turning = false;
  double speed = 0;                 ///< cm/s
  double from = 0, to = 0, over = 0;  ///< rad, rad, s
  int axis = 1;                     ///< the wall's normal axis
  /// The wall's velocity at time t (cm/s).
  std::array<double, 3> at(double t) const;
};

/// The endothelium's surface of dissertation eq. 5.5 over a wall's tangential axes (s, t) (for a
/// wall across y: s = x, t = z), lengths Ls and Lt: height = y0 + bump cos^2(theta - phi) sin^2(phi/2)
/// with theta = 2 pi s / Ls, phi = 2 pi t / Lt (bump = 0: the flat wall y = y0). cm.
struct EndotheliumSurface {
  double y0 = 0, bump = 0, Ls = 0, Lt = 0;
  double height(double s, double t) const;
  /// The unit normal pointing away from the wall it covers (into the flow), as (n_s, n_normal, n_t).
  std::array<double, 3> normal(double s, double t) const;
};

/// The surface a tethered point set lies on, kept as it was given so that the scene writes back:
/// a cell-centred lattice on a plane across `normal` at `at`, (i + 1/2) L / n on the two tangential
/// axes; or the toroidal spiral of Appendix B with N points on the surface of eq. 5.5 (bump 0: flat).
struct PointSurface {
  bool spiral = false;
  int normal = 1;                   ///< the axis the surface is across (0, 1, 2)
  double at = 0;                    ///< its position along that axis (cm); the spiral's y0
  std::array<int, 2> lattice{0, 0};  ///< plane: points along the tangential axes p < q
  index_t points = 0;               ///< spiral: N
  double bump = 0;                  ///< spiral: eq. 5.5's bump height (cm)
};

/// A set of points held to their positions by damped springs (eq. 2.10), k and eta per point:
/// given, or following the step by the seed's rule at a gain (sim/tether_stability.hpp; YAML
/// `follow_step: {gain: 0.5}` in place of k and eta).
struct PointSetEntry {
  std::string name;
  PointSurface surface;
  double k = 0;            ///< dyn/cm
  double eta = 0;          ///< dyn s/cm
  double follow_gain = 0;  ///< > 0: k and eta follow the step at this gain, in (0, 1)
};

/// A wall held exactly by a solve (sim/held_wall.hpp): markers on a surface, about 2h apart.
/// YAML: `held_walls: [{name: endothelium, plane: {y: 1 um, points: [40, 40]}}]`.
struct HeldWallEntry {
  std::string name;
  PointSurface surface;
};

/// The points of a set on its surface in a box of the given lengths (cm), n x 3 column-major.
std::vector<double> point_positions(const PointSurface& surface, const std::array<double, 3>& box);
/// The tethered points of an entry, anchored where they start.
sim::TetheredPoints tethered_points(const PointSetEntry& entry, const std::array<double, 3>& box);

/// The walls of a scene at rest, each knowing its axis: Scene::walls' starting value.
std::array<std::array<WallMotion, 2>, 3> walls_at_rest();

/// Where a scene's run starts: at rest at t = 0 (the default), or from another run's checkpoint
/// (Sec. 5.2.1: platelets placed into a developed flow of red cells): its fluid, clock and
/// tethered points, and the cells of the types named in `keep`; the scene's own cells are added.
/// YAML: `start: {checkpoint: FILE, keep: [red cell]}`.
struct Start {
  std::string checkpoint;         ///< a checkpoint file (io/checkpoint.hpp); empty: at rest at t = 0
  std::vector<std::string> keep;  ///< the cell types whose cells come from the checkpoint
};

/// The state a scene starts from, read from Start::checkpoint (io::read_starting_state).
struct StartingState {
  sim::ImmersedBoundary::Carried state;
  std::vector<std::string> batch_types;  ///< the cell type of each of its batches
  std::array<int, 3> cells{};            ///< its grid
};

struct Scene {
  std::string name;    ///< from the file name or the "name" key
  std::string source;  ///< the YAML text as read (kept with the output)
  MacGrid grid;
  FluidParameters fluid;
  NavierStokesOptions fluid_options;
  sim::IbOptions ib;
  /// The motion of each wall, [axis][side]; at rest on periodic axes.
  std::array<std::array<WallMotion, 2>, 3> walls = walls_at_rest();
  /// Start the flow as the steady shear between the walls (else at rest).
  bool initial_shear = false;
  Start start;
  double t_end = 0;  ///< s
  std::vector<CellTypeEntry> types;
  std::vector<CellEntry> cells;
  std::vector<PointSetEntry> point_sets;
  std::vector<HeldWallEntry> held_walls;
  int diagnostics_every = 1;  ///< steps between rows of the diagnostics table
  double checkpoint_every = 0;  ///< simulated time between checkpoints (s); 0: only at the end
  double snapshot_every = 0;    ///< simulated time between snapshots (s); 0: none
};

/// Reads a scene from YAML text; `origin` names it in messages (a file name).
Scene parse_scene(const std::string& yaml, const std::string& origin);
/// Reads a scene file.
Scene load_scene(const std::string& path);

/// The scene as YAML that parse_scene reads back to an equal scene: every quantity in CGS units
/// in the shortest text that reads back to the same double, the site counts, the point sets' surfaces and
/// each cell type's force model in full. `comment`: lines written first, each after "# ".
std::string to_yaml(const Scene& scene, const std::string& comment = "");

/// A scene filled in C++, checked as a file is: parse_scene(to_yaml(scene), name), so that the
/// result carries its text (Scene::source) and every field has passed the reader's checks.
Scene checked(const Scene& scene, const std::string& comment = "");

/// The walls' velocities as the fluid solver's boundary data (time-dependent walls included).
BoundaryVelocity boundary_velocity(const Scene& scene);

/// The cell types in the order of the coupled step's batches: each type with cells in the scene
/// or kept from its start.
std::vector<std::string> batch_types(const Scene& scene);

/// Contacts between the scene's cells, the walls and the point sets, from the cells' placed data
/// sites (cheap: no operators are built). Throws InputError naming the cell (cells[i]) when one of
/// its data sites lies inside another cell (the winding number of the other's triangulated data
/// sites exceeds 1/2; the nearest periodic image counts) or a tethered point lies inside it (the
/// reader has already refused cells through a wall). Returns one line for each pair closer than 2h (Sec. 5.2.1 keeps 2h between
/// cells: the kernels of closer sites overlap, and the forces of the two cells mix).
/// With a start, the kept cells and the tethered points are checked where the starting state has
/// them (the kept cells are named "start: <type> <k>").
std::vector<std::string> check_contacts(const Scene& scene, const StartingState* start = nullptr);

/// Builds the coupled step of a scene after check_contacts: the fluid solver with its walls, the
/// flow at t = 0, one batch per cell type with its cells, the point sets; with a start (required
/// when the scene has one), the fluid, clock, points and kept cells of the starting state.
/// Builds each type's operators (seconds to minutes for large types).
sim::ImmersedBoundary build(const Scene& scene, const StartingState* start = nullptr,
                            std::shared_ptr<const FluidDecomposition> parts = nullptr);

/// The flat sheet that models a point set's explicit stability in the scene (its normal axis must
/// have walls at both ends; InputError otherwise): its points per area over the box's tangential
/// face, its height above the lower wall (a bumpy spiral: its crest, the conservative choice).
sim::TetherSheet tether_sheet(const Scene& scene, const PointSetEntry& entry);

/// The shear rate between the walls at t = 0 (1/s): the largest wall-velocity difference over the
/// gap (0 without moving walls).
double shear_rate(const Scene& scene);

/// The dimensionless groups of one cell type in the scene's flow.
struct CellTypeGroups {
  std::string type;
  double radius = 0;         ///< the largest distance of the reference surface from its centre (cm)
  double reynolds = 0;       ///< rho gdot R^2 / mu
  double shear_modulus = 0;  ///< G_s of the first energy that resists shear (dyn/cm); 0: none does
  std::string modulus;       ///< which: e.g. "Skalak E"
  double capillary = NAN;    ///< mu gdot R / G_s (NaN without a shear modulus)
};
/// Reynolds and capillary numbers per cell type at the shear rate between the walls.
std::vector<CellTypeGroups> dimensionless_groups(const Scene& scene);

/// A multi-line summary with units: the box, grid, flow, step, kernel, types, cells, point sets.
std::string describe(const Scene& scene);

}  // namespace rbfib::scene
