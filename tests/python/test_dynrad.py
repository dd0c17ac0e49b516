"""`import dynrad` (plugin/python): a scene file's grid and report, a box from arrays
against its closed form, and bad input as Python errors. Run by ctest with the built
package on PYTHONPATH (tests/CMakeLists.txt)."""
import math
import os
import unittest

import numpy as np

import dynrad

SAMPLES = os.environ["DYNRAD_SAMPLES_DIR"]


def box(size=1.0):
    """A closed cube, two triangles per side facing inward: bottom, top, -y, +y, -x, +x."""
    v = np.array([[x, y, z] for z in (0, size) for y in (0, size) for x in (0, size)], dtype=float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    faces = []
    for d, c, b, a in quads:  # reversed: each quad above runs clockwise seen from inside
        faces += [(a, b, c), (a, c, d)]
    return v, np.array(faces)


class Dynrad(unittest.TestCase):
    def test_scene_file_gives_grids_and_report(self):
        r = dynrad.solve(os.path.join(SAMPLES, "daylight_clear.json"), quality="draft")
        n = r["positions"].shape[0]
        self.assertEqual(r["positions"].shape, (n, 3))
        self.assertEqual(r["radiosity"].shape, (n, 3))
        self.assertEqual(r["triangles"].shape[1], 3)
        self.assertLess(int(r["triangles"].max()), n)
        self.assertEqual(r["triangle_materials"].shape, (r["triangles"].shape[0],))
        self.assertTrue(np.all(np.isfinite(r["radiosity"])) and np.all(r["radiosity"] >= 0))
        grid = r["grids"]["room"]
        self.assertEqual(grid["points"].shape, (240, 3))
        lux = grid["illuminance"]
        lit = lux[~np.isnan(lux)]
        report = r["report"]
        self.assertEqual(report["units"], "photometric")
        self.assertIn(report["stopped_by"], ("error target", "error floor", "converged"))
        (summary,) = report["grids"]
        self.assertEqual(summary["name"], "room")
        # The report's Eavg is the mean of the points the arrays give.
        self.assertAlmostEqual(summary["Eavg"], float(lit.mean()), delta=1e-9 * summary["Eavg"])
        # The sun through the window: its patch far above the room's mean.
        self.assertGreater(float(lit.max()), 3 * summary["Eavg"])

    def test_furnace_box_from_arrays(self):
        # Every face emits E = 1 and reflects rho = 0.5: B = E / (1 - rho) = 2 everywhere.
        v, f = box()
        materials = [{"name": "glowing grey", "reflectance": 0.5, "emission": 1.0}]
        r = dynrad.solve_arrays(v, f, np.zeros(len(f), dtype=int), materials, converge=1e-6, max_level=1,
                                patch_size=0.5)
        b = r["radiosity"]
        self.assertTrue(np.allclose(b, 2.0, rtol=0.01), f"radiosity from {b.min()} to {b.max()}")
        self.assertEqual(r["grids"], {})
        self.assertEqual(r["report"]["units"], "radiometric")

    def test_lamp_lights_a_box_and_energy_balances(self):
        v, f = box(2.0)
        face_materials = np.zeros(len(f), dtype=int)
        face_materials[2:4] = 1  # the top face (-z facing) is the lamp
        materials = [{"reflectance": [0.6, 0.5, 0.4]}, {"reflectance": 0.0, "emission": 10.0, "name": "lamp"}]
        r = dynrad.solve_arrays(v, f, face_materials, materials, quality="draft")
        e = r["report"]["energy"]
        emitted, absorbed, escaped, unshot = (sum(e[k]) for k in ("emitted", "absorbed", "escaped", "unshot"))
        self.assertAlmostEqual(emitted, 3 * 10.0 * 4.0, delta=1e-6 * emitted)  # 10 W/m2 x 4 m2, per channel
        self.assertLess(escaped, 1e-9 * emitted)  # a closed box
        self.assertLess(abs(absorbed + unshot - emitted), 1e-3 * emitted)
        floor = r["positions"][:, 2] < 1e-9
        self.assertTrue(np.all(r["irradiance"][floor, 0] > 0))

    def test_bad_input_raises(self):
        with self.assertRaises(ValueError) as e:
            dynrad.solve(os.path.join(SAMPLES, "no_such_scene.json"))
        self.assertIn("no_such_scene.json", str(e.exception))
        with self.assertRaises(ValueError):
            dynrad.solve(os.path.join(SAMPLES, "cornell_box.obj"), quality="excellent")
        with self.assertRaises(TypeError):
            dynrad.solve(os.path.join(SAMPLES, "cornell_box.obj"), qualty="draft")
        v, f = box()
        with self.assertRaises(ValueError) as e:
            dynrad.solve_arrays(v, f, np.zeros(len(f), dtype=int), [{"reflectance": 1.2, "emission": 1.0}])
        self.assertIn("materials[0]", str(e.exception))
        with self.assertRaises(ValueError):
            dynrad.solve_arrays(v, f + 100, np.zeros(len(f), dtype=int), [{"reflectance": 0.5, "emission": 1.0}])
        with self.assertRaises(dynrad.InputError):  # nothing emits
            dynrad.solve_arrays(v, f, np.zeros(len(f), dtype=int), [{"reflectance": 0.5}])
        self.assertTrue(math.isfinite(float(dynrad.__version__.split(".")[0])))


if __name__ == "__main__":
    unittest.main()
