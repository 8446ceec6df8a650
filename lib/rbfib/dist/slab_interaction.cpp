#include "rbfib/dist/slab_interaction.hpp"


#include <cmath>

namespace rbfib::dist {

namespace {
std::array<Box, 3> component_boxes(const MacGrid& g) { return {g.component(0), g.component(1), g.component(2)}; }
}  // namespace

SlabInteraction::SlabInteraction(const SlabFluid& fluid, ib::Kernel kernel)
    : fluid_(fluid), ib_(component_boxes(fluid.lagrangian_grid()), kernel) {
  ib_.set_window(2, fluid.whole_grid().cells[2]);
}

int SlabInteraction::ghosts_needed(double beyond, double h, ib::Kernel kernel) {
  return int(std::ceil(std::max(0.0, beyond) / h)) + ib::kernel_support(kernel) / 2 + 1;
}

void SlabInteraction::interpolate(const dvec& X, const std::array<dvec, 3>& u, dvec& U) {
  for (int c = 0; c < 3; ++c) fluid_.widen(u[c], wide_[c]);
  fluid_.comm().agreed([&] { ib_.interpolate(X, wide_, U); });
}

void SlabInteraction::spread(const dvec& X, const dvec& F, std::array<dvec, 3>& f) {
  fluid_.comm().agreed([&] { ib_.spread(X, F, wide_); });
  for (int c = 0; c < 3; ++c) fluid_.narrow_sum(wide_[c], f[c]);
}

}  // namespace rbfib::dist
