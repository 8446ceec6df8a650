#pragma once
// The fluid's fields split among ranks in slabs along z. Storage is x fastest and z slowest
// (grid/box.hpp), so a slab of whole z-planes is one contiguous range of the global array: no
// packing to scatter or gather it, and the halo planes go out as they lie. (Slabs along x would
// make every plane a strided gather; z is periodic in every Fourier scene, as x is.)
//
// Rank r owns the planes [first(r), first(r) + planes(r)): FFTW's default block distribution,
// ceil(n_z / P) planes per rank and the last ranks fewer or none, so that the distributed Fourier
// solver (dist/fourier_solver.hpp) transforms the slabs where they lie.
#include "rbfib/dist/comm.hpp"
#include "rbfib/grid/box.hpp"

#include <utility>
#include <vector>

namespace rbfib::dist {

class Slabs {
 public:
  /// Throws InputError naming `name` for a box that is not 3D.
  Slabs(const Box& box, const Comm& comm, const std::string& name);

  const Box& box() const { return box_; }
  const Comm& comm() const { return comm_; }
  int planes(int rank) const { return planes_[static_cast<std::size_t>(rank)]; }
  int first(int rank) const { return first_[static_cast<std::size_t>(rank)]; }
  /// The rank that owns plane z (0 <= z < n_z): the blocks are ceil(n_z / P) planes.
  int owner(int z) const { return z / planes_[0]; }
  /// This rank's planes.
  int planes() const { return planes(comm_.rank()); }
  int first() const { return first(comm_.rank()); }
  /// Unknowns per z-plane (n_x n_y).
  index_t plane_size() const { return index_t(box_.n(0)) * box_.n(1); }
  /// Unknowns this rank owns.
  index_t local_size() const { return planes() * plane_size(); }

  /// This rank's part of a field given whole on every rank (initial data, tests).
  dvec scatter(const dvec& global) const;
  /// The whole field on every rank from each rank's part (output, tests; collective).
  dvec gather(const dvec& local) const;

 private:
  Box box_;
  Comm comm_;
  std::vector<int> planes_, first_;
};

/// A slab extended by `ghosts` planes on each side along z (periodic): planes [0, g) are copies of
/// the rank below's top planes, [g, g + n) the rank's own, [g + n, n + 2g) the rank above's bottom
/// planes. Interpolation reads the ghosts after fill(); spreading writes into them and sum() adds
/// them to their owners. Every rank must own at least `ghosts` planes, so that each ghost plane
/// has one owner among the two neighbours. Any box split like the slabs' (the MAC grid's
/// components and scalars share their z-planes) may pass through: a field's plane size is its
/// size over the extended planes.
class Halo {
 public:
  /// Throws InputError naming `name` when a rank owns fewer than `ghosts` planes.
  Halo(const Slabs& slabs, int ghosts, const std::string& name);

  int ghosts() const { return ghosts_; }
  index_t extended_size() const { return index_t(slabs_.planes() + 2 * ghosts_) * slabs_.plane_size(); }
  /// The owned planes of an extended field start here.
  index_t owned_offset() const { return index_t(ghosts_) * slabs_.plane_size(); }

  /// Ghost planes from the neighbours' owned planes (collective).
  void fill(dvec& extended) const;
  /// Each ghost plane added into the plane its neighbour owns; the ghosts are then zero (collective).
  void sum(dvec& extended) const;

  /// The entries of a plane of an extended field (InputError naming `what` unless whole planes).
  index_t plane_size_of(const dvec& extended, const char* what) const;
  /// The owned entries of an extended field: [first, last).
  std::pair<index_t, index_t> owned(const dvec& extended, const char* what) const {
    const index_t ps = plane_size_of(extended, what);
    return {index_t(ghosts_) * ps, index_t(ghosts_ + slabs_.planes()) * ps};
  }

 private:
  void count_exchange(index_t count) const;  // two messages of `count` doubles (Traffic)
  const Slabs& slabs_;
  int ghosts_;
  int below_, above_;
  mutable dvec buffer_;
};

}  // namespace rbfib::dist
