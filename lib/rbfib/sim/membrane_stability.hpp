#pragma once
// The explicit stability of membrane forces coupled to the fluid through the kernel, in the seed's
// coupling (a)-(g) with backward-forward Euler. The derivation and its numbers:
// docs/derivations/membrane_stability/README.md. In short: a membrane mode of wavenumber k relaxes
// at lambda = (its stiffness) x (the regularized Stokes mobility of a sheet), and the predicted
// coupling maps it by a real eigenvalue that crosses -1 (sign flips every step) when
//   gain = (d + 3/2 lambda dt) / (1 + 1.5 rho h^2 / (mu dt)) > 1,
// d = the explicit membrane dissipation's part (eq. 2.14, nu). Over the kernel's transfer the
// worst modes are grid-scale: for the 4-point B-spline, tangential area-stretch waves at
// kh = 0.68 give lambda = 0.0693 (K + mu_s) / (mu h); shear waves 0.2265 mu_s / (mu h); bending
// 0.4425 kappa / (mu h^3) (or less when the data sites are coarser than 2h), plus the normal modes
// that the reference shape's curvature couples to stretching. mu_s and K are the small-strain
// shear and area moduli of the energy (Skalak 2.11: mu_s = E, K = E + 2G; neo-Hookean 2.12:
// mu_s = E, K = G). The closed form lies within -11% / +7% of the grid sums of the derivation.
// Units: CGS.
#include "rbfib/cells/cell_type.hpp"
#include "rbfib/ib/kernels.hpp"

#include <string>

namespace rbfib::sim {

/// A membrane's constants as the bound reads them.
struct MembraneStiffness {
  double mu_s = 0, K = 0;  ///< small-strain shear and area moduli (dyn/cm)
  double kappa = 0;        ///< bending modulus (erg)
  double nu = 0;           ///< membrane viscosity (dyn s/cm)
  double curvature = 0;    ///< the reference shape's largest principal curvature (1/cm)
  double spacing = 0;      ///< data-site spacing sqrt(area / n_d) (cm)
};

/// The constants of a cell type (its energies summed; InputError for an energy the bound does not
/// know, such as surface tension).
MembraneStiffness membrane_stiffness(const cells::CellType& type);

/// The largest step (s) whose gain is at most `gain` for every mode family of the membrane, over a
/// grid of spacing h (cm) with the kernel, in a fluid of density rho and viscosity mu (CGS);
/// infinite for a membrane without stiffness, 0 when no step is stable (the dissipation alone
/// exceeds the gain). `gain` 1 is the stability limit; the adaptive step uses 1/2 (the factor of 2
/// the mode shapes leave open).
double membrane_dt_limit(const MembraneStiffness& m, double h, double rho, double mu, ib::Kernel kernel, double gain);

/// The family that sets the limit, for messages: "tangential along k", "tangential across k" or
/// "normal (bending and curvature)".
std::string membrane_limiting_family(const MembraneStiffness& m, double h, double rho, double mu, ib::Kernel kernel, double gain);

}  // namespace rbfib::sim
