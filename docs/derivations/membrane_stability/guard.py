"""The growth guard of README section 5 on the linear model: a red cell's worst mode (h = 0.4 um,
625 sites, 1 cP) started at 1e-9 of a smooth physical force that varies by 20% over T = 1 ms, at steps
around its threshold dt*. Two detectors on the sample-site forces F^n, each firing when, on 4
consecutive steps, cos(v_n, v_(n-1)) < -0.5 and |v_n|/|v_(n-1)| > 1.05:
  first difference   v_n = F^n - F^(n-1)
  second difference  v_n = F^n - 2 F^(n-1) + F^(n-2)
Compared with the step at which the mode's force equals the physical force (||f||_inf doubled)."""
import numpy as np
from bounds import case, CELLS, modes
from spectrum import step_matrix

cell, h, nd = "red cell", 0.4e-4, 625
cs = case(cell, h, nd)
r, dts = cs["r_in"], cs["dt_in"]
A = [a for (name, pol, a, d) in modes(CELLS[cell]) if name == r["mode"]][0]
rng = np.random.default_rng(7)

class Detector:
    def __init__(self, order):
        self.order, self.hist, self.prev, self.streak, self.fired = order, [], None, 0, None
    def see(self, n, F, ratio):
        self.hist = (self.hist + [F])[-(self.order + 1):]
        if len(self.hist) <= self.order:
            return
        v = self.hist[-1] - self.hist[-2] if self.order == 1 else self.hist[-1] - 2 * self.hist[-2] + self.hist[-3]
        if self.prev is not None:
            c = v @ self.prev / (np.linalg.norm(v) * np.linalg.norm(self.prev))
            g = np.linalg.norm(v) / np.linalg.norm(self.prev)
            self.streak = self.streak + 1 if (c < -0.5 and g > 1.05) else 0
            if self.streak >= 4 and self.fired is None:
                self.fired = (n, ratio)
        self.prev = v

print(f"{cell}, h = {h*1e4} um, n_d = {nd}: dt* = {dts*1e6:.2f} us ({r['mode']})")
for f in (0.25, 0.5, 0.9, 1.1, 1.25, 1.5, 2.0):
    dt = f * dts
    T = step_matrix(r, cell, h, dt)
    nf = T.shape[0] - len(r["ks"])
    s = rng.standard_normal(T.shape[0])
    mode_force = lambda s: -A(r["ks"][0]) * (s[nf] + dt * np.sum(s[:nf]))   # the mode's force at X*
    s *= 1e-9 / abs(mode_force(s))
    d1, d2, doubled = Detector(1), Detector(2), None
    for n in range(600):
        F = np.array([1 + 0.2 * np.sin(2 * np.pi * n * dt / 1e-3), mode_force(s)])  # smooth, grid-scale parts
        d1.see(n, F, abs(F[1])), d2.see(n, F, abs(F[1]))
        if doubled is None and abs(F[1]) >= 1:
            doubled = n
        if abs(F[1]) > 1e6:
            break
        s = T @ s
    fmt = lambda d: f"step {d.fired[0]} (mode at {d.fired[1]:.0e})" if d.fired else "never"
    print(f"  dt = {f:.2f} dt*: 1st difference fires {fmt(d1)}, 2nd difference {fmt(d2)}; "
          f"||f|| doubled at step {doubled if doubled is not None else 'never'} (600 steps)")
