#include "rbfib/fluid/mac_operators.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/fluid/mac_kernels.hpp"

#include <thrust/reduce.h>

namespace rbfib {

VelocityBoundaryData sample_velocity_boundary(
    const MacGrid& grid, const std::function<double(int, int, int, double, double, double)>& value) {
  VelocityBoundaryData data;
  for (int a = 0; a < grid.dims; ++a)
    data[a] = sample_boundary(grid.component(a), [&](int d, int side, double x, double y, double z) {
      return value(a, d, side, x, y, z);
    });
  return data;
}

VelocityBoundaryData zero_velocity_boundary(const MacGrid& grid) {
  return sample_velocity_boundary(grid, [](int, int, int, double, double, double) { return 0.0; });
}

MacOperators::MacOperators(const MacGrid& grid) : grid_(grid) {
  grid_.validate();
  scalar_ = grid_.scalar();
  scalar_shape_ = shape_of(scalar_);
  for (int a = 0; a < grid_.dims; ++a) {
    comp_[a] = grid_.component(a);
    shape_[a] = shape_of(comp_[a]);
    pad_[a] = kernels::padded_of(shape_[a]);
    for (int d = 0; d < grid_.dims; ++d) {
      if (grid_.periodic(d)) continue;
      const AxisStencil st = make_stencil(comp_[a].axes[d], Correction::none);
      ends_[a][d][0] = st.lo;
      ends_[a][d][1] = st.hi;
    }
  }
}

void MacOperators::check(const VectorField& u, const char* what) const {
  for (int a = 0; a < grid_.dims; ++a)
    require(index_t(u[a].size()) == comp_[a].size(), std::string(what) + "[" + std::to_string(a) + "].size", u[a].size(),
            "does not match velocity component " + std::to_string(a) + " of the MAC grid (" +
                std::to_string(comp_[a].size()) + " unknowns)");
}

void MacOperators::divergence(const VectorField& u, const VelocityBoundaryData* gamma, dvec& out) const {
  check(u, "divergence.u");
  kernels::Divergence k;
  k.s = scalar_shape_;
  for (int a = 0; a < 3; ++a) {
    k.periodic[a] = a < grid_.dims ? grid_.periodic(a) : true;
    k.u[a] = a < grid_.dims ? ptr(u[a]) : nullptr;
    k.inv_h[a] = a < grid_.dims ? 1.0 / grid_.h(a) : 0.0;
    k.comp[a] = a < grid_.dims ? shape_[a] : BoxShape{};
    k.normal_lo[a] = k.normal_hi[a] = nullptr;
    if (gamma && a < grid_.dims && !grid_.periodic(a)) {
      const dvec& lo = (*gamma)[a].face[a][0];
      const dvec& hi = (*gamma)[a].face[a][1];
      require(index_t(lo.size()) == face_size(scalar_, a) && index_t(hi.size()) == face_size(scalar_, a),
              "divergence.gamma[" + std::to_string(a) + "].size", lo.size(), "does not match the wall face");
      k.normal_lo[a] = ptr(lo);
      k.normal_hi[a] = ptr(hi);
    }
  }
  out.resize(scalar_.size());
  k.out = ptr(out);
  kernels::for_each_point(scalar_shape_, k);
}

void MacOperators::gradient(const dvec& q, VectorField& out) const {
  require(index_t(q.size()) == scalar_.size(), "gradient.q.size", q.size(), "does not match the cell-centred box");
  for (int a = 0; a < grid_.dims; ++a) {
    out[a].resize(comp_[a].size());
    kernels::for_each_point(shape_[a], kernels::Gradient{scalar_shape_, a, 1.0 / grid_.h(a), ptr(q), ptr(out[a])});
  }
}

void MacOperators::advection(const VectorField& u, const VelocityBoundaryData& gamma, VectorField& out) const {
  check(u, "advection.u");
  const int dims = grid_.dims;
  for (int a = 0; a < dims; ++a) {
    dvec& pa = padded_[a];
    pa.resize(pad_[a].size);
    kernels::for_each_point(shape_[a], kernels::PadInterior{pad_[a], ptr(u[a]), ptr(pa)});
    // walls first (over interior face points), then periodic axes over the whole padded extent.
    for (int d = 0; d < dims; ++d) {
      if (grid_.periodic(d)) continue;
      for (int side = 0; side < 2; ++side) {
        const dvec& g = gamma[a].face[d][side];
        const index_t nf = face_size(comp_[a], d);
        require(index_t(g.size()) == nf, "advection.gamma[" + std::to_string(a) + "].face[" + std::to_string(d) + "][" +
                                             std::to_string(side) + "].size",
                g.size(), "does not match the wall face");
        for_each_index(nf, kernels::PadWall{pad_[a], d, side, ends_[a][d][side], ptr(g), ptr(pa)});
      }
    }
    for (int d = 0; d < dims; ++d) {
      if (!grid_.periodic(d)) continue;
      int o, q;
      kernels::other_axes(d, o, q);
      for_each_index(index_t(pad_[a].extent(o)) * pad_[a].extent(q), kernels::PadPeriodic{pad_[a], d, ptr(pa)});
    }
  }
  kernels::Advection k;
  for (int b = 0; b < 3; ++b) {
    k.pad[b] = b < dims ? pad_[b] : kernels::PaddedShape{};
    k.u[b] = b < dims ? ptr(padded_[b]) : nullptr;
    k.inv_h[b] = b < dims ? 1.0 / grid_.h(b) : 0.0;
  }
  for (int a = 0; a < dims; ++a) {
    k.s = shape_[a];
    k.a = a;
    out[a].resize(comp_[a].size());
    k.out = ptr(out[a]);
    kernels::for_each_point(shape_[a], k);
  }
}

double MacOperators::boundary_outflow(const VelocityBoundaryData& gamma) const {
  double flux = 0.0;
  for (int d = 0; d < grid_.dims; ++d) {
    if (grid_.periodic(d)) continue;
    double area = 1.0;
    for (int e = 0; e < grid_.dims; ++e)
      if (e != d) area *= grid_.h(e);
    const dvec& lo = gamma[d].face[d][0];
    const dvec& hi = gamma[d].face[d][1];
    flux += area * (thrust::reduce(hi.begin(), hi.end(), 0.0) - thrust::reduce(lo.begin(), lo.end(), 0.0));
  }
  return flux;
}

double MacOperators::make_compatible(VelocityBoundaryData& gamma) const {
  double wall_area = 0.0;
  for (int d = 0; d < grid_.dims; ++d) {
    if (grid_.periodic(d)) continue;
    double area = 1.0;
    for (int e = 0; e < grid_.dims; ++e)
      if (e != d) area *= grid_.length[e];
    wall_area += 2.0 * area;
  }
  if (wall_area == 0.0) return 0.0;
  const double shift = boundary_outflow(gamma) / wall_area;  // outward normal velocity to remove
  for (int d = 0; d < grid_.dims; ++d) {
    if (grid_.periodic(d)) continue;
    dvec& lo = gamma[d].face[d][0];
    dvec& hi = gamma[d].face[d][1];
    double* plo = ptr(lo);
    double* phi = ptr(hi);
    for_each_index(index_t(lo.size()), [=] RBFIB_HD (index_t f) {
      plo[f] += shift;  // outward normal is -e_d on the lower wall
      phi[f] -= shift;
    });
  }
  return shift;
}

}  // namespace rbfib
