#pragma once
// Chapter 3's capillary (the JCP 2018 paper, Sec. 5.1), a setup no scene file describes: one run
// of a red cell (eq. 92) carried by pressure-driven flow through a
// tethered capillary, or the empty capillary, in steady Stokes flow on a periodic box.
//
// Model (CGS inside, um / pN / s in the tables):
//   cell       eq. (92) reference, R = 3.91 um, centred at (-8, 0, 0) um, symmetry axis x;
//              neo-Hookean eq. (68) (Gs = 2.5e-3 dyn/cm, A = 50) plus bending eq. (79)
//              E = k_bend int (2H)^2 dA (the library's 2 kappa H^2 with kappa = 2 k_bend);
//              SHVD (m interpolation sites, degree M, forces at n evaluation sites) or LDSM (the n
//              triangulated sites, eq. 66; no bending, as the paper, Sec. 5.1.2).
//   capillary  tethered nodes on the cylinder r = 5 um, -8 <= x <= 8 um (eq. 93, sim/capillary.hpp):
//              F^_k = -k_teth (X_k - Z_k), k_teth = 2.45e-3 dyn/cm per node.
//   background f_in = 8e3 dyn/cm^3 along +x at the x-faces inside the capillary (see Region),
//              f_out at the other x-faces with N_in f_in + N_out f_out = 0 exactly.
//   fluid      mu = 1.2e-2 P, box [-12, 12]^3 um periodic, eta^3 MAC cells, steady Stokes solved
//              exactly (fluid/periodic_stokes.hpp, alpha = 0), Peskin's 4-point kernel.
// Time update (Sec. 3.3 with the capillary's eqs. 94-95), per step k: cell forces at X^k (SHVD at
// the n sites times dA0; LDSM eq. 66) and tether forces; spread both plus the background force;
// Stokes solve; U = I u at the m (SHVD) or n (LDSM) cell sites and the nodes; X^_cap = X_cap^k +
// dt U_cap (eq. 94); u_c = mean over the nodes of (Z_cap - X^_cap) / dt (eq. 95, equal node areas);
// X_cap^{k+1} = X^_cap + dt u_c and X_cell^{k+1} = X_cell^k + dt (U_cell + u_c). The library's
// coupled step (forward Euler on steady periodic Stokes, the nodes holding the frame) stepped by
// its run loop; the records are the run's series, kept in its checkpoint: a resumed run continues
// bit for bit. The studies' bookkeeping (runs kept over sittings, results) is
// studies/common/capillary.hpp.
#include "rbfib/models/shell_relaxation.hpp"
#include "rbfib/surface/cylinder.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace rbfib::capillary {

constexpr double um = 1e-4;  // cm

/// Where the background force pushes forward.
enum class Region {
  core,     ///< r < R_cap at every x (the capillary's cylinder continued through the periodic gap)
  segment,  ///< r < R_cap and -8 <= x <= 8 um only (inside the tethered segment)
};
const char* to_string(Region r);

/// The paper's Sec. 5.1 parameters (CGS), and the resolution.
struct Model {
  double L = 12e-4;       ///< half box (cm): 24 um periodic box
  int eta = 96;           ///< cells per side
  double mu = 1.2e-2;     ///< P (1.2 cP)
  double f_in = 8e3;      ///< dyn/cm^3 (0.08 pN/um^3)
  Region region = Region::core;
  double R_cap = 5e-4, x0_cap = -8e-4, x1_cap = 8e-4;  ///< cm
  double k_teth = 2.45e-3;                             ///< dyn/cm per node (eq. 93)
  /// Node spacing (cm); 0: h/2. The paper does not state its nodes. Forward Euler at dt = 1e-4 s
  /// is unstable for a stiff wall (k_teth / spacing^2): 0.25 and 0.35 um blow up, 0.5 um does not.
  double cap_spacing = 0.5e-4;
  bool with_cell = true;
  chapter3::Method method = chapter3::Method::shvd;
  int M = 19;                  ///< SHVD degree, m = (M+1)^2
  double R_cell = 3.91e-4;     ///< cm (eq. 92)
  double Gs = 2.5e-3, A = 50;  ///< eq. (68)
  double k_bend = 0;           ///< erg (eq. 79)
  std::array<double, 3> start{-8e-4, 0, 0};
  double dt = 1e-4;  ///< s (t = 0.05 s = 500 dt, Sec. 5.1.1)
  int steps = 500;
  int record_every = 25;  ///< steps between records of the series
  int view_every = 50;    ///< steps between kept surface states (views and snapshots)
  ib::Kernel kernel = ib::Kernel::peskin4;
  double h() const { return 2 * L / eta; }
};

/// A record of the series.
struct Sample {
  double t;             ///< s
  double c[3];          ///< centroid of the enclosed volume (cm)
  double area, volume;  ///< cm^2, cm^3
  double uc[3];         ///< the constant velocity of eq. (95) of the step from t (cm/s)
  double u_max;         ///< max over x-faces of u_x + u_c,x of the step from t (cm/s)
  double cap_disp;      ///< max |X_cap - Z_cap| (cm)
  double max_density;   ///< max |force density| on the cell (dyn/cm^2)
};

/// The cell at one time: its n evaluation sites (cm), |force density| per unit reference area
/// (dyn/cm^2), the outward normals, and H (1/cm; SHVD only, NaN for LDSM).
struct View {
  double t = 0;
  std::vector<double> X;             ///< n x 3 column-major
  std::vector<double> f, H, normal;  ///< n, n, n x 3
};

class Run {
 public:
  /// eval: the cell's evaluation sites (ignored without a cell). With a checkpoint path the run
  /// continues from that checkpoint when it holds this setup; `sitting` bounds one advance().
  Run(const Model& model, const chapter3::EvaluationSet* eval, const std::string& checkpoint = "",
      double sitting = INFINITY);
  ~Run();
  /// Steps to the run's end or the sitting's; a NumericalError ends the run (failure()). Returns
  /// true when the run is over.
  bool advance();
  int step() const;
  bool done() const;
  std::string failure() const;
  bool continued() const;
  const std::vector<Sample>& series() const;
  const std::vector<View>& views() const;
  double seconds() const;           ///< wall time of the steps, over every sitting (s)
  double seconds_per_step() const;  ///< NaN before a timed step
  const Model& model() const;
  const surface::CylinderPoints& capillary() const;  ///< the nodes' reference positions
  const std::vector<surface::Triangle>& triangles() const;  ///< of the cell's evaluation sites
  /// u_x + u_c,x of the last step's flow at (x_probe, 0, z_j), z_j every h/2 across the box.
  std::vector<std::array<double, 2>> profile_x(double x_probe) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// DIR/<label>.xmf (XDMF 3, a temporal collection of the kept views) with one HDF5 file per view
/// (/cell/points in um, triangles, force_density in pN/um^2, mean_curvature in 1/um) and
/// DIR/capillary_eta<eta>.h5, the capillary's nodes (reference positions) and triangles.
void write_snapshots(const Run& run, const std::string& dir, const std::string& label);

}  // namespace rbfib::capillary
