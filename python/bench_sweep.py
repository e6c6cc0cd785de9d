#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The time per call of a render sweep (docs/PYTHON.md): lic3d.render called anew for each
picture against one lic3d.Renderer, over a sweep of the view (azimuth) and one of the LIC
(length), for a field given as numpy vectors and one named (made on the device).

    python3 python/bench_sweep.py --grid 256 --calls 8
"""
import argparse
import statistics
import sys
import time

import numpy as np

import lic3d


def swirl(n):
    """A vortex about a tilted axis with an updraft, float32 (n, n, n, 3)."""
    axis = np.linspace(-1, 1, n, dtype=np.float32)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    return np.stack([-y + 0.3 * z, x, 0.4 + 0.2 * x * y], axis=-1).astype(np.float32)


def per_call(call, sweep, warmup):
    """Seconds of each call after `warmup` ones, and the first call's."""
    seconds = []
    for params in sweep:
        start = time.perf_counter()
        call(params)
        seconds.append(time.perf_counter() - start)
    return seconds[0], seconds[warmup:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--grid", type=int, default=256, help="the field's cube edge (256)")
    parser.add_argument("--calls", type=int, default=8, help="calls timed per sweep (8)")
    parser.add_argument("--warmup", type=int, default=2, help="calls before those timed (2)")
    parser.add_argument("--width", type=int, default=800, help="picture width (800)")
    parser.add_argument("--height", type=int, default=600, help="picture height (600)")
    args = parser.parse_args()
    if args.grid < 2 or args.calls < 1 or args.warmup < 0:
        parser.error("--grid must be at least 2, --calls at least 1, --warmup at least 0")
    n = args.calls + args.warmup
    sweeps = {"view (azimuth)": [dict(azimuth=10 * i) for i in range(n)],
              "LIC (length)": [dict(length=10 + i) for i in range(n)]}
    fields = {"numpy vectors": dict(vectors=swirl(args.grid)),
              "field='tornado'": dict(field="tornado", grid=args.grid)}
    print(f"device: {lic3d.devices()[0]['name']}; lic3d {lic3d.__version__}; "
          f"{args.grid}^3, {args.width}x{args.height} pictures, median of {args.calls} calls after "
          f"{args.warmup}")
    print(f"{'field':<16} {'sweep':<15} {'lic3d.render':>13} {'Renderer':>10} {'speed-up':>9} "
          f"{'Renderer first':>15}")
    for field_name, field in fields.items():
        for sweep_name, sweep in sweeps.items():
            _, anew = per_call(lambda p: lic3d.render(**field, width=args.width, height=args.height, **p), sweep,
                               args.warmup)
            with lic3d.Renderer(**field, width=args.width, height=args.height) as r:
                first, kept = per_call(lambda p: r.render(**p), sweep, args.warmup)
            a, k = statistics.median(anew), statistics.median(kept)
            print(f"{field_name:<16} {sweep_name:<15} {a * 1e3:10.1f} ms {k * 1e3:7.1f} ms "
                  f"{a / k:8.1f}x {first * 1e3:12.1f} ms")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
