#pragma once
// The ranks of one run and what they agree on (MPI: Debian's OpenMPI). Each rank runs its own
// OpenMP team; MPI is called from the team's master thread only (MPI_THREAD_FUNNELED).
//
// Every reduction here is collective: all ranks of the communicator call it in the same order.
#include "rbfib/core/exec.hpp"

#include <mpi.h>

#include <exception>
#include <string>
#include <vector>

namespace rbfib::dist {

/// MPI and FFTW's distributed transforms for the life of the object (one per program, in main).
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

class Comm {
 public:
  explicit Comm(MPI_Comm comm = MPI_COMM_WORLD);

  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm get() const { return comm_; }

  double sum(double v) const;
  double max(double v) const;
  index_t sum(index_t v) const;
  /// true on every rank when `ok` is true on every rank (a stop agreed by all).
  bool all(bool ok) const;
  /// Sends to[q] to rank q (`to` has size() entries, any of them empty) and returns what every
  /// rank sent here, from[q] (MPI_Alltoallv after the counts' MPI_Alltoall).
  std::vector<std::vector<double>> exchange(const std::vector<std::vector<double>>& to) const;
  /// A failure on some ranks becomes the same failure on all: returns when `error` is null on
  /// every rank, else every rank throws the error of the lowest rank that failed (InputError,
  /// NumericalError with its cause, or std::runtime_error, with that rank's message). Call it
  /// before the next collective, so that no rank is left waiting in one.
  void agree(std::exception_ptr error) const;
  /// Runs fn() on this rank, then agree()s on whether it threw.
  template <class F>
  void agreed(F&& fn) const {
    std::exception_ptr error;
    try {
      fn();
    } catch (...) {
      error = std::current_exception();
    }
    agree(error);
  }

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

/// What this process has sent since the program started, by kind (bytes): the halo planes and the
/// Lagrangian data moving between owners as the library sends them; the distributed transforms'
/// transposes are FFTW's own messages, counted from its local sizes ((P - 1) / P of the rank's
/// data per transform). For the communication model of bench_scale.
struct Traffic {
  double halo = 0, cells = 0, transposes = 0;  ///< bytes
  long halo_exchanges = 0, transforms = 0, reductions = 0;
};
Traffic& traffic();

/// Throws NumericalError(Cause::solver) naming `what` when an MPI call did not succeed.
void check(int mpi_result, const std::string& what);

}  // namespace rbfib::dist
