#pragma once
// Closed-form solutions of the incompressible Navier-Stokes equations (2.1)-(2.2), used to verify
// the solver (tests and the `fluid` study). Host-side; CGS units as given by the caller.
//
//  - TaylorGreen: the decaying vortex on the periodic square [0, L]^2 (extended uniformly in z),
//      u = U sin(kx) cos(ky) E, v = -U cos(kx) sin(ky) E, w = 0, E = exp(-2 nu k^2 t), k = 2 pi / L,
//      p = rho U^2 / 4 (cos 2kx + cos 2ky) E^2,
//    an exact solution with f = 0 (advection balanced by the pressure gradient).
//  - Couette: start-up flow between a wall at y = 0 at rest and a wall at y = H moving with U in x,
//      u(y, t) = U y / H - sum_{n >= 1} 2 U (-1)^{n+1} / (n pi) sin(n pi y / H) exp(-nu (n pi / H)^2 t),
//    v = w = p = 0, f = 0 (the series of the heat equation with u(y, 0) = 0).
//  - Manufactured: u = g(t) curl(chi e_x + phi e_z), divergence-free by construction, with
//    phi, chi products of sines, p = rho P(t) pi_0(x), and the body force
//      f = rho (u_t + (u . grad) u) - mu Lap u + grad p
//    that makes it an exact solution; every derivative is taken analytically (TrigSum below).
#include <array>
#include "rbfib/core/constants.hpp"
#include <cmath>
#include <vector>

namespace rbfib::exact {


/// c prod_d sin(k_d x_d + s_d): closed under differentiation.
struct TrigTerm {
  double c = 1.0;
  std::array<double, 3> k{{0, 0, 0}};
  std::array<double, 3> s{{pi / 2, pi / 2, pi / 2}};

  double operator()(double x, double y, double z) const {
    return c * std::sin(k[0] * x + s[0]) * std::sin(k[1] * y + s[1]) * std::sin(k[2] * z + s[2]);
  }
  TrigTerm derivative(int d) const {
    TrigTerm t = *this;
    t.c *= k[d];
    t.s[d] += pi / 2;
    return t;
  }
};

struct TrigSum {
  std::vector<TrigTerm> terms;

  double operator()(double x, double y, double z) const {
    double v = 0.0;
    for (const TrigTerm& t : terms) v += t(x, y, z);
    return v;
  }
  TrigSum derivative(int d) const {
    TrigSum r;
    for (const TrigTerm& t : terms)
      if (t.k[d] != 0.0) r.terms.push_back(t.derivative(d));
    return r;
  }
  TrigSum operator-() const {
    TrigSum r = *this;
    for (TrigTerm& t : r.terms) t.c = -t.c;
    return r;
  }
  TrigSum operator+(const TrigSum& o) const {
    TrigSum r = *this;
    r.terms.insert(r.terms.end(), o.terms.begin(), o.terms.end());
    return r;
  }
  TrigSum laplacian() const {
    TrigSum r;
    for (int d = 0; d < 3; ++d) r = r + derivative(d).derivative(d);
    return r;
  }
};

struct TaylorGreen {
  double L = 1.0, U = 1.0, nu = 1.0, rho = 1.0;

  double k() const { return 2.0 * pi / L; }
  double decay(double t) const { return std::exp(-2.0 * nu * k() * k() * t); }
  double velocity(int a, double t, double x, double y, double) const {
    const double kk = k(), E = decay(t);
    if (a == 0) return U * std::sin(kk * x) * std::cos(kk * y) * E;
    if (a == 1) return -U * std::cos(kk * x) * std::sin(kk * y) * E;
    return 0.0;
  }
  double pressure(double t, double x, double y, double) const {
    const double kk = k(), E = decay(t);
    return rho * U * U / 4.0 * (std::cos(2 * kk * x) + std::cos(2 * kk * y)) * E * E;
  }
};

struct Couette {
  double H = 1.0, U = 1.0, nu = 1.0;

  double velocity(int a, double t, double, double y, double) const {
    if (a != 0) return 0.0;
    double u = U * y / H;
    for (int n = 1; n <= 100000; ++n) {
      const double decay = std::exp(-nu * (n * pi / H) * (n * pi / H) * t);
      const double term = 2.0 * U / (n * pi) * decay;
      u -= ((n % 2) ? term : -term) * std::sin(n * pi * y / H);
      if (term < 1e-18 * std::abs(U)) break;
    }
    return u;
  }
};

/// The manufactured flow on a box periodic in x with period Lx = 1 (any walls in y, z).
struct Manufactured {
  double rho = 1.0, mu = 0.1;
  TrigSum phi, chi, pres;  // potentials and pressure shape
  std::array<TrigSum, 3> U;               // spatial velocity shape: u = g(t) U
  std::array<std::array<TrigSum, 3>, 3> dU;  // dU[a][b] = d U_a / d x_b
  std::array<TrigSum, 3> lapU, gradP;

  Manufactured() {
    auto term = [](double c, double kx, double sx, double ky, double sy, double kz, double sz) {
      TrigTerm t;
      t.c = c;
      t.k = {kx, ky, kz};
      t.s = {sx, sy, sz};
      return t;
    };
    phi.terms = {term(1.0, 2 * pi, 0.0, pi, 0.3, pi, 0.2 + pi / 2)};
    chi.terms = {term(0.8, 2 * pi, 0.5 + pi / 2, pi, pi / 2, pi, 0.4)};
    pres.terms = {term(0.5, 2 * pi, pi / 2, pi, 0.1, pi, 0.7)};
    U[0] = phi.derivative(1);                          // phi_y
    U[1] = -phi.derivative(0) + chi.derivative(2);     // -phi_x + chi_z
    U[2] = -chi.derivative(1);                         // -chi_y
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) dU[a][b] = U[a].derivative(b);
      lapU[a] = U[a].laplacian();
      gradP[a] = pres.derivative(a);
    }
  }
  static double g(double t) { return 1.0 + 0.5 * std::sin(4.0 * t); }
  static double dg(double t) { return 2.0 * std::cos(4.0 * t); }
  static double P(double t) { return g(t) * g(t); }

  double velocity(int a, double t, double x, double y, double z) const { return g(t) * U[a](x, y, z); }
  double pressure(double t, double x, double y, double z) const { return rho * P(t) * pres(x, y, z); }
  /// inward normal derivative of u_a at a point of face (d, side)
  double normal_derivative(int a, int d, int side, double t, double x, double y, double z) const {
    return (side ? -1.0 : 1.0) * g(t) * dU[a][d](x, y, z);
  }
  double force(int a, double t, double x, double y, double z) const {
    const double G = g(t);
    double adv = 0.0;
    for (int b = 0; b < 3; ++b) adv += U[b](x, y, z) * dU[a][b](x, y, z);
    return rho * (dg(t) * U[a](x, y, z) + G * G * adv) - mu * G * lapU[a](x, y, z) + rho * P(t) * gradP[a](x, y, z);
  }
};

}  // namespace rbfib::exact
