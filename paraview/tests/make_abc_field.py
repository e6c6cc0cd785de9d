# SPDX-License-Identifier: BSD-3-Clause
"""Writes the ABC flow (docs/LIC_SEMANTICS.md, the `abc` field of lic3d) on an N^3 grid as .vti:
the large field of the scaling runs in docs/PARAVIEW.md. Run with pvpython:

    pvpython paraview/tests/make_abc_field.py 256 abc256.vti
"""

import sys

import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter


def main():
    n, path = int(sys.argv[1]), sys.argv[2]
    # Voxel centres spanning [0, 2 pi] along every axis, as lic3d samples it on a cubic grid.
    step = 2.0 * numpy.pi / n
    c = (numpy.arange(n) + 0.5) * step
    z, y, x = numpy.meshgrid(c, c, c, indexing="ij")  # x fastest in memory, as VTK stores it
    a, b, cc = numpy.sqrt(3.0), numpy.sqrt(2.0), 1.0
    v = numpy.stack([a * numpy.sin(z) + cc * numpy.cos(y),
                     b * numpy.sin(x) + a * numpy.cos(z),
                     cc * numpy.sin(y) + b * numpy.cos(x)], axis=-1).astype(numpy.float32)
    image = vtkImageData()
    image.SetDimensions(n, n, n)
    image.SetSpacing(step, step, step)
    image.SetOrigin(0.5 * step, 0.5 * step, 0.5 * step)
    array = numpy_to_vtk(v.reshape(-1, 3), deep=True)
    array.SetName("velocity")
    image.GetPointData().SetVectors(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.SetCompressorTypeToNone()
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    if not writer.Write():
        sys.exit("cannot write " + path)


if __name__ == "__main__":
    main()
