"""The closed form for the step controller (README section 5) against the grid sums of bounds.py."""
import numpy as np
import bounds
from sheet import Phi_b3

# B3 constants (extra.py): peak value and where it sits (kh)
C_L, X_L, C_T, X_T, C_K, X_K, BETA = 0.0693, 0.68, 0.2265, 1.00, 0.4425, 2.08, 1.5

def membrane_dt(mus, K, kappa, nu, c, spacing, h, mu, rho=1.0, safety=1.0, inertia=True):
    """Largest step (s) whose gain is at most `safety` for every membrane family (1: the stability
    limit). CGS; c the largest principal curvature (1/cm), spacing = sqrt(area/n_d) (cm)."""
    kmax = np.sqrt(4 * np.pi) / spacing
    # the three families: (lambda = A M, d = D M) at their peaks, capped by the data sites' k_max
    # tangential modes: their peaks (kh = 0.68 and 1.0) whatever k_max (conservative when the data
    # sites are coarser than about 5 h: 6% at k_max h = 0.49)
    sL, sT = C_L / (mu * h), C_T / (mu * h)
    Y = 4 * mus * K / (mus + K)
    lam_n = (C_K * kappa / (mu * h**3) if kmax * h >= X_K else 0.225 * kappa * kmax**3 * Phi_b3(kmax * h) ** 2 / mu)
    if c <= kmax:
        lam_n += 0.225 * Phi_b3(c * h) ** 2 * (Y * c + kappa * c**3) / mu
    fam = [((K + mus) * sL, nu * sL), (mus * sT, 0.5 * nu * sT), (lam_n, 0.0)]
    tau = rho * h * h / mu
    best = np.inf
    for lam, d in fam:
        if lam <= 0:
            continue
        g = lambda dt: (d + 1.5 * lam * dt) / ((1 + BETA * tau / dt) if inertia else 1.0)
        lo, hi = 1e-12, 1e-2
        if g(hi) <= safety:
            continue
        if g(lo) > safety:
            return 0.0
        for _ in range(80):
            m = np.sqrt(lo * hi)
            (lo, hi) = (m, hi) if g(m) <= safety else (lo, m)
        best = min(best, lo)
    return best

if __name__ == "__main__":
    um = 1e-4
    for mu in (0.01, 0.001):
        bounds.mu = mu
        print(f"mu = {mu*100:g} cP: case | grid sums: quasi-steady, inertia | closed form: quasi-steady, inertia (us)")
        for cell, h, nd, what in bounds.CASES:
            p = bounds.CELLS[cell]
            r = bounds.case(cell, h, nd)
            sp = np.sqrt(p["area"] / nd) * um
            a = membrane_dt(p["mus"], p["K"], p["kappa"], p["nu"], p["c"] / um, sp, h, mu, inertia=False)
            b = membrane_dt(p["mus"], p["K"], p["kappa"], p["nu"], p["c"] / um, sp, h, mu, inertia=True)
            print(f"  {cell:8s} h = {h/um:.1f} um n_d = {nd:4d} | {r['dt_qs']*1e6:6.3f} {r['dt_in']*1e6:6.3f} | {a*1e6:6.3f} {b*1e6:6.3f}")

    bounds.mu = 0.01
    print("gain <= 0.5 (the recommended margin), 1 cP, closed form with inertia (us):")
    for cell, h, nd, what in bounds.CASES:
        p = bounds.CELLS[cell]
        sp = np.sqrt(p["area"] / nd) * um
        print(f"  {cell:8s} h = {h/um:.1f} um n_d = {nd:4d}: {membrane_dt(p['mus'], p['K'], p['kappa'], p['nu'], p['c'] / um, sp, h, 0.01, safety=0.5)*1e6:.3f}")
