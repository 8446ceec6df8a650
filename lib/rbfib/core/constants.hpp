#pragma once
// Mathematical constants, one definition for the library, the studies and the tests.

namespace rbfib {

inline constexpr double pi = 3.14159265358979323846;

}  // namespace rbfib
