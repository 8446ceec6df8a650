#pragma once
// Internal units are CGS (cm, g, s; dyn, erg, poise), as most of the seed's parameters are.
// Convert at the edge with these factors: a length of 0.2 um is `0.2 * units::um`; print it
// as `x / units::um` with the unit named.
namespace rbfib::units {

inline constexpr double cm = 1.0;
inline constexpr double mm = 1e-1;
inline constexpr double um = 1e-4;
inline constexpr double nm = 1e-7;

inline constexpr double s = 1.0;
inline constexpr double ms = 1e-3;
inline constexpr double us = 1e-6;
inline constexpr double ns = 1e-9;

inline constexpr double g = 1.0;
inline constexpr double dyn = 1.0;       // g cm / s^2
inline constexpr double erg = 1.0;       // dyn cm
inline constexpr double pN = 1e-7;       // dyn
inline constexpr double poise = 1.0;     // g / (cm s)
inline constexpr double cP = 1e-2;

}  // namespace rbfib::units
