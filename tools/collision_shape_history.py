#!/usr/bin/python3
"""How a collision run's cells change shape over time (Fig. 5.3), between the moments the study keeps.

chapter5_collision records each cell's depth along the push d = (e1 + e3)/sqrt 2 over its width
along e2 (the figure's view, from above the plane x = z) at t = 0, at the figure's time and at the
end only. This tool reruns one of its runs from the scene the study kept
(runs/chapter5_collision/full/<setup>/<orientation>/scene.yaml, the same scene, step ladder and
eq. 5.4) with `build/bin/rbfib run` to --end-ms, a snapshot every --every-us, and prints from the
snapshots' sample sites each cell's extents along d, e2 and (e1 - e3)/sqrt 2 (the line of sight)
and depth over width, as the study's shapes table does (extents about the sites' mean, nearest
periodic image in x and z):

    /usr/bin/python3 tools/collision_shape_history.py [--setup h0.5] [--orientation c-d] [--end-ms 1.5] [--every-us 50]

The run goes to runs/collision_shape_history/<setup>_<orientation>/ and the table to stdout and
summary.csv there. --measure-only prints the table from the snapshots already there.
"""
import argparse
import csv
import glob
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

D = np.array([1.0, 0.0, 1.0]) / math.sqrt(2)  # the push, along the line of centres
E2 = np.array([0.0, 1.0, 0.0])                 # the figure's width
VIEW = np.array([1.0, 0.0, -1.0]) / math.sqrt(2)  # the line of sight
BOX_CM = 16e-4                                 # the study's box; periodic in x and z


def extents(X):
    """Extents (um) of the sites X (n x 3, cm) along D, E2, VIEW, about their mean."""
    r = X - X.mean(axis=0)
    for a in (0, 2):
        r[:, a] -= BOX_CM * np.round(r[:, a] / BOX_CM)
    return [float(np.ptp(r @ v)) * 1e4 for v in (D, E2, VIEW)]


def measure(run_dir):
    """Rows (t us, cell, depth, width_y, width_across, depth/width) per snapshot and cell."""
    rows = []
    for f in sorted(glob.glob(os.path.join(run_dir, "snapshots", "*.h5"))):
        with h5py.File(f, "r") as h:
            t = float(h.attrs["t"])
            X = np.array(h["cells/0/points"][()], dtype=float)  # the one type's sites, cell after cell
            n = len(X) // 2
            for c in (0, 1):
                dep, wy, wa = extents(X[c * n:(c + 1) * n])
                rows.append((t * 1e6, c + 1, dep, wy, wa, dep / wy))
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--setup", default="h0.5")
    p.add_argument("--orientation", default="c-d")
    p.add_argument("--end-ms", type=float, default=1.5)
    p.add_argument("--every-us", type=float, default=50.0)
    p.add_argument("--runs", default="runs/chapter5_collision/full", help="where the study's runs are")
    p.add_argument("--rbfib", default="build/bin/rbfib")
    p.add_argument("--measure-only", action="store_true", help="run nothing: the table from the snapshots already there")
    a = p.parse_args()
    if a.end_ms <= 0 or a.every_us <= 0:
        sys.exit(f"collision_shape_history: --end-ms ({a.end_ms}) and --every-us ({a.every_us}) must be positive")
    out = os.path.join("runs", "collision_shape_history", f"{a.setup}_{a.orientation}")
    if not a.measure_only:
        source = os.path.join(a.runs, a.setup, a.orientation, "scene.yaml")
        if not os.path.exists(source):
            sys.exit(f"collision_shape_history: no scene at {source}: run `make reproduce-chapter5_collision SCALE=full` first")
        text = open(source).read()
        text, n = re.subn(r"^output:.*$", f"output: {{diagnostics_every: 50, snapshot_every: {a.every_us:g} us}}", text, flags=re.M)
        if n != 1:
            sys.exit(f"collision_shape_history: {source}: expected one 'output:' line, found {n}")
        os.makedirs(out, exist_ok=True)
        for old in glob.glob(os.path.join(out, "snapshots", "*.h5")):
            os.remove(old)
        scene = os.path.join(out, "scene.in.yaml")
        with open(scene, "w") as f:
            f.write(text)
        r = subprocess.run([a.rbfib, "run", scene, "--out", out, "--until", f"{a.end_ms:g} ms"], capture_output=True, text=True)
        if r.returncode not in (0, 3):  # 3: a numerical stop (eq. 5.4); its snapshots up to it stand
            sys.exit(f"collision_shape_history: rbfib run failed ({r.returncode}):\n{r.stderr[-2000:]}")
        if r.returncode == 3:
            print("rbfib run stopped:", r.stdout.strip().splitlines()[-1] if r.stdout.strip() else r.stderr.strip()[-400:])
    rows = measure(out)
    if not rows:
        sys.exit(f"collision_shape_history: no snapshots in {out}/snapshots")
    head = ["t_us", "cell", "depth_um", "width_y_um", "width_across_um", "depth_over_width"]
    with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
        csv.writer(f).writerows([head] + [list(r) for r in rows])
    print(f"{a.setup} {a.orientation}: each cell's extents over its sample sites (um); depth along d, widths along e2 and the line of sight")
    print("  ".join(f"{h:>15}" for h in head))
    for r in rows:
        print("  ".join(f"{v:15.4g}" for v in r))


if __name__ == "__main__":
    main()
