#include "quadratics.hpp"

#include "common/tables.hpp"
#include "rbfib/fluid/diffusion.hpp"

#include <algorithm>

namespace rbfib::appendix_a {

using BC = BoundaryCondition;
using study::row;

QuadraticCheck check_quadratic(const Box& box, Correction corr) {
  const Quadratic q;
  StaggeredLaplacian L(box, corr);
  const dvec u = sample(box, q);
  const BoundaryData gamma = boundary_data_of(box, q);
  dvec Lu, target;
  L.apply(u, Lu);
  L.add_boundary(gamma, Lu, 1.0);
  L.apply_identity(dvec(u.size(), q.laplacian(box.dims)), target);
  blas::axpy(-1.0, target, Lu);
  double hmin = 1e300;
  for (int d = 0; d < box.dims; ++d) hmin = std::min(hmin, box.axes[d].h());
  QuadraticCheck c;
  const double qmax = blas::norm_inf(u);
  c.operator_error = blas::norm_inf(Lu) / (qmax / (hmin * hmin));
  // Backward-Euler Helmholtz solve with the quadratic as solution, from a zero initial guess:
  // (I~ - k L) x = I~ (q - k Lap q) + k B gamma has x = q exactly when L q + B gamma = I~ Lap q.
  const double k = hmin;
  dvec b, Iu;
  L.apply_identity(dvec(u.size(), -k * q.laplacian(box.dims)), b);
  L.apply_identity(u, Iu);
  blas::axpy(1.0, Iu, b);
  L.add_boundary(gamma, b, k);
  dvec x(u.size(), 0.0);
  auto helmholtz = [&](const dvec& in, dvec& out) { L.apply(in, out, 1.0, -k); };
  c.cg_iterations = conjugate_gradient(helmholtz, b, x, SolverOptions{"helmholtz (quadratic)", 1e-14, 2000}).iterations;
  blas::axpy(-1.0, u, x);
  c.steady_error = blas::norm_inf(x) / qmax;
  return c;
}

study::Json quadratics_table() {
  const std::pair<const char*, BC> boundaries[] = {
      {"dirichlet", BC::dirichlet()}, {"neumann", BC::neumann()}, {"robin(1,-0.1)", BC::robin(1.0, -0.1)}};
  study::Json t =
      study::table({"dims", "g_x", "g_y", "bc_x", "bc_y", "corrected", "operator_error", "steady_error", "cg_iterations"});
  for (int dims : {2, 3})
    for (double gx : {0.5, 1.0, 0.25})
      for (double gy : {0.5, 1.0, 0.25})
        for (const auto& [nx, bx] : boundaries)
          for (const auto& [ny, by] : boundaries)
            for (Correction corr : {Correction::appendix_a, Correction::none}) {
              Box box;
              box.dims = dims;
              box.axes[0] = Axis{9, 1.0, gx, bx, bx, 0.0};
              box.axes[1] = Axis{7, 0.8, gy, by, by, -0.3};
              box.axes[2] = Axis{6, 0.6, 0.5, BC::neumann(), BC::neumann(), 0.1};
              QuadraticCheck c;
              try {
                c = check_quadratic(box, corr);
              } catch (const NumericalError&) {
                if (corr == Correction::appendix_a) throw;  // the corrected solve must always converge
                c = QuadraticCheck{check_quadratic(box, Correction::none).operator_error, -1.0, -1};
              }
              t["rows"].push(row({dims, gx, gy, nx, ny, corr == Correction::appendix_a ? 1 : 0, c.operator_error,
                                  c.steady_error, c.cg_iterations}));
            }
  return t;
}

}  // namespace rbfib::appendix_a
