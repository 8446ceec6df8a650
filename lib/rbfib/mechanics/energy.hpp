#pragma once
// Membrane energy densities W(I1, I2) per unit reference area, behind one interface.
// Invariants of C = G G0^{-1} (paper eq. 15): I1 = tr C - 2, I2 = det C - 1 (= lambda1^2 +
// lambda2^2 - 2 and lambda1^2 lambda2^2 - 1, dissertation Sec. 2.2). Units: moduli in dyn/cm,
// W in erg/cm^2 (CGS).
//
//   skalak                 (diss. 2.11): W = E/4 (I1^2 + 2 I1 - 2 I2) + G/4 I2^2
//   neo_hookean (diss.)    (diss. 2.12): W = E/2 ((I1+2)/s - 2) + G/2 (s - 1)^2,   s = sqrt(I2+1)
//   neo_hookean (paper)    (paper 68):   W = Gs ((I1+2)/(2 s) - 1 + A/2 (I2 + 2 - 2 s))
//   surface_tension        (paper 72):   W = sigma s
// (2.12) with (E, G) equals (68) with Gs = E, A = G/E.
//
// evaluate() returns W and its first and second partial derivatives in (I1, I2), which is all
// the continuous force (paper eqs. 34-35) and the LDSM force (eq. 66) need. Pointwise and
// host+device: no virtual dispatch, a switch on the kind.
#include "rbfib/core/exec.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace rbfib::mechanics {

struct InvariantDerivatives {
  double W, W1, W2, W11, W12, W22;
  bool valid;  ///< false where det C = I2 + 1 <= 0 (an inverted or collapsed element)
};

enum class EnergyKind { skalak, neo_hookean_dissertation, neo_hookean_paper, surface_tension };

struct EnergyDensity {
  EnergyKind kind = EnergyKind::skalak;
  double a = 0;  ///< E (Skalak, 2.12), Gs (68), sigma (72)
  double b = 0;  ///< G (Skalak, 2.12), A (68)

  static EnergyDensity skalak(double E, double G);
  static EnergyDensity neo_hookean_dissertation(double E, double G);
  static EnergyDensity neo_hookean_paper(double Gs, double A);
  static EnergyDensity surface_tension(double sigma);
  std::string name() const;
  /// The law's shear modulus (dyn/cm): E of Skalak (2.11) and of neo-Hookean (2.12), Gs of (68);
  /// 0 for surface tension (72), which resists no shear.
  double shear_modulus() const;
  /// The law's parameters as the scene names them, with units: {"E", a, "dyn/cm"}, ...
  struct Parameter {
    const char* name;
    double value;
    const char* units;
  };
  std::vector<Parameter> parameters() const;

  RBFIB_HD InvariantDerivatives evaluate(double I1, double I2) const {
    InvariantDerivatives d{0, 0, 0, 0, 0, 0, true};
    const double J2 = I2 + 1;
    if (kind == EnergyKind::skalak) {
      d.W = a / 4 * (I1 * I1 + 2 * I1 - 2 * I2) + b / 4 * I2 * I2;
      d.W1 = a / 4 * (2 * I1 + 2);
      d.W2 = -a / 2 + b / 2 * I2;
      d.W11 = a / 2;
      d.W22 = b / 2;
      d.valid = J2 > 0;
      return d;
    }
    if (!(J2 > 0)) {
      d.valid = false;
      return d;
    }
    const double s = sqrt(J2), s3 = s * J2, s5 = s3 * J2;
    switch (kind) {
      case EnergyKind::neo_hookean_dissertation:
        d.W = a / 2 * ((I1 + 2) / s - 2) + b / 2 * (s - 1) * (s - 1);
        d.W1 = a / (2 * s);
        d.W2 = -a * (I1 + 2) / (4 * s3) + b / 2 * (1 - 1 / s);
        d.W12 = -a / (4 * s3);
        d.W22 = 3 * a * (I1 + 2) / (8 * s5) + b / (4 * s3);
        break;
      case EnergyKind::neo_hookean_paper:
        d.W = a * ((I1 + 2) / (2 * s) - 1 + b / 2 * (I2 + 2 - 2 * s));
        d.W1 = a / (2 * s);
        d.W2 = a * (-(I1 + 2) / (4 * s3) + b / 2 * (1 - 1 / s));
        d.W12 = -a / (4 * s3);
        d.W22 = a * (3 * (I1 + 2) / (8 * s5) + b / (4 * s3));
        break;
      case EnergyKind::surface_tension:
        d.W = a * s;
        d.W2 = a / (2 * s);
        d.W22 = -a / (4 * s3);
        break;
      default:
        break;
    }
    return d;
  }
};

}  // namespace rbfib::mechanics
