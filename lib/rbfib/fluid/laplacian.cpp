#include "rbfib/fluid/laplacian.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib {

StaggeredLaplacian::StaggeredLaplacian(const Box& box, Correction correction) : box_(box), correction_(correction) {
  box_.validate();
  stencil_ = kernels::make_laplacian_stencil(shape_of(box_));
  for (int d = 0; d < box_.dims; ++d) stencil_.axis[d] = make_stencil(box_.axes[d], correction);
}

void StaggeredLaplacian::apply(const dvec& u, dvec& out, double alpha, double beta) const {
  require(index_t(u.size()) == size(), "laplacian.input.size", u.size(), "does not match the box");
  out.resize(u.size());
  const kernels::HelmholtzApply k{stencil_, ptr(u), ptr(out), alpha, beta};
#if defined(RBFIB_BACKEND_CUDA)
  for_each_index(size(), k);
#else
  for_each_index(size() / stencil_.shape.n[0], kernels::HelmholtzApplyRows{k});
#endif
}

void StaggeredLaplacian::add_boundary(const BoundaryData& gamma, dvec& out, double beta) const {
  for (int d = 0; d < box_.dims; ++d) {
    if (box_.axes[d].periodic()) continue;
    for (int side = 0; side < 2; ++side) {
      const dvec& g = gamma.face[d][side];
      require(index_t(g.size()) == face_size(box_, d), "boundary_data.face[" + std::to_string(d) + "][" + std::to_string(side) + "].size",
              g.size(), "does not match the face of the box");
      for_each_index(index_t(g.size()), kernels::BoundaryApply{stencil_, d, side, ptr(g), ptr(out), beta});
    }
  }
}

dvec StaggeredLaplacian::diagonal(double alpha, double beta) const {
  // The coefficient of u[p] in row p of the stencil, evaluated pointwise.
  dvec diag(size());
  const auto s = stencil_;
  double* out = ptr(diag);
  for_each_index(size(), [=] RBFIB_HD (index_t p) {
    int i[3];
    s.shape.split(p, i);
    double lap = 0.0;
    for (int d = 0; d < s.shape.dims; ++d) {
      const AxisStencil& a = s.axis[d];
      double c = -2.0;
      if (!a.periodic) {
        if (i[d] == 0) c += a.lo.ghost;
        if (i[d] == a.n - 1) c += a.hi.ghost;
      } else if (a.n == 1) {
        c = 0.0;
      }
      lap += kernels::identity_weight(s, i, d) * c * a.inv_h2;
    }
    out[p] = alpha * kernels::identity_weight(s, i, -1) + beta * lap;
  });
  return diag;
}

}  // namespace rbfib
