#include "rbfib/surface/geometry.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib::surface {

namespace {
/// Uploads `cols` columns of data-site values and applies the operators: the jets on the device.
void device_jets(const SurfaceOperators& ops, const std::vector<double>& data, index_t cols, linalg::DeviceMatrix& V,
                 linalg::DeviceMatrix& D) {
  require(static_cast<index_t>(data.size()) == cols * ops.n_data(), "data-site values size", data.size(),
          "must be " + to_text(cols) + " x data sites (" + to_text(ops.n_data()) + ")");
  const index_t ns = ops.n_sample();
  const linalg::DeviceMatrix F = linalg::DeviceMatrix::from_host(ops.n_data(), cols, data.data());
  V.resize(ns, cols);
  D.resize(derivative_count * ns, cols);
  OperatorWorkspace work;
  apply_operators(ops, F.view(), V.view(), D.view(), work);
}
}  // namespace

std::vector<Jet> jets_on_host(const linalg::DeviceMatrix& value, const linalg::DeviceMatrix& derivatives) {
  const std::vector<double> v = value.to_host(), d = derivatives.to_host();
  const index_t n = value.rows();
  const JetView view{v.data(), n, d.data(), derivative_count * n, n, 1};
  std::vector<Jet> jets(static_cast<std::size_t>(n));
  for (index_t i = 0; i < n; ++i) jets[i] = view.jet(0, i);
  return jets;
}

std::vector<Jet> jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& X_data) {
  linalg::DeviceMatrix V, D;
  device_jets(ops, X_data, 3, V, D);
  return jets_on_host(V, D);
}

std::vector<ScalarJet> scalar_jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& u_data) {
  linalg::DeviceMatrix V, D;
  device_jets(ops, u_data, 1, V, D);
  const std::vector<double> v = V.to_host(), d = D.to_host();
  const index_t ns = ops.n_sample();
  const JetView view{v.data(), ns, d.data(), derivative_count * ns, ns, 1};
  std::vector<ScalarJet> jets(static_cast<std::size_t>(ns));
  for (index_t i = 0; i < ns; ++i) jets[i] = view.scalar(0, i);
  return jets;
}

std::vector<Jet> unit_sphere_jets(const SphereSites& sites) {
  std::vector<Jet> jets(static_cast<std::size_t>(sites.size()));
  for (index_t i = 0; i < sites.size(); ++i) {
    const double cl = std::cos(sites.lambda[i]), sl = std::sin(sites.lambda[i]);
    const double ct = std::cos(sites.theta[i]), st = std::sin(sites.theta[i]);
    Jet& j = jets[i];
    const double v[6][3] = {{cl * ct, sl * ct, st},  {-sl * ct, cl * ct, 0}, {-cl * st, -sl * st, ct},
                            {-cl * ct, -sl * ct, 0}, {sl * st, -cl * st, 0}, {-cl * ct, -sl * ct, -st}};
    for (int d = 0; d < 3; ++d) {
      j.x[d] = v[0][d];
      j.xl[d] = v[1][d];
      j.xt[d] = v[2][d];
      j.xll[d] = v[3][d];
      j.xlt[d] = v[4][d];
      j.xtt[d] = v[5][d];
    }
  }
  return jets;
}

std::vector<PointGeometry> surface_geometry(const std::vector<Jet>& jets, const std::string& cell) {
  std::vector<PointGeometry> g(jets.size());
  for (std::size_t i = 0; i < jets.size(); ++i) {
    g[i] = point_geometry(jets[i]);
    if (!(g[i].det_g > 0) || !std::isfinite(g[i].H))
      throw NumericalError(Cause::degenerate_site, "cell '" + cell + "': surface metric degenerate at site " + to_text(i) +
                           " (det G = " + to_text(g[i].det_g) + ", must be > 0)");
  }
  return g;
}

}  // namespace rbfib::surface
