#include "rbfib/cells/presets.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/point_sets.hpp"

namespace rbfib::cells {

namespace {
CellTypeSpec spiral_spec(const std::string& name, ReferenceShape shape, index_t n_data, index_t n_sample) {
  require(n_data > 0, name + " data sites", n_data, "must be > 0");
  require(n_sample > 0, name + " sample sites", n_sample, "must be > 0");
  CellTypeSpec s;
  s.name = name;
  s.shape = std::move(shape);
  s.data_sites = surface::bauer_spiral(n_data);
  s.sample_sites = surface::bauer_spiral(n_sample);
  return s;
}
}  // namespace

CellTypeSpec red_cell_spec(index_t n_data, index_t n_sample) {
  CellTypeSpec s = spiral_spec("red cell", evans_fung_red_cell(seed::red_cell_radius), n_data, n_sample);
  s.basis = surface::PhsBasis{7, 5};
  s.model.elastic = {mechanics::EnergyDensity::skalak(seed::red_cell_E, seed::red_cell_G)};
  s.model.kappa = seed::red_cell_kappa;
  s.model.H0 = 0;
  s.model.nu = seed::red_cell_nu;
  return s;
}

CellTypeSpec platelet_spec(index_t n_data, index_t n_sample) {
  CellTypeSpec s = spiral_spec("platelet", ellipsoid_shape(seed::platelet_a, seed::platelet_a, seed::platelet_c),
                               n_data, n_sample);
  s.basis = surface::PhsBasis{7, 0};
  s.model.elastic = {mechanics::EnergyDensity::neo_hookean_dissertation(seed::platelet_E, seed::platelet_G)};
  s.model.kappa = seed::platelet_kappa;
  s.model.H0_reference = true;
  return s;
}

CellTypeSpec skalak_sphere_spec(double radius, index_t n_data, index_t n_sample) {
  require(radius > 0, "Skalak sphere radius (cm)", radius, "must be > 0");
  CellTypeSpec s = spiral_spec("Skalak sphere", ellipsoid_shape(radius, radius, radius), n_data, n_sample);
  s.basis = surface::PhsBasis{7, 5};
  s.model.elastic = {mechanics::EnergyDensity::skalak(seed::red_cell_E, seed::red_cell_G)};
  return s;
}

CellTypeSpec chapter3_red_cell_spec(int M, index_t n_sample) {
  require(M >= 1, "chapter 3 red cell harmonic degree M", M, "must be >= 1");
  CellTypeSpec s = spiral_spec("chapter 3 red cell", chapter3_red_cell_shape(seed::red_cell_radius),
                               (M + 1) * (M + 1), n_sample);
  s.data_sites = surface::max_determinant_points(M).sites;
  s.interpolant = Interpolant::spherical_harmonics;
  s.sh_degree = M;
  s.model.elastic = {mechanics::EnergyDensity::neo_hookean_paper(seed::chapter3_Gs, seed::chapter3_A)};
  s.model.kappa = 2 * seed::chapter3_k_bend;
  return s;
}

std::shared_ptr<const CellType> red_cell(index_t n_data, index_t n_sample) {
  return std::make_shared<const CellType>(red_cell_spec(n_data, n_sample));
}
std::shared_ptr<const CellType> platelet(index_t n_data, index_t n_sample) {
  return std::make_shared<const CellType>(platelet_spec(n_data, n_sample));
}
std::shared_ptr<const CellType> skalak_sphere(double radius, index_t n_data, index_t n_sample) {
  return std::make_shared<const CellType>(skalak_sphere_spec(radius, n_data, n_sample));
}
std::shared_ptr<const CellType> chapter3_red_cell(int M, index_t n_sample) {
  return std::make_shared<const CellType>(chapter3_red_cell_spec(M, n_sample));
}

}  // namespace rbfib::cells
