#include "rbfib/mechanics/energy.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib::mechanics {

EnergyDensity EnergyDensity::skalak(double E, double G) {
  require(E >= 0, "Skalak shear modulus E (dyn/cm)", E, "must be >= 0");
  require(G >= 0, "Skalak bulk modulus G (dyn/cm)", G, "must be >= 0");
  return {EnergyKind::skalak, E, G};
}
EnergyDensity EnergyDensity::neo_hookean_dissertation(double E, double G) {
  require(E >= 0, "neo-Hookean shear modulus E (dyn/cm)", E, "must be >= 0");
  require(G >= 0, "neo-Hookean bulk modulus G (dyn/cm)", G, "must be >= 0");
  return {EnergyKind::neo_hookean_dissertation, E, G};
}
EnergyDensity EnergyDensity::neo_hookean_paper(double Gs, double A) {
  require(Gs >= 0, "neo-Hookean shear modulus Gs (dyn/cm)", Gs, "must be >= 0");
  require(A >= 0, "neo-Hookean area ratio A = K/Gs", A, "must be >= 0");
  return {EnergyKind::neo_hookean_paper, Gs, A};
}
EnergyDensity EnergyDensity::surface_tension(double sigma) {
  require(sigma >= 0, "surface tension sigma (dyn/cm)", sigma, "must be >= 0");
  return {EnergyKind::surface_tension, sigma, 0};
}
double EnergyDensity::shear_modulus() const { return kind == EnergyKind::surface_tension ? 0.0 : a; }

std::vector<EnergyDensity::Parameter> EnergyDensity::parameters() const {
  switch (kind) {
    case EnergyKind::skalak:
    case EnergyKind::neo_hookean_dissertation: return {{"E", a, "dyn/cm"}, {"G", b, "dyn/cm"}};
    case EnergyKind::neo_hookean_paper: return {{"Gs", a, "dyn/cm"}, {"A", b, ""}};
    case EnergyKind::surface_tension: return {{"sigma", a, "dyn/cm"}};
  }
  return {};
}

std::string EnergyDensity::name() const {
  switch (kind) {
    case EnergyKind::skalak: return "Skalak";
    case EnergyKind::neo_hookean_dissertation: return "neo-Hookean (diss. 2.12)";
    case EnergyKind::neo_hookean_paper: return "neo-Hookean (paper 68)";
    case EnergyKind::surface_tension: return "surface tension";
  }
  return "?";
}

}  // namespace rbfib::mechanics
