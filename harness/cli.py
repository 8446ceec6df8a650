"""Command line: python3 -m harness run <study|chapter|all> [--scale quick|full] [options]."""
import argparse
import datetime
import filecmp
import json
import os
import shutil
import subprocess
import sys
import time

from . import HarnessError, catalog, checks, report

ROOT = os.environ.get("RBFIB_ROOT") or os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise HarnessError(message)


def positive_seconds(text):
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not v > 0:
        raise HarnessError(f"--sitting = '{text}': must be a positive number of seconds")
    return v


def parse(argv):
    p = Parser(prog="python3 -m harness", description="Run rbfib studies, compare with reference/, render reports/.")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run studies and render their reports")
    r.add_argument("target", help="a study name, a chapter (chapter2, appendixA, ...) or 'all'")
    r.add_argument("--scale", default="quick", help="quick (CI sizes, default) or full (the paper's sizes)")
    r.add_argument("--build", default=os.path.join(ROOT, "build"), help="CMake build directory with studies/")
    r.add_argument("--out", default=os.path.join(ROOT, "runs"), help="where run directories go")
    r.add_argument("--reports", default=os.path.join(ROOT, "reports"), help="where reports go")
    r.add_argument("--sitting", type=positive_seconds, default=None,
                   help="wall seconds this sitting may take: runs kept over sittings then save their checkpoints "
                        "and report how far they came (default: no limit)")
    r.add_argument("--no-run", action="store_true", help="render from the existing results.json, do not run the driver")
    r.add_argument("--gate", default="all", help="which failed checks fail the command: all (default: reports and "
                   "`make reproduce`) or correctness (`make test`: checks marked speed are printed, not gating)")
    k = sub.add_parser("keep", help="copy a study's checkpoints from its run directory into kept/ (to commit), so that "
                       "a later `run` on another machine continues where this one stopped")
    k.add_argument("target", help="a study name, a chapter or 'all'")
    k.add_argument("--scale", default="full", help="full (default) or quick")
    k.add_argument("--out", default=os.path.join(ROOT, "runs"), help="where run directories are")
    k.add_argument("--max-mib", type=float, default=5.0, help="checkpoints larger than this (MiB) are not kept (default 5)")
    sub.add_parser("list", help="list the studies")
    a = p.parse_args(argv)
    if a.command in ("run", "keep") and a.scale not in ("quick", "full"):
        raise HarnessError(f"--scale = '{a.scale}' is not one of: quick, full")
    if a.command == "run" and a.gate not in ("all", "correctness"):
        raise HarnessError(f"--gate = '{a.gate}' is not one of: all, correctness")
    return a


def git_commit():
    """The source's commit (short hash, "+changes" when tracked files differ); a copy of the tree
    without its git history (a build machine's) names it in RBFIB_COMMIT, else "unknown"."""
    fallback = os.environ.get("RBFIB_COMMIT", "unknown")
    try:
        out = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True, timeout=10)
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"], capture_output=True,
                               text=True, timeout=10)
        return out.stdout.strip() + ("+changes" if dirty.stdout.strip() else "") if out.returncode == 0 else fallback
    except (OSError, subprocess.SubprocessError):
        return fallback


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def openblas_core(env):
    """The OpenBLAS kernel set for this CPU's vector units, when the user has not chosen one.

    OpenBLAS picks its kernels from the CPU model at load time; on a virtual machine that reports
    a generic model (here "Intel(R) Xeon(R) Processor" with AVX-512) it falls back to its oldest
    x86-64 kernels (Prescott, SSE3): measured 17 GFlop/s for a square DGEMM on 2 cores, against
    66 with the Haswell (AVX2/FMA) and 109 with the SkylakeX (AVX-512) kernels. The choice follows
    the instruction sets the CPU reports; a value already set in the environment is kept."""
    if env.get("OPENBLAS_CORETYPE"):
        return None
    flags = cpu_flags()
    if {"avx512f", "avx512bw", "avx512dq", "avx512vl"} <= flags:
        return "SkylakeX"
    if {"avx2", "fma"} <= flags:
        return "Haswell"
    return None


KEPT = os.path.join(ROOT, "kept")


def checkpoints(folder):
    """Paths (relative to folder) of the checkpoints (*.h5) under it, sorted."""
    out = []
    for d, _, files in os.walk(folder):
        out += [os.path.relpath(os.path.join(d, f), folder) for f in files if f.endswith(".h5")]
    return sorted(out)


def keep_study(name, scale, runs, max_mib=5.0):
    """Copies the checkpoints of runs/<name>/<scale> into kept/<name>/<scale> (replacing older copies).

    A checkpoint larger than max_mib is not kept (the repository is no place for a grid of the seed's
    size): it is named, an older kept copy of it is removed (the run has moved on from it), and its
    run continues only where it was written."""
    src, dst = os.path.join(runs, name, scale), os.path.join(KEPT, name, scale)
    files = checkpoints(src)
    if not files:
        print(f"harness: {name}: no checkpoints under {src}")
        return
    large = [rel for rel in files if os.path.getsize(os.path.join(src, rel)) > max_mib * 2**20]
    for rel in large:
        print(f"harness: {name}: not kept: {rel} ({os.path.getsize(os.path.join(src, rel)) / 2**20:.0f} MiB, "
              f"above --max-mib {max_mib:g}); its run continues only on this machine")
        if os.path.exists(os.path.join(dst, rel)):
            os.remove(os.path.join(dst, rel))
    files = [rel for rel in files if rel not in large]
    # Only the checkpoints that differ from their kept copies are copied: each one committed adds its
    # whole size to the repository's history, so a run's checkpoint is best kept once a sitting.
    changed = [rel for rel in files if not os.path.exists(os.path.join(dst, rel))
               or not filecmp.cmp(os.path.join(src, rel), os.path.join(dst, rel), shallow=False)]
    for rel in changed:
        os.makedirs(os.path.dirname(os.path.join(dst, rel)), exist_ok=True)
        shutil.copy2(os.path.join(src, rel), os.path.join(dst, rel))
    size = sum(os.path.getsize(os.path.join(dst, rel)) for rel in files)
    new = sum(os.path.getsize(os.path.join(dst, rel)) for rel in changed)
    print(f"harness: {name}: kept {len(files)} checkpoints ({size / 2**20:.1f} MiB) in {dst}; "
          f"{len(changed)} new or changed ({new / 2**20:.1f} MiB): {', '.join(changed) or 'none'}")
    return changed


def continue_from_kept(name, scale, run_dir):
    """Copies kept checkpoints (kept/<name>/<scale>) that the run directory lacks into it, so that a
    run started on another machine continues; a checkpoint already in the run directory is newer."""
    src = os.path.join(KEPT, name, scale)
    taken = [rel for rel in checkpoints(src) if not os.path.exists(os.path.join(run_dir, rel))]
    for rel in taken:
        os.makedirs(os.path.dirname(os.path.join(run_dir, rel)), exist_ok=True)
        shutil.copy2(os.path.join(src, rel), os.path.join(run_dir, rel))
    if taken:
        print(f"harness: {name}: continuing from {len(taken)} kept checkpoints ({src})", flush=True)


def run_study(meta, args):
    name = meta["name"]
    ref = catalog.reference(ROOT, name)  # validate before spending time on the run
    run_dir = os.path.join(args.out, name, args.scale)
    os.makedirs(run_dir, exist_ok=True)
    info = {"commit": git_commit(), "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}
    results_path = os.path.join(run_dir, "results.json")
    if not args.no_run:
        exe = os.path.join(args.build, "studies", f"study_{name}")
        if not os.path.isfile(exe):
            raise HarnessError(f"study '{name}': driver {exe} not built (run `make build`)")
        if os.path.exists(results_path):
            os.remove(results_path)
        if args.scale == "full":
            continue_from_kept(name, args.scale, run_dir)
        print(f"harness: running {name} at {args.scale} scale -> {run_dir}", flush=True)
        t0 = time.monotonic()
        # Recorded because it changes timings: on a loaded machine OMP_WAIT_POLICY=PASSIVE keeps a
        # spinning OpenMP team from waiting on a descheduled thread; on a quiet one the default is faster.
        info["omp_wait_policy"] = os.environ.get("OMP_WAIT_POLICY", "default")
        # A fixed team (OMP_NUM_THREADS) or one sized to the cores other programs leave free.
        info["omp_team"] = f"fixed at {os.environ['OMP_NUM_THREADS']}" if os.environ.get("OMP_NUM_THREADS") else "sized to the free cores"
        env = dict(os.environ)
        core = openblas_core(env)
        if core:
            env["OPENBLAS_CORETYPE"] = core
        info["openblas_coretype"] = env.get("OPENBLAS_CORETYPE", "unset (OpenBLAS's own detection)")
        info["driver_hash"] = catalog.driver_hash(ROOT, name)  # the sources that computed these results
        # The commit (drivers that keep partial runs record it with them), the source tree (stored
        # inputs) and the sitting's wall time are the driver's options, not its environment.
        command = [exe, "--scale", args.scale, "--out", run_dir, "--commit", info["commit"], "--source", ROOT]
        if args.sitting:
            command += ["--sitting", str(args.sitting)]
            info["sitting_seconds"] = args.sitting
        proc = subprocess.run(command, env=env)
        info["seconds"] = time.monotonic() - t0
        if proc.returncode != 0:
            raise HarnessError(f"study '{name}': driver exited with status {proc.returncode}")
        with open(os.path.join(run_dir, "run.json"), "w") as f:
            json.dump(info, f)
    else:
        info.update(earlier_run_info(run_dir, report_dir(args, name)))
    if not os.path.isfile(results_path):
        raise HarnessError(f"study '{name}': no results file {results_path}")
    try:
        with open(results_path) as f:
            results = json.load(f)
    except json.JSONDecodeError as e:
        raise HarnessError(f"study '{name}': {results_path} is not valid JSON: {e}")
    if results.get("study") != name:
        raise HarnessError(f"study '{name}': {results_path} is for study '{results.get('study')}'")
    outcome = checks.evaluate(ref, results)
    if not info.get("driver_hash"):  # a report older than the hash: the sources at its commit
        info["driver_hash"] = catalog.driver_hash_at(ROOT, name, info.get("commit")) or "unknown"
    info["reference_hash"] = catalog.reference_hash(ROOT, name)
    out_dir = report_dir(args, name)
    summary = report.render(meta, ref, results, outcome, out_dir, info)
    for c in outcome:
        print(f"  {c['status']:7s} {c['id']}{' (speed)' if c['speed'] else ''}: {c['detail']}")
    gating = [c for c in outcome if c["status"] == "FAIL" and not (args.gate == "correctness" and c["speed"])]
    summary["gating_failures"] = len(gating)
    note = ""
    if summary["failed"] > len(gating):
        note = f" ({summary['failed'] - len(gating)} of them speed checks, reported but not gating here)"
    print(f"harness: {name}: {summary['passed']} passed, {summary['failed']} failed{note}, {summary['differs']} known differences, "
          f"{summary['not_run']} not run; report {os.path.join(out_dir, 'README.md')}", flush=True)
    return summary


def report_dir(args, name):
    """Quick reports in reports/<name>, full-scale ones beside them in reports/<name>-full."""
    return os.path.join(args.reports, name if args.scale == "quick" else f"{name}-{args.scale}")


def earlier_run_info(run_dir, out_dir):
    """What the run being re-rendered recorded (commit, date, wall time, driver hash): its run.json,
    else the run record of the report rendered from it before."""
    for path, key in ((os.path.join(run_dir, "run.json"), None), (os.path.join(out_dir, "summary.json"), "run")):
        try:
            with open(path) as f:
                doc = json.load(f)
            if key is None:
                return doc
            return doc.get(key) or {k: doc[k] for k in ("commit", "date", "seconds") if k in doc}
        except (OSError, json.JSONDecodeError):
            continue
    return {}


def main(argv):
    try:
        args = parse(argv)
        if args.command == "list":
            for m in catalog.studies(ROOT).values():
                print(f"{m['name']:28s} {m['chapter']:10s} {m['title']}")
            return 0
        selected = catalog.select(ROOT, args.target)
        if args.command == "keep":
            for m in selected:
                keep_study(m["name"], args.scale, args.out, args.max_mib)
            return 0
        summaries, broken = [], []
        for m in selected:
            if len(selected) == 1:
                summaries.append(run_study(m, args))
                continue
            try:  # with several studies, one that cannot run does not stop the others
                summaries.append(run_study(m, args))
            except HarnessError as e:
                print(f"harness: error: {e}", file=sys.stderr)
                broken.append(m["name"])
        os.makedirs(args.reports, exist_ok=True)
        report.render_index(args.reports, ROOT)
        passed = sum(s["passed"] for s in summaries)
        failed = sum(s["failed"] for s in summaries)
        gating = sum(s["gating_failures"] for s in summaries)
        print(f"harness: {len(summaries)} studies: {passed} passed, {failed} failed"
              + (f" ({failed - gating} speed checks, not gating)" if failed > gating else "")
              + (f"; could not run: {', '.join(broken)}" if broken else ""))
        stale = report.stale_reports(ROOT, args.reports)
        if stale:
            print(f"harness: STALE reports (their driver or reference changed since they were made; rerun them): "
                  + "; ".join(f"{d} ({why})" for d, why in stale))
        return 2 if broken else (1 if gating else 0)
    except HarnessError as e:
        print(f"harness: error: {e}", file=sys.stderr)
        return 2
