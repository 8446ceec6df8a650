"""Renders reports/<study>/README.md (tables beside the paper's, checks, figures as PNG) and the
index reports/README.md."""
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import catalog  # noqa: E402
from .checks import CheckError, Table, fmt, tables  # noqa: E402

MAX_ROWS_SHOWN = 40


def _cell(v):
    if v is None:
        return "-"
    if isinstance(v, float):
        if v != 0 and (abs(v) < 1e-3 or abs(v) >= 1e6):
            return f"{v:.4e}"
        return f"{v:.9g}"
    return str(v)


def markdown_table(columns, rows):
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        lines.append("| " + " | ".join(_cell(v) for v in r) + " |")
    return "\n".join(lines)


def _header(t):
    return [f"{c} ({u})" if u else c for c, u in zip(t.columns, t.units)]


def paper_beside_ours(pt, ours):
    """The paper's table with, for each matched column, our value and the relative difference."""
    match = pt.get("match", {})
    cols = list(pt["columns"])
    out_cols = []
    for c in cols:
        out_cols.append(f"{c} (paper)" if c in match else c)
        if c in match:
            out_cols += [f"{match[c]} (ours)", "rel. diff"]
    rows = []
    for i, prow in enumerate(pt["rows"]):
        row = []
        for c, pv in zip(cols, prow):
            row.append(pv)
            if c in match:
                ov = None
                if ours is not None and i < len(ours.rows) and match[c] in ours.columns:
                    ov = ours.rows[i][ours.columns.index(match[c])]
                row.append(ov)
                if isinstance(ov, (int, float)) and isinstance(pv, (int, float)) and pv:
                    row.append(f"{(ov - pv) / abs(pv):+.2e}")
                else:
                    row.append("-")
        rows.append(row)
    return markdown_table(out_cols, rows)


def figure(fig_spec, tabs, out_dir):
    t = tabs.get(fig_spec["table"])
    if t is None:
        return None, f"figure '{fig_spec['id']}': no table '{fig_spec['table']}' in the results"
    ys = fig_spec["y"] if isinstance(fig_spec["y"], list) else [fig_spec["y"]]
    gcols = fig_spec.get("group") or []
    gcols = gcols if isinstance(gcols, list) else [gcols]
    for c in [fig_spec["x"]] + ys + gcols:
        if c not in t.columns:
            return None, f"figure '{fig_spec['id']}': table '{t.id}' has no column '{c}'"
    try:
        rows = t.select(fig_spec.get("where"))
    except CheckError as e:
        return None, f"figure '{fig_spec['id']}': {e}"
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    xi = t.columns.index(fig_spec["x"])
    gidx = [t.columns.index(c) for c in gcols]
    key = lambda r: ", ".join(str(r[i]) for i in gidx)  # noqa: E731
    groups = list(dict.fromkeys(key(r) for r in rows)) if gidx else [None]
    for g in groups:
        sub = rows if g is None else [r for r in rows if key(r) == g]
        for y in ys:
            yi = t.columns.index(y)
            pts = [(r[xi], r[yi]) for r in sub if isinstance(r[xi], (int, float)) and isinstance(r[yi], (int, float))]
            if fig_spec.get("logy"):
                pts = [(a, abs(b)) for a, b in pts if b != 0]
            if not pts:
                continue
            label = " ".join(str(s) for s in ([g] if g is not None else []) + ([y] if len(ys) > 1 else []))
            ax.plot([p[0] for p in pts], [p[1] for p in pts], fig_spec.get("style", "o-"), label=label or None, ms=4)
    if fig_spec.get("logx"):
        ax.set_xscale("log")
    if fig_spec.get("logy"):
        ax.set_yscale("log")
    if fig_spec.get("aspect") == "equal":
        ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(fig_spec.get("xlabel", fig_spec["x"]))
    ax.set_ylabel(fig_spec.get("ylabel", ", ".join(ys)))
    ax.set_title(fig_spec.get("title", fig_spec["id"]), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    fig.tight_layout()
    name = f"{fig_spec['id']}.png"
    fig.savefig(os.path.join(out_dir, name), dpi=110)
    plt.close(fig)
    return name, None


def render(meta, ref, results, outcome, out_dir, run_info):
    os.makedirs(out_dir, exist_ok=True)
    tabs = tables(results)
    prov = results.get("provenance", {})
    passed = sum(c["status"] == "PASS" for c in outcome)
    failed = sum(c["status"] == "FAIL" for c in outcome)
    differs = sum(c["status"] == "DIFFERS" for c in outcome)
    not_run = sum(c["status"] == "NOT RUN" for c in outcome)
    # Checks of the other scale belong to its report: named under the table, not counted here.
    other_scale = [c for c in outcome if c["status"] == "OTHER SCALE"]
    other = "full" if results.get("scale") == "quick" else "quick"
    outcome = [c for c in outcome if c["status"] != "OTHER SCALE"]
    L = [f"# {ref.get('title', meta['title'])}", ""]
    L.append(f"Study `{meta['name']}` ({meta['chapter']}): reproduces {', '.join(meta['reproduces'])}. "
             f"Source: {ref['source']}.")
    L.append("")
    L.append(meta["description"].strip())
    L.append("")
    L.append(f"**Scale: {results.get('scale', '?')}.** Checks: **{passed} passed, {failed} failed**"
             + (f", {differs} known difference{'s' if differs > 1 else ''} from the paper (see below)" if differs else "")
             + (f", {not_run} not run (each line says which run has not finished)." if not_run else ".")
             + (f" {len(other_scale)} more {'checks belong' if len(other_scale) > 1 else 'check belongs'} to the {other} scale's report."
                if other_scale else ""))
    L.append("")
    L.append(f"Ran on {prov.get('cpu', '?')} ({prov.get('threads', '?')} threads of {prov.get('hardware_threads', '?')})"
             + (f" with the GPU {prov['gpu']}" if prov.get('gpu') else "") + ", "
             f"backend {prov.get('backend', '?')}, {prov.get('compiler', '?')}, commit {run_info.get('commit', '?')}, "
             f"{run_info.get('date', '?')}; OMP_WAIT_POLICY={run_info.get('omp_wait_policy', 'unset')}; "
             f"OpenMP team {run_info.get('omp_team', 'not recorded')}; "
             f"OPENBLAS_CORETYPE={run_info.get('openblas_coretype', 'not recorded')}; "
             f"driver wall time {run_info.get('seconds') or 0:.1f} s; driver sources {run_info.get('driver_hash', 'unknown')}, "
             f"reference {run_info.get('reference_hash', 'unknown')} (the index marks the report STALE when they change).")
    L.append("")
    runs = results.get("runs") or {}
    if runs:
        keys = ["finished", "progress", "simulated", "steps", "seconds_per_step", "mean_dt_ns", "hours_to_go", "stopped"]
        keys = [k for k in keys if any(k in r for r in runs.values())]
        L += ["## Runs", "", "The resumable runs these results come from; a check that measures an unfinished run is NOT RUN.", "",
              markdown_table(["run"] + keys, [[rid] + [r.get(k) for k in keys] for rid, r in runs.items()]), ""]
    L += ["## Checks", "", markdown_table(["check", "source", "result", "detail"],
                                          [[c["id"] + (" (speed)" if c.get("speed") else ""), c["source"],
                                            c["status"] if c["passed"] else f"**{c['status']}**",
                                            c["detail"]] for c in outcome]), ""]
    if other_scale:
        L += [f"Checks of the {other} scale, evaluated in [its report](../{meta['name'] + ('' if other == 'quick' else '-' + other)}/README.md) "
              f"and not here: " + ", ".join(f"`{c['id']}`" for c in other_scale) + ".", ""]
    if any(c.get("speed") for c in outcome):
        L += ["Checks marked (speed) measure speed: they count here and in `make reproduce`, but `make test` "
              "prints them without failing on them (timings move with the machine's load).", ""]
    known = [c for c in outcome if c["status"] == "DIFFERS"]
    if known:
        L += ["### Known differences from the paper", "",
              "These checks fail as written; the difference is investigated and explained, not tuned away:", ""]
        L += [f"- **{c['id']}**: {c['known_difference'].strip()}" for c in known]
        L.append("")
    if ref.get("conventions"):
        L += ["## Conventions and choices", ""]
        for k, v in ref["conventions"].items():
            L.append(f"- **{k}**: {str(v).strip()}")
        L.append("")
    if ref.get("paper_tables"):
        L += ["## The paper's tables beside ours", ""]
        for pt in ref["paper_tables"]:
            L += [f"### {pt['source']} (ours: `{pt['id']}`)", "", paper_beside_ours(pt, tabs.get(pt["id"])), ""]
    # A figure with `scales: [...]` is drawn in the reports of those scales only.
    figs = [f for f in ref.get("figures", []) or [] if f.get("scales") is None or results.get("scale") in f["scales"]]
    if figs:
        L += ["## Figures", ""]
        for f in figs:
            name, err = figure(f, tabs, out_dir)
            L += [f"![{f.get('title', f['id'])}]({name})" if name else f"_{err}_", ""]
            if f.get("caption"):
                L += [f["caption"].strip(), ""]
    L += ["## Our tables", ""]
    for tid, t in tabs.items():
        L.append(f"### `{tid}`")
        L.append("")
        if len(t.rows) > MAX_ROWS_SHOWN:
            L.append(f"{len(t.rows)} rows (in results.json); the first {MAX_ROWS_SHOWN}:")
            L.append("")
        L += [markdown_table(_header(t), t.rows[:MAX_ROWS_SHOWN]), ""]
    if results.get("parameters"):
        L += ["## Parameters", ""]
        for k, v in results["parameters"].items():
            L.append(f"- `{k}`: {v}")
        L.append("")
    with open(os.path.join(out_dir, "README.md"), "w") as f:
        f.write("\n".join(L))
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    summary = {"study": meta["name"], "chapter": meta["chapter"], "title": meta["title"], "scale": results.get("scale"),
               "passed": passed, "failed": failed, "differs": differs, "not_run": not_run, "date": run_info.get("date"),
               "commit": run_info.get("commit"), "seconds": run_info.get("seconds"),
               "driver_hash": run_info.get("driver_hash"), "reference_hash": run_info.get("reference_hash"),
               "run": {k: v for k, v in run_info.items() if k not in ("reference_hash",)}}
    with open(os.path.join(out_dir, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    return summary


def _summaries(reports_dir):
    for name in sorted(os.listdir(reports_dir)):
        p = os.path.join(reports_dir, name, "summary.json")
        if os.path.isfile(p):
            with open(p) as f:
                yield name, json.load(f)


def staleness(root, s):
    """Why a report no longer matches the sources (its driver's folder or its reference file
    changed since it was made), or "" when it is current."""
    name = s["study"]
    if not os.path.isfile(os.path.join(root, "reference", f"{name}.yaml")):
        return "its study no longer exists"
    why = []
    if s.get("driver_hash") in (None, "unknown"):
        why.append("no record of the driver's sources")
    elif s["driver_hash"] != catalog.driver_hash(root, name):
        why.append("driver changed since the run")
    if s.get("reference_hash") != catalog.reference_hash(root, name):
        why.append("reference changed since the report")
    return ", ".join(why)


def stale_reports(root, reports_dir):
    """[(report folder, why)] for every stale report under reports_dir."""
    return [(d, why) for d, s in _summaries(reports_dir) if (why := staleness(root, s))]


def render_index(reports_dir, root):
    rows = []
    for name, s in _summaries(reports_dir):
        why = staleness(root, s)
        rows.append([f"[{s['study']}]({name}/README.md)", s["chapter"], s["title"], s["scale"],
                     f"{s['passed']} passed, {s['failed']} failed"
                     + (f", {s['differs']} known differences" if s.get("differs") else "")
                     + (f", {s['not_run']} not run" if s.get("not_run") else ""),
                     f"**STALE**: {why}" if why else "current",
                     f"{s.get('seconds') or 0:.0f} s", s.get("date", "")])
    L = ["# Reports", "", "Rendered by `make reproduce` (quick scale) or `make reproduce-NAME SCALE=full`. A report is "
         "STALE when its driver's sources (`studies/<name>/`) or its reference file changed after it was made.", "",
         markdown_table(["study", "chapter", "what", "scale", "checks", "sources", "driver time", "date"], rows), ""]
    with open(os.path.join(reports_dir, "README.md"), "w") as f:
        f.write("\n".join(L))
