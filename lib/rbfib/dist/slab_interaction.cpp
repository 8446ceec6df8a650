#include "rbfib/dist/slab_interaction.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::dist {

namespace {
std::array<Box, 3> component_boxes(const MacGrid& g) { return {g.component(0), g.component(1), g.component(2)}; }
}  // namespace

SlabInteraction::SlabInteraction(const SlabFluid& fluid, ib::Kernel kernel)
    : fluid_(fluid), ib_(component_boxes(fluid.local_grid()), kernel) {}

int SlabInteraction::ghosts_needed(double beyond, double h, ib::Kernel kernel) {
  const ib::Interaction probe(component_boxes(make_mac_grid(3, {4, 4, 4}, {4 * h, 4 * h, 4 * h},
                                                            {MacBoundary::periodic, MacBoundary::periodic,
                                                             MacBoundary::periodic})),
                              kernel);
  return int(std::ceil(std::max(0.0, beyond) / h)) + probe.support() / 2 + 1;
}

void SlabInteraction::localize(dvec& X) const {
  const MacGrid& local = fluid_.local_grid();
  const double lz = fluid_.grid().length[2], h = local.h(2);
  const double lo = local.origin[2], hi = lo + local.length[2];
  const double margin = (ib_.support() / 2 + 1) * h;  // the support, staggering included
  const double centre = 0.5 * (lo + hi);
  const index_t n = index_t(X.size()) / 3;
  double* z = ptr(X) + 2 * n;
  for_each_index(n, [=] RBFIB_HD (index_t k) { z[k] -= lz * std::round((z[k] - centre) / lz); });
  // The farthest any point lies beyond the part of the slab whose support stays inside it.
  const host_vector<double> zs(X.begin() + 2 * n, X.end());
  double worst = 0.0;
  index_t which = -1;
  for (index_t k = 0; k < n; ++k) {
    const double out = std::max((lo + margin) - zs[k], zs[k] - (hi - margin));
    if (out > worst) worst = out, which = k;
  }
  const Comm& comm = fluid_.comm();
  if (comm.all(which < 0)) return;
  const int more = int(std::ceil(comm.max(worst) / h));
  throw InputError(which >= 0 ? "point " + to_text(which) + " at z = " + to_text(zs[which]) + " cm" : "a point on another rank",
                   "reaches " + to_text(more) + " planes beyond the halo of " + to_text(fluid_.ghosts()),
                   "the fluid's ghost planes must cover the cells' reach beyond their rank's planes plus the kernel's "
                   "support (SlabInteraction::ghosts_needed)");
}

void SlabInteraction::spread(const dvec& X, const dvec& F, std::array<dvec, 3>& f) {
  ib_.spread(X, F, f);
  for (int c = 0; c < 3; ++c) fluid_.halo().sum(f[c]);
}

}  // namespace rbfib::dist
