#include "rbfib/sim/flow_profile.hpp"

namespace rbfib::sim {

std::vector<double> velocity_profile(const ImmersedBoundary& ib, const std::array<double, 3>& direction) {
  std::vector<double> u;
  for (int a : {0, 2}) {
    const rbfib::Box& b = ib.fluid().operators().component_box(a);
    const host_vector<double> v = ib.fluid_state().u[a];
    const int nx = b.n(0), ny = b.n(1), nz = b.n(2);
    u.resize(std::size_t(ny), 0.0);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          u[std::size_t(j)] += direction[std::size_t(a)] * v[std::size_t(i + nx * (j + ny * index_t(k)))] / (double(nx) * nz);
  }
  return u;
}

}  // namespace rbfib::sim
