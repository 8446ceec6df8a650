#pragma once
// Physical quantities written with their units, as the seed writes them ("16 um", "1 cP",
// "50 ns", "2.5e-3 dyn/cm", "2e-12 erg", "12 mm/s", "1000 1/s", "2.5e-7 dyn s/cm"), converted
// once, at the edge, to the internal CGS units of units.hpp.
//
// Grammar: a number, then a unit expression: factors separated by spaces or '*', each a unit
// name with an optional integer power ("cm^3", "s^-1"), and at most one '/' after which every
// factor divides ("dyn s/cm", "g/cm^3", "1/s"). Unit names: lengths m, cm, mm, um (also µm),
// nm; masses kg, g, mg; times s, ms, us (also µs), ns; dyn, N, pN; erg, J; P, cP, Pa; Hz;
// angles rad, deg (dimensionless). A bare number is dimensionless.
#include <string>

namespace rbfib {

/// Exponents of length, mass and time.
struct Dimension {
  int length = 0, mass = 0, time = 0;
  bool operator==(const Dimension&) const = default;
};

/// A value in CGS units with its dimension.
struct Quantity {
  double value = 0;
  Dimension dimension;
};

/// Parses "number [unit expression]". Throws InputError naming `field` and the text for a
/// malformed number, an unknown unit, or a non-finite value.
Quantity parse_quantity(const std::string& text, const std::string& field);

/// Parses text and checks that it has the dimension of `expected` (a unit expression such as
/// "um" or "dyn s/cm"); returns the value in CGS units. Throws InputError naming the field, the
/// value and the expected dimension otherwise.
double parse_quantity(const std::string& text, const std::string& expected, const std::string& field);

/// "length", "force / length", "mass length^-1 time^-1", ... (for messages).
std::string describe(const Dimension& d);

}  // namespace rbfib
