#!/bin/bash
# SPDX-License-Identifier: BSD-3-Clause
# Whole-process timings of two lic3d builds (before/after) on this machine, into $OUT.
OUT=${OUT:-.}
B=${LIC3D_BINS:-bin}  # the folder holding lic3d-before, lic3d-after and make_abc_vti
W=/tmp/w; mkdir -p $W
t() { local s=${EPOCHREALTIME/./}; "$@" > /dev/null 2>&1; local rc=$?; local e=${EPOCHREALTIME/./}; echo "$(( (e - s) / 1000 ))ms rc=$rc"; }
{
echo "== machine"; nproc; nvidia-smi -L 2>&1 | head -2
$B/lic3d-after devices
echo "== render (whole process; 3 runs each, warm disk)"
for g in 128 256 512; do for v in before after; do
  printf "render --grid %s %s: " $g $v; for r in 1 2 3; do t $B/lic3d-$v render -q --grid $g -o $W/r_$v.png | tr '\n' ' '; done; echo
done; done
echo "== compute --grid 512 -o x.nrrd"
for v in before after; do printf "%s: " $v; for r in 1 2 3; do t $B/lic3d-$v compute -q --grid 512 -o $W/x.nrrd | tr '\n' ' '; done; echo; done
echo "== turntable 360 frames, 256^3, 1024^2 PNGs"
for v in before after; do printf "%s: " $v; rm -rf $W/tt; mkdir $W/tt; t $B/lic3d-$v render -q --grid 256 --turntable 360 -o "$W/tt/f_%03d.png"; done
echo "== tornado time steps at 512^3 (--animate-time 8)"
for v in before after; do printf "%s: " $v; rm -rf $W/at; mkdir $W/at; t $B/lic3d-$v render -q --grid 512 --animate-time 8 -o "$W/at/t_%d.png"; done
echo "-- after, timings"; rm -rf $W/at; mkdir $W/at; $B/lic3d-after render -q --grid 512 --animate-time 8 --timings -o "$W/at/t_%d.png" 2>&1
echo "== 256^3 ABC .vti read and rendered"
s=${EPOCHREALTIME/./}; $B/make_abc_vti 256 $W/abc256; e=${EPOCHREALTIME/./}; echo "made in $(( (e - s) / 1000 )) ms"; ls -l $W/abc256_*
for f in raw zlib; do for v in before after; do
  printf "%s %s: " $f $v; for r in 1 2 3; do t $B/lic3d-$v render -q --field $W/abc256_$f.vti -o $W/v.png | tr '\n' ' '; done; echo
done; echo "-- after, timings"; $B/lic3d-after render -q --timings --field $W/abc256_$f.vti -o $W/v_$f.png 2>&1; done
echo "== timings after"
for g in 128 256 512; do echo "-- render --grid $g"; $B/lic3d-after render -q --grid $g --timings -o $W/r.png 2>&1; done
echo "-- compute --grid 512"; $B/lic3d-after compute -q --grid 512 --timings -o $W/x.nrrd 2>&1
echo "-- turntable 360"; rm -rf $W/tt; mkdir $W/tt; $B/lic3d-after render -q --grid 256 --turntable 360 --timings -o "$W/tt/f_%03d.png" 2>&1
echo "== peak RSS (KiB)"
for v in before after; do for a in "--grid 512" "--field $W/abc256_raw.vti"; do
  printf "%s %s: " $v "$a"; /usr/bin/time -f "%M KiB %e s" $B/lic3d-$v render -q $a -o $W/m.png 2>&1 | tail -1; done; done
echo "== sparsity change end to end (bench --distributions, 256^3)"
$B/lic3d-after bench --distributions --distribution-volume 256 --budget 60 2>&1 | tail -40
} > $OUT/end_to_end.txt 2>&1
cp $W/r.png $OUT/render512.png 2>/dev/null
cp $W/v_zlib.png $OUT/abc256.png 2>/dev/null
cp $W/tt/f_090.png $OUT/turntable_090.png 2>/dev/null
cp $W/at/t_3.png $OUT/time_3.png 2>/dev/null
