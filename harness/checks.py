"""Evaluates the checks of a reference file against a study's results.json.

Each check returns (passed, detail); a check that cannot be evaluated (missing table or column,
null values) fails with a detail saying what is missing.
"""
import math

from . import HarnessError


class Table:
    def __init__(self, tid, doc):
        if not isinstance(doc, dict) or "columns" not in doc or "rows" not in doc:
            raise HarnessError(f"results: table '{tid}' lacks 'columns' or 'rows'")
        self.id = tid
        self.columns = list(doc["columns"])
        self.units = list(doc.get("units", [""] * len(self.columns)))
        self.rows = [list(r) for r in doc["rows"]]
        for r in self.rows:
            if len(r) != len(self.columns):
                raise HarnessError(f"results: table '{tid}' has a row of {len(r)} entries for {len(self.columns)} columns")

    def col(self, name):
        if name not in self.columns:
            raise CheckError(f"table '{self.id}' has no column '{name}' (has {', '.join(self.columns)})")
        return self.columns.index(name)

    def select(self, where):
        rows = self.rows
        for key, want in (where or {}).items():
            j = self.col(key)
            rows = [r for r in rows if r[j] == want]
        return rows

    def column(self, name, where=None):
        j = self.col(name)
        return [r[j] for r in self.select(where)]


class CheckError(Exception):
    pass


def tables(results):
    return {tid: Table(tid, doc) for tid, doc in (results.get("tables") or {}).items()}


def _table(tabs, check):
    tid = check.get("table")
    if tid not in tabs:
        raise CheckError(f"results have no table '{tid}'")
    return tabs[tid]


def _numbers(values, what):
    for v in values:
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
            raise CheckError(f"{what} holds a non-number ({v!r})")
    return values


def fmt(x):
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def check_value(tabs, results, c):
    if "table" in c:
        ours = _numbers(_table(tabs, c).column(c["column"], c.get("where")), f"column '{c['column']}'")
    else:
        ours = _numbers([results.get("values", {}).get(c["value"])], f"value '{c['value']}'")
    paper = c["paper"] if isinstance(c["paper"], list) else [c["paper"]]
    if len(ours) < len(paper):
        raise CheckError(f"{len(ours)} rows for {len(paper)} paper values")
    worst, ok = 0.0, True
    for o, p in zip(ours, paper):
        if "sig_digits" in c:
            tol = 0.5 * 10 ** (math.floor(math.log10(abs(p))) - int(c["sig_digits"]) + 1)
        else:
            tol = c.get("atol", 0.0) + c.get("rtol", 0.0) * abs(p)
        ok = ok and abs(o - p) <= tol
        worst = max(worst, abs(o - p) / abs(p) if p else abs(o - p))
    rule = f"{c['sig_digits']} significant digits" if "sig_digits" in c else f"rtol {c.get('rtol', 0)}, atol {c.get('atol', 0)}"
    detail = f"ours {', '.join(fmt(o) for o in ours[:len(paper)])}; paper {', '.join(fmt(p) for p in paper)}; " \
             f"max relative difference {worst:.2e} ({rule})"
    return ok, detail


def orders(x, y, invert=False, floor=0.0):
    """p_k = log(y_k / y_{k+1}) / log(x_k / x_{k+1}) (x_{k+1} / x_k with invert), stopping at the floor."""
    ps = []
    for k in range(len(x) - 1):
        if y[k] <= floor or y[k + 1] <= floor:
            break
        rx = x[k + 1] / x[k] if invert else x[k] / x[k + 1]
        if rx <= 0 or rx == 1:
            raise CheckError(f"resolution column does not change monotonically ({x[k]} then {x[k + 1]}); use 'where' or 'by'")
        ps.append(math.log(y[k] / y[k + 1]) / math.log(rx))
    return ps


def check_order(tabs, results, c):
    """Orders from consecutive rows; with `by: column`, separately for each value of that column."""
    t = _table(tabs, c)
    if c.get("by"):
        verdicts = []
        for g in dict.fromkeys(t.column(c["by"], c.get("where"))):
            sub = dict(c, by=None, where=dict(c.get("where") or {}, **{c["by"]: g}))
            ok, detail = check_order(tabs, results, sub)
            verdicts.append((ok, f"[{g}] {detail}"))
        return all(v[0] for v in verdicts), "; ".join(v[1] for v in verdicts)
    x = _numbers(t.column(c["x"], c.get("where")), f"column '{c['x']}'")
    y = _numbers(t.column(c["y"], c.get("where")), f"column '{c['y']}'")
    ps = orders(x, y, c.get("invert", False), c.get("floor", 0.0))
    if not ps:
        raise CheckError("fewer than two usable rows to measure an order")
    use = c.get("use", "all")
    picked = {"all": ps, "last": ps[-1:], "mean": [sum(ps) / len(ps)]}.get(use)
    if picked is None:
        raise HarnessError(f"check '{c['id']}': use = '{use}' is not one of all, last, mean")
    expected = c.get("expected")
    ok = True
    if expected is not None:
        exp = expected if isinstance(expected, list) else [expected] * len(picked)
        if use == "all" and len(exp) < len(picked):
            picked = picked[:len(exp)]
        ok = all(abs(p - e) <= c["tol"] for p, e in zip(picked, exp))
        rule = f"expected {', '.join(fmt(e) for e in exp[:len(picked)])} +- {c['tol']}"
    else:
        rule = ""
    if "min" in c:
        ok = ok and all(p >= c["min"] for p in picked)
        rule += (", " if rule else "") + f"at least {c['min']}"
    if "max" in c:
        ok = ok and all(p <= c["max"] for p in picked)
        rule += (", " if rule else "") + f"at most {c['max']}"
    detail = f"measured orders {', '.join(f'{p:.5f}' for p in ps)} (checked: {use}); {rule}"
    return ok, detail


def check_bound(tabs, results, c):
    if "table" in c:
        vals = _numbers(_table(tabs, c).column(c["column"], c.get("where")), f"column '{c['column']}'")
        what = f"{c['table']}.{c['column']}"
    else:
        vals = _numbers([results.get("values", {}).get(c["value"])], f"value '{c['value']}'")
        what = c["value"]
    if not vals:
        raise CheckError(f"no rows selected from {what}")
    ok = True
    rule = []
    if "max" in c:
        ok = ok and max(vals) <= c["max"]
        rule.append(f"<= {c['max']:g}")
    if "min" in c:
        ok = ok and min(vals) >= c["min"]
        rule.append(f">= {c['min']:g}")
    if not rule:
        raise HarnessError(f"check '{c['id']}': a bound needs 'max' or 'min'")
    return ok, f"{what}: range [{min(vals):.3g}, {max(vals):.3g}] over {len(vals)} entries; required {' and '.join(rule)}"


KINDS = {"value": check_value, "order": check_order, "bound": check_bound}


def _run_line(rid, run):
    """'run X unfinished: 29% (8.8 of 30 ms), 0.045 s per step, about 7.1 hours to go here'."""
    if run is None:
        return f"run '{rid}' is not recorded in the results"
    bits = []
    if isinstance(run.get("progress"), (int, float)):
        bits.append(f"{100 * run['progress']:.3g}% done")
    if run.get("simulated"):
        bits.append(str(run["simulated"]))
    if isinstance(run.get("seconds_per_step"), (int, float)) and math.isfinite(run["seconds_per_step"]):
        bits.append(f"{run['seconds_per_step']:.3g} s per step")
    hours = run.get("hours_to_go")
    if isinstance(hours, (int, float)) and math.isfinite(hours):
        bits.append(f"about {hours:.3g} hours to go here")
    return f"run '{rid}' unfinished" + (f" ({', '.join(bits)})" if bits else "")


def unfinished_runs(results, c):
    """Why a check that measures resumable runs (`run: id`, a list of ids, or a mapping from scale to
    either) cannot be judged yet:
    one line per run that is unrecorded or not finished; empty when every run has finished."""
    ids = c.get("run")
    if isinstance(ids, dict):  # per scale: {quick: [...], full: [...]}
        ids = ids.get(results.get("scale"))
    if ids is None:
        return []
    ids = ids if isinstance(ids, list) else [ids]
    runs = results.get("runs") or {}
    return [_run_line(r, runs.get(r)) for r in ids if not (runs.get(r) or {}).get("finished")]


def _outcome(c, status, passed, detail):
    return {"id": c["id"], "source": c["source"], "kind": c["kind"], "passed": bool(passed), "status": status,
            "detail": detail, "why": c.get("why", ""), "known_difference": c.get("known_difference", ""),
            "speed": bool(c.get("speed", False))}


def evaluate(reference, results):
    """List of dicts: id, source, kind, passed, status, detail, speed.

    status is one of:
    - PASS;
    - FAIL: the check failed, or it could not be evaluated (a table, column or value missing, null,
      NaN or infinite: a value never measured never passes, with or without a known difference);
    - DIFFERS: a check that was evaluated and failed, whose reference carries `known_difference`
      (the investigated reason our number differs from the paper's); it does not fail the run;
    - OTHER SCALE: a check with `scales: [...]` that do not include the results' scale: it belongs
      to the other scale's report (e.g. a band stated for the quick window), not to this one;
    - NOT RUN: a check with `run: <id>` (or a list) while a run it measures is unfinished or
      unrecorded in the results' `runs`; the detail says how far the run is and the hours to go.
      Both are counted apart from passes and failures.
    `speed` marks checks that measure speed (`speed: true` in the reference): reported as any other
    check, but a gate for correctness only (`--gate correctness`) does not fail on them.
    """
    tabs = tables(results)
    out = []
    for c in reference["checks"]:
        scales = c.get("scales")
        if scales is not None and results.get("scale") not in scales:
            out.append(_outcome(c, "OTHER SCALE", True, f"evaluated at {', '.join(scales)} scale only"))
            continue
        waiting = unfinished_runs(results, c)
        if waiting:
            out.append(_outcome(c, "NOT RUN", True, "; ".join(waiting)))
            continue
        try:
            passed, detail = KINDS[c["kind"]](tabs, results, c)
            status = "PASS" if passed else ("DIFFERS" if c.get("known_difference") else "FAIL")
        except CheckError as e:
            passed, detail, status = False, f"cannot evaluate: {e}", "FAIL"
        except KeyError as e:
            raise HarnessError(f"check '{c['id']}' lacks the field {e}")
        out.append(_outcome(c, status, passed, detail))
    return out
