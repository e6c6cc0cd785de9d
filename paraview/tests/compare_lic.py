# SPDX-License-Identifier: BSD-3-Clause
"""Compares two LIC volumes (.vti or .pvti) voxel by voxel: run with pvpython.

    pvpython compare_lic.py A B [--array-a LIC] [--array-b LIC] [--max T] [--mean T]
                                [--within T --fraction F]

Both must cover the same extent, origin and spacing and hide (NaN) the same voxels. Over the
others, |A - B| must stay within each bound given: its largest value, its mean, and T for at
least the fraction F of the voxels. Prints one line of statistics.
"""

import argparse
import sys

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPImageDataReader


def read(path, array):
    reader = vtkXMLPImageDataReader() if path.endswith(".pvti") else vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    values = image.GetPointData().GetArray(array)
    if values is None:
        sys.exit("%s has no point array '%s'" % (path, array))
    return image, vtk_to_numpy(values).astype(numpy.float64)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--array-a", default="LIC")
    parser.add_argument("--array-b", default="LIC")
    parser.add_argument("--max", type=float, help="bound on the largest difference")
    parser.add_argument("--mean", type=float, help="bound on the mean difference")
    parser.add_argument("--within", type=float, help="bound for the fraction --fraction of voxels")
    parser.add_argument("--fraction", type=float, default=1.0)
    args = parser.parse_args()

    image_a, a = read(args.a, args.array_a)
    image_b, b = read(args.b, args.array_b)
    for what in ("GetExtent", "GetOrigin", "GetSpacing"):
        if getattr(image_a, what)() != getattr(image_b, what)():
            sys.exit("%s differ: %s against %s" % (what[3:].lower(), getattr(image_a, what)(),
                                                    getattr(image_b, what)()))
    hidden_a, hidden_b = numpy.isnan(a), numpy.isnan(b)
    if (hidden_a != hidden_b).any():
        sys.exit("%d voxel(s) hidden in one volume only" % (hidden_a != hidden_b).sum())
    shown = ~hidden_a
    difference = numpy.abs(a[shown] - b[shown])
    if difference.size == 0:
        difference = numpy.zeros(1)
    measured = {"max": difference.max(), "mean": difference.mean()}
    print("compare_lic: %d voxels (%d hidden), %d differ; difference: largest %.3g, mean %.3g, "
          "99th percentile %.3g, 99.9th %.3g"
          % (a.size, hidden_a.sum(), (difference > 0).sum(), measured["max"], measured["mean"],
             numpy.quantile(difference, 0.99), numpy.quantile(difference, 0.999)))
    failed = ["%s %.3g > %.3g" % (name, value, getattr(args, name))
              for name, value in measured.items()
              if getattr(args, name) is not None and value > getattr(args, name)]
    if args.within is not None:
        fraction = (difference <= args.within).mean()
        if fraction < args.fraction:
            failed.append("%.4f of the voxels within %.3g, fewer than %.4f"
                          % (fraction, args.within, args.fraction))
    if failed:
        sys.exit("compare_lic: above the bound: " + ", ".join(failed))

if __name__ == "__main__":
    main()
