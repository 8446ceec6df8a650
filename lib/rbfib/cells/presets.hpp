#pragma once
// Cell types with the seed's parameters (CGS). Data and sample sites are Bauer spirals (diss.
// eq. 5.1) of the given sizes unless stated; sample weights eq. (2.22) with phi = r, then eq. (51).
//
//   red_cell            diss. Sec. 2.2: Evans-Fung shape, R0 = 3.91 um; Skalak (2.11) E = 2.5e-3,
//                       G = 2.5e-1 dyn/cm; bending (2.13) kappa = 2e-12 erg, H' = 0; dissipation
//                       (2.14) nu = 2.5e-7 dyn s/cm; PHS r^7 with harmonics to degree 5. The
//                       whole-blood runs (Secs. 5.1.3, 5.2) use 2,500 data / 10,000 sample sites.
//   platelet            diss. Sec. 2.2: ellipsoid 1.55 x 1.55 x 0.5 um (short axis z); neo-Hookean
//                       (2.12) E = 0.1, G = 1 dyn/cm; bending kappa = 2e-11 erg with H' the
//                       reference curvature; PHS r^7 with a constant; 900 / 900 sites (Sec. 5.2).
//   skalak_sphere       diss. Sec. 4.2.2.1: a sphere with the red cell's Skalak law (E, G above),
//                       elastic only; the seed does not state its radius (R is an argument).
//   chapter3_red_cell   paper eq. (92), R = 3.91 um; neo-Hookean (68) Gs = 2.5e-3 dyn/cm, A = 50;
//                       bending k_bend = 1e-12 erg in E = k_bend int (2H)^2 dA (eq. 79), i.e.
//                       kappa = 2 k_bend in 2 kappa H^2; factored spherical harmonics of degree M
//                       (m = (M+1)^2 = 400 interpolation sites in the paper) on maximal-
//                       determinant-like sites, evaluated at n_s sites (8,281 in the paper).
#include "rbfib/cells/cell_type.hpp"

#include <memory>

namespace rbfib::cells {

/// The specifications, to adjust (name, sites, model) before building a type from them.
CellTypeSpec red_cell_spec(index_t n_data = 2500, index_t n_sample = 10000);
CellTypeSpec platelet_spec(index_t n_data = 900, index_t n_sample = 900);
CellTypeSpec skalak_sphere_spec(double radius, index_t n_data = 625, index_t n_sample = 880);
CellTypeSpec chapter3_red_cell_spec(int M = 19, index_t n_sample = 8281);

/// The types built from those specifications.
std::shared_ptr<const CellType> red_cell(index_t n_data = 2500, index_t n_sample = 10000);
std::shared_ptr<const CellType> platelet(index_t n_data = 900, index_t n_sample = 900);
std::shared_ptr<const CellType> skalak_sphere(double radius, index_t n_data = 625, index_t n_sample = 880);
std::shared_ptr<const CellType> chapter3_red_cell(int M = 19, index_t n_sample = 8281);

/// The seed's constants used by the presets (CGS).
namespace seed {
inline constexpr double red_cell_radius = 3.91e-4;        ///< cm (Sec. 2.2, paper eq. 92)
inline constexpr double red_cell_E = 2.5e-3, red_cell_G = 2.5e-1;  ///< dyn/cm (Skalak, Sec. 2.2)
inline constexpr double red_cell_kappa = 2e-12;            ///< erg
inline constexpr double red_cell_nu = 2.5e-7;              ///< dyn s/cm
inline constexpr double platelet_a = 1.55e-4, platelet_c = 0.5e-4;  ///< cm
inline constexpr double platelet_E = 0.1, platelet_G = 1.0;  ///< dyn/cm (neo-Hookean 2.12)
inline constexpr double platelet_kappa = 2e-11;            ///< erg
inline constexpr double chapter3_Gs = 2.5e-3, chapter3_A = 50;  ///< paper eq. (68) and Sec. 4.2
inline constexpr double chapter3_k_bend = 1e-12;           ///< erg (paper eq. 79)
}  // namespace seed

}  // namespace rbfib::cells
