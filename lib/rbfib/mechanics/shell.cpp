#include "rbfib/mechanics/shell.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::mechanics {

namespace {
void check_status(const std::string& cell, std::size_t i, const ForceAtSite& r) {
  const char* why = nullptr;
  Cause cause = Cause::solver;
  switch (r.status) {
    case force_degenerate_metric: why = "degenerate surface metric (det G <= 0 or det G0 <= 0)", cause = Cause::degenerate_site; break;
    case force_bad_energy: why = "energy density undefined (det C <= 0)", cause = Cause::inverted_cell; break;
    default: break;
  }
  if (why) throw NumericalError(cause, "cell '" + cell + "': " + why + " at sample site " + to_text(i));
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(r.F[d]))
      throw NumericalError(Cause::non_finite, "cell '" + cell + "': non-finite force density at sample site " + to_text(i) +
                           " (I1 = " + to_text(r.I1) + ", I2 = " + to_text(r.I2) + ")");
}
void require_same(const std::string& cell, std::size_t a, std::size_t b, const char* what) {
  if (a != b)
    throw InputError(std::string("cell '") + cell + "' " + what, to_text(a), "must equal " + to_text(b));
}
}  // namespace

std::vector<double> elastic_force_density(const std::string& cell, const std::vector<Jet>& X,
                                          const std::vector<Jet>& Z, const EnergyDensity& energy) {
  require_same(cell, X.size(), Z.size(), "reference jets");
  const std::size_t n = X.size();
  std::vector<double> F(3 * n);
  // Host loop over sites (the per-cell reference path; cells/ launches the same kernel on the device).
  for (std::size_t i = 0; i < n; ++i) {
    const ForceAtSite r = elastic_force_density(X[i], Z[i], energy);
    check_status(cell, i, r);
    for (int d = 0; d < 3; ++d) F[d * n + i] = r.F[d];
  }
  return F;
}

double elastic_energy(const std::string& cell, const std::vector<Jet>& X, const std::vector<Jet>& Z,
                      const EnergyDensity& energy, const std::vector<double>& dA0) {
  require_same(cell, X.size(), Z.size(), "reference jets");
  require_same(cell, dA0.size(), X.size(), "weights");
  double E = 0;
  for (std::size_t i = 0; i < X.size(); ++i) {
    const ForceAtSite r = elastic_force_density(X[i], Z[i], energy);
    check_status(cell, i, r);
    E += r.W * dA0[i];
  }
  return E;
}

std::vector<double> forces_from_density(const std::vector<double>& density, const std::vector<double>& dA0) {
  require(density.size() == 3 * dA0.size(), "force density size", density.size(),
          "must be 3 x number of weights (" + to_text(dA0.size()) + ")");
  const std::size_t n = dA0.size();
  std::vector<double> F(density.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < 3; ++d) F[d * n + i] = density[d * n + i] * dA0[i];
  return F;
}

namespace {
/// H' at the sample sites as scalar jets (constant model.H0, or model.H0_data reconstructed).
std::vector<surface::ScalarJet> spontaneous_curvature(const std::string& cell, const surface::SurfaceOperators& to_sample,
                                                      const BendingModel& model) {
  if (model.H0_data.empty())
    return std::vector<surface::ScalarJet>(to_sample.n_sample(), surface::ScalarJet{model.H0, 0, 0, 0, 0, 0});
  require(static_cast<index_t>(model.H0_data.size()) == to_sample.n_data(),
          "cell '" + cell + "': spontaneous curvature per data site, H0_data.size()", model.H0_data.size(),
          "must equal the number of data sites " + to_text(to_sample.n_data()));
  for (std::size_t i = 0; i < model.H0_data.size(); ++i)
    require(std::isfinite(model.H0_data[i]), "cell '" + cell + "': H0_data[" + to_text(i) + "] (1/cm)",
            model.H0_data[i], "must be finite");
  return surface::scalar_jets_from_operators(to_sample, model.H0_data);
}
}  // namespace

std::vector<double> bending_force_density(const std::string& cell, const surface::SurfaceOperators& at_data,
                                          const surface::SurfaceOperators& to_sample,
                                          const std::vector<double>& X_data, const std::vector<Jet>& Z,
                                          const BendingModel& model) {
  require(model.kappa >= 0, "bending modulus kappa (erg)", model.kappa, "must be >= 0");
  require_same(cell, Z.size(), static_cast<std::size_t>(to_sample.n_sample()), "reference jets");
  const std::vector<surface::ScalarJet> H0s = spontaneous_curvature(cell, to_sample, model);
  const std::vector<Jet> Xd = surface::jets_from_operators(at_data, X_data);
  const std::vector<surface::PointGeometry> gd = surface::surface_geometry(Xd, cell);
  // H - H' at the data sites; a constant H' drops out of the Laplacian, so it is left out here.
  std::vector<double> dH(gd.size());
  for (std::size_t i = 0; i < gd.size(); ++i) dH[i] = gd[i].H - (model.H0_data.empty() ? 0.0 : model.H0_data[i]);
  const std::vector<Jet> Xs = surface::jets_from_operators(to_sample, X_data);
  const std::vector<surface::PointGeometry> gs = surface::surface_geometry(Xs, cell);
  const std::vector<surface::ScalarJet> dHs = surface::scalar_jets_from_operators(to_sample, dH);
  const std::size_t n = Xs.size();
  std::vector<double> F(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const surface::PointGeometry g0 = surface::point_geometry(Z[i]);
    if (!(g0.det_g > 0))
      throw NumericalError(Cause::degenerate_site, "cell '" + cell + "': reference metric degenerate at sample site " + to_text(i));
    const double lap = surface::laplace_beltrami(Xs[i], dHs[i]);  // lap_s (H - H')
    double f[3];
    bending_force_density(gs[i], g0.det_g, lap, model.kappa, H0s[i].u, f);
    if (!model.H0_data.empty()) {  // tangential term of a material field H'
      double grad[3];
      surface::surface_gradient(Xs[i], H0s[i], grad);
      const double c = -4 * model.kappa * std::sqrt(gs[i].det_g / g0.det_g) * (gs[i].H - H0s[i].u);
      for (int d = 0; d < 3; ++d) f[d] += c * grad[d];
    }
    for (int d = 0; d < 3; ++d) F[d * n + i] = f[d];
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(f[d]))
        throw NumericalError(Cause::non_finite, "cell '" + cell + "': non-finite bending force density at sample site " + to_text(i));
  }
  return F;
}

double bending_energy(const std::string& cell, const std::vector<Jet>& X, const std::vector<Jet>& Z,
                      const BendingModel& model, const std::vector<double>& dA0,
                      const surface::SurfaceOperators* to_sample) {
  require_same(cell, X.size(), Z.size(), "reference jets");
  require_same(cell, dA0.size(), X.size(), "weights");
  if (!model.H0_data.empty() && !to_sample)
    throw InputError("cell '" + cell + "': bending_energy to_sample", "nullptr",
                     "is needed to reconstruct the per-site spontaneous curvature H0_data");
  const std::vector<surface::ScalarJet> H0s =
      model.H0_data.empty() ? std::vector<surface::ScalarJet>(X.size(), surface::ScalarJet{model.H0, 0, 0, 0, 0, 0})
                            : spontaneous_curvature(cell, *to_sample, model);
  require_same(cell, H0s.size(), X.size(), "spontaneous curvature sites");
  const std::vector<surface::PointGeometry> g = surface::surface_geometry(X, cell);
  double E = 0;
  for (std::size_t i = 0; i < X.size(); ++i) {
    const surface::PointGeometry g0 = surface::point_geometry(Z[i]);
    const double dh = g[i].H - H0s[i].u;
    E += 2 * model.kappa * dh * dh * std::sqrt(g[i].det_g / g0.det_g) * dA0[i];
  }
  return E;
}

std::vector<double> dissipative_force_density(const std::string& cell, const std::vector<Jet>& X,
                                              const std::vector<Jet>& U, const std::vector<Jet>& Z, double nu) {
  require(nu >= 0, "membrane viscosity nu (dyn s/cm)", nu, "must be >= 0");
  require_same(cell, X.size(), Z.size(), "reference jets");
  require_same(cell, U.size(), X.size(), "velocity jets");
  const std::size_t n = X.size();
  std::vector<double> F(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const ForceAtSite r = dissipative_force_density(X[i], U[i], Z[i], nu);
    check_status(cell, i, r);
    for (int d = 0; d < 3; ++d) F[d * n + i] = r.F[d];
  }
  return F;
}

double dissipation(const std::string& cell, const std::vector<Jet>& X, const std::vector<Jet>& U,
                   const std::vector<Jet>& Z, double nu, const std::vector<double>& dA0) {
  require_same(cell, dA0.size(), X.size(), "weights");
  require_same(cell, U.size(), X.size(), "velocity jets");
  require_same(cell, Z.size(), X.size(), "reference jets");
  double P = 0;
  for (std::size_t i = 0; i < X.size(); ++i) {
    const ForceAtSite r = dissipative_force_density(X[i], U[i], Z[i], nu);
    check_status(cell, i, r);
    P += r.W * dA0[i];
  }
  return P;
}

std::vector<double> tether_force_density(const std::vector<double>& X, const std::vector<double>& X_tether,
                                         const std::vector<double>& U, const std::vector<double>& U_tether,
                                         double k, double eta) {
  require(k >= 0, "spring constant k (dyn/cm)", k, "must be >= 0");
  require(eta >= 0, "damping constant eta (dyn s/cm)", eta, "must be >= 0");
  require(X_tether.size() == X.size(), "tether points size", X_tether.size(), "must equal " + to_text(X.size()));
  const bool damped = !U.empty() || !U_tether.empty();
  if (damped) {
    require(U.size() == X.size(), "velocities size", U.size(), "must equal " + to_text(X.size()));
    require(U_tether.size() == X.size(), "tether velocities size", U_tether.size(), "must equal " + to_text(X.size()));
  }
  std::vector<double> F(X.size());
  for (std::size_t i = 0; i < X.size(); ++i)
    F[i] = -k * (X[i] - X_tether[i]) - (damped ? eta * (U[i] - U_tether[i]) : 0.0);
  return F;
}

}  // namespace rbfib::mechanics
