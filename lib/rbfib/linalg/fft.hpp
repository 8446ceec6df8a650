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

/// The transform of a real array along the same choice of axes, x among them: the spectrum keeps
/// the modes k_x = 0 .. n_x / 2 of x (the others are their conjugates), stored x fastest with
/// h = n_x / 2 + 1 in place of n_x. Half the work and memory of the complex transform; backward
/// takes a Hermitian spectrum (as an operator with real coefficients per mode leaves one) to a real
/// array, overwriting the spectrum.
class RealFourierTransform {
 public:
  /// Throws InputError naming the axes when x is not transformed, n_x < 2, or the backend cannot
  /// batch the choice (as FourierTransform::supported).
  RealFourierTransform(std::array<int, 3> n, std::array<bool, 3> transform);
  ~RealFourierTransform();
  RealFourierTransform(const RealFourierTransform&) = delete;
  RealFourierTransform& operator=(const RealFourierTransform&) = delete;

  /// spectrum (resized) = the forward transform of real (size()); real is not changed.
  void forward(const dvec& real, cvec& spectrum) const;
  /// real (resized) = the backward transform of the spectrum, which is overwritten.
  void backward(cvec& spectrum, dvec& real) const;
  index_t size() const { return index_t(n_[0]) * n_[1] * n_[2]; }
  int half() const { return n_[0] / 2 + 1; }
  index_t spectrum_size() const { return index_t(half()) * n_[1] * n_[2]; }
  double scale() const;

  static bool supported(std::array<int, 3> n, std::array<bool, 3> transform);

 private:
  std::array<int, 3> n_;
  std::array<bool, 3> transform_;
  void* forward_ = nullptr;
  void* backward_ = nullptr;
};

}  // namespace rbfib::linalg
