#include "rbfib/surface/geometry.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib::surface {

std::vector<Jet> jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& X_data) {
  std::vector<double> out[6];
  apply_operators(ops, X_data, out);
  std::vector<Jet> jets(static_cast<std::size_t>(ops.n_sample()));
  for (index_t i = 0; i < ops.n_sample(); ++i)
    for (int d = 0; d < 3; ++d) {
      Jet& j = jets[i];
      j.x[d] = out[0][3 * i + d];
      j.xl[d] = out[1][3 * i + d];
      j.xt[d] = out[2][3 * i + d];
      j.xll[d] = out[3][3 * i + d];
      j.xlt[d] = out[4][3 * i + d];
      j.xtt[d] = out[5][3 * i + d];
    }
  return jets;
}

std::vector<ScalarJet> scalar_jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& u_data) {
  const DenseMatrix* M[6] = {&ops.id, &ops.d_l, &ops.d_t, &ops.d_ll, &ops.d_lt, &ops.d_tt};
  std::vector<double> out[6], c;
  const std::vector<double>* in = &u_data;
  if (ops.factored()) {
    c.resize(u_data.size());
    solve_coefficients(ops, u_data.data(), 1, c.data());
    in = &c;
  }
  for (int q = 0; q < 6; ++q) apply_to_scalars(*M[q], *in, out[q]);
  std::vector<ScalarJet> jets(static_cast<std::size_t>(ops.n_sample()));
  for (index_t i = 0; i < ops.n_sample(); ++i)
    jets[i] = ScalarJet{out[0][i], out[1][i], out[2][i], out[3][i], out[4][i], out[5][i]};
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
      throw NumericalError("cell '" + cell + "': surface metric degenerate at site " + to_text(i) +
                           " (det G = " + to_text(g[i].det_g) + ", must be > 0)");
  }
  return g;
}

}  // namespace rbfib::surface
