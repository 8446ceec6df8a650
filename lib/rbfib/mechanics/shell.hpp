#pragma once
// Continuous-energy forces on a reconstructed cell surface (paper Sec. 2.3-2.4, 3.1).
//
// A cell type owns shared surface operators (data sites -> sample sites), the reference jets Z
// at the sample sites and the reference area weights dA0 (eqs. 45/2.22 and 51). For current data
// X (3 per data site, site-major):
//   jets X(sample) = operators * X                  (O(n_d n_s))
//   force density F_i from eq. (35) per site         (per unit reference area)
//   force F^_i = F_i dA0_i                           (eq. 52)
//   energy E = sum_i W_i dA0_i                       (eq. 16 under the quadrature)
// Degenerate input raises NumericalError naming the cell, the site and the cause.
// Units (CGS): X in cm, moduli in dyn/cm, dA0 in cm^2 (reference area), force density in
// dyn/cm^2 (per unit reference area), force F^ in dyn, energy in erg. Arrays of points or
// forces of one cell are n x 3 column-major, X[d n + i] (docs/math.md).
// These are the per-cell host functions (the reference the batched device path of cells/ is
// tested against); both call the same pointwise kernels of force_kernels.hpp.
#include "rbfib/mechanics/force_kernels.hpp"
#include "rbfib/surface/geometry.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbfib::mechanics {

/// Force densities (3 per site) from jets; throws NumericalError on a degenerate site
/// or a non-finite value.
std::vector<double> elastic_force_density(const std::string& cell, const std::vector<Jet>& X,
                                          const std::vector<Jet>& Z, const EnergyDensity& energy);

/// sum_i W_i dA0_i.
double elastic_energy(const std::string& cell, const std::vector<Jet>& X, const std::vector<Jet>& Z,
                      const EnergyDensity& energy, const std::vector<double>& dA0);

/// F^_i = F_i dA0_i (eq. 52).
std::vector<double> forces_from_density(const std::vector<double>& density, const std::vector<double>& dA0);

struct BendingModel {
  double kappa = 0;   ///< bending modulus (erg), dissertation eq. 2.13
  double H0 = 0;      ///< spontaneous curvature H' (1/cm), a constant
  /// Optional H' per data site (1/cm), a material field (the platelet's "preference for its
  /// reference curvature", dissertation Sec. 2.2: H' = H of the reference shape). When given it
  /// replaces H0 and the force gains the terms of a varying H' (see bending_force_density).
  std::vector<double> H0_data;
};

/// Bending force density (eq. 84 / 2.13) at the sample sites. H is computed at the data sites
/// with `at_data` (data -> data operators), reconstructed with `to_sample`, and its surface
/// Laplacian (eq. 82) taken there. Z: reference jets at the sample sites. With a material field
/// H'(s) (model.H0_data) the variational derivative of int 2 kappa (H - H')^2 dA is
///   F = -2 kappa sqrt(det G / det G0) [ (lap_s (H - H') + 2 (H - H')(H^2 + H' H - K)) n
///                                       + 2 (H - H') grad_s H' ],
/// the tangential term because moving material along the surface carries H' with it.
std::vector<double> bending_force_density(const std::string& cell, const surface::SurfaceOperators& at_data,
                                          const surface::SurfaceOperators& to_sample,
                                          const std::vector<double>& X_data, const std::vector<Jet>& Z,
                                          const BendingModel& model);

/// sum_i 2 kappa (H_i - H'_i)^2 sqrt(det G/det G0)_i dA0_i at the sample sites; with
/// model.H0_data, H'_i is reconstructed from the data sites with `to_sample` (pass nullptr otherwise).
double bending_energy(const std::string& cell, const std::vector<Jet>& X, const std::vector<Jet>& Z,
                      const BendingModel& model, const std::vector<double>& dA0,
                      const surface::SurfaceOperators* to_sample = nullptr);

/// Viscous membrane force density (dissertation eq. 2.14, see force_kernels.hpp) from position
/// jets X and velocity jets U at the sample sites; nu in dyn s/cm.
std::vector<double> dissipative_force_density(const std::string& cell, const std::vector<Jet>& X,
                                              const std::vector<Jet>& U, const std::vector<Jet>& Z, double nu);

/// Rayleigh dissipation sum_i W_dissip,i dA0_i (erg/s).
double dissipation(const std::string& cell, const std::vector<Jet>& X, const std::vector<Jet>& U,
                   const std::vector<Jet>& Z, double nu, const std::vector<double>& dA0);

/// Tethers and damped springs (dissertation eq. 2.10): W = k/2 |X - X'|^2 + eta/2 |U - U'|^2,
/// force density F = -k (X - X') - eta (U - U'). All arrays 3 per site; U, U' may be empty (0).
std::vector<double> tether_force_density(const std::vector<double>& X, const std::vector<double>& X_tether,
                                         const std::vector<double>& U, const std::vector<double>& U_tether,
                                         double k, double eta);

}  // namespace rbfib::mechanics
