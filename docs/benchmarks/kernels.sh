#!/bin/bash
# SPDX-License-Identifier: BSD-3-Clause
# The LIC kernel, masked pass, launch shape, fidelity and frame measurements of
# docs/BENCHMARKS.md in one run: LIC3D_BINS holds `lic3d` from the bench preset (cmake --preset
# bench), DATA the two real fields of the fidelity table, OUT receives one text and one JSON file
# per measurement.
set -u
B=${LIC3D_BINS:-.}
DATA=${DATA:-data}
OUT=${OUT:-.}
mkdir -p "$OUT"
command -v nvidia-smi > /dev/null && nvidia-smi -L > "$OUT/device.txt"
run() {  # name, then the bench arguments
  local name=$1
  shift
  echo "== $name: lic3d bench $*" | tee -a "$OUT/summary.txt"
  local start=$SECONDS
  "$B/lic3d" bench "$@" --json "$OUT/$name.json" > "$OUT/$name.txt" 2>&1
  echo "exit $?, $((SECONDS - start)) s" >> "$OUT/summary.txt"
}
run kernels --kernels --sizes 256,512 --lengths 20 --repeats 7 --budget 300
run kernels1024 --kernels --sizes 1024 --lengths 20 --repeats 7 --budget 400
run fidelity --fidelity --sizes 64 --lengths 20 \
  --fidelity-files "$DATA/carotid.vtk,$DATA/example-femm-3d.vtk"
for i in 1 2 3; do
  run frames$i --sizes 64 --lengths 20 --frame-volume 256 --frame-sizes 512,1024,2048 \
    --repeats 7 --budget 120
done
