#pragma once
// Discrete Fourier transforms on the execution device: FFTW3 (threaded with OpenMP) in the CPU
// build, cuFFT in the CUDA build, behind one plan object made once and executed many times.
//
// A plan transforms a complex 3D array stored x fastest (p = i + n_x (j + n_y k)) in place along
// the chosen axes, batched over the others; unnormalized:
//   forward:  X(k) = sum_j x(j) exp(-2 pi i j k / n)  along each transformed axis,
//   backward: x(j) = sum_k X(k) exp(+2 pi i j k / n)  (backward(forward(x)) = x times the product of
//             the transformed n).
// cuFFT takes a batch with one stride: the untransformed axes may be none, or y alone (the
// channel geometry, x and z periodic); FFTW takes any choice. The constructor says which.
#include "rbfib/core/exec.hpp"

#include <thrust/complex.h>

#include <array>

namespace rbfib::linalg {

using complex = thrust::complex<double>;
using cvec = device_vector<complex>;

class FourierTransform {
 public:
  /// n: the array's extents (1 for absent axes); transform[d]: whether axis d is transformed.
  /// Throws InputError naming the axes for a layout the backend cannot batch.
  FourierTransform(std::array<int, 3> n, std::array<bool, 3> transform);
  ~FourierTransform();
  FourierTransform(const FourierTransform&) = delete;
  FourierTransform& operator=(const FourierTransform&) = delete;

  void forward(cvec& data) const;
  void backward(cvec& data) const;
  index_t size() const { return index_t(n_[0]) * n_[1] * n_[2]; }
  /// Product of the transformed extents (the factor backward(forward(x)) carries).
  double scale() const;

  /// Whether the backend can batch this choice of axes.
  static bool supported(std::array<int, 3> n, std::array<bool, 3> transform);

 private:
  void execute(cvec& data, int sign) const;
  std::array<int, 3> n_;
  std::array<bool, 3> transform_;
  void* forward_ = nullptr;   // fftw_plan, or a cufftHandle on the heap
  void* backward_ = nullptr;
};

}  // namespace rbfib::linalg
