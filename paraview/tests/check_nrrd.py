# SPDX-License-Identifier: BSD-3-Clause
"""ParaView reads lic3d's NRRD files as lic3d means them: the LIC volume and the RGBA volume of a
field on that field's 3D extent, the arrays named LIC (1 component) and RGBA (4 components).

    pvpython check_nrrd.py FIELD.vti LIC.nrrd RGBA.nrrd
"""
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile


def fetch(path):
    reader = OpenDataFile(path)
    reader.UpdatePipeline()
    return servermanager.Fetch(reader)


def main():
    field, lic, rgba = sys.argv[1:4]
    extent = fetch(field).GetExtent()
    for path, name, components in ((lic, "LIC", 1), (rgba, "RGBA", 4)):
        data = fetch(path)
        points = data.GetPointData()
        names = [points.GetArrayName(i) for i in range(points.GetNumberOfArrays())]
        array = points.GetArray(0)
        print(f"{path}: extent {data.GetExtent()}, arrays {names}, "
              f"{array.GetNumberOfComponents()} component(s)")
        if data.GetExtent() != extent:
            raise AssertionError(f"{path}: extent {data.GetExtent()}, the field's is {extent}")
        if names != [name] or array.GetNumberOfComponents() != components:
            raise AssertionError(f"{path}: expected one array {name} of {components} component(s)")


if __name__ == "__main__":
    main()
