#include "rbfib/mechanics/net_force.hpp"

#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::mechanics {

double net_force_inf(const std::vector<double>& F) {
  require(F.size() % 3 == 0, "net_force_inf: length of the force array", F.size(), "must be 3 n");
  const std::size_t n = F.size() / 3;
  double s[3] = {0, 0, 0};
  for (std::size_t i = 0; i < F.size(); ++i) s[i / n] += F[i];
  return std::max({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])});
}

double max_force_inf(const std::vector<double>& F) {
  double m = 0;
  for (double x : F) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace rbfib::mechanics
