"""Tests of the harness: the checks can fail, bad input gives one clear line and a non-zero exit."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import textwrap
import unittest

ROOT = os.environ.get("RBFIB_ROOT", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BUILD = os.environ.get("RBFIB_BUILD", os.path.join(ROOT, "build"))
sys.path.insert(0, ROOT)

from harness import HarnessError, checks  # noqa: E402

RESULTS = {
    "study": "fake",
    "tables": {
        "conv": {"columns": ["h", "err", "method"], "units": ["", "", ""],
                 "rows": [[0.1, 1e-2, "a"], [0.05, 2.5e-3, "a"], [0.025, 6.25e-4, "a"],
                          [0.1, 1e-1, "b"], [0.05, 5e-2, "b"], [0.025, 2.5e-2, "b"]]},
    },
    "values": {"speed": 3.0},
}


def run_checks(*cs):
    return checks.evaluate({"checks": list(cs)}, RESULTS)


class Checks(unittest.TestCase):
    def test_value_significant_digits(self):
        ok = {"id": "v", "source": "s", "kind": "value", "table": "conv", "column": "err",
              "where": {"method": "a"}, "paper": [1.0004e-2, 2.5e-3], "sig_digits": 4}
        bad = dict(ok, paper=[1.001e-2, 2.5e-3])
        self.assertTrue(run_checks(ok)[0]["passed"])
        self.assertFalse(run_checks(bad)[0]["passed"])

    def test_orders_measured_from_the_sizes(self):
        self.assertEqual([round(p, 12) for p in checks.orders([0.1, 0.05, 0.025], [1e-2, 2.5e-3, 6.25e-4])], [2.0, 2.0])
        self.assertEqual([round(p, 12) for p in checks.orders([10, 20], [1e-2, 2.5e-3], invert=True)], [2.0])
        two = {"id": "o", "source": "s", "kind": "order", "table": "conv", "x": "h", "y": "err",
               "where": {"method": "a"}, "expected": 2.0, "tol": 0.01}
        self.assertTrue(run_checks(two)[0]["passed"])
        self.assertFalse(run_checks(dict(two, where={"method": "b"}))[0]["passed"])  # first order
        by = dict(two, where=None, by="method")
        self.assertFalse(run_checks(by)[0]["passed"])
        self.assertTrue(run_checks(dict(by, expected=None, tol=None, min=0.9))[0]["passed"])

    def test_known_difference_is_reported_not_hidden(self):
        c = {"id": "b", "source": "s", "kind": "bound", "value": "speed", "max": 2.9, "known_difference": "why"}
        out = run_checks(c)[0]
        self.assertFalse(out["passed"])
        self.assertEqual(out["status"], "DIFFERS")
        self.assertEqual(run_checks(dict(c, max=3.0))[0]["status"], "PASS")
        self.assertEqual(run_checks(dict(c, known_difference=None))[0]["status"], "FAIL")

    def test_check_limited_to_a_scale(self):
        c = {"id": "b", "source": "s", "kind": "bound", "value": "speed", "max": 2.9, "scales": ["full"]}
        quick = checks.evaluate({"checks": [c]}, dict(RESULTS, scale="quick"))[0]
        self.assertEqual(quick["status"], "OTHER SCALE")  # belongs to the full report, not a run unfinished
        full = checks.evaluate({"checks": [c]}, dict(RESULTS, scale="full"))[0]
        self.assertEqual(full["status"], "FAIL")

    def test_check_waiting_for_an_unfinished_run(self):
        c = {"id": "b", "source": "s", "kind": "bound", "value": "speed", "max": 2.9, "run": "long"}
        unrecorded = run_checks(c)[0]
        self.assertEqual(unrecorded["status"], "NOT RUN")
        self.assertIn("not recorded", unrecorded["detail"])
        going = dict(RESULTS, runs={"long": {"finished": False, "progress": 0.29, "simulated": "8.8 of 30 ms",
                                             "seconds_per_step": 0.045, "hours_to_go": 7.1}})
        out = checks.evaluate({"checks": [c]}, going)[0]
        self.assertEqual(out["status"], "NOT RUN")
        for words in ("29% done", "8.8 of 30 ms", "0.045 s per step", "7.1 hours to go"):
            self.assertIn(words, out["detail"])
        done = dict(RESULTS, runs={"long": {"finished": True}, "other": {"finished": False}})
        self.assertEqual(checks.evaluate({"checks": [c]}, done)[0]["status"], "FAIL")
        both = dict(c, run=["long", "other"])  # a check over several runs waits for all of them
        self.assertEqual(checks.evaluate({"checks": [both]}, done)[0]["status"], "NOT RUN")
        per_scale = dict(c, run={"quick": "long", "full": ["long", "other"]})  # the runs differ by scale
        self.assertEqual(checks.evaluate({"checks": [per_scale]}, dict(done, scale="quick"))[0]["status"], "FAIL")
        self.assertEqual(checks.evaluate({"checks": [per_scale]}, dict(done, scale="full"))[0]["status"], "NOT RUN")

    def test_a_value_never_measured_never_passes(self):
        for v in (None, float("nan"), float("inf")):
            res = dict(RESULTS, values={"speed": v})
            for extra in ({}, {"known_difference": "why"}):  # not even as a known difference
                c = dict({"id": "b", "source": "s", "kind": "bound", "value": "speed", "min": 0.0}, **extra)
                out = checks.evaluate({"checks": [c]}, res)[0]
                self.assertEqual(out["status"], "FAIL", (v, extra))
                self.assertIn("cannot evaluate", out["detail"])
        absent = {"id": "b", "source": "s", "kind": "value", "value": "nothing", "paper": 1.0, "rtol": 0.1,
                  "known_difference": "why"}
        self.assertEqual(run_checks(absent)[0]["status"], "FAIL")

    def test_bound_and_missing_data_fail(self):
        self.assertTrue(run_checks({"id": "b", "source": "s", "kind": "bound", "value": "speed", "max": 3.0})[0]["passed"])
        self.assertFalse(run_checks({"id": "b", "source": "s", "kind": "bound", "value": "speed", "max": 2.9})[0]["passed"])
        missing = run_checks({"id": "m", "source": "s", "kind": "bound", "table": "nope", "column": "err", "max": 1})[0]
        self.assertFalse(missing["passed"])
        self.assertIn("no table 'nope'", missing["detail"])


def harness(*args, root=ROOT):
    env = dict(os.environ, RBFIB_ROOT=root, PYTHONPATH=ROOT)
    return subprocess.run([sys.executable, "-m", "harness", *args], cwd=ROOT, env=env, capture_output=True, text=True)


class BadInput(unittest.TestCase):
    def assert_one_line_error(self, proc, *words):
        self.assertNotEqual(proc.returncode, 0)
        lines = proc.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, proc.stderr)
        for w in words:
            self.assertIn(w, lines[0])

    def test_unknown_study(self):
        self.assert_one_line_error(harness("run", "nosuchstudy"), "unknown study", "nosuchstudy")

    def test_bad_scale(self):
        self.assert_one_line_error(harness("run", "appendixA", "--scale", "huge"), "--scale", "huge")

    def test_bad_sitting(self):
        # The harness refuses it before running anything; a driver refuses it on its own command line.
        self.assert_one_line_error(harness("run", "appendixA", "--sitting", "-5"), "--sitting", "-5")
        driver = os.path.join(BUILD, "studies", "study_appendixA")
        if not os.path.isfile(driver):
            self.skipTest("drivers not built")
        for bad in ("0", "ten", "5s"):
            with tempfile.TemporaryDirectory() as out:
                r = subprocess.run([driver, "--sitting", bad, "--out", out], capture_output=True, text=True)
            self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
            self.assert_one_line_error(r, "--sitting", bad)

    def test_missing_and_malformed_reference(self):
        tmp = tempfile.mkdtemp()
        try:
            os.makedirs(os.path.join(tmp, "studies", "fake"))
            os.makedirs(os.path.join(tmp, "reference"))
            with open(os.path.join(tmp, "studies", "fake", "study.yaml"), "w") as f:
                f.write(textwrap.dedent("""\
                    name: fake
                    chapter: chapter0
                    title: fake
                    reproduces: [nothing]
                    description: a test
                """))
            self.assert_one_line_error(harness("run", "fake", "--no-run", root=tmp), "reference", "does not exist")
            with open(os.path.join(tmp, "reference", "fake.yaml"), "w") as f:
                f.write("study: fake\nchecks: [\n")
            self.assert_one_line_error(harness("run", "fake", "--no-run", root=tmp), "not valid YAML")
            with open(os.path.join(tmp, "reference", "fake.yaml"), "w") as f:
                f.write("study: fake\nsource: x\nchecks:\n  - {id: a, kind: guess, source: y}\n")
            self.assert_one_line_error(harness("run", "fake", "--no-run", root=tmp), "kind 'guess'")
            with open(os.path.join(tmp, "reference", "fake.yaml"), "w") as f:
                f.write("study: fake\nsource: x\nchecks:\n  - {id: a, kind: bound, source: y, value: v, max: 1}\n")
            self.assert_one_line_error(harness("run", "fake", "--no-run", root=tmp), "speed_vs_error")
        finally:
            shutil.rmtree(tmp)

    def test_full_scale_reports_go_beside_the_quick_ones(self):
        tmp = tempfile.mkdtemp()
        try:
            os.makedirs(os.path.join(tmp, "studies", "fake"))
            os.makedirs(os.path.join(tmp, "reference"))
            os.makedirs(os.path.join(tmp, "runs", "fake", "full"))
            with open(os.path.join(tmp, "studies", "fake", "study.yaml"), "w") as f:
                f.write("name: fake\nchapter: chapter0\ntitle: fake\nreproduces: [nothing]\ndescription: a test\n")
            with open(os.path.join(tmp, "reference", "fake.yaml"), "w") as f:
                f.write("study: fake\nsource: x\nchecks:\n  - {id: a, kind: bound, source: y, value: v, max: 1}\n"
                        "figures:\n  - {id: speed_vs_error, table: t, x: s, y: e}\n")
            with open(os.path.join(tmp, "runs", "fake", "full", "results.json"), "w") as f:
                json.dump({"study": "fake", "scale": "full", "values": {"v": 0.5},
                           "tables": {"t": {"columns": ["s", "e"], "units": ["s", ""], "rows": [[1.0, 0.1], [2.0, 0.05]]}}}, f)
            reports = os.path.join(tmp, "reports")
            proc = harness("run", "fake", "--scale", "full", "--no-run", "--out", os.path.join(tmp, "runs"), "--reports", reports, root=tmp)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertTrue(os.path.isfile(os.path.join(reports, "fake-full", "README.md")))
            self.assertFalse(os.path.exists(os.path.join(reports, "fake")))
            with open(os.path.join(reports, "README.md")) as f:
                self.assertIn("fake-full/README.md", f.read())
        finally:
            shutil.rmtree(tmp)

    def fake_study(self, tmp, checks_yaml, values, figures_yaml=""):
        os.makedirs(os.path.join(tmp, "studies", "fake"), exist_ok=True)
        os.makedirs(os.path.join(tmp, "reference"), exist_ok=True)
        os.makedirs(os.path.join(tmp, "runs", "fake", "quick"), exist_ok=True)
        with open(os.path.join(tmp, "studies", "fake", "study.yaml"), "w") as f:
            f.write("name: fake\nchapter: chapter0\ntitle: fake\nreproduces: [nothing]\ndescription: a test\n")
        with open(os.path.join(tmp, "studies", "fake", "main.cpp"), "w") as f:
            f.write("int main() {}\n")
        with open(os.path.join(tmp, "reference", "fake.yaml"), "w") as f:
            f.write("study: fake\nsource: x\nchecks:\n" + checks_yaml + "figures:\n  - {id: speed_vs_error, table: t, x: s, y: e}\n" + figures_yaml)
        with open(os.path.join(tmp, "runs", "fake", "quick", "results.json"), "w") as f:
            json.dump({"study": "fake", "scale": "quick", "values": values,
                       "tables": {"t": {"columns": ["s", "e"], "units": ["s", ""], "rows": [[1.0, 0.1], [2.0, 0.05]]}}}, f)
        return ["run", "fake", "--no-run", "--out", os.path.join(tmp, "runs"), "--reports", os.path.join(tmp, "reports")]

    def test_checks_of_the_other_scale_are_named_not_counted(self):
        tmp = tempfile.mkdtemp()
        try:
            full_only = "  - {id: long_one, kind: bound, source: y, value: v, max: 1, scales: [full]}\n"
            here = "  - {id: here, kind: bound, source: y, value: w, max: 1}\n"
            proc = harness(*self.fake_study(tmp, full_only + here, {"w": 0.5}), root=tmp)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            with open(os.path.join(tmp, "reports", "fake", "README.md")) as f:
                text = f.read()
            self.assertIn("Checks: **1 passed, 0 failed**. 1 more check belongs to the full scale's report.", text)
            self.assertNotIn("NOT RUN", text)
            self.assertNotIn("| long_one", text)  # not a row of the checks table
            self.assertIn("evaluated in [its report](../fake-full/README.md) and not here: `long_one`.", text)
            with open(os.path.join(tmp, "reports", "fake", "summary.json")) as f:
                summary = json.load(f)
            self.assertEqual((summary["passed"], summary["not_run"]), (1, 0))
        finally:
            shutil.rmtree(tmp)

    def test_a_figure_of_the_other_scale_is_not_drawn(self):
        tmp = tempfile.mkdtemp()
        try:
            here = "  - {id: here, kind: bound, source: y, value: w, max: 1}\n"
            full_only = "  - {id: fine_grid, table: t, x: s, y: e, scales: [full]}\n"
            proc = harness(*self.fake_study(tmp, here, {"w": 0.5}, full_only), root=tmp)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            with open(os.path.join(tmp, "reports", "fake", "README.md")) as f:
                text = f.read()
            self.assertIn("(speed_vs_error.png)", text)
            self.assertNotIn("fine_grid", text)
            self.assertFalse(os.path.exists(os.path.join(tmp, "reports", "fake", "fine_grid.png")))
        finally:
            shutil.rmtree(tmp)

    def test_speed_checks_do_not_gate_the_tests(self):
        tmp = tempfile.mkdtemp()
        try:
            speed = "  - {id: fast, kind: bound, source: y, value: v, max: 1, speed: true}\n"
            right = "  - {id: right, kind: bound, source: y, value: w, max: 1}\n"
            args = self.fake_study(tmp, speed + right, {"v": 5.0, "w": 0.5})
            self.assertEqual(harness(*args, root=tmp).returncode, 1)  # reports and `make reproduce` count it
            proc = harness(*args, "--gate", "correctness", root=tmp)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            self.assertIn("FAIL    fast (speed)", proc.stdout)  # printed all the same
            args = self.fake_study(tmp, speed + right, {"v": 5.0, "w": 5.0})
            self.assertEqual(harness(*args, "--gate", "correctness", root=tmp).returncode, 1)  # correctness still gates
            self.assert_one_line_error(harness(*args, "--gate", "some", root=tmp), "--gate", "some")
            bad = self.fake_study(tmp, "  - {id: a, kind: bound, source: y, value: w, max: 1, when: done}\n", {"w": 0.5})
            self.assert_one_line_error(harness(*bad, root=tmp), "'when'", "run:")
        finally:
            shutil.rmtree(tmp)

    def test_reports_are_stale_when_their_sources_change(self):
        tmp = tempfile.mkdtemp()
        try:
            args = self.fake_study(tmp, "  - {id: right, kind: bound, source: y, value: w, max: 1}\n", {"w": 0.5})
            index = os.path.join(tmp, "reports", "README.md")
            with open(os.path.join(tmp, "runs", "fake", "quick", "run.json"), "w") as f:
                json.dump({"commit": "abc", "driver_hash": __import__("harness.catalog").catalog.driver_hash(tmp, "fake")}, f)
            proc = harness(*args, root=tmp)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertNotIn("STALE", proc.stdout)
            with open(index) as f:
                self.assertIn("current", f.read())
            with open(os.path.join(tmp, "studies", "fake", "main.cpp"), "a") as f:
                f.write("// changed\n")
            with open(os.path.join(tmp, "reference", "fake.yaml"), "a") as f:
                f.write("# changed\n")
            harness_root = tmp
            from harness import report as rep
            stale = rep.stale_reports(harness_root, os.path.join(tmp, "reports"))
            self.assertEqual(len(stale), 1)
            self.assertIn("driver changed", stale[0][1])
            self.assertIn("reference changed", stale[0][1])
            # Rendering again from the same results takes the new reference but not the new driver.
            os.remove(os.path.join(tmp, "runs", "fake", "quick", "run.json"))
            proc = harness(*args, root=tmp)
            self.assertIn("STALE", proc.stdout)
            self.assertIn("fake (driver changed since the run)", proc.stdout)
            with open(index) as f:
                self.assertIn("**STALE**", f.read())
        finally:
            shutil.rmtree(tmp)

    def test_driver_rejects_bad_scale(self):
        exe = os.path.join(BUILD, "studies", "study_appendixA")
        if not os.path.isfile(exe):
            self.skipTest("driver not built")
        proc = subprocess.run([exe, "--scale", "huge"], capture_output=True, text=True)
        self.assertEqual(proc.returncode, 2)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1)
        self.assertIn("--scale = 'huge'", proc.stderr)


if __name__ == "__main__":
    unittest.main()


class KeptCheckpoints(unittest.TestCase):
    """`keep` copies a run's checkpoints into kept/; a later full run on a fresh machine takes the
    ones its run directory lacks and leaves newer ones alone."""

    def test_keep_then_continue(self):
        from harness import cli
        with tempfile.TemporaryDirectory() as tmp:
            runs, kept = os.path.join(tmp, "runs"), os.path.join(tmp, "kept")
            src = os.path.join(runs, "study_x", "full", "grid_a")
            os.makedirs(src)
            for name, text in (("checkpoint.h5", "state 1"), ("results.json", "{}"), ("large.h5", "x" * 2**20)):
                with open(os.path.join(src, name), "w") as f:
                    f.write(text)
            old = cli.KEPT
            cli.KEPT = kept
            try:
                self.assertEqual(cli.keep_study("study_x", "full", runs, max_mib=0.5),  # the 1 MiB checkpoint is not kept
                                 [os.path.join("grid_a", "checkpoint.h5")])
                self.assertEqual(cli.keep_study("study_x", "full", runs, max_mib=0.5), [])  # unchanged: nothing copied
                with open(os.path.join(kept, "study_x", "full", "grid_a", "large.h5"), "w") as f:
                    f.write("small once")  # kept when it was small; its run has grown past the limit since
                self.assertEqual(cli.keep_study("study_x", "full", runs, max_mib=0.5), [])
                self.assertFalse(os.path.exists(os.path.join(kept, "study_x", "full", "grid_a", "large.h5")))
                self.assertEqual(cli.checkpoints(os.path.join(kept, "study_x", "full")), [os.path.join("grid_a", "checkpoint.h5")])
                fresh = os.path.join(tmp, "fresh")
                cli.continue_from_kept("study_x", "full", fresh)
                with open(os.path.join(fresh, "grid_a", "checkpoint.h5")) as f:
                    self.assertEqual(f.read(), "state 1")
                with open(os.path.join(fresh, "grid_a", "checkpoint.h5"), "w") as f:
                    f.write("state 2")  # the run went on here: the kept copy is older
                cli.continue_from_kept("study_x", "full", fresh)
                with open(os.path.join(fresh, "grid_a", "checkpoint.h5")) as f:
                    self.assertEqual(f.read(), "state 2")
            finally:
                cli.KEPT = old
