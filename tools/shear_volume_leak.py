#!/usr/bin/python3
"""How fast a red cell's volume drifts in chapter5_shear's 1000/s, 1 cP run, by grid and sites.

Runs the study's scene (one red cell, full model, shear 1000/s along z, 1 cP, the seed's ladder
50 to 800 ns) with `build/bin/rbfib run` over a short window at several grid spacings h and site
counts, and prints for each the volume's change per unit strain, fitted by least squares over the
strains [FROM, END] (after the start-up), beside the time it took:

    /usr/bin/python3 tools/shear_volume_leak.py [--end-ms 8] [--from-strain 3] [--only LABEL ...]

Each variant's run directory is runs/shear_volume_leak/<label>/ (scene.yaml, diagnostics.csv).
The variants: the study's h = 0.4 um with 625 / 2,500 sites (its run), the same sites on h = 0.8,
0.57 and 0.32 um (the grid alone), h = 0.4 um with 625 / 10,000 and 1,600 / 6,400 sites (the sites
alone), and 1,600 / 6,400 sites on h = 0.32 and 0.27 um (the grid, the data sites 0.85-0.72 h
apart as the seed's 625 are at h = 0.57-0.4 um).
"""
import argparse
import csv
import os
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GDOT = 1000.0  # 1/s

SCENE = """# chapter5_shear's 1000/s, 1 cP scene at h = {h} um, {nd} / {ns} sites (tools/shear_volume_leak.py)
name: shear_volume_leak_{label}
domain:
  size: [16 um, 16 um, 16 um]
  periodic: [x, z]
  walls:
    y: {{lower: [0 cm/s, 0 cm/s, -0.8 cm/s], upper: [0 cm/s, 0 cm/s, 0.8 cm/s]}}
  initial_flow: shear
fluid: {{density: 1 g/cm^3, viscosity: 1 cP}}
grid: {{cells: [{n}, {n}, {n}]}}
time: {{integrator: backward_forward_euler, coupling: seed, dt: 50 ns, end: {end} ms, adaptive: {{dt_min: 50 ns, max_level: 4, grow_after: 16}}}}
ib: {{kernel: bspline3}}
cell_types:
  - {{name: red cell, preset: red_cell, data_sites: {nd}, sample_sites: {ns}, model: {{elastic: [{{law: skalak, E: 0.0025 dyn/cm, G: 0.25 dyn/cm}}], kappa: 2e-12 erg, H0: 0 1/cm, nu: 2.5e-07 dyn s/cm}}}}
cells:
  - {{type: red cell, center: [8 um, 8 um, 8 um], axis: [1, 0, 0], angle: -0.5707963267948966 rad}}
output: {{diagnostics_every: 20}}
"""

# label: (grid cells per side, data sites, sample sites)
VARIANTS = {
    "h0.8": (20, 625, 2500),
    "h0.57": (28, 625, 2500),
    "h0.4": (40, 625, 2500),
    "h0.32": (50, 625, 2500),
    "h0.4_ns10000": (40, 625, 10000),
    "h0.4_nd1600": (40, 1600, 6400),
    "h0.32_nd1600": (50, 1600, 6400),
    "h0.27_nd1600": (60, 1600, 6400),
}


def run(label, end_ms):
    n, nd, ns = VARIANTS[label]
    out = os.path.join(ROOT, "runs", "shear_volume_leak", label)
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(out, "scene.yaml")
    with open(scene, "w") as f:
        f.write(SCENE.format(h=round(16.0 / n, 3), nd=nd, ns=ns, label=label, n=n, end=end_ms))
    t0 = time.time()
    subprocess.run([os.path.join(ROOT, "build", "bin", "rbfib"), "run", scene, "--out", out], check=True,
                   stdout=subprocess.DEVNULL)
    return out, time.time() - t0


def leak(out, from_strain):
    with open(os.path.join(out, "diagnostics.csv")) as f:
        rows = list(csv.reader(f))
    head, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    t = data[:, head.index("t_s")]
    v = data[:, [i for i, c in enumerate(head) if c.startswith("volume_")][0]]
    v0 = v[0]  # the first row is after the first step: the volume at t = 0 to within one step
    strain = GDOT * t
    keep = strain >= from_strain
    slope = np.polyfit(strain[keep], v[keep] / v0, 1)[0]
    return slope, v[-1] / v0 - 1, strain[-1], len(t)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--end-ms", type=float, default=8.0)
    p.add_argument("--from-strain", type=float, default=3.0)
    p.add_argument("--only", nargs="*", default=list(VARIANTS))
    a = p.parse_args()
    print("| variant | h (um) | data / sample sites | change per unit strain | change at the end | strain | wall time (s) |")
    print("|---|---|---|---|---|---|---|")
    for label in a.only:
        out, seconds = run(label, a.end_ms)
        slope, total, strain, _ = leak(out, a.from_strain)
        n, nd, ns = VARIANTS[label]
        print(f"| {label} | {16.0 / n:.3f} | {nd} / {ns} | {slope:.3e} | {total:.3e} | {strain:.2f} | {seconds:.0f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
