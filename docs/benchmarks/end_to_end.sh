#!/bin/bash
# Whole-process timings of two lic3d builds on this machine (before/after), into $OUT (default .).
OUT=${OUT:-.}
B=${LIC3D_BINS:-bin}  # the folder holding lic3d-before and lic3d-after
W=/tmp/w; mkdir -p $W
{
echo "== machine"; nproc; nvidia-smi -L 2>&1 | head -2
$B/lic3d-after devices
t() { local s=${EPOCHREALTIME/./}; "$@" > /dev/null 2>&1; local rc=$?; local e=${EPOCHREALTIME/./}; echo "$(( (e - s) / 1000 ))ms rc=$rc"; }
echo "== render (whole process, seconds; 3 runs each, warm disk)"
for g in 128 256 512; do for v in before after; do
  printf "render --grid %s %s: " $g $v; for r in 1 2 3; do t $B/lic3d-$v render -q --grid $g -o $W/r.png | tr '\n' ' '; done; echo
done; done
echo "== compute --grid 512 -o x.nrrd"
for v in before after; do printf "%s: " $v; for r in 1 2 3; do t $B/lic3d-$v compute -q --grid 512 -o $W/x.nrrd | tr '\n' ' '; done; echo; done
echo "== turntable 60 frames, 256^3, 1024^2 PNGs"
for v in before after; do printf "%s: " $v; rm -rf $W/tt; mkdir $W/tt; t $B/lic3d-$v render -q --grid 256 --turntable 60 -o "$W/tt/f_%02d.png"; done
echo "== timings after"
for g in 128 256 512; do echo "-- render --grid $g"; $B/lic3d-after render -q --grid $g --timings -o $W/r.png 2>&1; done
echo "-- compute --grid 512"; $B/lic3d-after compute -q --grid 512 --timings -o $W/x.nrrd 2>&1
echo "-- turntable"; rm -rf $W/tt; mkdir $W/tt; $B/lic3d-after render -q --grid 256 --turntable 60 --timings -o "$W/tt/f_%02d.png" 2>&1
echo "-- before, render --grid 512 (summary)"; $B/lic3d-before render --grid 512 -o $W/r.png 2>&1 | grep summary | cut -c1-160
} > $OUT/h100.txt 2>&1
cp $W/r.png $OUT/render512.png 2>/dev/null
