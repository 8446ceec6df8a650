#include "rbfib/linalg/fft.hpp"

#include "rbfib/core/error.hpp"

#include <string>
#include <vector>

#if defined(RBFIB_BACKEND_CUDA)
#include <cufft.h>
#else
#include <fftw3.h>
#include <omp.h>

#include <mutex>
#endif

namespace rbfib::linalg {

namespace {
std::string axes_text(std::array<int, 3> n, std::array<bool, 3> t) {
  std::string s;
  const char* names = "xyz";
  for (int d = 0; d < 3; ++d)
    if (n[d] > 1) s += std::string(s.empty() ? "" : ", ") + names[d] + (t[d] ? " (transformed)" : " (batched)");
  return s;
}

#if defined(RBFIB_BACKEND_CUDA)
/// Axes with more than one point that are not transformed.
int batched_axes(std::array<int, 3> n, std::array<bool, 3> t, int* which) {
  int count = 0;
  for (int d = 0; d < 3; ++d)
    if (n[d] > 1 && !t[d]) {
      if (which) *which = d;
      ++count;
    }
  return count;
}

void cufft_check(cufftResult r, const char* what) {
  if (r != CUFFT_SUCCESS) throw NumericalError(Cause::solver, std::string(what) + ": cuFFT error " + std::to_string(int(r)));
}
#else
std::once_flag fftw_threads_once;
std::mutex fftw_planner;  // FFTW's planner is not thread-safe
#endif
}  // namespace

bool FourierTransform::supported(std::array<int, 3> n, std::array<bool, 3> transform) {
#if defined(RBFIB_BACKEND_CUDA)
  int which = -1;
  const int b = batched_axes(n, transform, &which);
  return b == 0 || (b == 1 && which == 1);
#else
  (void)n;
  (void)transform;
  return true;
#endif
}

double FourierTransform::scale() const {
  double s = 1;
  for (int d = 0; d < 3; ++d)
    if (transform_[d]) s *= n_[d];
  return s;
}

FourierTransform::FourierTransform(std::array<int, 3> n, std::array<bool, 3> transform) : n_(n), transform_(transform) {
  for (int d = 0; d < 3; ++d) require(n[d] >= 1, "FFT extent n[" + std::to_string(d) + "]", n[d], "must be >= 1");
  require(supported(n, transform), "FFT axes", axes_text(n, transform),
          "this backend batches only over y (or over no axis)");
  const index_t stride[3] = {1, n[0], index_t(n[0]) * n[1]};
#if defined(RBFIB_BACKEND_CUDA)
  // cuFFT lists dimensions slowest first; the batch, if any, is over y with distance n_x.
  std::vector<int> dims, embed;
  for (int d = 2; d >= 0; --d)
    if (transform[d] && n[d] > 1) dims.push_back(n[d]);
  if (dims.empty()) dims.push_back(1);
  const bool batched = batched_axes(n, transform, nullptr) == 1;
  int howmany = 1, dist = int(size());
  if (batched) {  // element (z, x) of batch j at j n_x + z (n_x n_y) + x
    howmany = n[1];
    dist = n[0];
    embed = dims;
    if (embed.size() == 2) embed[1] = n[0] * n[1];
  }
  for (void** p : {&forward_, &backward_}) {
    auto* h = new cufftHandle;
    cufft_check(cufftPlanMany(h, int(dims.size()), dims.data(), batched ? embed.data() : nullptr, 1, dist,
                              batched ? embed.data() : nullptr, 1, dist, CUFFT_Z2Z, howmany),
                "cufftPlanMany");
    *p = h;
  }
#else
  std::call_once(fftw_threads_once, [] { fftw_init_threads(); });
  std::vector<fftw_iodim64> dims, loops;
  for (int d = 0; d < 3; ++d) {
    if (n[d] == 1) continue;
    fftw_iodim64 io{n[d], stride[d], stride[d]};
    (transform[d] ? dims : loops).push_back(io);
  }
  // Plans are made on scratch arrays and executed on any array of the same layout: FFTW_UNALIGNED,
  // since device_vector storage has no SIMD alignment promise. FFTW_ESTIMATE, not FFTW_MEASURE:
  // a measured plan depends on timings, so two runs of the same scene could take different plans
  // and differ in the last bits (measured: 1e-13 relative after 160 steps on a 64^3 grid); an
  // estimated plan is the same every run, as bitwise reproducible runs and restarts need.
  std::vector<fftw_complex> scratch(static_cast<std::size_t>(size()));
  std::lock_guard<std::mutex> lock(fftw_planner);
  fftw_plan_with_nthreads(omp_get_max_threads());
  for (int sign : {FFTW_FORWARD, FFTW_BACKWARD}) {
    fftw_plan p = fftw_plan_guru64_dft(int(dims.size()), dims.data(), int(loops.size()), loops.data(), scratch.data(),
                                       scratch.data(), sign, FFTW_ESTIMATE | FFTW_UNALIGNED);
    if (!p) throw NumericalError(Cause::solver, "FFTW could not plan a transform over " + axes_text(n, transform));
    (sign == FFTW_FORWARD ? forward_ : backward_) = p;
  }
#endif
}

FourierTransform::~FourierTransform() {
#if defined(RBFIB_BACKEND_CUDA)
  for (void* p : {forward_, backward_})
    if (p) {
      cufftDestroy(*static_cast<cufftHandle*>(p));
      delete static_cast<cufftHandle*>(p);
    }
#else
  std::lock_guard<std::mutex> lock(fftw_planner);
  for (void* p : {forward_, backward_})
    if (p) fftw_destroy_plan(static_cast<fftw_plan>(p));
#endif
}

void FourierTransform::execute(cvec& data, int sign) const {
  require(static_cast<index_t>(data.size()) == size(), "FFT data size", data.size(), "must be " + std::to_string(size()));
#if defined(RBFIB_BACKEND_CUDA)
  auto* d = reinterpret_cast<cufftDoubleComplex*>(thrust::raw_pointer_cast(data.data()));
  cufft_check(cufftExecZ2Z(*static_cast<cufftHandle*>(sign < 0 ? forward_ : backward_), d, d, sign < 0 ? CUFFT_FORWARD : CUFFT_INVERSE),
              "cufftExecZ2Z");
#else
  auto* d = reinterpret_cast<fftw_complex*>(thrust::raw_pointer_cast(data.data()));
  fftw_execute_dft(static_cast<fftw_plan>(sign < 0 ? forward_ : backward_), d, d);
#endif
}

void FourierTransform::forward(cvec& data) const { execute(data, -1); }
void FourierTransform::backward(cvec& data) const { execute(data, +1); }

}  // namespace rbfib::linalg
