#pragma once
// Chapter 3's blebbing cell (the JCP 2018 paper, Sec. 5.2, eqs. 96-104, Table 2), a setup no
// scene file describes: a membrane, a cortex just inside it and the adhesion links between them,
// in steady Stokes flow on a periodic box; the bleb is initiated by removing the links where the
// polar angle phi <= 2 pi / 25 (about +z through the cell's centre) after the cell has equilibrated.
//
// Model (CGS inside; Table 2's values in um / pN / s):
//   membrane  sphere r_mem = 10 um, surface tension (eq. 72) gamma = 40 pN/um plus neo-Hookean
//             (eq. 71, bulk K = 40 pN/um and shear G_S = 40 pN/um: eq. 68 with A = K / G_S);
//             impermeable, moving with the fluid (eq. 103); forces by SHVD (m interpolation
//             sites of degree M, forces at the n evaluation sites; m = n: the evaluation sites
//             interpolate) or by LDSM (the n triangulated sites, eq. 66).
//   cortex    sphere r_cortex = 9.99 um on the same n sites (sim/cortex.hpp): the lattice of eqs.
//             99-100 with k = 87 pN/um (Table 2 prints pN/um^2; mechanics/cortex.hpp says why we
//             read pN/um), drag xi = 10 pN s/um^3 (Table 2's "cytosolic viscosity" row: its units
//             are a drag's; the "stiffness coefficient" row, 1 Pa s, is the viscosity mu: the two
//             labels are swapped), moving by eq. (104).
//   adhesion  k_adh = 3e4 pN/um^3, membrane site i tied to cortex site i (eqs. 101-102).
//   fluid     mu = 1 Pa s, box 30 um periodic, eta^3 MAC cells (the paper: eta = 32), steady
//             Stokes solved exactly (fluid/periodic_stokes.hpp), Peskin's 4-point kernel.
// Time update: Chapter 3's forward Euler (Sec. 3.3) on the library's coupled step: forces at X^n,
// one Stokes solve, X^{n+1} = X^n + dt U (the cortex: + dt F / (xi dA), eq. 104). The paper does
// not state its step. Equilibration for t_equilibrate (the paper: 0.2 s, until the boundary speed
// is about 0.01 um/s), then the links with phi <= 2 pi / 25 are removed; times are reported from
// then on. The records are the run's series, kept in its checkpoint: a resumed run continues bit
// for bit.
#include "rbfib/models/shell_relaxation.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rbfib::blebbing {

constexpr double um = 1e-4;  // cm
constexpr double pN = 1e-7;  // dyn

/// Table 2 (CGS) and the resolution.
struct Model {
  double box = 30 * um;  ///< periodic box side (cm)
  int eta = 32;          ///< cells per side (h = box / eta)
  double mu = 10;        ///< P (1 Pa s)
  double r_mem = 10 * um, r_cortex = 9.99 * um;
  std::array<double, 3> center{15 * um, 15 * um, 15 * um};
  double gamma = 40 * pN / um;  ///< membrane surface tension (dyn/cm)
  double K = 40 * pN / um;      ///< membrane bulk modulus (dyn/cm)
  double Gs = 40 * pN / um;     ///< membrane shear modulus (dyn/cm)
  double k_cortex = 87 * pN / um;           ///< cortex lattice stiffness (dyn/cm)
  double k_adh = 3e4 * pN / (um * um * um);  ///< adhesion (dyn/cm^3)
  double xi = 10 * pN / (um * um * um);      ///< cortical drag (dyn s/cm^3)
  double phi_bleb = 2 * 3.141592653589793 / 25;  ///< links removed where the polar angle <= this
  chapter3::Method method = chapter3::Method::ldsm;
  int M = 68;  ///< SHVD degree, m = (M+1)^2 (m = n: the evaluation sites interpolate)
  double dt = 1e-4;             ///< s
  double t_equilibrate = 0.2;   ///< s, links all attached
  double t_bleb = 15;           ///< s after equilibration
  int record_every = 100;       ///< steps between records
  int view_every = 1000;        ///< steps between kept surface states (sections, curvature)
  double h() const { return box / eta; }
  long steps() const;  ///< to t_equilibrate + t_bleb
};

/// A record of the series (times from the start of the run; the study subtracts t_equilibrate).
struct Sample {
  double t;             ///< s
  double volume, area;  ///< of the membrane (cm^3, cm^2)
  double bleb_size;     ///< z_top - z_ring (cm), the paper's Fig. 12 before subtracting its start
  double ring_diameter;  ///< the bleb ring's diameter (cm)
  double boundary_speed;  ///< max |S* u| over the membrane sites, the last step's flow (cm/s)
  double boundary_speed_rms;  ///< its root mean square over the sites (cm/s)
  double cortex_radius;  ///< mean distance of the cortex sites from the centre (cm)
  double link_max;       ///< max |X_mem - X_cortex| over the attached links (cm)
};

/// The membrane at one time: its n sites (cm, n x 3) and mean curvature H (1/cm; SHVD: the
/// interpolant's; LDSM: NaN).
struct View {
  double t = 0;
  std::vector<double> X, H;
};

class Run {
 public:
  /// `eval`: the n sites of the membrane and the cortex (a Bauer spiral with its triangulation).
  /// With a checkpoint path the run continues from that checkpoint when it holds this setup;
  /// `sitting` bounds one advance() in wall seconds.
  /// `progress` receives a line on the run's progress every 30 s of wall time and at the sitting's end.
  Run(const Model& model, const chapter3::EvaluationSet& eval, const std::string& checkpoint = "",
      double sitting = INFINITY, std::function<void(const std::string&)> progress = {});
  ~Run();
  /// Steps to the run's end or the sitting's; a NumericalError ends the run (failure()). Returns
  /// true when the run is over.
  bool advance();
  long step() const;
  bool done() const;
  std::string failure() const;
  bool continued() const;
  const std::vector<Sample>& series() const;
  const std::vector<View>& views() const;
  double seconds() const;           ///< wall time of the steps, over every sitting (s)
  double seconds_per_step() const;  ///< NaN before a timed step
  double hours_to_go() const;
  const Model& model() const;
  const std::vector<surface::Triangle>& triangles() const;
  /// Per site: whether its link is removed at the bleb (phi <= phi_bleb on the reference sphere).
  const std::vector<char>& detached() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rbfib::blebbing
