"""Explicit-stability bounds of the membrane modes in the seed's coupling (README.md sections 2-4).

A sheet mode: grid wavenumber q (along the grid axis, or at 45 deg), polarization n / L / T. The
Lagrangian modes that share q (k_m = |q + 2 pi m/h| <= k_max, the data sites' highest mode) act as
one (rank-one mobility):  SA = sum_m Phi(k_m h)^2 A(k_m),  SD = sum_m Phi(k_m h)^2 D(k_m),
lambda = SA g0(q), D-gain = SD g0(q), with g0 / gdt the grid part of the sheet mobility at a = 0 /
a = 2 rho/dt (sheet.py). Sign-flip threshold (eigenvalue -1): (SD + 3/2 SA dt) gdt(q) = 1;
quasi-steady: (D M + 3/2 lambda dt) = 1, i.e. z = lambda dt = 2/3 without dissipation.
"""
import numpy as np
from sheet import mobility, Phi_b3

rho, mu = 1.0, 0.01          # g/cm^3, P (1 cP)
um = 1e-4

CELLS = {
    # small-strain moduli (README section 1): shear mus, area K (dyn/cm); kappa (erg); nu (dyn s/cm);
    # reference area (um^2, geometry.py); largest principal curvature c (1/um, geometry.py)
    "red cell": dict(mus=2.5e-3, K=2.5e-3 + 2 * 2.5e-1, kappa=2e-12, nu=2.5e-7, area=134.2, c=1.02),
    "platelet": dict(mus=0.1, K=1.0, kappa=2e-11, nu=0.0, area=18.08, c=6.20),
}

def modes(p):
    """(name, pol, A(k), D(k)) for a sheet mode of wavenumber k (1/cm): A in dyn/cm^3, D in dyn s/cm^3."""
    mus, K, kap, nu, c = p["mus"], p["K"], p["kappa"], p["nu"], p["c"] / um
    Y = 4 * mus * K / (mus + K)   # uniaxial-stress modulus, which curvature couples a normal mode to
    return [
        ("tangential along k", "L", lambda k: (K + mus) * k**2, lambda k: nu * k**2),
        ("tangential across k", "T", lambda k: mus * k**2, lambda k: 0.5 * nu * k**2),
        # bending kappa k^4 (+ kappa c^2 k^2), and Y c^2 (Donnell: a mode along one line of curvature
        # stretches the other) where the mode fits the curved band (k >= c): an upper estimate
        ("normal", "n", lambda k: kap * k**4 + kap * c**2 * k**2 + np.where(k >= c, Y * c**2, 0.0), lambda k: 0.0 * k),
    ]

def partners(q, h, kmax, angle):
    if angle != 0.0:
        return np.array([q]), Phi_b3(q * np.cos(angle) * h) ** 2 * Phi_b3(q * np.sin(angle) * h) ** 2 * np.ones(1)
    ks = [abs(q + 2 * np.pi * m / h) for m in range(-4, 5)]
    ks = np.array([k for k in ks if k <= kmax * (1 + 1e-12)])
    return ks, Phi_b3(ks * h) ** 2

def mode_rows(cell, h, nd, kmax_factor=np.sqrt(4 * np.pi), nq=48, nu=None):
    p = dict(CELLS[cell])
    if nu is not None:
        p["nu"] = nu
    spacing = np.sqrt(p["area"] / nd) * um
    kmax = kmax_factor / spacing
    rows = []
    for name, pol, A, D in modes(p):
        for angle in (0.0, np.pi / 4):
            qtop = min(kmax, np.pi / h / (np.cos(angle) if angle else 1.0))
            for q in np.linspace(qtop / nq, qtop, nq):
                ks, w = partners(q, h, kmax, angle)
                if len(ks) == 0:
                    continue
                SA, SD = np.sum(w * A(ks)), np.sum(w * D(ks))
                g0 = mobility(q, h, mu, 0.0, pol, angle, kernel_in_plane=False)
                rows.append(dict(lam=SA * g0, dM=SD * g0, SA=SA, SD=SD, q=q, ks=ks, mode=name, pol=pol, angle=angle))
    return p, spacing, kmax, rows

def gain(r, h, dt):
    return (r["SD"] + 1.5 * r["SA"] * dt) * mobility(r["q"], h, mu, 2 * rho / dt, r["pol"], r["angle"], kernel_in_plane=False)

def flip_dt(r, h, lo=1e-9, hi=1e-3):
    """Largest dt with gain <= 1 (the gain grows with dt); hi if never reached, lo if always."""
    if gain(r, h, hi) <= 1:
        return hi
    if gain(r, h, lo) > 1:
        return lo
    for _ in range(50):
        m = np.sqrt(lo * hi)
        (lo, hi) = (m, hi) if gain(r, h, m) <= 1 else (lo, m)
    return lo

def case(cell, h, nd, **kw):
    p, spacing, kmax, rows = mode_rows(cell, h, nd, **kw)
    top = max(rows, key=lambda r: r["lam"])
    dtop = max(rows, key=lambda r: r["dM"])
    qs = [((1 - r["dM"]) / (1.5 * r["lam"]) if r["dM"] < 1 else 0.0, r) for r in rows if r["lam"] > 0]
    dt_qs, r_qs = min(qs, key=lambda t: t[0])
    cand = sorted(rows, key=lambda r: -r["lam"])[:10] + sorted(rows, key=lambda r: -r["dM"])[:4]
    dts = [(flip_dt(r, h), r) for r in cand]
    dt_in, r_in = min(dts, key=lambda t: t[0])
    by_mode = {}
    for r in rows:
        by_mode[r["mode"]] = max(by_mode.get(r["mode"], 0.0), r["lam"])
    return dict(cell=cell, h=h, nd=nd, spacing=spacing, kmax=kmax, top=top, dtop=dtop, dt_qs=dt_qs, r_qs=r_qs,
                dt_in=dt_in, r_in=r_in, by_mode=by_mode)

CASES = [("red cell", 0.2 * um, 2500, "whole blood, Sec. 5.2: 2,500 / 10,000"),
         ("red cell", 0.2 * um, 400, "400 data sites"),
         ("red cell", 0.4 * um, 400, "quick whole-blood scene: 400 / 1,600"),
         ("red cell", 0.4 * um, 625, "chapter5_shear full: 625 / 2,500"),
         ("red cell", 0.8 * um, 400, "chapter5_shear quick: 400 / 1,600"),
         ("platelet", 0.2 * um, 900, "Sec. 5.2: 900 / 900"),
         ("platelet", 0.4 * um, 400, "quick whole-blood scene: 400 / 400")]

def fmt_k(r, h):
    return f"{r['q']*um:.2f}/um (qh = {r['q']*h:.2f}, {np.degrees(r['angle']):.0f} deg)"

if __name__ == "__main__":
    print("| cell | h | sites | spacing, k_max | lambda_max (1/s) | mode, q | nu k^2 M max | dt*, quasi-steady | dt*, with inertia |")
    print("|---|---|---|---|---|---|---|---|---|")
    for cell, h, nd, what in CASES:
        r = case(cell, h, nd)
        t = r["top"]
        print(f"| {cell} | {h/um:.1f} um | {what} | {r['spacing']/um:.3f} um, {r['kmax']*um:.1f}/um | {t['lam']:.3g} | "
              f"{t['mode']}, {fmt_k(t, h)} | {r['dtop']['dM']:.3f} | {r['dt_qs']*1e6:.2f} us | {r['dt_in']*1e6:.2f} us ({r['r_in']['mode']}) |")
    print()
    print("largest lambda (1/s) per mode family:")
    for cell, h, nd, what in CASES:
        r = case(cell, h, nd)
        print(f"  {cell:8s} h = {h/um:.1f} um, n_d = {nd:4d}: " + ", ".join(f"{k}: {v:.3g}" for k, v in r["by_mode"].items()))
