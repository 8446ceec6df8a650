#pragma once
// One run of the paper's Sec. 5.1 (JCP 2018, Chapter 3 of the seed): a red cell (eq. 92) carried
// by pressure-driven flow through a tethered capillary, in steady Stokes flow on a periodic box.
//
// Model (CGS inside, um / pN / s in the tables):
//   cell       eq. (92) reference, R = 3.91 um, centred at (-8, 0, 0) um, symmetry axis x;
//              neo-Hookean eq. (68) (Gs = 2.5e-3 dyn/cm, A = 50) plus bending eq. (79)
//              E = k_bend int (2H)^2 dA (the library's 2 kappa H^2 with kappa = 2 k_bend);
//              SHVD (m interpolation sites, degree M, forces at n evaluation sites) or LDSM (the n
//              triangulated sites, eq. 66; no bending, as the paper, Sec. 5.1.2).
//   capillary  tethered nodes on the cylinder r = 5 um, -8 <= x <= 8 um (eq. 93):
//              F^_k = -k_teth (X_k - Z_k), k_teth = 2.45e-3 dyn/cm per node.
//   background f_in = 8e3 dyn/cm^3 along +x at the x-faces inside the capillary (see Region),
//              f_out at the other x-faces with N_in f_in + N_out f_out = 0 exactly ("a uniform force
//              in the opposite direction outside ... so that the integral ... is zero").
//   fluid      mu = 1.2e-2 P, box [-12, 12]^3 um periodic, eta^3 MAC cells, steady Stokes solved
//              exactly (fluid/periodic_stokes.hpp, alpha = 0), Peskin's 4-point kernel.
// Time update (Sec. 3.3 with the capillary's modification, eqs. 94-95), per step k:
//   1.-2. cell forces at X^k (SHVD: interpolant through the m sites, force at the n sites times
//         dA0; LDSM: eq. 66), tether forces at X_cap^k;
//   3.    spread both (the cell from its n sites) and add the background force;
//   4.    Stokes solve;
//   5.    U = I u at the m (SHVD) or n (LDSM) cell sites and at the capillary nodes;
//   6.    X^_cap = X_cap^k + dt U_cap (eq. 94); u_c = (1/(A_cap dt)) int (Z_cap - X^_cap) dq
//         (eq. 95, equal node areas: the mean over the nodes); X_cap^{k+1} = X^_cap + dt u_c and
//         X_cell^{k+1} = X_cell^k + dt (U_cell + u_c): the constant velocity u_c is added
//         throughout the domain, the cell included.
// The run is the library's coupled step (forward Euler on steady periodic Stokes, the capillary's
// nodes holding the frame, the background force as a body force density) stepped by the library's
// run loop; its records are the run's series, kept in its checkpoint; a resumed run continues bit
// for bit.
#include "common/chapter3_relaxation.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/ib/interaction.hpp"

#include <cmath>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace rbfib::capillary {

/// Where the background force pushes forward.
enum class Region {
  core,     ///< r < R_cap at every x (the capillary's cylinder continued through the periodic gap)
  segment,  ///< r < R_cap and -8 <= x <= 8 um only (inside the tethered segment)
};
const char* to_string(Region r);

/// The paper's Sec. 5.1 parameters (CGS), and the resolution.
struct Model {
  // fluid
  double L = 12e-4;       ///< half box (cm): 24 um periodic box
  int eta = 96;           ///< cells per side
  double mu = 1.2e-2;     ///< P (1.2 cP)
  double f_in = 8e3;      ///< dyn/cm^3 (0.08 pN/um^3)
  Region region = Region::core;
  // capillary
  double R_cap = 5e-4, x0_cap = -8e-4, x1_cap = 8e-4;  ///< cm
  double k_teth = 2.45e-3;                             ///< dyn/cm per node (eq. 93)
  /// Node spacing (cm); 0: h/2. The paper does not state its nodes. The tether's stiffness per
  /// unit area is k_teth / spacing^2, and forward Euler at dt = 1e-4 s becomes unstable when it is
  /// too large: spacing 0.25 and 0.35 um blow up within 150 steps (eta = 32-96), 0.5 um does not.
  double cap_spacing = 0.5e-4;
  // cell
  bool with_cell = true;
  chapter3::Method method = chapter3::Method::shvd;
  int M = 19;               ///< SHVD degree, m = (M+1)^2
  double R_cell = 3.91e-4;  ///< cm (eq. 92)
  double Gs = 2.5e-3, A = 50;  ///< eq. (68)
  double k_bend = 0;        ///< erg (eq. 79)
  std::array<double, 3> start{-8e-4, 0, 0};
  // time
  double dt = 1e-4;  ///< s (t = 0.05 s = 500 dt, Sec. 5.1.1)
  int steps = 500;
  int record_every = 25;  ///< steps between records of the series
  int view_every = 50;    ///< steps between kept surface states (views and snapshots)
  ib::Kernel kernel = ib::Kernel::peskin4;
  double h() const { return 2 * L / eta; }
};

/// A record of the series.
struct Sample {
  double t;           ///< s
  double c[3];        ///< centroid of the enclosed volume (cm)
  double area, volume;  ///< cm^2, cm^3
  double uc[3];       ///< the constant velocity of eq. (95) of the step from t (cm/s)
  double u_max;       ///< max over x-faces of u_x + u_c,x of the step from t (cm/s)
  double cap_disp;    ///< max |X_cap - Z_cap| (cm)
  double max_density; ///< max |force density| on the cell (dyn/cm^2)
};

/// The surface of the cell at one time: its n evaluation sites (cm), |force density| per unit
/// reference area there (dyn/cm^2), the outward normals, and H (1/cm; SHVD only, NaN for LDSM).
struct View {
  double t = 0;
  std::vector<double> X;  ///< n x 3 column-major
  std::vector<double> f, H, normal;  ///< n, n, n x 3
};

/// Wall time per phase (s, summed over the steps of this process).
struct Phases {
  double forces = 0, spread = 0, solve = 0, interpolate = 0, update = 0;
  double total() const { return forces + spread + solve + interpolate + update; }
};

class Run {
 public:
  /// eval: the cell's evaluation sites (ignored without a cell). The run goes through the
  /// library's run loop: with a checkpoint path it continues from that checkpoint when it holds
  /// this setup (written every five minutes, at the sitting's end and at the run's end); `sitting`
  /// bounds the wall seconds of one advance().
  Run(const Model& model, const chapter3::EvaluationSet* eval, const std::string& checkpoint = "",
      double sitting = INFINITY);
  ~Run();
  /// Takes steps to the run's end or the sitting's; a NumericalError ends the run (kept in
  /// failure()), the last good state kept. Returns true when the run is over.
  bool advance();
  int step() const;
  bool done() const;
  std::string failure() const;
  bool continued() const;  ///< restored from its checkpoint
  const std::vector<Sample>& series() const;
  const std::vector<View>& views() const;
  const Phases& phases() const;
  int steps_timed() const;  ///< steps timed in phases() (over every sitting of a resumed run)
  const Model& model() const;
  /// Capillary nodes, reference (cm), 3 n_cap column-major, and their ring count (around) and
  /// axial count.
  const std::vector<double>& capillary_reference() const;
  int capillary_around() const;
  int capillary_along() const;
  /// The x velocity of the last step's flow (cm/s, u_c added), interpolated with the run's kernel at
  /// (x_probe, 0, z_j), z_j every h/2 across the box: pairs (z_j, u_x).
  std::vector<std::array<double, 2>> profile_x(double x_probe) const;
  /// Triangles of the cell's evaluation sites (convex hull on the sphere).
  const std::vector<surface::Triangle>& triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rbfib::capillary
