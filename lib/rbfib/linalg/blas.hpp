#pragma once
// Level-1 operations on device vectors, through Thrust (one source for both backends).
#include "rbfib/core/exec.hpp"

#include <thrust/inner_product.h>
#include <thrust/transform_reduce.h>

#include <cmath>

namespace rbfib::blas {

inline double dot(const dvec& x, const dvec& y) { return thrust::inner_product(x.begin(), x.end(), y.begin(), 0.0); }
inline double norm2(const dvec& x) { return std::sqrt(dot(x, x)); }

/// max_i |x_i|
inline double norm_inf(const dvec& x) {
  return thrust::transform_reduce(x.begin(), x.end(), [] RBFIB_HD (double v) { return v < 0 ? -v : v; }, 0.0,
                                  [] RBFIB_HD (double a, double b) { return a > b ? a : b; });
}

/// Whether every entry is finite (false on NaN or Inf).
inline bool all_finite(const dvec& x) {
  return thrust::transform_reduce(x.begin(), x.end(), [] RBFIB_HD (double v) { return (v - v) == 0.0 ? 0 : 1; }, 0,
                                  [] RBFIB_HD (int a, int b) { return a + b; }) == 0;
}

/// y = a x + y
inline void axpy(double a, const dvec& x, dvec& y) {
  const double* px = ptr(x);
  double* py = ptr(y);
  for_each_index(index_t(x.size()), [=] RBFIB_HD (index_t i) { py[i] += a * px[i]; });
}

/// y = x + b y
inline void xpby(const dvec& x, double b, dvec& y) {
  const double* px = ptr(x);
  double* py = ptr(y);
  for_each_index(index_t(x.size()), [=] RBFIB_HD (index_t i) { py[i] = px[i] + b * py[i]; });
}

/// x = a x
inline void scale(double a, dvec& x) {
  double* px = ptr(x);
  for_each_index(index_t(x.size()), [=] RBFIB_HD (index_t i) { px[i] *= a; });
}

/// x = x + c (every entry)
inline void shift(double c, dvec& x) {
  double* px = ptr(x);
  for_each_index(index_t(x.size()), [=] RBFIB_HD (index_t i) { px[i] += c; });
}

/// z = x * y (entrywise)
inline void multiply(const dvec& x, const dvec& y, dvec& z) {
  z.resize(x.size());
  const double *px = ptr(x), *py = ptr(y);
  double* pz = ptr(z);
  for_each_index(index_t(x.size()), [=] RBFIB_HD (index_t i) { pz[i] = px[i] * py[i]; });
}

}  // namespace rbfib::blas
