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
        self.assertEqual(quick["status"], "NOT RUN")
        full = checks.evaluate({"checks": [c]}, dict(RESULTS, scale="full"))[0]
        self.assertEqual(full["status"], "FAIL")

    def test_check_waiting_for_an_unfinished_run(self):
        c = {"id": "b", "source": "s", "kind": "bound", "value": "speed", "max": 2.9, "when": "completed"}
        self.assertEqual(run_checks(c)[0]["status"], "NOT RUN")
        done = dict(RESULTS, values=dict(RESULTS["values"], completed=1.0))
        self.assertEqual(checks.evaluate({"checks": [c]}, done)[0]["status"], "FAIL")

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
