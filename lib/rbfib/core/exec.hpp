#pragma once
// The one portability header: what differs between the CPU build (g++, Thrust's OpenMP device
// system) and the CUDA build (nvcc, Thrust's CUDA device system). Kernels are functions of one
// index marked RBFIB_HD; the launch lives in the caller (for_each_index).
#include <thrust/device_vector.h>
#include <thrust/host_vector.h>
#include <thrust/for_each.h>
#include <thrust/iterator/counting_iterator.h>

#include "rbfib/core/threads.hpp"

#include <cstddef>

#if defined(__CUDACC__)
#define RBFIB_HD __host__ __device__
#else
#define RBFIB_HD
#endif

#if defined(RBFIB_BACKEND_CUDA)
#define RBFIB_BACKEND_NAME "CUDA (Thrust/CUDA)"
#else
#define RBFIB_BACKEND_NAME "CPU (Thrust/OpenMP)"
#endif

namespace rbfib {

using index_t = std::ptrdiff_t;

/// Storage on the execution device (host memory in the CPU build).
template <class T>
using device_vector = thrust::device_vector<T>;
template <class T>
using host_vector = thrust::host_vector<T>;

using dvec = device_vector<double>;

/// Raw pointer to device storage, for capture in kernels.
template <class T>
T* ptr(device_vector<T>& v) { return thrust::raw_pointer_cast(v.data()); }
template <class T>
const T* ptr(const device_vector<T>& v) { return thrust::raw_pointer_cast(v.data()); }

/// Calls kernel(i) for i in [0, n) on the execution device, in parallel. One index may stand for
/// much work (a grid row, a slab of a spreading colour), so n alone says nothing about the cost.
/// On the CPU the OpenMP team is first fitted to the cores other programs leave free (threads.hpp).
template <class Kernel>
void for_each_index(index_t n, Kernel kernel) {
#if !defined(RBFIB_BACKEND_CUDA)
  share_cores();
#endif
  thrust::for_each(thrust::counting_iterator<index_t>(0), thrust::counting_iterator<index_t>(n), kernel);
}

/// Waits until all work launched on the execution device has finished (for timing phases; a
/// no-op in the CPU build, whose launches return when done).
inline void synchronize() {
#if defined(__CUDACC__)
  cudaDeviceSynchronize();
#endif
}

/// Human-readable name of the backend this library was built for.
inline const char* backend_name() { return RBFIB_BACKEND_NAME; }

}  // namespace rbfib
