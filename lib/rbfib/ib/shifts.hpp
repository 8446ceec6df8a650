#pragma once
// Shifts sigma_1, ..., sigma_{s^d} of Alg. 4.1, generated at compile time, in lexicographic order
// with the first component fastest: sigma_j,a = mod(j', s) - floor(s/2) with j' = j - 1 written in
// base s. Shift j touches grid cell floor(X) + sigma_j (eq. 4.4).
#include <array>

namespace rbfib::ib {

/// Component a of shift j (j = 0, ..., s^d - 1, zero-based), Alg. 4.1.
constexpr int shift_component(int j, int s, int a) {
  for (int i = 0; i < a; ++i) j /= s;
  return j % s - s / 2;
}

template <int S, int D = 3>
struct Shifts {
  static constexpr int count = [] {
    int c = 1;
    for (int a = 0; a < D; ++a) c *= S;
    return c;
  }();
  /// value[j][a]: component a of sigma_{j+1}.
  static constexpr std::array<std::array<int, D>, count> value = [] {
    std::array<std::array<int, D>, count> v{};
    for (int j = 0; j < count; ++j)
      for (int a = 0; a < D; ++a) v[j][a] = shift_component(j, S, a);
    return v;
  }();
};

}  // namespace rbfib::ib
