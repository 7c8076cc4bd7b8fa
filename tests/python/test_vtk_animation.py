"""`mbfe simulate --vtk`: every frame of the two-axle vehicle's animation read
back by VTK (vtkXMLPolyDataReader), its beam coordinates and contact forces
against the CSV of the same run, and one frame rendered off screen."""
import os
import shutil
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ET

import numpy as np
import vtk

SOURCE = os.environ.get("MBFE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("MBFE_CLI", os.path.join(SOURCE, "build", "bin", "mbfe"))
SCALE = 50.0


class Animation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp()
        cls.csv = os.path.join(cls.tmp, "truck.csv")
        cls.vtk_dir = os.path.join(cls.tmp, "vtk")
        r = subprocess.run([CLI, "simulate", os.path.join(SOURCE, "models", "bridge_two_axle_vehicle.yaml"),
                            "--probe", "deck@10", "--out", cls.csv, "--vtk", cls.vtk_dir, "--vtk-scale", str(SCALE),
                            "--vtk-frames", "81", "--quiet"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        with open(cls.csv) as f:
            cls.header = f.readline().strip().split(",")
        cls.rows = np.loadtxt(cls.csv, delimiter=",", skiprows=1)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def frames(self):
        root = ET.parse(os.path.join(self.vtk_dir, "bridge_two_axle_vehicle.pvd")).getroot()
        return [(float(d.get("timestep")), os.path.join(self.vtk_dir, d.get("file"))) for d in root.iter("DataSet")]

    def read(self, path):
        reader = vtk.vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        self.assertEqual(reader.GetErrorCode(), 0, path)
        return reader.GetOutput()

    def row_at(self, t):
        k = int(np.argmin(np.abs(self.rows[:, 0] - t)))
        self.assertAlmostEqual(self.rows[k, 0], t, places=12)
        return self.rows[k]

    def test_every_frame_reads_back(self):
        frames = self.frames()
        self.assertEqual(len(frames), 81)
        self.assertEqual(frames[0][0], 0.0)
        self.assertAlmostEqual(frames[-1][0], 1.6, places=9)
        for _, path in frames:
            data = self.read(path)
            # approach 41 + deck 161 + exit 41 beam points, 4 body outline points, 2 wheel points, 6 contacts
            self.assertEqual(data.GetNumberOfPoints(), 41 + 161 + 41 + 4 + 2 + 6, path)
            self.assertEqual(data.GetNumberOfLines(), 3 + 1)

    def test_coordinates_and_forces_match_the_csv(self):
        t, path = self.frames()[40]
        data = self.read(path)
        row = self.row_at(t)
        points = np.array([data.GetPoint(i) for i in range(data.GetNumberOfPoints())])
        w = np.array([data.GetPointData().GetArray("w").GetValue(i) for i in range(data.GetNumberOfPoints())])
        # The deck's midspan node: the 121st beam point (41 of the approach, then 80 along the deck).
        mid = 41 + 80
        self.assertEqual(points[mid, 0], 10.0)
        self.assertEqual(w[mid], row[self.header.index("deck@10")])
        self.assertAlmostEqual(points[mid, 1], SCALE * row[self.header.index("deck@10")], places=12)
        # Contact forces: the front wheel's vector on the deck has the CSV's force along the normal (0, 1).
        force = data.GetPointData().GetArray("contact_force")
        contacts = range(data.GetNumberOfPoints() - 6, data.GetNumberOfPoints())
        expected = [row[self.header.index("force_" + n)] for n in
                    ("front_approach", "front_deck", "front_exit", "rear_approach", "rear_deck", "rear_exit")]
        got = [force.GetTuple3(i)[1] for i in contacts]
        self.assertEqual(got, expected)
        self.assertGreater(expected[1], 30000.0)  # the front wheel is on the deck at t = 0.8 s

    def test_a_slider_pin_force_is_its_multiplier_on_the_body(self):
        vtk_dir = os.path.join(self.tmp, "pendulum")
        csv_path = os.path.join(self.tmp, "pendulum.csv")
        r = subprocess.run([CLI, "simulate", os.path.join(SOURCE, "models", "double_pendulum_beam.yaml"), "--step",
                            "1e-5", "--t-end", "0.05", "--probe", "beam1@0.5", "--out", csv_path, "--vtk", vtk_dir,
                            "--vtk-frames", "6", "--quiet"], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(csv_path) as f:
            header = f.readline().strip().split(",")
        rows = np.loadtxt(csv_path, delimiter=",", skiprows=1)
        root = ET.parse(os.path.join(vtk_dir, "double_pendulum_beam.pvd")).getroot()
        t, name = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")][-1]
        data = self.read(os.path.join(vtk_dir, name))
        row = rows[int(np.argmin(np.abs(rows[:, 0] - t)))]
        lam = row[header.index("lambda_tip_slider")]
        fx, fy, _ = data.GetPointData().GetArray("contact_force").GetTuple3(data.GetNumberOfPoints() - 1)
        # A horizontal beam: the normal is (0, 1), so f_y is the multiplier itself and
        # f_x = -lambda w'(s), small against it.
        self.assertEqual(fy, lam)
        self.assertLess(abs(fx), 0.05 * abs(lam))
        self.assertGreater(abs(lam), 1.0)

    def test_a_frame_renders_off_screen(self):
        if shutil.which("xvfb-run") is None:
            self.fail("xvfb-run is missing (scripts/install-deps.sh installs xvfb)")
        png = os.path.join(self.tmp, "frame.png")
        r = subprocess.run(["xvfb-run", "-a", "/usr/bin/python3", os.path.join(SOURCE, "scripts", "render_frame.py"),
                            self.frames()[40][1], png], capture_output=True, text=True, timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        reader = vtk.vtkPNGReader()
        reader.SetFileName(png)
        reader.Update()
        image = reader.GetOutput()
        self.assertEqual(image.GetDimensions()[:2], (1200, 420))
        scalars = image.GetPointData().GetScalars()
        pixels = np.array([scalars.GetTuple(i)[:3] for i in range(0, scalars.GetNumberOfTuples(), 7)])
        dark = (pixels.sum(axis=1) < 400).mean()
        self.assertGreater(dark, 0.001)  # something was drawn
        self.assertLess(dark, 0.2)       # on a white background


class FrameTimes(unittest.TestCase):
    def test_the_last_frame_is_at_t_end_when_the_interval_is_not_a_multiple_of_the_step(self):
        # 1.2 s in steps of 1 ms, 200 frames: an interval of 1.2/199 s that no
        # row falls on. Frames at the rows that first reach k * 1.2/199, the
        # last one at t_end, and every one of the 200 (the interval is longer
        # than a step).
        tmp = tempfile.mkdtemp()
        try:
            out = os.path.join(tmp, "vtk")
            r = subprocess.run([CLI, "simulate", os.path.join(SOURCE, "models", "bridge_moving_mass.yaml"),
                                "--vtk", out, "--vtk-frames", "200", "--quiet"], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            root = ET.parse(os.path.join(out, "bridge_moving_mass.pvd")).getroot()
            times = [float(d.get("timestep")) for d in root.iter("DataSet")]
            self.assertEqual(len(times), 200)
            self.assertAlmostEqual(times[-1], 1.2, places=9)
            interval = 1.2 / 199
            for k, t in enumerate(times):
                # the first row (1 ms apart) at or after k * interval
                self.assertGreaterEqual(t, k * interval - 1e-9)
                self.assertLess(t, k * interval + 1e-3)
        finally:
            shutil.rmtree(tmp)


if __name__ == "__main__":
    unittest.main()


class SpatialAnimation(unittest.TestCase):
    """The spatial slider-crank's frames: each body a polyline from its frame's
    origin through its points, each frame a right-handed triad of equal
    orthogonal axes (cell data `axis`), and the loop closed in the picture:
    the rod's end where the slider's origin is."""

    def test_bodies_and_triads(self):
        with tempfile.TemporaryDirectory() as tmp:
            vtk_dir = os.path.join(tmp, "vtk")
            r = subprocess.run([CLI, "simulate", os.path.join(SOURCE, "models", "slider_crank_3d.yaml"), "--t-end",
                                "0.2", "--out", os.path.join(tmp, "sc.csv"), "--vtk", vtk_dir, "--vtk-frames", "5",
                                "--quiet"], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            reader = vtk.vtkXMLPolyDataReader()
            reader.SetFileName(os.path.join(vtk_dir, "frames", "frame_000004.vtp"))
            reader.Update()
            data = reader.GetOutput()
        axis = data.GetCellData().GetArray("axis")
        part = data.GetCellData().GetArray("part")
        self.assertIsNotNone(axis)
        cells = {}
        for c in range(data.GetNumberOfCells()):
            ids = data.GetCell(c).GetPointIds()
            points = [np.array(data.GetPoint(ids.GetId(k))) for k in range(ids.GetNumberOfIds())]
            cells.setdefault(int(part.GetValue(c)), []).append((int(axis.GetValue(c)), points))
        # Parts 0..2: crank, rod, slider (origin, then points); 3..5 their triads.
        rod_end = cells[1][0][1][-1]
        slider_origin = cells[2][0][1][0]
        np.testing.assert_allclose(rod_end, slider_origin, atol=1e-12)
        for body in range(3, 6):
            axes = sorted(cells[body], key=lambda c: c[0])
            self.assertEqual([a for a, _ in axes], [0, 1, 2])
            e = np.array([p[1] - p[0] for _, p in axes])
            lengths = np.linalg.norm(e, axis=1)
            np.testing.assert_allclose(lengths, lengths[0], rtol=1e-12)
            np.testing.assert_allclose(e @ e.T / lengths[0] ** 2, np.eye(3), atol=1e-12)
            self.assertAlmostEqual(np.dot(np.cross(e[0], e[1]), e[2]) / lengths[0] ** 3, 1.0, places=12)
