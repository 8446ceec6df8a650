#pragma once
// A scene: the box, the flow, the cells and the point sets of a run, read from YAML with every
// physical quantity carrying its unit ("16 um", "1 cP", "50 ns", "2.5e-3 dyn/cm"; see
// core/quantity.hpp), converted once here to CGS, and built into a coupled IB step (sim/).
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

struct CellTypeEntry {
  cells::CellTypeSpec spec;
  std::string preset;  ///< the preset it started from
};

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

struct Scene {
  std::string name;    ///< from the file name or the "name" key
  std::string source;  ///< the YAML text as read (kept with the output)
  MacGrid grid;
  FluidParameters fluid;
  NavierStokesOptions fluid_options;
  sim::IbOptions ib;
  /// The motion of each wall, [axis][side]; at rest on periodic axes.
  std::array<std::array<WallMotion, 2>, 3> walls{};
  /// Start the flow as the steady shear between the walls (else at rest).
  bool initial_shear = false;
  double t_end = 0;  ///< s
  std::vector<CellTypeEntry> types;
  std::vector<CellEntry> cells;
  std::vector<sim::TetheredPoints> point_sets;
  int diagnostics_every = 1;  ///< steps between rows of the diagnostics table
  double checkpoint_every = 0;  ///< simulated time between checkpoints (s); 0: only at the end
  double snapshot_every = 0;    ///< simulated time between snapshots (s); 0: none
};

/// Reads a scene from YAML text; `origin` names it in messages (a file name).
Scene parse_scene(const std::string& yaml, const std::string& origin);
/// Reads a scene file.
Scene load_scene(const std::string& path);

/// The walls' velocities as the fluid solver's boundary data (time-dependent walls included).
BoundaryVelocity boundary_velocity(const Scene& scene);

/// Contacts between the scene's cells, the walls and the point sets, from the cells' placed data
/// sites (cheap: no operators are built). Throws InputError naming the cell (cells[i]) when one of
/// its data sites lies inside another cell (the winding number of the other's triangulated data
/// sites exceeds 1/2; the nearest periodic image counts) or a tethered point lies inside it (the
/// reader has already refused cells through a wall). Returns one line for each pair closer than 2h (Sec. 5.2.1 keeps 2h between
/// cells: the kernels of closer sites overlap, and the forces of the two cells mix).
std::vector<std::string> check_contacts(const Scene& scene);

/// Builds the coupled step of a scene (after check_contacts): the fluid solver with its walls, the
/// flow at t = 0, one batch per cell type with its cells, the point sets. Builds each type's
/// operators (seconds to minutes for large types). check_placements = false skips check_contacts,
/// for a caller that replaces the placed state at once by one it has checked itself (a run
/// continued from another run's state with cells added, as the platelets of Sec. 5.2.1).
sim::ImmersedBoundary build(const Scene& scene, bool check_placements = true);

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
