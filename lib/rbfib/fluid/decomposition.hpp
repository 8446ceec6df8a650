#pragma once
// A fluid split among processes, as the Navier-Stokes solver and the coupled step see it
// (implemented by dist/, which comes after sim in the module graph; they know only this interface).
//
// Each process steps its own part of the grid extended by ghost planes along the split axis: the
// local grid. Every field the solver keeps has its ghosts filled from their owners on exit, so the
// stencils (reach <= ghosts) give the right values on the owned planes; what they give on ghost
// planes is never read before the next fill. The direct solves read the owned planes of their
// right-hand side and return a filled solution.
#include "rbfib/fluid/laplacian.hpp"
#include "rbfib/grid/mac.hpp"
#include "rbfib/linalg/blas.hpp"

#include <algorithm>
#include <exception>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace rbfib {

/// x = A^{-1} b for one of the fluid's operators (b and x on the local grid; x is resized).
using DirectSolve = std::function<void(const dvec& b, dvec& x)>;

class FluidDecomposition {
 public:
  virtual ~FluidDecomposition() = default;

  /// The whole grid, of which every process steps a part.
  virtual const MacGrid& whole_grid() const = 0;
  /// The grid this process steps: its part with the ghost planes.
  virtual const MacGrid& local_grid() const = 0;
  /// Fills the ghost planes of a field of the local grid (any of its boxes) from their owners.
  virtual void fill(dvec& field) const = 0;
  /// Adds the ghost planes of a field of the local grid into the planes their owners hold, then
  /// zeroes them (spreading's counterpart of fill).
  virtual void sum_ghosts(dvec& field) const = 0;
  /// The grid the Lagrangian side sees: this process's part with the halo its cells reach beyond
  /// it, at least the local grid's (the fluid steps only the planes its stencils need, the
  /// Lagrangian halo is only filled and summed). Interpolation reads a velocity widened to it;
  /// spreading writes forces on it, which narrow_sum() brings back to the local grid.
  virtual const MacGrid& lagrangian_grid() const = 0;
  /// A field of the local grid on the Lagrangian grid, its ghost planes filled from their owners.
  virtual void widen(const dvec& local, dvec& wide) const = 0;
  /// A field spread on the Lagrangian grid: its ghost planes added into their owners' planes, then
  /// its owned planes as a field of the local grid (ghost planes zero); `wide` is left summed.
  virtual void narrow_sum(dvec& wide, dvec& local) const = 0;
  /// The split axis and its number of cells on the whole grid: the Lagrangian grid is a window of
  /// it (ib::Interaction::set_window).
  virtual int split_axis() const = 0;
  virtual int split_cells() const = 0;
  /// The direct (Fourier) solve of alpha I~ + beta L on the global box of which `local_box` is this
  /// process's part; its solution comes back filled.
  virtual DirectSolve fourier(const Box& local_box, Correction correction, double alpha, double beta,
                              const std::string& name) const = 0;
  /// max |v| over the owned entries of every process, of every field in `v` (fields of the local
  /// grid): one reduction for all of them.
  virtual double max_abs(const std::vector<const dvec*>& v) const = 0;
  double max_abs(const dvec& v) const { return max_abs(std::vector<const dvec*>{&v}); }
  /// The sum over the pairs (a, b) of sum_i a_i b_i over the owned entries of every process: one
  /// reduction for all of them.
  virtual double dot(const std::vector<std::pair<const dvec*, const dvec*>>& pairs) const = 0;
  /// v summed over the processes.
  virtual double sum(double v) const = 0;
  /// true on every process when ok is true on every process.
  virtual bool all(bool ok) const = 0;
  /// This process's number (0 writes the run's files) and the number of processes.
  virtual int process() const = 0;
  virtual int processes() const = 0;
  /// The process owning the plane that holds `x`, a coordinate along the split axis (any periodic
  /// image): the owner of a cell whose centroid lies there.
  virtual int owner(double x) const = 0;
  /// Sends to[q] to process q (one entry per process, any of them empty) and returns what every
  /// process sent here, from[q] (collective): Lagrangian data moving between owners.
  virtual std::vector<std::vector<double>> exchange(const std::vector<std::vector<double>>& to) const = 0;
  /// The whole field on every process from each process's part (collective; `local_box` a box of
  /// the local grid), and this process's part, ghosts filled, of a field given whole: checkpoints
  /// that do not depend on the number of processes.
  virtual dvec gather(const Box& local_box, const dvec& local) const = 0;
  virtual dvec extend(const Box& local_box, const dvec& whole) const = 0;
  /// Returns when `error` is null on every process; else every process throws the error of the
  /// lowest that failed (call it before the next collective step, so that none is left waiting).
  virtual void agree(std::exception_ptr error) const = 0;
};

/// max |v| over the three components of a field: on one process (parts null), or over every
/// process's owned entries in one reduction.
inline double max_abs(const FluidDecomposition* parts, const VectorField& v) {
  if (parts) return parts->max_abs({&v[0], &v[1], &v[2]});
  return std::max({blas::norm_inf(v[0]), blas::norm_inf(v[1]), blas::norm_inf(v[2])});
}

/// The sum over the three components of a . b, likewise.
inline double dot(const FluidDecomposition* parts, const VectorField& a, const VectorField& b) {
  if (parts) return parts->dot({{&a[0], &b[0]}, {&a[1], &b[1]}, {&a[2], &b[2]}});
  return blas::dot(a[0], b[0]) + blas::dot(a[1], b[1]) + blas::dot(a[2], b[2]);
}

/// Runs `phase`; on a split fluid a failure on one process becomes every process's (agree) before
/// the next collective step, so that none is left waiting.
template <class Phase>
void agreed(const FluidDecomposition* parts, Phase&& phase) {
  if (!parts) return phase();
  std::exception_ptr error;
  try {
    phase();
  } catch (...) {
    error = std::current_exception();
  }
  parts->agree(error);
}

}  // namespace rbfib
