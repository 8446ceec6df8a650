#pragma once
// The Fourier solver of fluid/fourier_solver.hpp on slabs along z (dist/slabs.hpp): the same
// discrete operator (alpha I~ + beta L), the same modes, the same answer to rounding, on any number
// of ranks.
//
// A rank holds its planes z in [z0, z0 + n) of b, x fastest. It reorders them to (z, x, y), y
// fastest, and FFTW's distributed 2D real transform over (z, x), batched over y, returns them
// transposed: the rank then holds the modes k_x in [x0, x0 + m) of 0..nx/2 (the others are their
// conjugates) for every k_z, each mode's y-line contiguous. Walls in y: each line is the tridiagonal system of fluid/wall_modes.hpp, solved
// where it lies. y periodic: a local transform along y, then a diagonal. The backward transform
// takes the transposed modes back to the slabs. Communication: the two all-to-all transposes of
// FFTW (each rank sends about (P - 1) / P of its slab's half spectrum per transform).
#include "rbfib/dist/slabs.hpp"
#include "rbfib/fluid/laplacian.hpp"

#include <string>

namespace rbfib::dist {

class FourierSolver {
 public:
  /// Throws InputError naming `name` when the box is not periodic along x and z, when the operator
  /// is not definite or semidefinite, or when the slabs are not FFTW's distribution.
  FourierSolver(const Slabs& slabs, Correction correction, double alpha, double beta, const std::string& name);
  ~FourierSolver();
  FourierSolver(const FourierSolver&) = delete;
  FourierSolver& operator=(const FourierSolver&) = delete;

  /// x = (alpha I~ + beta L)^{-1} b on this rank's slab (collective). For a singular operator, b's
  /// mean over the whole box is removed first and x is returned mean-free.
  void solve(const dvec& b, dvec& x) const;
  /// The same on the slab's entries of b and x from b_offset and x_offset on (an extended slab's
  /// owned planes, say): no copies in and out. b and x may be the same vector.
  void solve(const dvec& b, index_t b_offset, dvec& x, index_t x_offset) const;

  bool singular() const { return singular_; }
  /// Modes k_x this rank solves after the transpose: [first_mode(), first_mode() + modes()).
  index_t modes() const { return modes_; }
  index_t first_mode() const { return first_mode_; }

 private:
  void count_transposes() const;  // Traffic: the two transposes of one solve
  const Slabs& slabs_;
  StaggeredLaplacian lap_;
  double alpha_, beta_;
  std::string name_;
  bool wall_ = false, singular_ = false;
  index_t modes_ = 0, first_mode_ = 0, alloc_ = 0;
  host_vector<double> mux_, muy_, muz_;
  void* work_ = nullptr;  // fftw_complex[alloc_], in place of the padded real planes
  void* forward_ = nullptr;
  void* backward_ = nullptr;
  void* forward_y_ = nullptr;  // y periodic: the local transforms along y
  void* backward_y_ = nullptr;
  mutable dvec thomas_;
};

}  // namespace rbfib::dist
