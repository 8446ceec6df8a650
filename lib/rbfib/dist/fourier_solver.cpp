#include "rbfib/dist/fourier_solver.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/fluid/wall_modes.hpp"

#include <fftw3-mpi.h>
#include <thrust/reduce.h>
#include <omp.h>

#include <cmath>

namespace rbfib::dist {

namespace {
/// Sum over this rank's entries (from `offset` on), then over all ranks: the mean of a field over
/// the whole box.
double global_mean(const Slabs& slabs, const dvec& v, index_t offset) {
  const auto first = v.begin() + offset;
  return slabs.comm().sum(thrust::reduce(first, first + slabs.local_size(), 0.0)) / double(slabs.box().size());
}
}  // namespace

FourierSolver::FourierSolver(const Slabs& slabs, Correction correction, double alpha, double beta, const std::string& name)
    : slabs_(slabs), lap_(slabs.box(), correction), alpha_(alpha), beta_(beta), name_(name) {
  const Box& box = slabs.box();
  require(box.dims == 3 && box.axes[0].periodic() && box.axes[2].periodic(), name + ": box",
          "not periodic along x and z", "the distributed Fourier solver needs x and z periodic (walls in y only)");
  require(alpha >= 0 && std::isfinite(alpha), name + ": alpha (coefficient of I~)", alpha, "must be finite and >= 0");
  require(beta <= 0 && std::isfinite(beta), name + ": beta (coefficient of L)", beta, "must be finite and <= 0");
  require(alpha > 0 || beta < 0, name + ": alpha, beta", "0, 0", "the operator must not vanish");
  const kernels::LaplacianStencil& s = lap_.stencil();
  wall_ = !box.axes[1].periodic();
  const bool neumann_both = wall_ && s.axis[1].lo.ghost == 1.0 && s.axis[1].hi.ghost == 1.0;
  singular_ = alpha == 0 && (!wall_ || neumann_both);
  const int nx = box.n(0), ny = box.n(1), nz = box.n(2);
  mux_ = kernels::periodic_eigenvalues(s.axis[0], nx);
  muy_ = kernels::periodic_eigenvalues(s.axis[1], ny);
  muz_ = kernels::periodic_eigenvalues(s.axis[2], nz);

  // Real transforms over (z, x): x keeps its modes k_x = 0..nx/2 (the rest are their conjugates),
  // as the one-process solver does; FFTW's local sizes take those complex dimensions.
  const ptrdiff_t n[2] = {nz, nx}, spectrum[2] = {nz, nx / 2 + 1};
  ptrdiff_t local_n0 = 0, local_0_start = 0, local_n1 = 0, local_1_start = 0;
  alloc_ = fftw_mpi_local_size_many_transposed(2, spectrum, ny, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, slabs.comm().get(),
                                               &local_n0, &local_0_start, &local_n1, &local_1_start);
  // Agreed by all ranks (a rank that threw alone would leave the others in the plan's collectives);
  // an empty slab's start is any.
  const bool same = local_n0 == slabs.planes() && (local_n0 == 0 || local_0_start == slabs.first());
  require(slabs.comm().all(same), name + ": slabs",
          "planes " + to_text(slabs.first()) + " + " + to_text(slabs.planes()),
          "must be FFTW's distribution, planes " + to_text(local_0_start) + " + " + to_text(local_n0));
  modes_ = local_n1;
  first_mode_ = local_1_start;
  alloc_ = std::max<index_t>(alloc_, 1);
  auto* work = fftw_alloc_complex(static_cast<std::size_t>(alloc_));
  work_ = work;
  // FFTW_ESTIMATE: the same plan every run, as bitwise restarts need (linalg/fft.cpp). In place:
  // the real planes are padded to 2 (nx/2 + 1) values along x.
  fftw_plan_with_nthreads(omp_get_max_threads());
  MPI_Comm comm = slabs.comm().get();
  double* real = reinterpret_cast<double*>(work);
  forward_ = fftw_mpi_plan_many_dft_r2c(2, n, ny, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, real, work, comm,
                                        FFTW_ESTIMATE | FFTW_MPI_TRANSPOSED_OUT);
  backward_ = fftw_mpi_plan_many_dft_c2r(2, n, ny, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, work, real, comm,
                                         FFTW_ESTIMATE | FFTW_MPI_TRANSPOSED_IN);
  if (!forward_ || !backward_) throw NumericalError(Cause::solver, name + ": FFTW could not plan the distributed transform");
  if (!wall_ && modes_ > 0) {
    // Along y, contiguous, one transform per (k_x, k_z) this rank holds.
    fftw_iodim64 dim{ny, 1, 1}, loop{modes_ * nz, ny, ny};
    forward_y_ = fftw_plan_guru64_dft(1, &dim, 1, &loop, work, work, FFTW_FORWARD, FFTW_ESTIMATE);
    backward_y_ = fftw_plan_guru64_dft(1, &dim, 1, &loop, work, work, FFTW_BACKWARD, FFTW_ESTIMATE);
    if (!forward_y_ || !backward_y_) throw NumericalError(Cause::solver, name + ": FFTW could not plan the transforms along y");
  }
  if (wall_) thomas_.resize(static_cast<std::size_t>(alloc_));
}

FourierSolver::~FourierSolver() {
  for (void* p : {forward_, backward_, forward_y_, backward_y_})
    if (p) fftw_destroy_plan(static_cast<fftw_plan>(p));
  fftw_free(work_);
}

void FourierSolver::count_transposes() const {
  const int P = slabs_.comm().size();
  if (P == 1) return;
  // Each transposed transform sends the rank's half spectrum (planes x (nx/2 + 1) x ny complex
  // values) but the part it keeps: (P - 1) / P.
  const Box& box = slabs_.box();
  const double local = double(slabs_.planes()) * double(box.n(0) / 2 + 1) * box.n(1) * 2 * sizeof(double);
  traffic().transforms += 2;
  traffic().transposes += 2 * local * double(P - 1) / double(P);
}

void FourierSolver::solve(const dvec& b, dvec& x) const {
  const index_t local = slabs_.local_size();
  require(static_cast<index_t>(b.size()) == local, name_ + ": right-hand side size", b.size(),
          "must be this rank's slab, " + to_text(local));
  x.resize(static_cast<std::size_t>(local));
  solve(b, 0, x, 0);
}

void FourierSolver::solve(const dvec& b, index_t b_offset, dvec& x, index_t x_offset) const {
  const index_t local = slabs_.local_size();
  require(b_offset >= 0 && b_offset + local <= static_cast<index_t>(b.size()), name_ + ": right-hand side size", b.size(),
          "must hold this rank's slab, " + to_text(local) + " values, from " + to_text(b_offset));
  require(x_offset >= 0 && x_offset + local <= static_cast<index_t>(x.size()), name_ + ": solution size", x.size(),
          "must hold this rank's slab, " + to_text(local) + " values, from " + to_text(x_offset));
  const Box& box = slabs_.box();
  const int nx = box.n(0), ny = box.n(1), nz = box.n(2);
  const double mean = singular_ ? global_mean(slabs_, b, b_offset) : 0.0;

  // (z, y, x) -> (z, x, y): y fastest, as the batched transform wants, x padded to 2 (nx/2 + 1).
  auto* w = reinterpret_cast<linalg::complex*>(work_);
  double* r = reinterpret_cast<double*>(work_);
  const index_t padded = 2 * (nx / 2 + 1);
  const double* in = ptr(b) + b_offset;
  for_each_index(local, [=] RBFIB_HD (index_t p) {
    const index_t i = p % nx, q = p / nx, j = q % ny, k = q / ny;
    r[(k * padded + i) * ny + j] = in[p] - mean;
  });
  fftw_execute(static_cast<fftw_plan>(forward_));
  count_transposes();  // this one and the backward transform's
  if (forward_y_) fftw_execute(static_cast<fftw_plan>(forward_y_));

  // This rank's modes: (k_x local, k_z, y), y fastest.
  const double alpha = alpha_, beta = beta_;
  const bool singular = singular_;
  const double *mux = mux_.data() + first_mode_, *muy = muy_.data(), *muz = muz_.data();
  const bool owns_zero = first_mode_ == 0;
  if (!wall_) {
    for_each_index(modes_ * nz * ny, [=] RBFIB_HD (index_t p) {
      const index_t j = p % ny, q = p / ny, k = q % nz, i = q / nz;
      const double a = alpha + beta * (mux[i] + muy[j] + muz[k]);
      w[p] = (singular && owns_zero && p == 0) ? linalg::complex(0.0, 0.0) : w[p] / a;
    });
  } else {
    const kernels::WallModes modes{lap_.stencil().axis[1], alpha, beta};
    double* cp = ptr(thomas_);
    for_each_index(modes_ * nz, [=] RBFIB_HD (index_t m) {
      const index_t k = m % nz, i = m / nz;
      modes.solve(mux[i] + muz[k], singular && owns_zero && m == 0, w, cp, m * ny, 1);
    });
  }

  if (backward_y_) fftw_execute(static_cast<fftw_plan>(backward_y_));
  fftw_execute(static_cast<fftw_plan>(backward_));
  const double inv = 1.0 / (double(nx) * nz * (wall_ ? 1 : ny));
  double* out = ptr(x) + x_offset;
  for_each_index(local, [=] RBFIB_HD (index_t p) {
    const index_t i = p % nx, q = p / nx, j = q % ny, k = q / ny;
    out[p] = r[(k * padded + i) * ny + j] * inv;
  });
  if (singular_) {
    const double m = global_mean(slabs_, x, x_offset);
    for_each_index(local, [=] RBFIB_HD (index_t p) { out[p] -= m; });
  }
}

}  // namespace rbfib::dist
