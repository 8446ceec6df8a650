"""Tests of the rbfib command on the example scenes: they check and run; mutants of them (missing
and unknown keys, wrong types and units, negative, zero, NaN and huge values) either pass the
check or exit with status 2 and one line naming the field, never a crash or a hang."""
import glob
import os
import random
import re
import subprocess
import tempfile
import time
import unittest

ROOT = os.environ.get("RBFIB_ROOT", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BUILD = os.environ.get("RBFIB_BUILD", os.path.join(ROOT, "build"))
RBFIB = os.path.join(BUILD, "bin", "rbfib")
SCENES = sorted(glob.glob(os.path.join(ROOT, "scenes", "*.yaml")))
MUTANTS = int(os.environ.get("RBFIB_MUTANTS", "500"))
RUN_VALID = int(os.environ.get("RBFIB_MUTANTS_RUN", "8"))  # valid mutants that also run a step


def rbfib(*args, timeout=60):
    return subprocess.run([RBFIB, *args], capture_output=True, text=True, timeout=timeout)


def mutate(text, rng):
    """One random mutation of a scene's text (line-based, so it stays close to valid YAML)."""
    lines = text.split("\n")
    body = [i for i, l in enumerate(lines) if l.strip() and not l.strip().startswith("#")]
    i = rng.choice(body)
    line = lines[i]
    kind = rng.randrange(7)
    if kind == 0:  # a missing key
        del lines[i]
    elif kind == 1:  # an unknown key beside it
        indent = len(line) - len(line.lstrip(" -"))
        lines.insert(i, " " * indent + "colour: red")
    elif ":" in line and line.split(":", 1)[1].strip():
        key, value = line.split(":", 1)
        junk = ["-1 um", "0", "nan cP", "1e300 s", "1e-300 um", "12 parsec", "[1, 2]", "{a: 1}", "''", "true",
                "-5", "1e9", "3 dyn/cm", "0.5 us"]
        if kind == 2:  # a number in place of a quantity or the other way round
            value = " " + re.sub(r"[a-zA-Z/^]+.*$", "", value.strip()) if re.search(r"\d", value) else " 42"
        elif kind == 3:  # a wrong unit
            value = re.sub(r"(\d)\s*[a-zA-Z][a-zA-Z/^0-9 -]*", r"\1 erg", value)
        elif kind == 4:  # a value scaled far out of range
            value = re.sub(r"(-?\d+(\.\d*)?(e-?\d+)?)", lambda m: repr(float(m.group(1)) * rng.choice([-1, 0, 1e6, 1e-6])), value, count=1)
        else:
            value = " " + rng.choice(junk)
        lines[i] = key + ":" + value
    else:
        del lines[i]
    return "\n".join(lines)


class ExampleScenes(unittest.TestCase):
    def test_every_example_checks(self):
        self.assertTrue(SCENES, "no example scenes in scenes/")
        for path in SCENES:
            r = rbfib("check", path)
            self.assertEqual(r.returncode, 0, f"{path}: {r.stderr}")
            self.assertIn("stopping condition (eq. 5.4)", r.stdout)
            self.assertRegex(r.stdout, r"time per step on this machine, roughly: [0-9.e+-]+ s")

    def test_a_short_run_writes_its_diagnostics(self):
        with tempfile.TemporaryDirectory() as out:
            r = rbfib("run", os.path.join(ROOT, "scenes", "relaxing_sphere.yaml"), "--out", out, "--until", "4 us", timeout=300)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            with open(os.path.join(out, "diagnostics.csv")) as f:
                rows = f.read().strip().split("\n")
            self.assertEqual(len(rows), 1 + 10)  # header and 10 steps of 0.4 us
            self.assertTrue(rows[0].startswith("step,t_s,dt_s"))
            self.assertTrue(os.path.exists(os.path.join(out, "scene.yaml")))

    def test_overlapping_cells_and_a_cell_through_a_wall_exit_2(self):
        with open(os.path.join(ROOT, "scenes", "two_red_cells.yaml")) as f:
            text = f.read()
        cases = {
            "overlap": (text.replace("center: [11 um, 8 um, 11 um]", "center: [6 um, 8 um, 6 um]"), "overlap"),
            "wall": (text.replace("center: [5 um, 8 um, 5 um]", "center: [5 um, 2 um, 5 um]"), "reaches through a wall"),
        }
        with tempfile.TemporaryDirectory() as d:
            for name, (scene, why) in cases.items():
                self.assertNotEqual(scene, text, name)
                path = os.path.join(d, name + ".yaml")
                with open(path, "w") as f:
                    f.write(scene)
                r = rbfib("check", path)
                self.assertEqual(r.returncode, 2, f"{name}: {r.stdout}{r.stderr}")
                lines = r.stderr.strip().split("\n")
                self.assertEqual(len(lines), 1, r.stderr)
                self.assertIn("cells[", lines[0])
                self.assertIn(why, lines[0])

    def test_bad_command_lines_exit_2(self):
        self.assertEqual(rbfib("run", SCENES[0]).returncode, 2)  # --out missing
        r = rbfib("run", SCENES[0], "--out", tempfile.gettempdir(), "--until", "4 um")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--until", r.stderr)
        self.assertEqual(rbfib("check", "/nonexistent.yaml").returncode, 2)


class Restart(unittest.TestCase):
    def physics(self, out):
        """The diagnostics rows without their timing columns."""
        with open(os.path.join(out, "diagnostics.csv")) as f:
            return [",".join(l.split(",")[:8]) for l in f.read().strip().split("\n")]

    def test_restart_continues_bit_for_bit(self):
        scene = os.path.join(ROOT, "scenes", "relaxing_sphere.yaml")
        with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
            self.assertEqual(rbfib("run", scene, "--out", a, "--until", "2 us", timeout=300).returncode, 0)
            r = rbfib("restart", a, "--until", "4 us", timeout=300)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertEqual(rbfib("run", scene, "--out", b, "--until", "4 us", timeout=300).returncode, 0)
            self.assertEqual(self.physics(a), self.physics(b))
            self.assertEqual(len(self.physics(a)), 1 + 10)

    def test_a_finished_run_is_not_stepped_again(self):
        # The checkpoint of a run that reached its end is marked finished: restart says so and
        # takes no step; the table keeps its rows.
        with open(os.path.join(ROOT, "scenes", "relaxing_sphere.yaml")) as f:
            text = f.read().replace("end: 40 us", "end: 2 us")
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "scene.yaml")
            with open(scene, "w") as f:
                f.write(text)
            out = os.path.join(d, "out")
            self.assertEqual(rbfib("run", scene, "--out", out, timeout=300).returncode, 0)
            rows = self.physics(out)
            r = rbfib("restart", out, timeout=300)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertIn("done: 0 steps", r.stdout)
            self.assertIn("finished", r.stdout)
            self.assertEqual(self.physics(out), rows)
            self.assertEqual(len(rows), 1 + 5)
            # Slimmed (its fluid left out), the finished run still answers the same and is smaller.
            checkpoint = os.path.join(out, "checkpoint.h5")
            before = os.path.getsize(checkpoint)
            r = rbfib("slim", checkpoint)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertIn("without its fluid", r.stdout)
            self.assertLess(os.path.getsize(checkpoint), before)
            self.assertIn("already", rbfib("slim", checkpoint).stdout)
            r = rbfib("restart", out, timeout=300)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertIn("done: 0 steps", r.stdout)
            self.assertEqual(self.physics(out), rows)

    def test_slim_refuses_a_running_run_and_a_missing_file(self):
        scene = os.path.join(ROOT, "scenes", "relaxing_sphere.yaml")
        with tempfile.TemporaryDirectory() as d:
            self.assertEqual(rbfib("run", scene, "--out", d, "--until", "0.8 us", timeout=300).returncode, 0)
            checkpoint = os.path.join(d, "checkpoint.h5")
            before = os.path.getsize(checkpoint)
            r = rbfib("slim", checkpoint)
            self.assertEqual(r.returncode, 2)
            self.assertIn("only a run that has ended", r.stderr)
            self.assertEqual(os.path.getsize(checkpoint), before)
            r = rbfib("slim", os.path.join(d, "none.h5"))
            self.assertEqual(r.returncode, 2)
            self.assertIn("does not exist", r.stderr)

    def test_two_runs_of_one_scene_are_bitwise_identical(self):
        # Two processes, one scene on a 48^3 grid: the checkpoints hold the same bits. (FFT plans
        # chosen by timing, FFTW_MEASURE, made two runs differ in the last bits on such grids.)
        import h5py
        import numpy as np
        with open(os.path.join(ROOT, "scenes", "relaxing_sphere.yaml")) as f:
            text = f.read().replace("h: 1 um", "h: 0.3333333333333333 um").replace("dt: 0.4 us", "dt: 0.1 us")
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "scene.yaml")
            with open(scene, "w") as f:
                f.write(text)
            for run in ("a", "b"):
                r = rbfib("run", scene, "--out", os.path.join(d, run), "--until", "0.5 us", timeout=300)
                self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            with h5py.File(os.path.join(d, "a", "checkpoint.h5"), "r") as a, h5py.File(os.path.join(d, "b", "checkpoint.h5"), "r") as b:
                for name in ("fluid/u0", "fluid/u1", "fluid/u2", "fluid/p", "batches/0"):
                    np.testing.assert_array_equal(a[name][()], b[name][()], name)

    def test_a_kill_at_any_moment_leaves_a_valid_checkpoint(self):
        # A checkpoint after every step; SIGKILL at random moments (20 tries): restart must
        # always find a whole checkpoint and continue.
        with open(os.path.join(ROOT, "scenes", "relaxing_sphere.yaml")) as f:
            text = f.read().replace("end: 40 us", "end: 400 us") + "\noutput: {checkpoint_every: 0.4 us}\n"
        rng = random.Random(7)
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "scene.yaml")
            with open(scene, "w") as f:
                f.write(text)
            out = os.path.join(d, "out")
            first = rbfib("run", scene, "--out", out, "--until", "0.8 us", timeout=300)
            self.assertEqual(first.returncode, 0, first.stderr)
            for k in range(20):
                p = subprocess.Popen([RBFIB, "restart", out, "--until", "400 us"], stdout=subprocess.DEVNULL,
                                     stderr=subprocess.PIPE, text=True)
                time.sleep(rng.uniform(0.3, 1.5))
                p.kill()
                p.wait()
                self.assertNotIn("Error", p.stderr.read())
            r = rbfib("restart", out, "--until", "1 us", timeout=300)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertIn("restarting at step", r.stdout)


class Mutants(unittest.TestCase):
    def test_mutants_pass_or_name_their_field(self):
        rng = random.Random(20261130)
        texts = []
        for p in SCENES:
            with open(p) as f:
                texts.append(f.read())
        counts = {0: 0, 2: 0}
        ran = 0
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "mutant.yaml")
            for k in range(MUTANTS):
                text = mutate(rng.choice(texts), rng)
                with open(path, "w") as f:
                    f.write(text)
                r = rbfib("check", path)
                self.assertIn(r.returncode, (0, 2), f"mutant {k} exited {r.returncode}:\n{text}\n{r.stderr}")
                counts[r.returncode] += 1
                if r.returncode == 0 and ran < RUN_VALID:
                    # A valid mutant also runs: one step, then exit 0, or a named stop (2: a problem
                    # only building finds; 3: a numerical stop), never a crash or a hang.
                    ran += 1
                    out = os.path.join(d, f"run{k}")
                    run = rbfib("run", path, "--out", out, "--until", "1 ns", timeout=600)
                    self.assertIn(run.returncode, (0, 2, 3), f"mutant {k} run exited {run.returncode}:\n{text}\n{run.stderr}")
                    if run.returncode == 2:
                        self.assertRegex(run.stderr.strip(), r"^rbfib: \S.* = [^\n]*$", f"mutant {k}:\n{run.stderr}")
                    if run.returncode == 3:
                        self.assertIn("rbfib: stopped: ", run.stdout + run.stderr, f"mutant {k}")
                if r.returncode == 2:
                    lines = r.stderr.strip().split("\n")
                    self.assertEqual(len(lines), 1, f"mutant {k}: more than one line:\n{r.stderr}")
                    self.assertRegex(lines[0], r"^rbfib: \S.* = ", f"mutant {k}: no field named:\n{text}")
        print(f"{MUTANTS} mutants: {counts[0]} valid ({ran} of them run a step), {counts[2]} rejected with a named field")


if __name__ == "__main__":
    unittest.main()
