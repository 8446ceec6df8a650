#!/usr/bin/python3
"""Velocity convergence of chapter5_convergence by distance from the membrane.

Reads the finished grids' comparison files (grid_r<r>.h5, as kept by `make keep-chapter5_convergence`),
splits the 20^3 coarse cell centres into bands by their distance from the finest grid's surface
points, and prints per band the successive velocity differences eps_r = |u_r - u_{r+1}| (L2 over the
band's centres and the maximum) and the orders the seed's formula (Sec. 5.1.1) gives for each pair.

    /usr/bin/python3 tools/convergence_bands.py [DIR]   (default kept/chapter5_convergence/full)
"""
import glob
import os
import re
import sys

import h5py
import numpy as np

UM = 1e-4  # cm
BANDS_UM = [(0.0, 0.3), (0.3, 0.8), (0.8, 2.0), (2.0, np.inf)]


def order(ratio, r):
    """p with ratio = ((r+1)/r)^p - 1) / (1 - ((r+1)/(r+2))^p), by bisection; None out of reach."""
    f = lambda p: ((r + 1) / r) ** p - 1 - ratio * (1 - ((r + 1) / (r + 2)) ** p)
    lo, hi = 1e-6, 20.0
    if f(lo) * f(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "kept/chapter5_convergence/full"
    grid = lambda p: int(re.fullmatch(r"grid_r(\d+)\.h5", os.path.basename(p)).group(1))
    files = sorted(glob.glob(os.path.join(folder, "grid_r*.h5")), key=grid)
    rs = [grid(p) for p in files]
    if len(rs) < 3 or rs != list(range(1, len(rs) + 1)):
        sys.exit(f"convergence_bands: need grid_r1.h5, grid_r2.h5, grid_r3.h5, ... in {folder}; found r = {rs}")
    u, x = [], []
    for p in files:
        with h5py.File(p, "r") as f:
            u.append(f["u_centres"][:].reshape(3, -1).T)  # stored as 3 x 8000 (cm/s)
            x.append(f["X"][:].reshape(3, -1).T)  # 3 x 1000 surface points (cm)
    n = 20
    q = np.arange(n ** 3)
    centres = (np.stack([q % n, q // n % n, q // (n * n)], 1) + 0.5) * 0.8 * UM  # x fastest, as the driver
    surface = x[-1]
    dist = np.sqrt(((centres[:, None, :] - surface[None, :, :]) ** 2).sum(2)).min(1)
    print(f"grids r = 1..{rs[-1]}; distances from the r = {rs[-1]} surface (1,000 points); orders from eps_1/eps_2, eps_2/eps_3, ... (the seed's formula at r = 1, 2, ...)")
    for lo, hi in BANDS_UM:
        m = (dist >= lo * UM) & (dist < hi * UM)
        e2 = [float(np.sqrt(((u[k] - u[k + 1])[m] ** 2).sum(1).mean())) for k in range(len(u) - 1)]
        ei = [float(np.sqrt(((u[k] - u[k + 1])[m] ** 2).sum(1)).max()) for k in range(len(u) - 1)]
        p2 = [order(e2[k] / e2[k + 1], k + 1) for k in range(len(e2) - 1)]
        pi = [order(ei[k] / ei[k + 1], k + 1) for k in range(len(ei) - 1)]
        fmt = lambda v: "none" if v is None else f"{v:.2f}"
        print(f"band {lo:.1f}-{hi:.1f} um ({m.sum()} centres): eps_2 " + " ".join(f"{e:.2e}" for e in e2)
              + " cm/s; order_2 " + " ".join(fmt(p) for p in p2) + "; order_inf " + " ".join(fmt(p) for p in pi))


if __name__ == "__main__":
    main()
