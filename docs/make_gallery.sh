#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Renders every picture of docs/GALLERY.md with the lic3d CLI and writes the page, so each picture
# sits beside the exact command that made it. Usage: docs/make_gallery.sh [path/to/lic3d]
set -eu
cd "$(dirname "$0")"
LIC3D=${1:-../build/release/lic3d}
OUT=images/gallery
SIZE="--width 320 --height 320"
mkdir -p "$OUT"
page=GALLERY.md.tmp

render() {  # name, arguments...
  name=$1
  shift
  # shellcheck disable=SC2086
  "$LIC3D" render -q $SIZE "$@" -o "$OUT/$name.png"
}

row() {  # title, before, after, arguments shown
  printf '| %s | ![](%s) | ![](%s) | `%s` |\n' "$1" "$OUT/$2.png" "$OUT/$3.png" "$4" >> "$page"
}

cat > "$page" <<'EOF'
# Gallery

Every picture was made by `docs/make_gallery.sh`, which runs the command beside it
(`lic3d render --width 320 --height 320 --field FIELD …`) and writes this page. Defaults: 128³
grid for analytic fields, L = 20 steps of h = 0.5 voxel, RK2, box kernel.

## Looks

`--look` ([LOOKS.md](LOOKS.md)) sets the display parameters from the data: percentile ranges of
the speed, an optical depth, empty space below 2 % of the fast speeds left clear. With no flags,
`lic3d render` uses `see-through`; `dense` is the thesis' look. Each picture is
`lic3d render --look LOOK` plus the flags in the first column.

| field | dense | see-through (the default) | streamlines | sparse |
|---|---|---|---|---|
EOF

looks_row() {  # title, key, flags... (render() sets $name: other names here)
  row_title=$1 row_key=$2
  shift 2
  cells=""
  for look in dense see-through streamlines sparse; do
    render "look-$row_key-$look" "$@" --look "$look"
    cells="$cells ![]($OUT/look-$row_key-$look.png) |"
  done
  # shellcheck disable=SC2001
  printf '| %s: `%s` |%s\n' "$row_title" "$(echo "$*" | sed 's#\.\./assets#assets#')" "$cells" >> "$page"
}
looks_row "Tornado (Crawfis)" tornado --field tornado
looks_row "Carotid artery, MRI, 76×49×45, LIC on a grid twice as fine" carotid \
  --field ../assets/data/carotid.vtk --resolution 2x --distance 1.7 --azimuth 20
looks_row "Magnetic mirror, FEM, 47×47×47, twice as fine" femm \
  --field ../assets/data/example-femm-3d.vtk --resolution 2x --azimuth 60 --elevation 20
looks_row "ABC flow" abc --field abc

cat >> "$page" <<'EOF'

## Depth cues

Each field in the default look without depth cues (`--halo 0`), as it is (halos 0.3), with
occlusion shading added (`--occlusion 0.5`) and with lighting from the LIC gradient added
(`--lighting gradient`) ([LOOKS.md, Depth cues](LOOKS.md#depth-cues---halo---occlusion---lighting-gradient-the-apps-depth-panel)).
The last row is the depth criterion's scene: two layers of flow one behind the other, seen face
on, the near one streaked horizontally.

| field | no cues | halos (the default) | + occlusion | + gradient lighting |
|---|---|---|---|---|
EOF

depth_row() {  # title, key, flags...
  row_title=$1 row_key=$2
  shift 2
  render "depth-$row_key-none" "$@" --halo 0
  render "depth-$row_key-halo" "$@"
  render "depth-$row_key-occlusion" "$@" --occlusion 0.5
  render "depth-$row_key-lit" "$@" --lighting gradient
  # shellcheck disable=SC2001
  printf '| %s: `%s` | ![](%s) | ![](%s) | ![](%s) | ![](%s) |\n' "$row_title" \
    "$(echo "$*" | sed 's#\.\./assets#assets#; s#[^ ]*/layers.nrrd#layers.nrrd#')" \
    "$OUT/depth-$row_key-none.png" "$OUT/depth-$row_key-halo.png" \
    "$OUT/depth-$row_key-occlusion.png" "$OUT/depth-$row_key-lit.png" >> "$page"
}
depth_row "Tornado" tornado --field tornado
depth_row "Carotid artery, twice as fine" carotid --field ../assets/data/carotid.vtk \
  --resolution 2x --distance 1.7 --azimuth 20
depth_row "Magnetic mirror, twice as fine" femm --field ../assets/data/example-femm-3d.vtk \
  --resolution 2x --azimuth 60 --elevation 20
depth_row "ABC flow" abc --field abc
layers=$(mktemp -d)
# The scene of tests/test_cli_depth.cpp: 64^3, flow along y for 0.6 < x < 0.8 (near the camera
# at azimuth 0), along z for 0.2 < x < 0.4.
python3 - "$layers/layers.nrrd" <<'PY'
import array, sys
n = 64
v = array.array('f', [0.0]) * (3 * n * n * n)
for z in range(n):
    for y in range(n):
        for x in range(n):
            f, i = (x + 0.5) / n, 3 * ((z * n + y) * n + x)
            if 0.6 < f < 0.8: v[i + 1] = 1.0
            if 0.2 < f < 0.4: v[i + 2] = 1.0
head = ("NRRD0004\ntype: float\ndimension: 4\nsizes: 3 %d %d %d\nkinds: vector domain domain "
        "domain\nencoding: raw\nendian: little\nspacings: nan 1 1 1\n\n" % (n, n, n))
with open(sys.argv[1], 'wb') as out:
    out.write(head.encode() + v.tobytes())
PY
depth_row "Two layers, seen face on" layers --field "$layers/layers.nrrd" --azimuth 0 --elevation 0
rm -rf "$layers"

cat >> "$page" <<'EOF'

Without halos a near streak and a far one merge where they cross; with them the near one cuts
the far one. Occlusion darkens what lies behind the first layer of flow (the carotid's vessels
behind others, the tornado's far side); the gradient's relief shows most on the carotid's thick
streaks.

## A figure for print

One picture at poster size: `--scale 2` doubles the width, height and font size of a 720²
figure with a title, a legend named by `--legend-title`, and ticked axes. Shown here at 320
pixels wide; [the full picture](images/gallery/poster-carotid.png) is 1440².

EOF
"$LIC3D" render -q --field ../assets/data/carotid.vtk --resolution 2x --distance 3.0 --azimuth 20 \
  --width 720 --height 720 --legend --legend-title "blood speed" --axes \
  --title "Carotid bifurcation, MRI velocity, systole" --scale 2 -o "$OUT/poster-carotid.png"
cat >> "$page" <<'EOF'
<img src="images/gallery/poster-carotid.png" width="320">

`lic3d render --field assets/data/carotid.vtk --resolution 2x --distance 3.0 --azimuth 20 --width 720 --height 720 --legend --legend-title "blood speed" --axes --title "Carotid bifurcation, MRI velocity, systole" --scale 2`

## The thesis' techniques on the dense look


A dense 3D LIC volume is a solid block: its faces hide the inside (the "before" column,
`--look dense`). The thesis' chapter 5 techniques open it up. Each row shows one technique on
one field; every command starts with `lic3d render --look dense`, and the field names the row's
before picture.

EOF

for field in tornado corner solenoidal; do
  render "$field" --look dense --field "$field"
done

section() {
  printf '\n## %s\n\n| technique | before | after | flags |\n|---|---|---|---|\n' "$1" >> "$page"
}

technique() {  # title, field, name, flags...
  title=$1 field=$2 name=$3
  shift 3
  render "$name" --look dense --field "$field" "$@"
  row "$title ($field)" "$field" "$name" "$*"
}

section "Global view (thesis 5.1)"
for f in tornado corner solenoidal; do
  technique "Transparency: global alpha" $f "$f-alpha" --opacity constant --alpha 0.04
done
for f in tornado corner solenoidal; do
  technique "Colour by magnitude, thesis ramp, legend" $f "$f-color" --color magnitude --legend
done
technique "Colour by magnitude, viridis" tornado tornado-viridis --color magnitude --colormap viridis --legend
technique "Colour by magnitude, cool-warm" tornado tornado-coolwarm --color magnitude --colormap coolwarm --legend
for f in tornado corner solenoidal; do
  technique "Magnitude opacity" $f "$f-magopacity" --color magnitude --magnitude-opacity 2
done
for f in tornado corner solenoidal; do
  technique "Sparsity + magnitude opacity" $f "$f-sparse" --sparsity poisson --alpha 0.6 \
    --magnitude-opacity 1.5 --color magnitude
done
for d in checkerboard poisson poisson-approx jitter halton hammersley; do
  technique "Sparsity: $d" solenoidal "solenoidal-$d" --sparsity $d --alpha 0.6
done
for f in tornado corner solenoidal; do
  technique "Seed noise: 4000 spots instead of white noise" $f "$f-seeds" --seed-noise 4000 --alpha 0.8
done
technique "Contrast stretch off (grey = LIC value)" tornado tornado-contrast-off --contrast off

section "Local view (thesis 5.2)"
for f in tornado corner solenoidal; do
  technique "Clip planes" $f "$f-clip" --clip 0,1,0,0.5,0,1
done
technique "Region of interest: sphere" tornado tornado-sphere --roi sphere --roi-size 0.7
technique "Region of interest: cube, rotated" tornado tornado-cube --roi cube --roi-size 0.6 --roi-rotate 30,0,45
technique "Region of interest: cylinder, rotated" corner corner-cylinder --roi cylinder --roi-size 0.7 --roi-rotate 60,0,0
technique "Region of interest: outside of a sphere" solenoidal solenoidal-outside --roi sphere --roi-size 0.9 --roi-outside

section "Depth (thesis 5.3)"
for f in tornado corner solenoidal; do
  technique "Fog (depth cueing)" $f "$f-fog" --fog 0,1
done
technique "Stereo: red/cyan anaglyph" tornado tornado-anaglyph --stereo anaglyph
SIZE="--width 160 --height 320"  # per eye: the picture is 320 wide
technique "Stereo: side by side (left, right)" solenoidal solenoidal-sbs --stereo side-by-side
SIZE="--width 320 --height 320"
for f in tornado solenoidal; do
  technique "Lighting: Phong with TNB normals" $f "$f-phong" --lighting phong
  technique "Lighting: illuminated lines" $f "$f-lines" --lighting lines
done
technique "Nearest filtering of a 32³ LIC volume, close up" tornado tornado-nearest --grid 32 --filter nearest --distance 1.9
technique "Linear filtering of a 32³ LIC volume, close up" tornado tornado-linear --grid 32 --filter linear --distance 1.9
technique "Cubic filtering (the default when zoomed), close up" tornado tornado-cubic --grid 32 --filter cubic --distance 1.9
technique "Plain slicing from close by: linear, no jitter (facets and bands)" tornado tornado-plain --grid 96 --distance 1.0 --filter linear --jitter off
technique "The same with the defaults (cubic, jitter, exact slice ends)" tornado tornado-zoom --grid 96 --distance 1.0
technique "Lighting: Phong from the LIC gradient" tornado tornado-gradient --lighting gradient
technique "Occlusion shading" tornado tornado-occlusion --occlusion 0.6

cat >> "$page" <<'EOF'

## Real data, colour by any scalar, transfer functions, annotation

The two fields in `assets/data` (provenance and licences in
[assets/data/README.md](../assets/data/README.md)), read from their VTK files with their own
grids and spacing. "before" is `lic3d render --field FILE` with no other flag (the default
look); "after" adds the flags shown.

| data set | before | after | flags |
|---|---|---|---|
EOF
realdata() {  # title, file, picture name, flags...
  title=$1 file=$2 picture=$3
  shift 3
  render "$picture-default" --field "../assets/data/$file"
  render "$picture" --field "../assets/data/$file" "$@"
  shown="--field assets/data/$file"
  for arg in "$@"; do  # quoted where it holds a space, as one would type it
    case $arg in *" "*) shown="$shown \"$arg\"" ;; *) shown="$shown $arg" ;; esac
  done
  # shellcheck disable=SC2001
  row "$title" "$picture-default" "$picture" "$(echo "$shown" | sed 's/|/\\|/g')"
}
realdata "Carotid artery, 76×49×45: LIC on a grid twice as fine, closer, with a title, the legend and ticked axes" \
  carotid.vtk carotid --resolution 2x --distance 1.6 --azimuth 20 --legend --axes \
  --title "Carotid bifurcation, MRI velocity"
realdata "Carotid artery: colour (and opacity) by vorticity \|curl v\|" \
  carotid.vtk carotid-vorticity --resolution 2x --distance 1.6 --azimuth 20 \
  --color-by vorticity --legend
realdata "Magnetic mirror, 47×47×47, spacing 0.05, 0.05, 0.125: cut by an oblique plane, colour by \|B\| in tesla" \
  example-femm-3d.vtk femm --resolution 2x --clip-plane 0.5,0.5,0.5,1,1,0 --azimuth 60 \
  --elevation 20 --legend --legend-title "|B| [T]" --axes
render abc-helicity --field abc --color-by helicity --tf ../assets/presets/blue-orange.json --legend
cat >> "$page" <<'EOF'
| ABC flow: colour by helicity v · curl v through a ParaView preset ([blue-orange.json](../assets/presets/blue-orange.json), its opacities too) | ![](images/gallery/look-abc-see-through.png) | ![](images/gallery/abc-helicity.png) | `--field abc --color-by helicity --tf assets/presets/blue-orange.json --legend` |
EOF

# ---- 2D LIC (thesis chapter 3) and time (thesis 3.5, chapter 7) ----
picture2d() {  # name, arguments...
  name=$1
  shift
  # shellcheck disable=SC2086
  "$LIC3D" render2d -q "$@" -o "$OUT/$name.png"
}
plane() {  # title, name, flags...
  title=$1 name=$2
  shift 2
  picture2d "$name" "$@"
  # shellcheck disable=SC2001
  printf '| %s | ![](%s) | `lic3d render2d %s` |\n' "$title" "$OUT/$name.png" \
    "$(echo "$*" | sed 's#\.\./assets#assets#')" >> "$page"
}
cat >> "$page" <<'EOF'

## 2D LIC (thesis chapter 3)

`lic3d render2d` makes the LIC image of a 2D field, or of a plane of a 3D one, through the same
integrators, kernels and bias ([LIC semantics](LIC_SEMANTICS.md#2d-lic)). The noise lives at the
image's resolution, so an image larger than the field's grid stays sharp.

| what | picture | command |
|---|---|---|
EOF
plane "The thesis' Figure 3.7: a circular field, 320² grid" circle-320 --field circle --grid 320
plane "An oblique plane through the tornado's centre, normal (1, 1, 1): the box's hexagonal cut, colour by \|v\|" \
  tornado-oblique --field tornado --grid 96 --plane 0.5,0.5,0.5,1,1,1 --width 320 --color magnitude \
  --legend
plane "The same field on a 40² grid, drawn at 320²: fine noise, smooth field" circle-40-up \
  --field circle --grid 40 --width 320
plane "A saddle point, Hann kernel, L = 40" saddle --field saddle --grid 320 --kernel hann --length 40
plane "A plane of the 3D tornado (z = 32 of 64³), colour by \|v\|" tornado-plane --field tornado \
  --grid 64 --width 320 --color magnitude --legend
plane "The carotid artery (assets/data, 76×49×45), the plane x = 30 along a vessel, colour by speed" \
  carotid-plane --field ../assets/data/carotid.vtk --slice x:30 --width 320 --color magnitude \
  --color-range 0,15 --legend
plane "Thesis 3.5: the time-varying wave at t = 0" wave-t0 --field wave --grid 320
plane "… and at t = 0.25: the pattern has travelled a quarter of the width" wave-t25 --field wave \
  --grid 320 --time 0.25

cat >> "$page" <<'EOF'

## Time (thesis 3.5 and chapter 7)

Frames of a field's time ([TIME.md](TIME.md)): each is the LIC of the field at that instant. The
loops run over one period of the field; in the first the bias cycles (thesis 3.3.3) twice
meanwhile, so the last frame leads back into the first.

| what | picture | command |
|---|---|---|
EOF
frames=$(mktemp -d)
trap 'rm -rf "$frames"' EXIT
# The wave through one period, six frames side by side (ffmpeg tiles them; lic3d needs no ffmpeg
# but for --video).
"$LIC3D" render2d -q --field wave --grid 160 --animate-time 6 -o "$frames/wave_%d.png"
ffmpeg -loglevel error -y -i "$frames/wave_%d.png" -vf tile=6x1:padding=4 -frames:v 1 \
  "$OUT/wave-strip.png"
# Time and bias together: 32 frames of the period, the bias cycling every 16.
"$LIC3D" render2d -q --field wave --grid 128 --length 12 --animate-time 32 --animate-bias 16 \
  --fps 12 -o "$frames/loop_%02d.png" --video "$OUT/wave-loop.gif"
# The tornado through its period as 32 steps blended on the GPU; 4 of the 24 frames in a strip.
tornado_time="--look dense --field tornado --grid 64 --time-steps 32 --animate-time 24 --width 200 --height 200 \
  --clip 0,1,0,0.5,0,1 --color magnitude --elevation 10"
# shellcheck disable=SC2086
"$LIC3D" render -q $tornado_time --fps 12 -o "$frames/tornado_%02d.png" --video "$OUT/tornado-time.gif"
ffmpeg -loglevel error -y -start_number 0 -i "$frames/tornado_%02d.png" \
  -vf 'select=not(mod(n\,6)),tile=4x1:padding=4' -frames:v 1 "$OUT/tornado-strip.png"
{
  printf '| The wave through one period, t = 0, 1/6, …, 5/6 | ![](%s) | `%s` |\n' \
    "$OUT/wave-strip.png" "lic3d render2d --field wave --grid 160 --animate-time 6 -o 'wave_%d.png'"
  printf '| Time and bias together: 32 frames, one loop | ![](%s) | `%s` |\n' "$OUT/wave-loop.gif" \
    "lic3d render2d --field wave --grid 128 --length 12 --animate-time 32 --animate-bias 16 --fps 12 -o 'loop_%02d.png' --video wave-loop.gif"
  printf '| The tornado over its period (200π) as 32 steps blended on the GPU, cut open at y = 0.5: its core (red) sways; frames 0, 6, 12 and 18 of 24 | ![](%s) | `%s` |\n' \
    "$OUT/tornado-strip.png" "lic3d render $tornado_time -o 'tornado_%02d.png'"
  printf '| … all 24 as a loop | ![](%s) | `%s` |\n' "$OUT/tornado-time.gif" \
    "the same with --fps 12 --video tornado-time.gif"
} >> "$page"

mv "$page" GALLERY.md
echo "wrote docs/GALLERY.md and $(ls "$OUT" | wc -l) pictures in docs/$OUT"
