#pragma once
// Interpolation and spreading (ib/interaction.hpp, Algs. 4.2-4.6) for the Lagrangian points a rank
// owns, on its slab of a split fluid (dist/slab_fluid.hpp). A rank owns whole cells, so its
// points may lie beyond its planes by up to a cell's size: the slab's ghost planes must cover
// that reach plus the kernel's support. Then
//   spreading:     each rank spreads onto its extended slab, and the halo sum adds the ghost
//                  planes into the planes' owners (the ghosts are left zero);
//   interpolation: each rank fills the velocity's ghost planes, then interpolates locally.
// Both equal the one-process algorithms on the whole grid up to the order of summation.
//
// The slab is a window of the periodic z axis (Interaction::set_window): each point is used at
// its image nearest the slab, so a cell that straddles z = 0 spreads into the planes on both
// sides of the seam; a point whose support leaves the slab is refused, on every rank.
#include "rbfib/dist/slab_fluid.hpp"
#include "rbfib/ib/interaction.hpp"

namespace rbfib::dist {

class SlabInteraction {
 public:
  SlabInteraction(const SlabFluid& fluid, ib::Kernel kernel);

  /// Planes of halo a set of points needs when it lies at most `beyond` (cm) outside the planes of
  /// the rank that owns it: its reach plus the kernel's half support, plus one for the staggering.
  static int ghosts_needed(double beyond, double h, ib::Kernel kernel);

  /// U = I u at this rank's points; u: the local grid's velocity (widened here to the Lagrangian
  /// grid; collective: a point beyond the slab throws InputError on every rank).
  void interpolate(const dvec& X, const std::array<dvec, 3>& u, dvec& U);
  /// f = S F on this rank's planes of the local grid (collective: the halo sum); the ghost planes
  /// of f are zero.
  void spread(const dvec& X, const dvec& F, std::array<dvec, 3>& f);


 private:
  const SlabFluid& fluid_;
  ib::Interaction ib_;  // on the Lagrangian grid
  std::array<dvec, 3> wide_;
};

}  // namespace rbfib::dist
