#pragma once
// The IB kernels delta_1 (seed eq. 4.3ff, Fig. 5.1) and the run-time choice among them.
// delta_h(x) = prod_a h^{-1} phi(x_a / h) (eq. 4.4). A kernel is a small type with
//   static constexpr int support;          // s of eq. 4.3
//   static constexpr const char* name;     // the name chosen at run time
//   RBFIB_HD static double phi(double r);  // delta_1(r), r in units of h
// and optionally, for speed,
//   RBFIB_HD static void weights(double delta, double w[support]);
// giving w[t] = phi(t - floor(s/2) + delta) for delta in (0, 1] (s even) or (-1/2, 1/2] (s odd),
// the s weights of one axis (grid.hpp); without it they are s calls of phi.
// Adding a kernel: one header like kernel_bspline3.hpp, and its name in `Kernels` below.
#include "rbfib/core/error.hpp"
#include "rbfib/ib/kernel_bspline3.hpp"
#include "rbfib/ib/kernel_cosine4.hpp"
#include "rbfib/ib/kernel_peskin4.hpp"
#include "rbfib/ib/kernel_roma3.hpp"

#include <string>
#include <vector>

namespace rbfib::ib {

template <class... K>
struct KernelList {};

using Kernels = KernelList<Roma3, BSpline3, Cosine4, Peskin4>;

/// The s weights of one axis for offset delta (see above).
template <class K>
RBFIB_HD inline void axis_weights(double delta, double* w) {
  if constexpr (requires(double* v) { K::weights(0.0, v); }) {
    K::weights(delta, w);
  } else {
    for (int t = 0; t < K::support; ++t) w[t] = K::phi(double(t - K::support / 2) + delta);
  }
}

/// The kernels by name: the choice a scene (ib.kernel) or a study makes, in the order of `Kernels`.
enum class Kernel { roma3, bspline3, cosine4, peskin4 };
/// The kernel's name ("roma3", ...), as scenes write it.
const char* to_string(Kernel k);
/// The kernel of a name; throws InputError naming `field` and listing the names otherwise.
Kernel kernel_named(const std::string& name, const std::string& field = "kernel");
std::vector<Kernel> all_kernels();
/// Names of all kernels, in the order of `Kernels`.
std::vector<std::string> kernel_names();

/// Support width s of the kernel.
int kernel_support(Kernel k);

/// Calls f(K{}) for the kernel type K whose name is `name`; InputError("kernel", name) if none.
template <class F, class... K>
void with_kernel(const std::string& name, F&& f, KernelList<K...>) {
  bool found = false;
  ((!found && name == K::name ? (f(K{}), found = true) : false), ...);
  if (!found) {
    std::string all;
    ((all += std::string(all.empty() ? "" : ", ") + K::name), ...);
    throw InputError("kernel", name, "is not a known IB kernel (one of: " + all + ")");
  }
}

/// Calls f(K{}) with the kernel type K of k.
template <class F>
void with_kernel(Kernel k, F&& f) {
  with_kernel(std::string(to_string(k)), static_cast<F&&>(f), Kernels{});
}

}  // namespace rbfib::ib
