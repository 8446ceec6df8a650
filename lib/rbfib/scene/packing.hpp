#pragma once
// The initialization of dissertation Sec. 5.2.1 as a reproducible procedure: every random draw
// comes from one std::mt19937_64 seeded by the caller, so a seed gives the same scene everywhere.
//
// 1. red_cell_layout: "2 rows of 4 RBCs, each in their reference configuration, ... with its
//    center of mass on the plane y = 6 um and oriented with concavities facing in the z
//    direction ... staggered by 2 um. These locations are then randomly translated and rotated
//    while maintaining a distance of at least 2h between cells." Rows at x = Lx/4 and 3Lx/4, cells
//    Lz/4 apart in a row, the second row shifted by 2 um in z. Each cell in turn is then moved by a
//    random rigid motion (a translation uniform in [-d, d]^3 and a rotation by an angle uniform in
//    [0, a] about a uniformly random axis), drawn again, each time 2% smaller, until the moved cell
//    keeps 2h from every other cell (periodic images included), from the top wall and from the
//    endothelium; after `max_draws` refused draws it stays where it is. The seed gives neither d
//    nor a. The rows leave 0.89 um between neighbouring cells and 1.44 um within a row, so at a
//    coarse h (2h = 0.8 um at h = 0.4 um) only small moves fit.
// 2. starting_times: "a series of times, sampled from a Poisson distribution to be approximately
//    3 ms apart", read as a Poisson process after the settling time: exponential gaps of mean 3 ms.
// 3. place_platelets: "we randomly choose points on the endothelium and one on each platelet
//    surface ... two points on the endothelium that are at least 3.9 um, a platelet diameter plus
//    4h, apart ... The platelets are oriented so that the normal emanating from the platelet
//    opposes the normal at the corresponding point on the endothelium. The platelet is then placed
//    so its chosen surface point is separated from the endothelium point by a random distance
//    between 0.3 um and 1 um. If the generated orientation does not pass within 0.4 um of an RBC,
//    the platelet is accepted. Otherwise, we try again with a different platelet point." The spin
//    about the normal, which the seed leaves open, is drawn uniformly; a placement is also refused
//    when a platelet site lies below the endothelium's surface or outside the box.
// Distances between cells are between their data sites (the sites the scene places), cm.
#include "rbfib/cells/batch.hpp"
#include "rbfib/scene/scene.hpp"

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace rbfib::scene {

using Vec3 = std::array<double, 3>;

/// A reference shape at its data sites, n x 3 column-major (cm), centred at the origin, with
/// the outward unit normal at each site.
struct ReferenceSites {
  std::vector<double> X, normals;
  index_t n = 0;
};
ReferenceSites reference_sites(const cells::CellTypeSpec& spec);

/// The box and the endothelium the cells are placed in (walls across y, periodic in x and z).
struct Domain {
  double Lx = 0, Ly = 0, Lz = 0;
  scene::EndotheliumSurface endothelium;
};

struct LayoutSpec {
  double h = 0;                     ///< grid spacing: cells keep 2h apart
  double y = 6e-4;                  ///< the rows' plane (cm)
  double stagger = 2e-4;            ///< the second row's shift in z (cm)
  double max_shift = 1e-4;          ///< d (cm)
  double max_angle = 0.349065850398866;  ///< a (rad): 20 deg
  double shrink = 0.98;              ///< the move's size after a refusal, relative
  int max_draws = 200;
};

struct Layout {
  std::vector<cells::Placement> red_cells;
  int moved = 0;       ///< cells whose random motion was accepted
  int draws = 0;       ///< motions drawn in all
  double closest = 0;  ///< the smallest distance between two cells after the moves (cm)
};
Layout red_cell_layout(const ReferenceSites& red_cell, const Domain& box, const LayoutSpec& spec, std::mt19937_64& rng);

/// Settling time, then `count` times separated by exponential gaps of mean `mean_gap` (s).
std::vector<double> starting_times(double settle, double mean_gap, int count, std::mt19937_64& rng);

struct PlateletSpec {
  double min_separation = 3.9e-4;  ///< between the two endothelium points (a diameter plus 4h)
  double gap_min = 0.3e-4, gap_max = 1e-4;  ///< the chosen points' distance (cm)
  double red_cell_clearance = 0.4e-4;       ///< from every red cell site (cm)
  int max_draws = 1000;
};

struct PlateletPlacement {
  std::vector<cells::Placement> platelets;
  std::vector<double> gaps;  ///< the drawn distances (cm)
  int draws = 0;             ///< platelet points drawn in all
  std::vector<int> attempts; ///< per platelet placed: the platelet points drawn for it (the accepted one included)
  int refused_red_cells = 0; ///< draws refused for passing within the clearance of a red cell (the seed's test)
  int refused_surface = 0;   ///< draws refused for a site below the endothelium's surface or outside the box
};
/// Places `count` platelets over the endothelium points `E` (3m, X[d m + k]) against the red
/// cells' data sites `red` (n_r x 3N column-major, cells::Batch::positions_host's layout; may be
/// empty). Throws NumericalError when max_draws draws find no placement.
PlateletPlacement place_platelets(const ReferenceSites& platelet, const Domain& box, const std::vector<double>& E,
                                  const std::vector<double>& red, index_t n_red, int count, const PlateletSpec& spec,
                                  std::mt19937_64& rng);

/// The smallest distance between the sites of cell A and of cell B (nearest periodic image in x,
/// z). A distance above `cutoff` may be returned as a lower bound (from the bounding spheres).
double cell_distance(const std::vector<double>& A, index_t na, const std::vector<double>& B, index_t nb, const Domain& box,
                     double cutoff = INFINITY);

/// The smallest distance from the sites of a cell (n x 3) to red cells given in a batch's layout
/// (n_red x 3N, X[(d N + c) n_red + i]; infinite for none). Distances above `cutoff` may be
/// returned as a lower bound.
double distance_to_red_cells(const std::vector<double>& X, index_t n, const std::vector<double>& red, index_t n_red, const Domain& box,
                             double cutoff = INFINITY);

/// Cells of one reference shape placed, in a batch's layout (n x 3N, X[(d N + c) n + i]).
std::vector<double> batch_layout(const ReferenceSites& r, const std::vector<cells::Placement>& placements);

/// The smallest distance between two of the N cells of n sites in a batch's layout (n x 3N).
double closest_cells(const std::vector<double>& X, index_t n, index_t N, const Domain& box);

/// The smallest distance from the sites of a cell to points E (3m) spread over the whole period in x
/// and z (the endothelium), each pair at its nearest periodic image.
double sheet_distance(const std::vector<double>& X, index_t n, const std::vector<double>& E, const Domain& box);

}  // namespace rbfib::scene
