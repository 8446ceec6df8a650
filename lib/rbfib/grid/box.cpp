#include "rbfib/grid/box.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib {

void Box::validate() const {
  require(dims >= 1 && dims <= 3, "box.dims", dims, "must be 1, 2 or 3");
  static const char* names[3] = {"box.x", "box.y", "box.z"};
  for (int d = 0; d < dims; ++d) axes[d].validate(names[d]);
}

BoxShape shape_of(const Box& box) {
  BoxShape s;
  s.dims = box.dims;
  for (int d = 0; d < 3; ++d) s.n[d] = box.n(d);
  s.stride[0] = 1;
  s.stride[1] = s.n[0];
  s.stride[2] = index_t(s.n[0]) * s.n[1];
  return s;
}

index_t face_size(const Box& box, int d) { return box.size() / box.n(d); }

dvec sample(const Box& box, const std::function<double(double, double, double)>& f) {
  host_vector<double> v(box.size());
  index_t p = 0;
  for (int k = 0; k < box.n(2); ++k)
    for (int j = 0; j < box.n(1); ++j)
      for (int i = 0; i < box.n(0); ++i) v[p++] = f(box.x(0, i), box.x(1, j), box.x(2, k));
  return dvec(v);
}

BoundaryData sample_boundary(const Box& box,
                             const std::function<double(int, int, double, double, double)>& gamma) {
  BoundaryData data;
  for (int d = 0; d < box.dims; ++d) {
    const Axis& ax = box.axes[d];
    if (ax.periodic()) continue;
    const int a = (d + 1) % 3 < (d + 2) % 3 ? (d + 1) % 3 : (d + 2) % 3;  // lower other axis
    const int b = 3 - d - a;                                              // higher other axis
    for (int side = 0; side < 2; ++side) {
      host_vector<double> v(face_size(box, d));
      const double xb = side ? ax.origin + ax.length : ax.origin;
      index_t f = 0;
      for (int jb = 0; jb < box.n(b); ++jb)
        for (int ja = 0; ja < box.n(a); ++ja) {
          double x[3];
          x[d] = xb;
          x[a] = box.x(a, ja);
          x[b] = box.x(b, jb);
          v[f++] = gamma(d, side, x[0], x[1], x[2]);
        }
      data.face[d][side] = dvec(v);
    }
  }
  return data;
}

}  // namespace rbfib
