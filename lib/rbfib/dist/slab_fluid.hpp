#pragma once
// The fluid of a MAC grid split among ranks in slabs along z (fluid/decomposition.hpp): each rank
// steps its planes with the fluid_reach planes of halo its stencils need on each side, the direct
// solves are the distributed Fourier solver's (dist/fourier_solver.hpp), and the reductions are
// over all ranks. Give it to NavierStokesSolver and the one-process code steps a rank's slab
// unchanged. The Lagrangian side sees a wider slab, `ghosts` planes a side (the reach of the cells a
// rank owns plus the kernel's support): velocities are widened to it before interpolation and
// spread forces narrowed back, so the fluid's work does not grow with the cells' size.
//
// Every box of the grid (the three velocity components, the scalars) is periodic along z with n_z
// unknowns, so one split of the planes serves them all.
#include "rbfib/dist/fourier_solver.hpp"
#include "rbfib/fluid/decomposition.hpp"

#include <memory>

namespace rbfib::dist {

class SlabFluid : public FluidDecomposition {
 public:
  /// Planes of halo the Navier-Stokes stencils need: advection reaches two cells (eq. 2.5).
  static constexpr int fluid_reach = 2;

  /// `ghosts`: the Lagrangian halo (at least fluid_reach). Throws InputError naming the field when
  /// the grid is not periodic along x and z, or when a rank would own fewer planes than the halo
  /// (too many ranks for n_z).
  SlabFluid(const MacGrid& grid, const Comm& comm, int ghosts = fluid_reach);

  const MacGrid& whole_grid() const override { return grid_; }
  const MacGrid& local_grid() const override { return local_; }
  const MacGrid& lagrangian_grid() const override { return wide_; }
  void widen(const dvec& local, dvec& wide) const override;
  void narrow_sum(dvec& wide, dvec& local) const override;
  void fill(dvec& field) const override { halo_->fill(field); }
  void sum_ghosts(dvec& field) const override { halo_->sum(field); }
  int split_axis() const override { return 2; }
  int split_cells() const override { return grid_.cells[2]; }
  DirectSolve fourier(const Box& local_box, Correction correction, double alpha, double beta,
                      const std::string& name) const override;
  using FluidDecomposition::max_abs;
  double max_abs(const std::vector<const dvec*>& v) const override;
  double dot(const std::vector<std::pair<const dvec*, const dvec*>>& pairs) const override;
  double sum(double v) const override { return comm_.sum(v); }
  bool all(bool ok) const override { return comm_.all(ok); }
  void agree(std::exception_ptr error) const override { comm_.agree(error); }
  int process() const override { return comm_.rank(); }
  int processes() const override { return comm_.size(); }
  int owner(double z) const override;
  std::vector<std::vector<double>> exchange(const std::vector<std::vector<double>>& to) const override {
    return comm_.exchange(to);
  }

  const Comm& comm() const { return comm_; }
  const Slabs& slabs() const { return slabs_; }
  int ghosts() const { return wide_ghosts_; }  ///< the Lagrangian halo (planes a side)
  const Halo& halo() const { return *halo_; }  ///< the fluid's
  /// The whole grid's box of which `local_box` (a box of the local grid) is this rank's part.
  Box global_box(const Box& local_box) const;

  /// This rank's part, with filled ghosts, of a field given whole on every rank.
  dvec extend(const Box& local_box, const dvec& global) const override;
  /// The whole field on every rank from each rank's part (collective).
  dvec gather(const Box& local_box, const dvec& local) const override;

 private:
  MacGrid grid_, local_, wide_;
  Comm comm_;
  Slabs slabs_;
  int ghosts_ = fluid_reach, wide_ghosts_;  // the fluid's halo, the Lagrangian side's
  std::unique_ptr<Halo> halo_, wide_halo_;
};

}  // namespace rbfib::dist
