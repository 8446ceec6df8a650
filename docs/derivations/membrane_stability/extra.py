"""Constants of the closed form (README section 5), the sheet's orientation to the grid, the dissipation's
gain, the seed's "prohibitive" nu = 1e-3 dyn s/cm, the gain at the steps used, and sensitivities."""
import numpy as np
import bounds
from bounds import case, mode_rows, gain, flip_dt, CELLS, um
from sheet import mobility, Phi_b3

mu, h = 0.01, 0.2e-4
# 1. Closed-form constants (sheet along a grid plane, k along an axis), per kernel:
#    lambda_L = C_L (K+mus)/(mu h), lambda_T = C_T mus/(mu h), bending C_k kappa/(mu h^3)
from sheet import KERNELS, Phi
x = np.linspace(0.01, np.pi, 315)
q = x / h
for kern in KERNELS:
    ML = np.array([mobility(k, h, mu, 0, "L", kernel=kern) for k in q])
    MT = np.array([mobility(k, h, mu, 0, "T", kernel=kern) for k in q])
    Mn = np.array([mobility(k, h, mu, 0, "n", kernel=kern) for k in q])
    out = []
    for name, y in [("C_L", q**2 * ML * mu * h), ("C_T", q**2 * MT * mu * h), ("C_kappa", q**4 * Mn * mu * h**3)]:
        i = np.argmax(y)
        out.append(f"{name} = {y[i]:.4f} at kh = {x[i]:.2f}")
    print(f"{kern:9s}: " + ", ".join(out))
    if kern == "bspline3":
        ML_b3, Mn_b3 = ML, Mn
ML, Mn = ML_b3, Mn_b3
print("B3 normal mobility 4 mu k M_n / Phi(kh)^2 at kh = 0.5, 1, 1.5, 2, 2.5, 3:",
      [round(mobility(v / h, h, mu, 0, 'n') * 4 * mu * v / h / Phi_b3(v) ** 2, 3) for v in (0.5, 1, 1.5, 2, 2.5, 3)])
print("B3 tangential-along-k 4 mu k M_L / Phi(kh)^2 at kh = 0.25, 0.5, 0.7, 1, 1.5, 2:",
      [round(mobility(v / h, h, mu, 0, 'L') * 4 * mu * v / h / Phi_b3(v) ** 2, 3) for v in (0.25, 0.5, 0.7, 1, 1.5, 2)])
# a one-line fit of M_L: Phi(kh)^2 / (4 mu k (1 + b kh))
b = np.median((Phi_b3(x) ** 2 / (4 * mu * q * ML) - 1) / x)
fit = Phi_b3(x) ** 2 / (4 * mu * q * (1 + b * x))
print(f"M_L ~ Phi(kh)^2 / (4 mu k (1 + {b:.2f} kh)): ratio to the grid sum over kh in (0, pi]: {np.min(fit/ML):.2f}-{np.max(fit/ML):.2f};"
      f" its peak of k^2 M mu h: {np.max(q**2*fit*mu*h):.4f}")
# 2. Orientation: continuum-regularized sheet, any normal n and in-plane direction t
s = np.linspace(-60, 60, 24001) / h
def M_cont(k, n, t, pol):
    n, t = np.array(n, float) / np.linalg.norm(n), np.array(t, float) / np.linalg.norm(t)
    e = {"L": t, "n": n, "T": np.cross(n, t)}[pol]
    K = k * t[:, None] + s[None, :] * n[:, None]
    K2 = np.sum(K * K, axis=0)
    P = 1 - (e @ K) ** 2 / K2
    w = np.prod(Phi_b3(K * h) ** 2, axis=0)
    return np.trapz(w * P / (mu * K2), s) / (2 * np.pi)
ref = None
print("orientation (continuum-regularized sheet): max_k k^2 M_L relative to the grid plane, k along an axis")
for n, t in [((0, 1, 0), (1, 0, 0)), ((0, 1, 0), (1, 0, 1)), ((1, 1, 0), (0, 0, 1)), ((1, 1, 0), (1, -1, 0)),
             ((1, 1, 1), (1, -1, 0)), ((1, 1, 1), (1, 1, -2))]:
    ks = np.linspace(0.2, 2.0, 37) / h
    v = max(k**2 * M_cont(k, n, t, "L") for k in ks)
    ref = ref or v
    print(f"  normal {n}, k along {t}: {v/ref:.3f}")
# the inertial factor G(dt)/M of the tangential peak (kh = 0.68): fit 1/(1 + beta rho h^2/(mu dt))
for hh in (0.2 * um, 0.4 * um, 0.8 * um):
    k = 0.68 / hh
    M = mobility(k, hh, mu, 0, "L")
    r = [mobility(k, hh, mu, 2 / t, "L") / M for t in (0.2e-6, 0.4e-6, 0.8e-6, 1.6e-6, 3.2e-6)]
    tau = hh**2 / mu
    beta = [(1 / v - 1) * t / tau for v, t in zip(r, (0.2e-6, 0.4e-6, 0.8e-6, 1.6e-6, 3.2e-6))]
    print(f"h = {hh/um} um (rho h^2/mu = {tau*1e9:.0f} ns): G/M at 0.2-3.2 us {np.round(r, 3)}; beta {np.round(beta, 2)}")
# 3. Dissipation: its gain nu k^2 M (dt-independent) and the limits it sets
for cell, hh, nd in [("red cell", 0.2 * um, 2500), ("red cell", 0.4 * um, 625)]:
    r = case(cell, hh, nd)
    print(f"{cell}, h = {hh/um} um: max nu k^2 M = {r['dtop']['dM']:.3f} at k = {r['dtop']['q']*um:.2f}/um; "
          f"nu alone is stable below nu = {CELLS[cell]['nu']/r['dtop']['dM']:.2e} dyn s/cm (quasi-steady, any dt)")
for nu in [1e-6, 1e-5, 1e-4, 1e-3]:
    r = case("red cell", 0.2 * um, 2500, nu=nu)
    rows = mode_rows("red cell", 0.2 * um, 2500, nu=nu)[3]
    cand = sorted(rows, key=lambda x: -x["dM"])[:6] + sorted(rows, key=lambda x: -x["lam"])[:6]
    r["dt_in"] = min(flip_dt(x, 0.2 * um, lo=1e-13) for x in cand)
    print(f"  red cell h = 0.2 um with nu = {nu:g} dyn s/cm: quasi-steady gain {r['dtop']['dM']:.3g}; dt* with inertia {r['dt_in']*1e9:.3g} ns")
# 4. The gain (D + 3/2 A dt) G(dt) of the worst mode at the steps used (1 = threshold)
print("gain of the worst mode at dt = 0.2, 0.4, 0.8, 1.6, 3.2 us (stable below 1); G(dt)/M of that mode:")
for cell, hh, nd, what in bounds.CASES:
    r = case(cell, hh, nd)["r_in"]
    M = mobility(r["q"], hh, mu, 0, r["pol"], r["angle"], kernel_in_plane=False)
    g = [gain(r, hh, t * 1e-6) for t in (0.2, 0.4, 0.8, 1.6, 3.2)]
    GM = [mobility(r["q"], hh, mu, 2 / (t * 1e-6), r["pol"], r["angle"], kernel_in_plane=False) / M for t in (0.2, 0.4, 0.8, 1.6, 3.2)]
    print(f"  {cell}, h = {hh/um} um, n_d = {nd}: " + " ".join(f"{x:.3f}" for x in g) + " | " + " ".join(f"{x:.2f}" for x in GM))
# 5. Sensitivity: the highest mode (pi/spacing, sqrt(4 pi)/spacing, pi sqrt2/spacing) and the box height
for f, lab in [(np.pi, "pi"), (np.sqrt(4 * np.pi), "sqrt(4pi)"), (np.pi * np.sqrt(2), "pi sqrt2")]:
    out = []
    for cell, hh, nd, what in bounds.CASES:
        out.append(f"{case(cell, hh, nd, kmax_factor=f)['dt_in']*1e6:.2f}")
    print(f"k_max = {lab}/spacing: dt* (us) " + " ".join(out))
