#include "rbfib/sim/membrane_stability.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/geometry_kernels.hpp"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace rbfib::sim {

namespace {
/// The peaks of a kernel's sheet mobility per mode family (docs/derivations/membrane_stability,
/// section 5): C_L and C_T for the tangential families, C_k at x_k = k h for bending.
struct KernelConstants {
  double C_L, C_T, C_k, x_k;
};
KernelConstants constants(ib::Kernel k) {
  switch (k) {
    case ib::Kernel::bspline3: return {0.0693, 0.2265, 0.4425, 2.08};
    case ib::Kernel::roma3: return {0.0733, 0.2405, 0.5177, 2.15};
    case ib::Kernel::peskin4: return {0.0529, 0.1729, 0.1897, 1.54};
    case ib::Kernel::cosine4: return {0.0529, 0.1730, 0.1899, 1.54};
  }
  return {0.0693, 0.2265, 0.4425, 2.08};
}

/// The kernel's Fourier transform at xi (unit spacing): int phi(r) cos(xi r) dr, by the midpoint rule.
double transfer(ib::Kernel kernel, double xi) {
  double s = 0;
  ib::with_kernel(kernel, [&](auto k) {
    using K = decltype(k);
    const int n = 800;
    const double a = 0.5 * K::support + 1, dr = 2 * a / n;
    for (int i = 0; i < n; ++i) {
      const double r = -a + (i + 0.5) * dr;
      s += K::phi(r) * std::cos(xi * r) * dr;
    }
  });
  return s;
}

struct Family {
  const char* name;
  double lambda, d;  // relaxation rate (1/s), dissipation's gain
};

std::vector<Family> families(const MembraneStiffness& m, double h, double mu, ib::Kernel kernel) {
  const KernelConstants c = constants(kernel);
  const double sL = c.C_L / (mu * h), sT = c.C_T / (mu * h);
  const double kmax = m.spacing > 0 ? std::sqrt(4 * M_PI) / m.spacing : INFINITY;
  const double Y = m.mu_s + m.K > 0 ? 4 * m.mu_s * m.K / (m.mu_s + m.K) : 0.0;
  double normal = 0;
  if (m.kappa > 0)
    normal = kmax * h >= c.x_k ? c.C_k * m.kappa / (mu * h * h * h)
                               : 0.225 * m.kappa * std::pow(kmax, 3) * std::pow(transfer(kernel, kmax * h), 2) / mu;
  if (m.curvature > 0 && m.curvature <= kmax)
    normal += 0.225 * std::pow(transfer(kernel, m.curvature * h), 2) * (Y * m.curvature + m.kappa * std::pow(m.curvature, 3)) / mu;
  return {{"tangential along k", (m.K + m.mu_s) * sL, m.nu * sL},
          {"tangential across k", m.mu_s * sT, 0.5 * m.nu * sT},
          {"normal (bending and curvature)", normal, 0.0}};
}

/// The largest dt with (d + 1.5 lambda dt) / (1 + 1.5 tau / dt) <= gain (bisection in log dt).
double family_limit(const Family& f, double tau, double gain) {
  auto g = [&](double dt) { return (f.d + 1.5 * f.lambda * dt) / (1 + 1.5 * tau / dt); };
  if (!(f.lambda > 0)) return INFINITY;
  double lo = 1e-15, hi = 1.0;
  if (g(hi) <= gain) return INFINITY;
  if (g(lo) > gain) return 0.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = std::sqrt(lo * hi);
    (g(mid) <= gain ? lo : hi) = mid;
  }
  return lo;
}
}  // namespace

MembraneStiffness membrane_stiffness(const cells::CellType& type) {
  const cells::ForceModel& model = type.model();
  MembraneStiffness m;
  for (const mechanics::EnergyDensity& e : model.elastic) {
    switch (e.kind) {
      case mechanics::EnergyKind::skalak: m.mu_s += e.a, m.K += e.a + 2 * e.b; break;
      case mechanics::EnergyKind::neo_hookean_dissertation: m.mu_s += e.a, m.K += e.b; break;
      default:
        throw InputError("cell type '" + type.name() + "': energy", e.name(),
                         "has no membrane stability bound (sim/membrane_stability.hpp): Skalak or the dissertation's neo-Hookean");
    }
  }
  m.kappa = model.kappa;
  m.nu = model.nu;
  m.spacing = std::sqrt(type.reference_area() / double(type.n_data()));
  for (const surface::Jet& j : type.reference_jets_host()) {
    const surface::PointGeometry g = surface::point_geometry(j);
    const double K = 0.5 * g.R;
    m.curvature = std::max(m.curvature, std::abs(g.H) + std::sqrt(std::max(g.H * g.H - K, 0.0)));
  }
  return m;
}

namespace {
/// The limit over the mode families and the family that sets it.
std::pair<double, std::string> limit(const MembraneStiffness& m, double h, double rho, double mu, ib::Kernel kernel, double gain) {
  require(h > 0 && rho > 0 && mu > 0, "membrane stability: h, rho, mu", to_text(h) + ", " + to_text(rho) + ", " + to_text(mu),
          "must be positive");
  require(gain > 0, "membrane stability: gain", gain, "must be positive");
  std::pair<double, std::string> best{INFINITY, "none"};
  for (const Family& f : families(m, h, mu, kernel)) {
    const double l = family_limit(f, rho * h * h / mu, gain);
    if (l < best.first) best = {l, f.name};
  }
  return best;
}
}  // namespace

double membrane_dt_limit(const MembraneStiffness& m, double h, double rho, double mu, ib::Kernel kernel, double gain) {
  return limit(m, h, rho, mu, kernel, gain).first;
}

std::string membrane_limiting_family(const MembraneStiffness& m, double h, double rho, double mu, ib::Kernel kernel, double gain) {
  return limit(m, h, rho, mu, kernel, gain).second;
}

}  // namespace rbfib::sim
