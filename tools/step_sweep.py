#!/usr/bin/python3
"""The coupled step's stability by a dt sweep: a scene stepped at fixed steps with eq. 5.4 off.

Takes a scene (and optionally a checkpoint to start from, a developed state), and for each step
size runs it with `build/bin/rbfib run` at that fixed step (no ladder, `stopping_condition: off`,
`output.stability: yes`) for a number of steps, then reads each run's diagnostics and says whether
the step held: a run is UNSTABLE when it stopped (a non-finite value, an inverted cell) or when the
forces' sign-flipping part (the growth guard's measure, lib/rbfib/sim/ib_step.hpp) pointed against
itself and grew for GUARD_STEPS steps in a row; else STABLE over the window. Beside it: the largest
||f||_inf against the first step's, eq. 5.4's bound at the end (for comparison only), which set the
peak force sat nearest (its share of the steps), and the seconds per step. The derivation's bounds
to compare with: docs/derivations/membrane_stability (README section 5).

    /usr/bin/python3 tools/step_sweep.py --scene SCENE.yaml [--start CHECKPOINT --keep "red cell"]
        --dt-ns 200 400 800 1600 --steps 60 --label NAME [--report FILE]

Run directories: runs/step_sweep/<label>/dt_<dt>ns/ (scene.yaml, diagnostics.csv, log.txt).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GUARD_STEPS, GUARD_GROWTH = 4, 1.05  # as AdaptiveStep's defaults


def checkpoint_time(path):
    """The simulated time (s) of a checkpoint (group fluid, attribute t)."""
    import h5py
    with h5py.File(path, "r") as f:
        return float(f["fluid"].attrs["t"])


def set_names(scene):
    """The Lagrangian sets in the order the step adds them: cell types with cells or kept, then point sets."""
    kept = set((scene.get("start") or {}).get("keep", []))
    with_cells = {c["type"] for c in scene.get("cells", [])}
    names = [t["name"] for t in scene.get("cell_types", []) if t["name"] in with_cells or t["name"] in kept]
    return names + [p["name"] for p in scene.get("tethered_points", [])]


def variant(base, dt_ns, steps, t0, start, keep):
    s = dict(base)
    t = {k: v for k, v in base["time"].items() if k not in ("adaptive", "dt", "end", "stopping_condition")}
    t.update({"dt": f"{dt_ns} ns", "end": f"{(t0 * 1e9 + steps * dt_ns) / 1e3:.6f} us", "stopping_condition": "off"})
    s["time"] = t
    s["output"] = {"diagnostics_every": 1, "stability": "yes"}
    if start:
        s["start"] = {"checkpoint": os.path.abspath(start), "keep": keep}
        # a run from a start adds the scene's cells: the kept types' cells come from the checkpoint
        s["cells"] = [c for c in base.get("cells", []) if c["type"] not in keep]
    s["name"] = f"{base.get('name', 'scene')}_dt{dt_ns}ns"
    return s


def flips(rows):
    """The longest run of consecutive steps whose sign-flipping part pointed back and grew."""
    best = run = 0
    for r in rows:
        g, c = float(r["oscillation_growth"]), float(r["oscillation_cosine"])
        run = run + 1 if (c < -0.5 and g > GUARD_GROWTH) else 0
        best = max(best, run)
    return best


def summarize(rows, log, names, rho=1.0):
    s = {"steps": len(rows)}
    stopped = [l for l in log.splitlines() if "stopped" in l]
    s["stopped"] = stopped[-1].split("stopped:", 1)[-1].strip()[:160] if stopped else ""
    if not rows:
        return s
    f = [float(r["max_force_density_dyn_cm3"]) for r in rows]
    s["f_growth"] = max(f) / f[0] if f[0] > 0 else math.nan
    s["eq54_bound_ns"] = float(rows[-1]["dt_bound_s"]) * 1e9
    s["flips"] = flips(rows)
    cos = [float(r["oscillation_cosine"]) for r in rows if r["oscillation_cosine"] not in ("nan", "")]
    s["min_cosine"] = min(cos) if cos else math.nan
    peaks = [int(float(r["peak_set"])) for r in rows]
    share = {}
    for p in peaks:
        share[p] = share.get(p, 0) + 1
    s["peak"] = ", ".join(f"{names[p] if 0 <= p < len(names) else p} {100 * n / len(peaks):.0f}%"
                          for p, n in sorted(share.items(), key=lambda kv: -kv[1]))
    secs = sorted(float(r["seconds_interpolation"]) + float(r["seconds_forces"]) + float(r["seconds_spreading"])
                  + float(r["seconds_fluid"]) for r in rows)
    s["seconds_per_step"] = secs[len(secs) // 2]
    s["verdict"] = "UNSTABLE" if (s["stopped"] or s["flips"] >= GUARD_STEPS) else "stable"
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--start", help="a checkpoint to start from (a developed state)")
    ap.add_argument("--keep", nargs="*", default=[], help="the cell types kept from the start")
    ap.add_argument("--dt-ns", nargs="+", type=float, required=True)
    ap.add_argument("--steps", type=int, default=60)
    ap.add_argument("--label", required=True)
    ap.add_argument("--report", help="append the table (markdown) to this file")
    a = ap.parse_args()
    with open(a.scene) as fh:
        base = yaml.safe_load(fh)
    t0 = checkpoint_time(a.start) if a.start else 0.0
    names = set_names(dict(base, start={"keep": a.keep}) if a.start else base)
    exe = os.path.join(ROOT, "build", "bin", "rbfib")
    lines = [f"### {a.label}: {a.steps} steps at each fixed dt from t = {t0 * 1e3:.4f} ms"
             f"{' (start: ' + os.path.basename(a.start) + ')' if a.start else ''}, eq. 5.4 off",
             "", "| dt (ns) | verdict | steps | stopped | longest flipping run | min cosine | max ||f|| / first | "
             "eq. 5.4 bound at end (ns) | peak force nearest | s per step |", "|---|---|---|---|---|---|---|---|---|---|"]
    for dt in a.dt_ns:
        dt_ns = int(dt) if float(dt).is_integer() else dt
        out = os.path.join(ROOT, "runs", "step_sweep", a.label, f"dt_{dt_ns}ns")
        os.makedirs(out, exist_ok=True)
        scene_path = os.path.join(out, "scene.yaml")
        with open(scene_path, "w") as fh:
            fh.write(f"# tools/step_sweep.py: {a.label}, dt = {dt_ns} ns\n")
            yaml.safe_dump(variant(base, dt_ns, a.steps, t0, a.start, a.keep), fh, sort_keys=False, default_flow_style=None)
        for old in ("checkpoint.h5", "diagnostics.csv"):
            if os.path.exists(os.path.join(out, old)):
                os.remove(os.path.join(out, old))
        t = time.time()
        p = subprocess.run([exe, "run", scene_path, "--out", out], capture_output=True, text=True)
        log = p.stdout + p.stderr
        with open(os.path.join(out, "log.txt"), "w") as fh:
            fh.write(log)
        rows = []
        if os.path.exists(os.path.join(out, "diagnostics.csv")):
            with open(os.path.join(out, "diagnostics.csv")) as fh:
                rows = list(csv.DictReader(fh))
        s = summarize(rows, log, names)
        print(f"dt = {dt_ns} ns: {s.get('verdict', 'NO STEPS')} after {s['steps']} steps ({time.time() - t:.0f} s)"
              f"{'; stopped: ' + s['stopped'] if s['stopped'] else ''}", flush=True)
        lines.append(f"| {dt_ns} | {s.get('verdict', 'no steps')} | {s['steps']} | {s['stopped'] or '-'} | {s.get('flips', '-')} | "
                     f"{s.get('min_cosine', math.nan):.3f} | {s.get('f_growth', math.nan):.3g} | {s.get('eq54_bound_ns', math.nan):.0f} | "
                     f"{s.get('peak', '-')} | {s.get('seconds_per_step', math.nan):.3g} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if a.report:
        with open(a.report, "a") as fh:
            fh.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
