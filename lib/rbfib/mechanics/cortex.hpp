#pragma once
// The cortex of a blebbing cell and its adhesion to the membrane (the JCP 2018 paper, Sec. 5.2.1,
// eqs. 99-102): a lattice of springs on a triangulated surface, and springs that tie each membrane
// site to its cortex site.
//
// Lattice (eqs. 99-100). Each edge ij of the triangulation is a spring of coefficient
//   kappa_ij = (8 k / (3 dl_ij)) (dA_i + dA_j) / 2                                   (100)
// (dl_ij its reference length, dA the vertex area weights of eq. 67), and the force on vertex i is
//   F^_i = F_i dA_i = -sum_j kappa_ij (|X_i - X_j| / dl_ij) (X_i - X_j) / |X_i - X_j|   (99)
// = -dE/dX_i with E = sum_edges kappa_ij |X_i - X_j|^2 / (2 dl_ij). The printed eq. (99) has no
// minus sign; a spring pulls its ends together, so we take F = -dE/dX. The springs have zero rest
// length: on an equilateral lattice their sum is a uniform tension T = 4 k at any stretch (the
// virial of three springs per vertex), the cortical tension that pressurizes the cell (Sec. 5.2.1).
// Units: eq. (99)'s left side is a force only if k is a force per length; Table 2 prints 87
// pN/um^2 for its average. We take k in dyn/cm (87 pN/um = 0.087 dyn/cm), so T = 0.348 dyn/cm.
//
// Adhesion (eqs. 101-102). Link i ties membrane site i to cortex site i; with d = X_mem - X_cortex,
//   on the cortex  F^_i = k_adh dA_i d,      on the membrane  -k_adh dA_i d              (101)
// (k_adh per unit volume, dA_i the cortex site's area weight, the printed sign again that of a
// spring's extension). The two are equal and opposite link by link, so their spread densities
// integrate to zero (eq. 102): the membrane's coefficient k_adh dA^cortex / dA^mem of the paper,
// times its own dA^mem. A detached link carries no force.
// Positions and forces: n x 3 column-major, X[d n + i] (docs/math.md); CGS.
#include "rbfib/surface/triangulation.hpp"

#include <array>
#include <vector>

namespace rbfib::mechanics {

/// The springs of eqs. (99)-(100) on a triangulated reference surface Z.
struct CortexLattice {
  std::vector<std::array<index_t, 2>> edges;  ///< each edge once, i < j
  std::vector<double> kappa;                  ///< kappa_ij of eq. (100) (dyn)
  std::vector<double> length;                 ///< dl_ij (cm)
  std::vector<double> dA;                     ///< vertex area weights, eq. (67) (cm^2)
  index_t n = 0;                              ///< vertices
};

/// The lattice of stiffness k (dyn/cm, see above) on the triangles over Z (n x 3). Throws
/// InputError naming the field for k < 0 or not finite, a vertex out of range, or a zero-length edge.
CortexLattice cortex_lattice(const std::vector<surface::Triangle>& tris, const std::vector<double>& Z, double k);

struct PointForces {
  std::vector<double> F;  ///< force at each point (dyn), n x 3
  double energy = 0;      ///< erg
};

/// Eq. (99) at positions X (n x 3): F^_i and the springs' energy.
PointForces cortex_forces(const CortexLattice& lattice, const std::vector<double>& X);

struct AdhesionForces {
  std::vector<double> on_membrane, on_cortex;  ///< dyn, n x 3 each
  double energy = 0;                           ///< sum over attached links of k_adh dA_i |d|^2 / 2 (erg)
};

/// Eq. (101) for the links whose `attached` entry is nonzero: membrane sites Xm, cortex sites Xc
/// (both n x 3, site i linked to site i), k_adh in dyn/cm^3, dA the cortex's weights (cm^2).
/// Throws InputError naming the field for mismatched sizes or k_adh < 0.
AdhesionForces adhesion_forces(const std::vector<double>& Xm, const std::vector<double>& Xc, const std::vector<double>& dA,
                               double k_adh, const std::vector<char>& attached);

}  // namespace rbfib::mechanics
