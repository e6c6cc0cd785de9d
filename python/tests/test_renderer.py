# SPDX-License-Identifier: BSD-3-Clause
"""lic3d.Renderer: what it keeps between calls, and that it gives what lic3d.compute and
lic3d.render give (docs/PYTHON.md)."""
import _thread
import os
import tempfile
import threading
import unittest

import numpy as np

import lic3d
from test_lic3d import read_nrrd_bytes, read_png_rgba, swirl, write_float_noise_nrrd

LIC3D = os.environ["LIC3D_EXECUTABLE"]


class Renderer(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.dir = self.folder.name
        self.vectors = swirl(14, 12, 16)
        self.noise = np.random.default_rng(7).integers(0, 256, (14, 12, 16), dtype=np.uint8)
        self.field = dict(spacing=(0.5, 0.75, 1.0), origin=(-2.0, 1.0, 0.25), noise=self.noise)
        self.view = dict(width=64, height=48, color="magnitude")

    def tearDown(self):
        self.folder.cleanup()

    def test_a_sweep_gives_the_pictures_and_volumes_of_the_functions(self):
        # A look's noise is not compute's: the calls alternate between two sets of inputs.
        with lic3d.Renderer(self.vectors, **self.field, **self.view, look="streamlines") as r:
            for azimuth in (0, 40, 80):
                np.testing.assert_array_equal(
                    r.render(azimuth=azimuth),
                    lic3d.render(self.vectors, **self.field, **self.view, look="streamlines",
                                 azimuth=azimuth))
            for length in (5, 12):
                self.assertEqual(r.compute(length=length).tobytes(),
                                 lic3d.compute(self.vectors, **self.field, length=length).tobytes())
                np.testing.assert_array_equal(
                    r.render(length=length, colormap="viridis"),
                    lic3d.render(self.vectors, **self.field, **self.view, look="streamlines",
                                 length=length, colormap="viridis"))
            # The CPU reference beside the kept device, and the device again after it.
            self.assertEqual(r.compute(cpu=True, length=6).tobytes(),
                             lic3d.compute(self.vectors, **self.field, cpu=True,
                                           length=6).tobytes())
            np.testing.assert_array_equal(
                r.render(), lic3d.render(self.vectors, **self.field, **self.view,
                                         look="streamlines"))

    def test_a_view_sweep_makes_nothing_again(self):
        with lic3d.Renderer(self.vectors, **self.field, **self.view) as r:
            first = r.render()
            made = r.made
            self.assertEqual((made["inputs"], made["renderers"]), (1, 1))
            self.assertGreater(made["lic_dispatches"], 0)
            pictures = [r.render(azimuth=a, elevation=10, colormap="coolwarm") for a in range(0, 90, 30)]
            self.assertEqual(r.made, made)
            self.assertTrue(all(not np.array_equal(p, first) for p in pictures))
            # The LIC volume of the pictures, read back without making it again.
            r.compute()
            self.assertEqual(r.made, made)
            # A LIC parameter makes the LIC again, on the same renderer and inputs.
            r.render(length=7)
            again = r.made
            self.assertEqual((again["inputs"], again["renderers"]), (1, 1))
            self.assertGreater(again["lic_dispatches"], made["lic_dispatches"])
        # A new grid, or new noise, is new inputs.
        with lic3d.Renderer(self.vectors) as r:
            r.compute()
            self.assertEqual(r.compute(resolution="8,8,8").shape, (8, 8, 8))
            r.compute(resolution="8,8,8", seed=3)
            self.assertEqual(r.made["inputs"], 3)

    def test_a_field_by_name_moves_in_time(self):
        with lic3d.Renderer(field="tornado", grid=(24, 24, 20), **self.view) as r:
            for t in (0.0, 0.5):
                self.assertEqual(r.compute(time=t).tobytes(),
                                 lic3d.compute(field="tornado", grid=(24, 24, 20), time=t).tobytes())
                np.testing.assert_array_equal(
                    r.render(time=t), lic3d.render(field="tornado", grid=(24, 24, 20), time=t,
                                                   **self.view))
            self.assertEqual(r.made["inputs"], 1)

    def test_color_by_a_named_array(self):
        pressure = np.linspace(0.0, 3.0, self.vectors[..., 0].size,
                               dtype=np.float32).reshape(self.vectors.shape[:3])
        path = os.path.join(self.dir, "pressure.nrrd")
        write_float_noise_nrrd(path, pressure)
        # The picture of the command line's scalar file, named as the file is (its stem).
        by_file = lic3d.render(self.vectors, **self.field, **self.view, color_by=path)
        by_speed = lic3d.render(self.vectors, **self.field, **self.view)
        self.assertGreater(np.abs(by_file.astype(int) - by_speed.astype(int)).mean(), 1.0)
        with lic3d.Renderer(self.vectors, **self.field, **self.view,
                            scalars={"pressure": pressure}) as r:
            np.testing.assert_array_equal(r.render(color_by="pressure"), by_file)
            np.testing.assert_array_equal(r.render(), by_speed)
            with self.assertRaisesRegex(ValueError, "pressure"):
                r.render(color_by="temperature")
        np.testing.assert_array_equal(
            lic3d.render(self.vectors, **self.field, **self.view, scalars={"pressure": pressure},
                         color_by="pressure"), by_file)
        # An array given to color_by itself.
        os.replace(path, os.path.join(self.dir, "color_by.nrrd"))
        np.testing.assert_array_equal(
            lic3d.render(self.vectors, **self.field, **self.view, color_by=pressure),
            lic3d.render(self.vectors, **self.field, **self.view,
                         color_by=os.path.join(self.dir, "color_by.nrrd")))
        with self.assertRaisesRegex(ValueError, "grid"):
            lic3d.render(self.vectors, **self.field, color_by=pressure[:, :, :8])
        with self.assertRaisesRegex(ValueError, "derives"):
            lic3d.Renderer(self.vectors, scalars={"speed": pressure})

    def test_devices_are_chosen_once(self):
        with lic3d.Renderer(self.vectors, **self.field, devices="all") as r:
            self.assertGreaterEqual(len(r.device_names), 1)
            self.assertEqual(r.compute().tobytes(), lic3d.compute(self.vectors, **self.field).tobytes())
            # In bricks over the devices where the budget asks, as the function makes it.
            self.assertEqual(
                r.compute(memory_budget=60000, length=3).tobytes(),
                lic3d.compute(self.vectors, **self.field, devices="all", memory_budget=60000,
                              length=3).tobytes())
            np.testing.assert_array_equal(r.render(**self.view),
                                          lic3d.render(self.vectors, **self.field, **self.view))
            with self.assertRaisesRegex(TypeError, "chosen when it is made"):
                r.render(device="0")
        with self.assertRaisesRegex(ValueError, "999"):
            lic3d.Renderer(self.vectors, devices="999")
        with self.assertRaisesRegex(TypeError, "lenght"):
            lic3d.Renderer(self.vectors, lenght=3)

    def test_close_gives_the_devices_back(self):
        r = lic3d.Renderer(self.vectors, **self.field)
        self.assertFalse(r.closed)
        r.compute()
        r.close()
        r.close()
        self.assertTrue(r.closed)
        with self.assertRaisesRegex(RuntimeError, "closed"):
            r.render()
        with lic3d.Renderer(self.vectors) as r:
            pass
        self.assertTrue(r.closed)
        with self.assertRaisesRegex(RuntimeError, "closed"):
            r.compute()

    def test_calls_from_threads_take_turns(self):
        expected = {a: lic3d.render(self.vectors, **self.field, **self.view, azimuth=a)
                    for a in (10, 50)}
        with lic3d.Renderer(self.vectors, **self.field, **self.view) as r:
            got, failed = {}, []

            def work(azimuth):
                try:
                    for _ in range(3):
                        got[azimuth] = r.render(azimuth=azimuth, length=4 + azimuth // 10)
                        got[azimuth] = r.render(azimuth=azimuth)
                except Exception as e:  # noqa: BLE001 - reported below
                    failed.append(e)

            threads = [threading.Thread(target=work, args=(a,)) for a in expected]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            self.assertEqual(failed, [])
            for a, picture in expected.items():
                np.testing.assert_array_equal(got[a], picture)

    def test_ctrl_c_leaves_the_renderer_usable(self):
        with lic3d.Renderer(self.vectors, **self.field) as r:
            reports = []

            def interrupt(fraction):
                reports.append(fraction)
                if len(reports) == 1:
                    _thread.interrupt_main()

            with self.assertRaises(KeyboardInterrupt):
                r.compute(length=30, progress=interrupt)
            self.assertEqual(len(reports), 1)
            self.assertEqual(r.compute(length=30).tobytes(),
                             lic3d.compute(self.vectors, **self.field, length=30).tobytes())


if __name__ == "__main__":
    unittest.main()
