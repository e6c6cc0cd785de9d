# SPDX-License-Identifier: BSD-3-Clause
"""3D LIC of a vector field in ParaView with the lic3d plugin, on one process or many.

One process:
    pvbatch docs/paraview_lic3d.py --plugin build/release/lib/paraview-5.11/plugins/Lic3D/Lic3D.so \
        field.vti lic.vti
Four processes (each computes a piece of the grid; write .pvti, one .vti per piece):
    mpirun -np 4 pvbatch --mpi docs/paraview_lic3d.py --plugin .../Lic3D.so field.vti lic.pvti

The input should be a VTK XML image (.vti or .pvti): those readers give each process its piece
and the ghost layers the filter asks for. A legacy .vtk file is read whole by the first process;
convert it once with `--convert-only` (or `lic3d`'s own readers accept .vti). See docs/PARAVIEW.md.
"""

import argparse
import sys
import time

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, SaveData


def main():
    parser = argparse.ArgumentParser(description="3D LIC with the lic3d ParaView plugin")
    parser.add_argument("input", help="image data with a 3-component point array (.vti, .pvti, .vtk)")
    parser.add_argument("output", help=".vti (one process) or .pvti (any number of processes)")
    parser.add_argument("--plugin", help="path of Lic3D.so (needed unless --convert-only)")
    parser.add_argument("--array", help="the vector array (default: the active vectors)")
    parser.add_argument("--length", type=int, default=20, help="L, steps each way (default 20)")
    parser.add_argument("--step", type=float, default=0.5, help="h in voxels (default 0.5)")
    parser.add_argument("--bias", type=int, default=0, help="L-B steps backward, L+B forward")
    parser.add_argument("--integrator", choices=["Euler", "RK2", "RK4"], default="RK2")
    parser.add_argument("--kernel", choices=["Box", "Hann", "Gauss"], default="Box")
    parser.add_argument("--noise-filter", choices=["Nearest", "Linear"], default="Linear")
    parser.add_argument("--direction", choices=["Normalized", "Magnitude"], default="Normalized")
    parser.add_argument("--seed", type=int, default=1, help="noise seed (default 1)")
    parser.add_argument("--sparsity", default="None",
                        help="None, Checkerboard, Poisson, 'Poisson (best candidate)', Jitter, "
                             "Halton or Hammersley")
    parser.add_argument("--sparsity-points", type=int, default=0)
    parser.add_argument("--sparsity-radius", type=float, default=0.0)
    parser.add_argument("--sparsity-ratio", type=float, default=0.05)
    parser.add_argument("--sparsity-seed", type=int, default=1)
    parser.add_argument("--device", default="", help="Vulkan device (index or part of its name)")
    parser.add_argument("--cpu", action="store_true",
                        help="compute with lic3d's CPU reference instead of the Vulkan device")
    parser.add_argument("--convert-only", action="store_true",
                        help="write the input unchanged to OUTPUT (e.g. a legacy .vtk as .vti)")
    args = parser.parse_args()

    reader = OpenDataFile(args.input)
    if reader is None:
        sys.exit("cannot read " + args.input)
    if args.convert_only:
        SaveData(args.output, proxy=reader)
        return

    if not args.plugin:
        sys.exit("--plugin PATH/Lic3D.so is needed")
    LoadPlugin(args.plugin, ns=globals())
    lic = globals()["a3DLIC"](Input=reader)  # the filter labelled "3D LIC"
    if args.array:
        lic.Vectors = ["POINTS", args.array]
    lic.Length = args.length
    lic.Step = args.step
    lic.Bias = args.bias
    lic.Integrator = args.integrator
    lic.Kernel = args.kernel
    lic.NoiseFilter = args.noise_filter
    lic.Direction = args.direction
    lic.NoiseSeed = args.seed
    lic.Sparsity = args.sparsity
    lic.SparsityPoints = args.sparsity_points
    lic.SparsityRadius = args.sparsity_radius
    lic.SparsityRatio = args.sparsity_ratio
    lic.SparsitySeed = args.sparsity_seed
    lic.Device = args.device
    lic.CPUReference = 1 if args.cpu else 0

    start = time.perf_counter()
    lic.UpdatePipeline()  # every process reads its piece with ghost layers and computes it
    computed = time.perf_counter()
    if lic.GetDataInformation().GetNumberOfPoints() == 0:
        sys.exit("lic3d-paraview: 3D LIC gave no output (the messages above say why)")
    SaveData(args.output, proxy=lic, CompressorType="None")
    written = time.perf_counter()
    processes = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
    print("lic3d-paraview: %d process(es): read and LIC %.2f s, write %.2f s -> %s"
          % (processes, computed - start, written - computed, args.output))


if __name__ == "__main__":
    main()
