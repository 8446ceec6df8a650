#pragma once
// Reproducible random fields for the unit tests.
#include "rbfib/core/exec.hpp"

#include <random>

namespace rbfib::testing {

/// n values uniform in [-1, 1), from a seeded generator.
inline dvec random_vector(index_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  host_vector<double> h(n);
  for (auto& v : h) v = U(gen);
  return dvec(h);
}

}  // namespace rbfib::testing
