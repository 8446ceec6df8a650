"""The full one-step matrix of a sheet mode with the fluid's inertia (README.md section 3): state
(v_m, X_i), v_m the contribution of the fluid's wall-normal Fourier mode m to the interpolated
velocity, X_i the Lagrangian partners sharing the grid wavenumber. Checks that the spectral radius
crosses 1 where (SD + 3/2 SA dt) G(dt) = 1 (bounds.flip_dt), with a real eigenvalue -1, and gives the
growth factor per step above the threshold and the flip root's decay below it."""
import numpy as np
from sheet import wbar2, Phi_b3
from bounds import case, CASES, modes, CELLS, flip_dt, rho, mu, um

def grid_weights(q, h, pol, angle, Ly=16e-4):
    N = int(round(Ly / h))
    m = np.fft.fftfreq(N, d=1.0 / N)
    ky = 2 * np.pi * m / (N * h)
    dx, dz = 2 / h * np.sin(q * np.cos(angle) * h / 2), 2 / h * np.sin(q * np.sin(angle) * h / 2)
    dy = 2 / h * np.sin(ky * h / 2)
    d2 = dx**2 + dy**2 + dz**2
    ed = {"n": dy, "L": (np.cos(angle) * dx + np.sin(angle) * dz) * np.ones_like(dy),
          "T": (-np.sin(angle) * dx + np.cos(angle) * dz) * np.ones_like(dy)}[pol]
    ok = d2 > 0
    b = wbar2(N)[ok] * (1 - ed[ok] ** 2 / d2[ok]) / (N * h)
    return b, d2[ok]

def step_matrix(r, cell, h, dt):
    p = CELLS[cell]
    A, D = [(a, d) for (name, pol, a, d) in modes(p) if name == r["mode"]][0]
    b, d2 = grid_weights(r["q"], h, r["pol"], r["angle"])
    ks = r["ks"]
    if r["angle"] == 0.0:
        ph = Phi_b3(ks * h)
    else:
        ph = np.array([Phi_b3(r["q"] * np.cos(r["angle"]) * h) * Phi_b3(r["q"] * np.sin(r["angle"]) * h)])
    Ai, Di = A(ks), D(ks)
    nf, nl = len(b), len(ks)
    den = rho / dt + mu * d2
    R = (rho / dt) / den
    c = b / den
    # U_i = ph_i sum(v); F_i = -A_i (X_i + dt U_i) - D_i U_i; f = sum_i ph_i F_i;
    # v' = R v + c f;  X_i' = X_i + dt ph_i sum(v')
    T = np.zeros((nf + nl, nf + nl))
    coefV = -np.sum(ph * ph * (Ai * dt + Di))     # f's dependence on sum(v)
    coefX = -ph * Ai                              # f's dependence on X_i
    T[:nf, :nf] = np.diag(R) + np.outer(c, coefV * np.ones(nf))
    T[:nf, nf:] = np.outer(c, coefX)
    T[nf:, :] = dt * np.outer(ph, np.ones(nf)) @ T[:nf, :]
    T[nf:, nf:] += np.eye(nl)
    return T

def radius(r, cell, h, dt):
    ev = np.linalg.eigvals(step_matrix(r, cell, h, dt))
    i = np.argmax(abs(ev))
    return abs(ev[i]), ev[i]

def flip_root(r, cell, h, dt):
    ev = np.linalg.eigvals(step_matrix(r, cell, h, dt))
    neg = ev[(ev.real < 0)]
    return neg[np.argmax(abs(neg))] if len(neg) else 0.0

if __name__ == "__main__":
    for cell, h, nd, what in CASES:
        cs = case(cell, h, nd)
        r = cs["r_in"]
        lo, hi = 1e-8, 1e-4
        for _ in range(50):
            m = np.sqrt(lo * hi)
            (lo, hi) = (m, hi) if radius(r, cell, h, m)[0] <= 1 + 1e-12 else (lo, m)
        dts = lo
        e = radius(r, cell, h, 1.001 * dts)[1]
        print(f"{cell}, h = {h/um:.1f} um, n_d = {nd}: spectral-radius threshold {dts*1e6:.3f} us, flip formula "
              f"{flip_dt(r, h)*1e6:.3f} us; eigenvalue just above: {e.real:+.4f}{e.imag:+.1e}i")
        g = ", ".join(f"{f:g}x: {radius(r, cell, h, f*dts)[1].real:+.3f}" for f in (1.1, 1.25, 1.5, 2.0))
        print(f"   growth per step above dt*: {g}")
        c = ", ".join(f"{f:g}x: {flip_root(r, cell, h, f*dts).real:+.3f}" for f in (0.25, 0.5, 0.75))
        print(f"   flip root below dt*: {c}")
        b = ", ".join(f"{t:g} us: {flip_root(r, cell, h, t*1e-6).real:+.3f}" for t in (0.2, 0.4, 0.8, 1.6))
        print(f"   flip root at the steps used: {b}")
