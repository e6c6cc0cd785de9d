# SPDX-License-Identifier: BSD-3-Clause
"""The Python module lic3d against the command line it shares its engine with.

Run by ctest (python.module) with PYTHONPATH at the built module, LIC3D_EXECUTABLE the lic3d
binary, lavapipe pinned and validation on (a validation message raises RuntimeError).
"""
import json
import os
import struct
import subprocess
import tempfile
import threading
import _thread
import time
import unittest
import zlib

import numpy as np

import lic3d

LIC3D = os.environ["LIC3D_EXECUTABLE"]


def swirl(nz, ny, nx):
    """A vortex about a tilted axis with an updraft: streamlines of every direction."""
    z, y, x = np.meshgrid(np.linspace(-1, 1, nz), np.linspace(-1, 1, ny),
                          np.linspace(-1, 1, nx), indexing="ij")
    v = np.stack([-y + 0.3 * z, x, 0.4 + 0.2 * x * y], axis=-1)
    return v.astype(np.float32)


def write_field_nrrd(path, vectors, spacing, origin):
    nz, ny, nx, _ = vectors.shape
    sx, sy, sz = spacing
    with open(path, "wb") as f:
        f.write((f"NRRD0004\ntype: float\ndimension: 4\nsizes: 3 {nx} {ny} {nz}\n"
                 f"space dimension: 3\nspace directions: none ({sx},0,0) (0,{sy},0) (0,0,{sz})\n"
                 f"kinds: vector domain domain domain\nendian: little\nencoding: raw\n"
                 f"space origin: ({origin[0]},{origin[1]},{origin[2]})\n\n").encode())
        f.write(np.ascontiguousarray(vectors, "<f4").tobytes())


def write_noise_nrrd(path, noise):
    nz, ny, nx = noise.shape
    with open(path, "wb") as f:
        f.write((f"NRRD0004\ntype: uchar\ndimension: 3\nsizes: {nx} {ny} {nz}\n"
                 "encoding: raw\n\n").encode())
        f.write(noise.tobytes())


def write_float_noise_nrrd(path, noise):
    nz, ny, nx = noise.shape
    with open(path, "wb") as f:
        f.write((f"NRRD0004\ntype: float\ndimension: 3\nsizes: {nx} {ny} {nz}\n"
                 "endian: little\nencoding: raw\n\n").encode())
        f.write(np.ascontiguousarray(noise, "<f4").tobytes())


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def read_nrrd_bytes(path):
    data = read_bytes(path)
    return data[data.index(b"\n\n") + 2:]


def read_png_rgba(path):
    """The pixels of an 8-bit RGBA PNG as lic3d writes them (no interlace), (h, w, 4)."""
    data = read_bytes(path)
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat, width, height = 8, b"", 0, 0
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 6), "expected 8-bit RGBA"
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw = zlib.decompress(idat)
    stride = 4 * width
    rows = np.zeros((height, stride), np.int32)
    previous = np.zeros(stride, np.int32)
    for r in range(height):
        line = raw[r * (stride + 1):(r + 1) * (stride + 1)]
        kind, row = line[0], np.frombuffer(line[1:], np.uint8).astype(np.int32)
        out = np.zeros(stride, np.int32)
        for i in range(stride):
            a = out[i - 4] if i >= 4 else 0
            b = previous[i]
            c = previous[i - 4] if i >= 4 else 0
            if kind == 0:
                p = 0
            elif kind == 1:
                p = a
            elif kind == 2:
                p = b
            elif kind == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            out[i] = (row[i] + p) & 255
        rows[r] = previous = out
    return rows.astype(np.uint8).reshape(height, width, 4)


class Lic3dModule(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.dir = self.folder.name
        self.vectors = swirl(14, 12, 16)
        self.spacing = (0.5, 0.75, 1.0)
        self.origin = (-2.0, 1.0, 0.25)
        self.field = os.path.join(self.dir, "field.nrrd")
        write_field_nrrd(self.field, self.vectors, self.spacing, self.origin)
        self.noise = np.random.default_rng(7).integers(0, 256, (14, 12, 16), dtype=np.uint8)
        self.noise_file = os.path.join(self.dir, "noise.nrrd")
        write_noise_nrrd(self.noise_file, self.noise)

    def tearDown(self):
        self.folder.cleanup()

    def test_scratch_lies_in_the_test_folder_named_by_tmpdir(self):
        # ctest names a folder inside the build folder; tempfile falls back to /tmp silently
        # when TMPDIR is unset or cannot be written.
        self.assertIn("TMPDIR", os.environ)
        self.assertEqual(os.path.realpath(tempfile.gettempdir()),
                         os.path.realpath(os.environ["TMPDIR"]))
        self.assertTrue(os.path.realpath(self.dir).startswith(
            os.path.realpath(os.environ["TMPDIR"]) + os.sep))

    def cli(self, *args):
        done = subprocess.run([LIC3D, "--quiet", *args], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)

    def test_compute_is_byte_identical_to_the_command_line(self):
        params = dict(length=9, step=0.4, integrator="rk4", kernel="hann",
                      noise_filter="nearest", bias=2)
        out = os.path.join(self.dir, "lic.nrrd")
        self.cli("compute", "--field", self.field, "--noise", self.noise_file, "--length", "9",
                 "--step", "0.4", "--integrator", "rk4", "--kernel", "hann", "--noise-filter",
                 "nearest", "--bias", "2", "-o", out)
        volume = lic3d.compute(self.vectors, spacing=self.spacing, origin=self.origin,
                               noise=self.noise, **params)
        self.assertEqual(volume.dtype, np.float32)
        self.assertEqual(volume.shape, (14, 12, 16))
        self.assertGreater(volume.std(), 0.01)
        self.assertEqual(volume.tobytes(), read_nrrd_bytes(out))
        # The same noise as a file, and the CPU reference as --cpu gives it.
        self.assertEqual(lic3d.compute(self.vectors, spacing=self.spacing, origin=self.origin,
                                       noise=self.noise_file, **params).tobytes(),
                         read_nrrd_bytes(out))
        self.cli("compute", "--cpu", "--field", self.field, "--seed", "3", "-L", "6", "-o", out)
        self.assertEqual(lic3d.compute(self.vectors, spacing=self.spacing, origin=self.origin,
                                       cpu=True, seed=3, length=6).tobytes(),
                         read_nrrd_bytes(out))

    def test_an_analytic_field_by_name_as_the_command_line(self):
        out = os.path.join(self.dir, "tornado.nrrd")
        self.cli("compute", "--field", "abc", "--grid", "20,18,16", "--sparsity", "halton",
                 "-o", out)
        volume = lic3d.compute(field="abc", grid=(20, 18, 16), sparsity="halton")
        self.assertEqual(volume.shape, (16, 18, 20))
        self.assertEqual(volume.tobytes(), read_nrrd_bytes(out))

    def test_render_is_the_picture_of_the_command_line(self):
        png = os.path.join(self.dir, "picture.png")
        self.cli("render", "--field", self.field, "--noise", self.noise_file, "--width", "80",
                 "--height", "60", "--look", "streamlines", "--azimuth", "30", "--colormap",
                 "viridis", "-o", png)
        image = lic3d.render(self.vectors, spacing=self.spacing, origin=self.origin,
                             noise=self.noise, width=80, height=60, look="streamlines",
                             azimuth=30, colormap="viridis")
        self.assertEqual((image.shape, image.dtype), ((60, 80, 4), np.uint8))
        np.testing.assert_array_equal(image, read_png_rgba(png))
        # A picture, not a blank: many colours, the box drawn over the background.
        self.assertGreater(len(np.unique(image.reshape(-1, 4), axis=0)), 50)
        # The session the PNG holds remakes the same picture from here.
        session = lic3d.session(session=png)
        self.assertEqual(session["view"]["width"], 80)
        again = lic3d.render(self.vectors, spacing=self.spacing, origin=self.origin,
                             noise=self.noise, session=session)
        np.testing.assert_array_equal(again, image)

    def test_depth_cues_are_keyword_parameters(self):
        common = dict(spacing=self.spacing, origin=self.origin, noise=self.noise, width=64,
                      height=64, look="dense")
        plain = lic3d.render(self.vectors, **common)
        for cue in (dict(halo=1.0), dict(occlusion=0.8), dict(lighting="gradient")):
            image = lic3d.render(self.vectors, **common, **cue)
            self.assertGreater(np.abs(image.astype(int) - plain.astype(int)).mean(), 0.5, cue)
        session = lic3d.session(halo=0.5, occlusion=0.25, halo_radius=2)
        self.assertEqual((session["view"]["halo"], session["view"]["occlusion"],
                          session["view"]["halo_radius"]), (0.5, 0.25, 2))

    def test_sessions_are_dicts(self):
        session = lic3d.session(length=7, look="streamlines", integrator="euler")
        self.assertEqual(session["lic"]["length"], 7)
        self.assertEqual(session["lic"]["integrator"], "euler")
        self.assertEqual(json.loads(json.dumps(session)), session)
        # A dict is the base the keyword parameters override.
        base = lic3d.compute(self.vectors, noise=self.noise, session=session)
        self.assertEqual(base.tobytes(),
                         lic3d.compute(self.vectors, noise=self.noise, length=7,
                                       integrator="euler").tobytes())
        over = lic3d.compute(self.vectors, noise=self.noise, session=session, length=3)
        self.assertNotEqual(over.tobytes(), base.tobytes())
        session["lic"]["length"] = -4
        with self.assertRaisesRegex(ValueError, "length"):
            lic3d.compute(self.vectors, session=session)

    def test_bad_input_raises_value_error_with_the_message(self):
        cases = [
            (dict(length=5000), r"--length: must be in \[0, 4096\]"),
            (dict(integrator="rk5"), "--integrator"),
            (dict(step=float("nan")), "--step"),
            (dict(sparsity_ratio=1.5), "--sparsity-ratio"),
            (dict(grid=8), "--grid chooses the field"),
            (dict(noise=np.zeros((14, 12, 15), np.uint8)), "noise grid 15x12x14"),
            (dict(noise=np.zeros((14, 12, 16), np.int64)), "uint8, uint16 or float32"),
            (dict(spacing=(1, 0, 1)), "spacing along y is 0"),
            (dict(noise=os.path.join(self.dir, "missing.nrrd")), "missing.nrrd"),
        ]
        for params, message in cases:
            with self.subTest(params=params), self.assertRaisesRegex(ValueError, message):
                lic3d.compute(self.vectors, **params)
        with self.assertRaisesRegex(ValueError, r"shape \(nz, ny, nx, 3\), got \(4, 4, 2\)"):
            lic3d.compute(np.ones((4, 4, 2), np.float32))
        with self.assertRaisesRegex(ValueError, "every vector of the field is zero"):
            lic3d.compute(np.zeros((4, 4, 4, 3), np.float32))
        with self.assertRaisesRegex(ValueError, "no such file"):
            lic3d.compute(field=os.path.join(self.dir, "none.vti"))
        with self.assertRaisesRegex(TypeError, "unexpected keyword argument 'lenght'"):
            lic3d.compute(self.vectors, lenght=3)
        with self.assertRaisesRegex(TypeError, "'output'"):
            lic3d.render(self.vectors, output="x.png")
        with self.assertRaisesRegex(ValueError, "--device"):
            lic3d.compute(self.vectors, device="no such device")

    def test_non_finite_vectors_warn_and_stop_streamlines(self):
        vectors = self.vectors.copy()
        vectors[3, 4, 5] = np.nan
        with self.assertWarnsRegex(RuntimeWarning, "1 vector"):
            volume = lic3d.compute(vectors.astype(np.float64), noise=self.noise)
        zeroed = self.vectors.copy()
        zeroed[3, 4, 5] = 0
        self.assertEqual(volume.tobytes(), lic3d.compute(zeroed, noise=self.noise).tobytes())

    def test_the_gil_is_released_while_the_gpu_works(self):
        # Counted, not timed: this thread counts while the other one is inside compute(). Holding
        # the GIL there would leave the count where compute() found it, give or take the thread
        # switches at its door; released, the count moves with the work. The work grows until
        # the count is well past those switches, so a fast machine passes as a slow one does.
        enough = 20
        for size in (24, 40, 64, 96):
            vectors = swirl(size, size, size)
            count, counted = [0], []

            def work():
                before = count[0]
                lic3d.compute(vectors, length=40)
                counted.append(count[0] - before)

            worker = threading.Thread(target=work)
            worker.start()
            while worker.is_alive():
                count[0] += 1
                time.sleep(0.0005)
            worker.join()
            if counted[0] >= enough:
                break
        self.assertGreaterEqual(counted[0], enough,
                                f"this thread counted {counted[0]} times while a {size}^3 "
                                "computation ran in the other one: compute() holds the GIL")

    def test_devices(self):
        devices = lic3d.devices()
        self.assertGreaterEqual(len(devices), 1)
        self.assertEqual(set(devices[0]), {"index", "name", "type"})
        chosen = lic3d.compute(self.vectors, noise=self.noise, device=devices[0]["name"][:4])
        self.assertEqual(chosen.tobytes(), lic3d.compute(self.vectors, noise=self.noise).tobytes())

    def test_nested_and_self_containing_values_are_refused(self):
        # A value lic3d takes is a flat list at most: deeper ones are refused, not followed.
        looped = []
        looped.append(looped)
        deep = []
        for _ in range(100000):
            deep = [deep]
        for name, value in (("looped", looped), ("deep", deep), ("nested", [1, [2, 3]])):
            with self.subTest(value=name):
                with self.assertRaisesRegex(TypeError, "color_range: expected a number"):
                    lic3d.session(color_range=value)
                with self.assertRaisesRegex(TypeError, "color_range: expected a number"):
                    lic3d.render(self.vectors, color_range=value)
                with self.assertRaisesRegex(TypeError, "length: expected a number"):
                    lic3d.compute(self.vectors, length=value)
        with self.assertRaisesRegex(TypeError, "length: expected a number.*dict"):
            lic3d.compute(self.vectors, length={"a": 1})
        with self.assertRaisesRegex(TypeError, "noise: expected an array"):
            lic3d.compute(self.vectors, noise=5)
        with self.assertRaisesRegex(TypeError, "session: expected a dict"):
            lic3d.session(session=looped)

    def test_numpy_scalars_are_numbers(self):
        vectors = self.vectors[:, :, :12]
        plain = lic3d.compute(vectors, noise=self.noise[:, :, :12], spacing=2, length=5)
        given = [dict(spacing=s) for s in (np.float32(2), np.int64(2), np.array(2),
                                           (2, np.float32(2), np.int8(2)), np.array([2.0] * 3))]
        given += [dict(spacing=2, length=n) for n in (np.int64(5), np.float32(5), 5.0)]
        for params in given:
            with self.subTest(params=params):
                made = lic3d.compute(vectors, noise=self.noise[:, :, :12],
                                     **{"length": 5, **params})
                self.assertEqual(made.tobytes(), plain.tobytes())
        cases = [
            (dict(spacing="abc"), TypeError, "spacing: expected 3 numbers .* got a str"),
            (dict(spacing=None), TypeError, "spacing: expected 3 numbers .* got a NoneType"),
            (dict(origin=10**400), ValueError, "origin: expected 3 numbers .* beyond a double"),
            (dict(spacing=(1, 10**400, 1)), ValueError, "spacing: .* beyond a double"),
            (dict(spacing=float("nan")), ValueError, "spacing: expected .* finite"),
            (dict(spacing=(1, 2)), ValueError, r"spacing: expected 3 numbers \(x, y, z\) or one"),
            (dict(spacing=True), TypeError, "spacing: .* got a bool"),
            (dict(length="abc"), ValueError,
             r"--length: expected a whole number in \[0, 4096\], got 'abc'"),
            (dict(length=10**400), ValueError, r"--length: must be in \[0, 4096\], got '1000"),
            (dict(length=5.5), ValueError, "--length: expected a whole number .* got '5.5'"),
            (dict(step=np.float32("nan")), ValueError, "--step"),
        ]
        for params, error, message in cases:
            with self.subTest(params=str(params)[:40]), self.assertRaisesRegex(error, message):
                lic3d.compute(self.vectors, **params)

    def test_float_noise_is_checked_as_a_noise_file_is(self):
        # Values outside [0, 1] are rescaled as `lic3d compute --noise f.nrrd` rescales them.
        noise = np.random.default_rng(3).uniform(-2, 5, (14, 12, 16)).astype(np.float32)
        path = os.path.join(self.dir, "float_noise.nrrd")
        write_float_noise_nrrd(path, noise)
        out = os.path.join(self.dir, "lic.nrrd")
        self.cli("compute", "--field", self.field, "--noise", path, "-L", "6", "-o", out)
        made = lic3d.compute(self.vectors, spacing=self.spacing, origin=self.origin, noise=noise,
                             length=6)
        self.assertEqual(made.tobytes(), read_nrrd_bytes(out))
        for bad, message in ((np.nan, r"voxel \(5,4,3\) is NaN or infinite"),
                             (np.inf, "NaN or infinite"), (-np.inf, "NaN or infinite")):
            broken = noise.copy()
            broken[3, 4, 5] = bad
            with self.subTest(bad=bad), self.assertRaisesRegex(ValueError, "noise: .*" + message):
                lic3d.compute(self.vectors, noise=broken)
        with self.assertRaisesRegex(ValueError, "noise: float noise is the constant 3"):
            lic3d.compute(self.vectors, noise=np.full((14, 12, 16), 3, np.float32))
        # An array of noise on an analytic field's grid would be ignored: it is refused.
        with self.assertRaisesRegex(ValueError, "noise: an array of noise goes with vectors"):
            lic3d.compute(grid=16, noise=np.zeros((16, 16, 16), np.uint8))

    def test_numpy_memory_error_stays_a_memory_error(self):
        # 3 PiB once made whole: numpy cannot, and says so with MemoryError.
        huge = np.broadcast_to(np.float64(1), (2**24, 2**24, 1, 3))
        with self.assertRaises(MemoryError):
            lic3d.compute(huge)
        with self.assertRaisesRegex(ValueError, "vectors: expected an array of numbers"):
            lic3d.compute([["a"]])

    def test_devices_as_the_command_line_takes_them(self):
        with self.assertRaisesRegex(ValueError, "999"):
            lic3d.compute(self.vectors, devices="999")
        with self.assertRaisesRegex(ValueError, "--cpu computes on the CPU"):
            lic3d.compute(self.vectors, devices="0", cpu=True)
        with self.assertRaisesRegex(ValueError, "not both"):
            lic3d.compute(self.vectors, devices="0", device="0")
        with self.assertRaisesRegex(ValueError, "lic3d.render draws on one device"):
            lic3d.render(self.vectors, devices="0")
        one = lic3d.compute(self.vectors, noise=self.noise)
        self.assertEqual(lic3d.compute(self.vectors, noise=self.noise, devices="all").tobytes(),
                         one.tobytes())
        # In bricks over the device list, as `lic3d compute --devices 0 --memory-budget` makes it.
        out = os.path.join(self.dir, "lic.nrrd")
        self.cli("compute", "--field", self.field, "--devices", "0", "--memory-budget", "60000",
                 "-L", "3", "-o", out)
        self.assertEqual(lic3d.compute(self.vectors, spacing=self.spacing, origin=self.origin,
                                       devices="0", memory_budget=60000, length=3).tobytes(),
                         read_nrrd_bytes(out))

    def test_progress_reports_the_finished_fraction(self):
        for params in (dict(), dict(cpu=True), dict(devices="0", memory_budget=60000, length=3)):
            with self.subTest(**params):
                reports = []
                lic3d.compute(self.vectors, noise=self.noise, progress=reports.append, **params)
                self.assertGreater(len(reports), 1)
                self.assertEqual(reports, sorted(reports))
                self.assertEqual(reports[-1], 1.0)

    def test_ctrl_c_stops_a_long_call(self):
        # Ctrl-C (here interrupt_main, as SIGINT does) at the first progress report: the work
        # stops at the end of its unit in flight (a slab of the GPU pass, a row of the CPU
        # reference, a brick), before the next one, and KeyboardInterrupt is raised once nothing
        # runs any more: no further report comes, from this call or later.
        cases = [("compute", dict()), ("compute", dict(cpu=True, threads=1)),
                 ("compute", dict(devices="0", memory_budget=60000, length=3)),
                 ("render", dict(width=32, height=32)),
                 ("render", dict(width=32, height=32, cpu=True))]
        seen = []
        for command, params in cases:
            with self.subTest(command=command, **params):
                reports = []
                seen.append(reports)

                def interrupt(fraction, reports=reports):
                    reports.append(fraction)
                    if len(reports) == 1:
                        _thread.interrupt_main()

                with self.assertRaises(KeyboardInterrupt):
                    getattr(lic3d, command)(self.vectors, noise=self.noise, progress=interrupt,
                                            **params)
                self.assertEqual(len(reports), 1)
                self.assertLess(reports[0], 1.0)
        # The module works on after interrupted calls, and the work they stopped stays stopped.
        self.assertEqual(lic3d.compute(self.vectors, noise=self.noise, length=60).shape,
                         (14, 12, 16))
        self.assertEqual([len(reports) for reports in seen], [1] * len(cases))

    def test_an_exception_from_progress_stops_the_call(self):
        reports = []

        def fail(fraction):
            reports.append(fraction)
            raise ValueError("enough")

        with self.assertRaisesRegex(ValueError, "enough"):
            lic3d.compute(self.vectors, noise=self.noise, progress=fail)
        self.assertEqual(len(reports), 1)
        self.assertEqual(lic3d.compute(self.vectors, noise=self.noise).shape, (14, 12, 16))

if __name__ == "__main__":
    unittest.main()
