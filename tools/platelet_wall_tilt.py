#!/usr/bin/python3
"""How a lone platelet lying flat turns in shear 1000/s, by its gap to a flat wall.

chapter5_platelets measures both platelets of Sec. 5.2 first tilting *against* the shear (the
short axis turning from the wall normal y toward -z), over every wall treatment alike, while a
rigid oblate spheroid in unbounded shear turns with it (Jeffery). This tool separates the wall
from the model: it runs one platelet of the study's full sizes (h = 0.2 um, 900 / 900 sites, the
platelet preset: neo-Hookean 0.1 / 1 dyn/cm, bending about the reference curvature, 1.55 x 0.5 um
semi-axes; 1 cP, B3 kernel, backward-forward Euler on the seed's ladder 50 to 800 ns by eq. 5.4)
in the study's 16 x 12 x 16 um box, the grid's own no-slip wall at y = 0 and the top wall at
12 mm/s (shear 1000/s), with `build/bin/rbfib run`, the platelet's centre at the gap + 0.5 um, and
a variant in the middle of the box (y = 6 um, 5.5 um from either wall: free shear). From the
snapshots' sample sites it takes the short axis (the covariance's least eigenvector), its tilt
toward the flow (positive with the shear) and the gap (the lowest site), beside Jeffery's tilt
from flat, atan(r tan(gdot t / (r + 1/r))), r = 0.5 / 1.55:

    /usr/bin/python3 tools/platelet_wall_tilt.py [--end-ms 2] [--only LABEL ...] [--h-um 0.2] [--sites N] [--quick]

Each variant's run directory is runs/platelet_wall_tilt/<label>/; the table (tilt, gap, Jeffery's
tilt and the volume's change, from the diagnostics every 50 steps, at 0.25, 0.5, 1, 2 ms and the
end) goes to stdout and to runs/platelet_wall_tilt/summary.csv (with --only, summary_<labels>.csv,
so that two runs side by side keep theirs). --quick: h = 0.4 um and 400 / 400 sites (the study's
quick sizes), to check the tool itself in a minute. With the free variant among them (or with
--measure-only, on the snapshots already written, finished or not) it prints each variant's tilt
less the free platelet's every 30 us: the wall's part of the turn. --h-um and --sites refine the grid and the
surface (the sites default to the seed's n h^2: 3,600 at h = 0.1 um), into
runs/platelet_wall_tilt_h<h>_n<sites>/.
"""
import argparse
import csv
import glob
import math
import os
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GDOT = 1000.0  # 1/s
R = 0.5 / 1.55  # the platelet's aspect ratio

SCENE = """# One platelet lying flat in shear 1000/s, its centre at y = {y} um (tools/platelet_wall_tilt.py)
name: platelet_wall_tilt_{label}
domain:
  size: [16 um, 12 um, 16 um]
  periodic: [x, z]
  walls:
    y: {{lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [0 mm/s, 0 mm/s, 12 mm/s]}}
  initial_flow: shear
fluid: {{density: 1 g/cm^3, viscosity: 1 cP}}
grid: {{h: {h} um}}
time: {{integrator: backward_forward_euler, dt: 50 ns, end: {end} ms, adaptive: {{dt_min: 50 ns, max_level: 4, grow_after: 16}}}}
ib: {{kernel: bspline3}}
cell_types:
  - {{name: platelet, preset: platelet, data_sites: {n}, sample_sites: {n}}}
cells:
  - {{type: platelet, center: [8 um, {y} um, 8 um], axis: [1, 0, 0], angle: 90 deg}}
output: {{diagnostics_every: 50, snapshot_every: {every} us}}
"""

# label: the centre's height above the grid wall (um); the gap is 0.5 um less
VARIANTS = {"gap0.3": 0.8, "gap0.5": 1.0, "gap1.0": 1.5, "gap2.0": 2.5, "free": 6.0}


def jeffery_tilt(t):
    """Jeffery's tilt (rad) of an oblate spheroid's axis from the gradient direction, started flat."""
    return math.atan(R * math.tan(GDOT * t / (R + 1 / R)))


def volumes(run_dir):
    """(t s, volume um^3) from the run's diagnostics (every 50 steps)."""
    with open(os.path.join(run_dir, "diagnostics.csv")) as f:
        rows = list(csv.DictReader(f))
    return np.array([float(r["t_s"]) for r in rows]), np.array([float(r["volume_platelet_0_um3"]) for r in rows])


def measure(run_dir):
    """(t s, tilt rad, gap um) per snapshot, from the sample sites."""
    rows = []
    for f in sorted(glob.glob(os.path.join(run_dir, "snapshots", "*.h5"))):
        with h5py.File(f, "r") as h:
            t = float(h.attrs["t"])
            X = h["cells/0/points"][()]
        c = X.mean(axis=0)
        _, v = np.linalg.eigh((X - c).T @ (X - c))
        a = v[:, 0]  # the short axis
        rows.append((t, math.atan(a[2] / a[1]), X[:, 1].min() * 1e4))
    return rows


def wall_part(base, labels, every_us=30.0):
    """Each label's tilt less the free platelet's (deg), at common times every `every_us` up to the
    end both reached: the wall's part of the turn. Works on unfinished runs (their snapshots)."""
    series = {}
    for label in labels + ["free"]:
        rows = measure(os.path.join(base, label))
        if rows:
            series[label] = (np.array([q[0] for q in rows]) * 1e6, np.degrees([q[1] for q in rows]))
    if "free" not in series:
        return
    for label in labels:
        if label == "free" or label not in series:
            continue
        end = min(series[label][0][-1], series["free"][0][-1])
        times = np.arange(every_us, end + 1e-9, every_us)
        parts = [f"{t:g} us {np.interp(t, *series[label]) - np.interp(t, *series['free']):+.3f}" for t in times]
        print(f"{label} less free (deg): " + ", ".join(parts), flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--end-ms", type=float, default=2.0, help="simulated time of each run (ms; default 2, the study's A/B window)")
    p.add_argument("--only", nargs="*", default=None, help="labels to run: " + ", ".join(VARIANTS))
    p.add_argument("--quick", action="store_true", help="h = 0.4 um, 400 / 400 sites (a check of the tool)")
    p.add_argument("--h-um", type=float, default=0.2, help="grid spacing (um; default 0.2, the study's full scale)")
    p.add_argument("--sites", type=int, default=None, help="data = sample sites (default 900 (0.2 um / h)^2, the seed's n h^2)")
    p.add_argument("--measure-only", action="store_true",
                   help="run nothing: print each label's tilt less the free platelet's from the snapshots already there")
    p.add_argument("--rbfib", default=os.path.join(ROOT, "build", "bin", "rbfib"))
    a = p.parse_args()
    if a.end_ms <= 0:
        sys.exit(f"platelet_wall_tilt: --end-ms = {a.end_ms}: must be positive")
    labels = a.only or list(VARIANTS)
    for label in labels:
        if label not in VARIANTS:
            sys.exit(f"platelet_wall_tilt: --only {label}: not one of {', '.join(VARIANTS)}")
    if not os.access(a.rbfib, os.X_OK):
        sys.exit(f"platelet_wall_tilt: {a.rbfib} not built (make build)")
    h = 0.4 if a.quick else a.h_um
    n = 400 if a.quick else (a.sites or round(900 * (0.2 / h) ** 2))
    if h <= 0 or n < 16:
        sys.exit(f"platelet_wall_tilt: --h-um = {h}, --sites = {n}: need h > 0 and at least 16 sites")
    base = os.path.join(ROOT, "runs", "platelet_wall_tilt" + ("_quick" if a.quick else "" if (h, n) == (0.2, 900) else f"_h{h:g}_n{n}"))
    if a.measure_only:
        wall_part(base, labels)
        return
    at_ms = sorted({x for x in (0.25, 0.5, 1.0, 2.0, 4.0, 8.0) if x < a.end_ms * (1 - 1e-9)} | {a.end_ms})
    table = []
    for label in labels:
        y = VARIANTS[label]
        d = os.path.join(base, label)
        os.makedirs(d, exist_ok=True)
        scene = os.path.join(d, "scene.in.yaml")
        with open(scene, "w") as f:
            f.write(SCENE.format(label=label, y=y, h=h, n=n, end=a.end_ms, every=max(1, round(a.end_ms * 1000 / 80))))
        for old in glob.glob(os.path.join(d, "snapshots", "*.h5")):
            os.remove(old)
        t0 = time.monotonic()
        r = subprocess.run([a.rbfib, "run", scene, "--out", d], capture_output=True, text=True)
        seconds = time.monotonic() - t0
        if r.returncode != 0:
            sys.exit(f"platelet_wall_tilt: {label}: rbfib run failed ({r.returncode}):\n{r.stderr[-2000:]}")
        rows = measure(d)
        ts = np.array([q[0] for q in rows])
        tv, vol = volumes(d)
        row = {"label": label, "centre_um": y, "gap0_um": round(y - 0.5, 3), "seconds": round(seconds, 1)}
        for ms in at_ms:
            i = int(np.argmin(abs(ts - ms * 1e-3)))
            row[f"tilt_deg_{ms:g}ms"] = round(math.degrees(rows[i][1]), 3)
            row[f"gap_um_{ms:g}ms"] = round(rows[i][2], 4)
            row[f"jeffery_deg_{ms:g}ms"] = round(math.degrees(jeffery_tilt(rows[i][0])), 3)
            row[f"volume_change_{ms:g}ms"] = float(f"{vol[int(np.argmin(abs(tv - ms * 1e-3)))] / vol[0] - 1:.3e}")
        row["min_tilt_deg"] = round(min(math.degrees(q[1]) for q in rows), 3)
        table.append(row)
        print(", ".join(f"{k} {v}" for k, v in row.items()), flush=True)
    name = "summary.csv" if a.only is None else "summary_" + "_".join(labels) + ".csv"  # runs side by side keep theirs
    with open(os.path.join(base, name), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0]))
        w.writeheader()
        w.writerows(table)
    wall_part(base, labels)


if __name__ == "__main__":
    main()
