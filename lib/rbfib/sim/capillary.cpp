#include "rbfib/sim/capillary.hpp"

#include "rbfib/core/error.hpp"

#include <vector>

namespace rbfib::sim {

TetheredPoints tethered_capillary(const std::string& name, const surface::CylinderPoints& nodes, double k_teth) {
  require(k_teth >= 0, "k_teth (dyn/cm)", k_teth, "must be >= 0");
  const dvec Z(nodes.X.begin(), nodes.X.end());
  TetheredPoints p;
  p.name = name;
  p.X = p.anchors = Z;
  p.k = k_teth;
  p.frame = true;
  return p;
}

VectorField capillary_driving_force(const MacOperators& ops, double R, double f_in, double x0, double x1) {
  const Box& b = ops.component_box(0);
  std::vector<double> f(static_cast<std::size_t>(b.size()));
  std::vector<char> in(f.size());
  index_t n_in = 0;
  for (int kz = 0; kz < b.n(2); ++kz)
    for (int jy = 0; jy < b.n(1); ++jy)
      for (int ix = 0; ix < b.n(0); ++ix) {
        const double x = b.x(0, ix), y = b.x(1, jy), z = b.x(2, kz);
        const bool inside = y * y + z * z < R * R && x >= x0 && x <= x1;
        const index_t p = ix + index_t(b.n(0)) * (jy + index_t(b.n(1)) * kz);
        in[p] = inside;
        n_in += inside;
      }
  require(n_in > 0 && n_in < index_t(f.size()), "capillary x-faces inside", n_in, "must be some but not all");
  const double f_out = -f_in * double(n_in) / double(index_t(f.size()) - n_in);
  for (std::size_t p = 0; p < f.size(); ++p) f[p] = in[p] ? f_in : f_out;
  return {dvec(f.begin(), f.end()), dvec(ops.component_box(1).size(), 0.0), dvec(ops.component_box(2).size(), 0.0)};
}

}  // namespace rbfib::sim
