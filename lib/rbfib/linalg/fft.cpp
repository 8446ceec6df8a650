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

/// Destroys a transform's two plans (either may be null).
void destroy_plans(void* forward, void* backward) {
#if defined(RBFIB_BACKEND_CUDA)
  for (void* p : {forward, backward})
    if (p) {
      cufftDestroy(*static_cast<cufftHandle*>(p));
      delete static_cast<cufftHandle*>(p);
    }
#else
  std::lock_guard<std::mutex> lock(fftw_planner);
  for (void* p : {forward, backward})
    if (p) fftw_destroy_plan(static_cast<fftw_plan>(p));
#endif
}

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

namespace {
double transformed_points(std::array<int, 3> n, std::array<bool, 3> transform) {
  double s = 1;
  for (int d = 0; d < 3; ++d)
    if (transform[d]) s *= n[d];
  return s;
}
}  // namespace

double FourierTransform::scale() const { return transformed_points(n_, transform_); }

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

FourierTransform::~FourierTransform() { destroy_plans(forward_, backward_); }

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

bool RealFourierTransform::supported(std::array<int, 3> n, std::array<bool, 3> transform) {
  return transform[0] && n[0] >= 2 && FourierTransform::supported(n, transform);
}

double RealFourierTransform::scale() const { return transformed_points(n_, transform_); }

RealFourierTransform::RealFourierTransform(std::array<int, 3> n, std::array<bool, 3> transform) : n_(n), transform_(transform) {
  for (int d = 0; d < 3; ++d) require(n[d] >= 1, "FFT extent n[" + std::to_string(d) + "]", n[d], "must be >= 1");
  require(supported(n, transform), "real FFT axes", axes_text(n, transform),
          "x must be transformed with at least 2 points, and the backend able to batch the rest");
  const int h = n[0] / 2 + 1;
  // Strides of the real array and of the spectrum (x fastest, h complex values along x).
  const index_t rs[3] = {1, n[0], index_t(n[0]) * n[1]}, cs[3] = {1, h, index_t(h) * n[1]};
#if defined(RBFIB_BACKEND_CUDA)
  // cuFFT lists dimensions slowest first, the halved one (x) last; the batch, if any, is over y.
  std::vector<int> dims;
  for (int d = 2; d >= 1; --d)
    if (transform[d] && n[d] > 1) dims.push_back(n[d]);
  dims.push_back(n[0]);
  const bool batched = batched_axes(n, transform, nullptr) == 1;
  int howmany = 1, rdist = int(size()), cdist = int(spectrum_size());
  std::vector<int> rembed, cembed;
  if (batched) {  // element (z, x) of batch j at j n_x + z (n_x n_y) + x, and j h + z (h n_y) + x
    howmany = n[1];
    rdist = n[0];
    cdist = h;
    rembed = cembed = dims;
    if (dims.size() == 2) rembed[1] = n[0] * n[1], cembed[1] = h * n[1];
    else cembed[0] = h;
  }
  int* re = batched ? rembed.data() : nullptr;
  int* ce = batched ? cembed.data() : nullptr;
  auto* f = new cufftHandle;
  cufft_check(cufftPlanMany(f, int(dims.size()), dims.data(), re, 1, rdist, ce, 1, cdist, CUFFT_D2Z, howmany), "cufftPlanMany (D2Z)");
  forward_ = f;
  auto* b = new cufftHandle;
  cufft_check(cufftPlanMany(b, int(dims.size()), dims.data(), ce, 1, cdist, re, 1, rdist, CUFFT_Z2D, howmany), "cufftPlanMany (Z2D)");
  backward_ = b;
#else
  std::call_once(fftw_threads_once, [] { fftw_init_threads(); });
  // FFTW halves the last of the transform's dimensions: x, listed last. Strides are (input,
  // output): real then complex forward, complex then real backward.
  std::vector<fftw_iodim64> fdims, bdims, floops, bloops;
  for (int d = 2; d >= 1; --d) {
    if (n[d] == 1) continue;
    (transform[d] ? fdims : floops).push_back({n[d], rs[d], cs[d]});
    (transform[d] ? bdims : bloops).push_back({n[d], cs[d], rs[d]});
  }
  fdims.push_back({n[0], 1, 1});
  bdims.push_back({n[0], 1, 1});
  // Estimated plans, as FourierTransform's (bitwise reproducible runs), on scratch arrays.
  std::vector<double> real(static_cast<std::size_t>(size()));
  std::vector<fftw_complex> spectrum(static_cast<std::size_t>(spectrum_size()));
  std::lock_guard<std::mutex> lock(fftw_planner);
  fftw_plan_with_nthreads(omp_get_max_threads());
  forward_ = fftw_plan_guru64_dft_r2c(int(fdims.size()), fdims.data(), int(floops.size()), floops.data(), real.data(), spectrum.data(),
                                      FFTW_ESTIMATE | FFTW_UNALIGNED);
  backward_ = fftw_plan_guru64_dft_c2r(int(bdims.size()), bdims.data(), int(bloops.size()), bloops.data(), spectrum.data(), real.data(),
                                       FFTW_ESTIMATE | FFTW_UNALIGNED);
  if (!forward_ || !backward_) throw NumericalError(Cause::solver, "FFTW could not plan a real transform over " + axes_text(n, transform));
#endif
}

RealFourierTransform::~RealFourierTransform() { destroy_plans(forward_, backward_); }

void RealFourierTransform::forward(const dvec& real, cvec& spectrum) const {
  require(static_cast<index_t>(real.size()) == size(), "FFT data size", real.size(), "must be " + std::to_string(size()));
  spectrum.resize(static_cast<std::size_t>(spectrum_size()));
  // An out-of-place forward real transform leaves its input as it was (FFTW and cuFFT): the
  // const_cast only meets the C interfaces.
  auto* in = const_cast<double*>(thrust::raw_pointer_cast(real.data()));
#if defined(RBFIB_BACKEND_CUDA)
  auto* out = reinterpret_cast<cufftDoubleComplex*>(thrust::raw_pointer_cast(spectrum.data()));
  cufft_check(cufftExecD2Z(*static_cast<cufftHandle*>(forward_), in, out), "cufftExecD2Z");
#else
  auto* out = reinterpret_cast<fftw_complex*>(thrust::raw_pointer_cast(spectrum.data()));
  fftw_execute_dft_r2c(static_cast<fftw_plan>(forward_), in, out);
#endif
}

void RealFourierTransform::backward(cvec& spectrum, dvec& real) const {
  require(static_cast<index_t>(spectrum.size()) == spectrum_size(), "FFT spectrum size", spectrum.size(),
          "must be " + std::to_string(spectrum_size()));
  real.resize(static_cast<std::size_t>(size()));
  double* out = thrust::raw_pointer_cast(real.data());
#if defined(RBFIB_BACKEND_CUDA)
  auto* in = reinterpret_cast<cufftDoubleComplex*>(thrust::raw_pointer_cast(spectrum.data()));
  cufft_check(cufftExecZ2D(*static_cast<cufftHandle*>(backward_), in, out), "cufftExecZ2D");
#else
  auto* in = reinterpret_cast<fftw_complex*>(thrust::raw_pointer_cast(spectrum.data()));
  fftw_execute_dft_c2r(static_cast<fftw_plan>(backward_), in, out);
#endif
}

}  // namespace rbfib::linalg
