"""Tests of a run's output (docs/output.md): every array the XDMF names exists in its HDF5 file
with the shape the XDMF states, the values are what the run computed (the steady shear on the
grid, a sphere's mean curvature -1/R and radius R), units are attributes, and VTK's XDMF reader
(the one ParaView uses) opens the series and reads the same arrays."""
import json
import os
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ET

import h5py
import numpy as np

ROOT = os.environ.get("RBFIB_ROOT", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BUILD = os.environ.get("RBFIB_BUILD", os.path.join(ROOT, "build"))
RBFIB = os.path.join(BUILD, "bin", "rbfib")
VTK_PYTHON = os.path.join(ROOT, ".venv-vtk", "bin", "python")  # made by `make deps`

# Run by VTK's Python: open run.xmf, go to the second time, report each block's arrays.
READ_WITH_VTK = """
import json, sys
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy
r = vtk.vtkXdmfReader()
r.SetFileName(sys.argv[1])
r.UpdateInformation()
times = r.GetOutputInformation(0).Get(vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS())
r.UpdateTimeStep(times[1])
out = r.GetOutputDataObject(0)
blocks = {}
for i in range(out.GetNumberOfBlocks()):
    b = out.GetBlock(i)
    name = out.GetMetaData(i).Get(vtk.vtkCompositeDataSet.NAME()).split("[")[0]
    arrays = {}
    for data in (b.GetPointData(), b.GetCellData()):
        for k in range(data.GetNumberOfArrays()):
            arrays[data.GetArrayName(k)] = vtk_to_numpy(data.GetArray(k)).tolist()
    blocks[name] = {"points": b.GetNumberOfPoints(), "cells": b.GetNumberOfCells(),
                    "xyz": vtk_to_numpy(b.GetPoints().GetData()).tolist() if b.GetPoints() else None,
                    "arrays": arrays}
print(json.dumps({"times": list(times), "blocks": blocks}))
"""

SCENE = """
domain:
  size: [16 um, 16 um, 16 um]
  periodic: [x, z]
  walls:
    y: {lower: [-8 mm/s, 0 mm/s, 0 mm/s], upper: [8 mm/s, 0 mm/s, 0 mm/s]}
  initial_flow: shear
fluid: {density: 1 g/cm^3, viscosity: 0.1 cP}
grid: {h: 1 um}
time: {integrator: backward_forward_euler, dt: 0.2 us, end: 0.4 us}
ib: {kernel: bspline3}
cell_types:
  - {name: ball, preset: skalak_sphere, radius: 3 um, data_sites: 144, sample_sites: 400}
cells:
  - {type: ball, center: [8 um, 8 um, 8 um]}
tethered_points:
  - {name: wall, plane: {y: 1 um, points: [8, 8]}, k: 2.5 dyn/cm, eta: 0 dyn s/cm}
output: {snapshot_every: 0.2 us}
"""


class Output(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        scene = os.path.join(cls.dir.name, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        cls.out = os.path.join(cls.dir.name, "out")
        r = subprocess.run([RBFIB, "run", scene, "--out", cls.out], capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stdout + r.stderr

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def test_every_array_of_the_xdmf_exists_with_its_shape(self):
        root = ET.parse(os.path.join(self.out, "run.xmf")).getroot()
        series = root.find("Domain/Grid")
        self.assertEqual(series.get("CollectionType"), "Temporal")
        snapshots = series.findall("Grid")
        self.assertEqual(len(snapshots), 3)  # t = 0, 0.2, 0.4 us
        self.assertEqual([float(s.find("Time").get("Value")) for s in snapshots], [0.0, 2e-7, 4e-7])
        items = [d for d in root.iter("DataItem") if d.get("Format") == "HDF"]
        self.assertEqual(len(items), 3 * (2 + 5 + 1))
        for d in items:
            path, dataset = d.text.split(":")
            with h5py.File(os.path.join(self.out, path), "r") as f:
                self.assertIn(dataset, f, d.text)
                shape = tuple(int(x) for x in d.get("Dimensions").split())
                self.assertEqual(f[dataset].shape, shape, d.text)
        for g in snapshots[0].findall("Grid"):
            topology = g.find("Topology")
            if topology.get("TopologyType") == "Triangle":
                path, dataset = topology.find("DataItem").text.split(":")
                with h5py.File(os.path.join(self.out, path), "r") as f:
                    tri = f[dataset][()]
                    n = f[dataset.replace("triangles", "points")].shape[0]
                self.assertEqual(tri.shape[0], 2 * n - 4)  # a closed triangulation of n sites
                self.assertTrue((tri >= 0).all() and (tri < n).all())

    def test_values_are_those_of_the_run(self):
        with h5py.File(os.path.join(self.out, "snapshots", "snapshot_000000.h5"), "r") as f:
            self.assertEqual(f.attrs["t"], 0.0)
            u = f["fluid/velocity"][()]
            units = f["fluid/velocity"].attrs["units"]
            self.assertEqual(units.decode() if isinstance(units, bytes) else units, "cm/s")
            h = 1e-4
            y = (np.arange(16) + 0.5) * h
            shear = 1000.0 * (y - 8e-4)  # the steady shear, cm/s
            np.testing.assert_allclose(u[:, :, :, 0], np.broadcast_to(shear[None, :, None], (16, 16, 16)), atol=1e-12)
            np.testing.assert_allclose(u[:, :, :, 1:], 0.0, atol=1e-12)
            X = f["cells/0/points"][()]
            r = np.linalg.norm(X - 8e-4, axis=1)
            np.testing.assert_allclose(r, 3e-4, rtol=1e-3)
            np.testing.assert_allclose(f["cells/0/mean_curvature"][()], -1 / 3e-4, rtol=1e-3)
            np.testing.assert_allclose(f["cells/0/force_density"][()], 0.0, atol=1e-6)  # at rest
            # The interpolated velocity at the sites is the shear at their height (B3 reproduces linears).
            np.testing.assert_allclose(f["cells/0/velocity"][()][:, 0], 1000.0 * (X[:, 1] - 8e-4), atol=1e-9)
            P = f["points/0/points"][()]
            self.assertEqual(P.shape, (64, 3))
            np.testing.assert_allclose(P[:, 1], 1e-4)


    def test_vtk_reads_the_series_as_written(self):
        self.assertTrue(os.path.exists(VTK_PYTHON), "VTK's Python is missing: run `make deps` (it makes .venv-vtk)")
        r = subprocess.run([VTK_PYTHON, "-c", READ_WITH_VTK, os.path.join(self.out, "run.xmf")], capture_output=True, text=True,
                           timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        got = json.loads(r.stdout.strip().split("\n")[-1])
        np.testing.assert_allclose(got["times"], [0.0, 2e-7, 4e-7])
        blocks = got["blocks"]
        self.assertEqual(sorted(blocks), ["ball", "fluid", "wall"])
        with h5py.File(os.path.join(self.out, "snapshots", "snapshot_000001.h5"), "r") as f:
            fluid = blocks["fluid"]
            self.assertEqual(fluid["cells"], 16 ** 3)
            # VTK orders cell data x fastest, as the (z, y, x) datasets are stored.
            np.testing.assert_array_equal(np.array(fluid["arrays"]["velocity"]), f["fluid/velocity"][()].reshape(-1, 3))
            np.testing.assert_array_equal(np.array(fluid["arrays"]["pressure"]), f["fluid/pressure"][()].reshape(-1))
            ball = blocks["ball"]
            self.assertEqual(ball["points"], 400)
            self.assertEqual(ball["cells"], 2 * 400 - 4)
            np.testing.assert_array_equal(np.array(ball["xyz"]), f["cells/0/points"][()])
            for name in ("velocity", "force_density", "mean_curvature"):
                np.testing.assert_array_equal(np.array(ball["arrays"][name]), f["cells/0/" + name][()])
            np.testing.assert_array_equal(np.array(blocks["wall"]["xyz"]), f["points/0/points"][()])


class WholeBloodExample(unittest.TestCase):
    def test_vtk_opens_the_whole_blood_example(self):
        # The shipped example of Sec. 5.2, run for 2 us: every cell type and the endothelium are blocks.
        self.assertTrue(os.path.exists(VTK_PYTHON), "VTK's Python is missing: run `make deps` (it makes .venv-vtk)")
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "scene.yaml")
            with open(os.path.join(ROOT, "scenes", "whole_blood_bumpy.yaml")) as f:
                text = f.read().replace("snapshot_every: 10 us", "snapshot_every: 1 us")
            with open(scene, "w") as f:
                f.write(text)
            r = subprocess.run([RBFIB, "run", scene, "--out", os.path.join(d, "out"), "--until", "2 us"], capture_output=True,
                               text=True, timeout=600)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            r = subprocess.run([VTK_PYTHON, "-c", READ_WITH_VTK, os.path.join(d, "out", "run.xmf")], capture_output=True, text=True,
                               timeout=300)
            self.assertEqual(r.returncode, 0, r.stderr)
            got = json.loads(r.stdout.strip().split("\n")[-1])
            np.testing.assert_allclose(got["times"], [0.0, 1e-6, 2e-6])
            blocks = got["blocks"]
            self.assertEqual(sorted(blocks), ["endothelium", "fluid", "platelet", "red cell"])
            self.assertEqual(blocks["red cell"]["points"], 8 * 1600)
            self.assertEqual(blocks["platelet"]["points"], 2 * 400)
            self.assertEqual(blocks["endothelium"]["points"], 4096)
            self.assertEqual(blocks["fluid"]["cells"], 40 * 30 * 40)
            # The bumpy endothelium of eq. 5.5 between 0.75 and 1.75 um.
            y = np.array(blocks["endothelium"]["xyz"])[:, 1]
            self.assertGreater(y.min(), 0.74e-4)
            self.assertLess(y.max(), 1.76e-4)


if __name__ == "__main__":
    unittest.main()
