#include "rbfib/grid/boundary_values.hpp"

namespace rbfib {

BoundaryData robin_boundary_data(const Box& box, const std::function<double(double, double, double)>& u,
                                 const std::function<double(int, double, double, double)>& grad) {
  return sample_boundary(box, [&](int d, int side, double x, double y, double z) {
    const BoundaryCondition& bc = side ? box.axes[d].upper : box.axes[d].lower;
    return bc.alpha * u(x, y, z) + bc.beta * (side ? -1.0 : 1.0) * grad(d, x, y, z);
  });
}

}  // namespace rbfib
