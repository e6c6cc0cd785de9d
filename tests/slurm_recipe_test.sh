#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# The Slurm recipe (docs/examples/slurm_render.sh) covers every frame exactly once for any
# --array start and task count: each task is run with Slurm's variables and a lic3d on PATH that
# records its --frames range; the ranges must tile 0..N-1.
set -eu
recipe=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin"
cat > "$work/bin/lic3d" <<'STUB'
#!/bin/sh
while [ $# -gt 0 ]; do
  [ "$1" = "--frames" ] && echo "$2" >> "$RANGES"
  shift
done
STUB
chmod +x "$work/bin/lic3d"
for case in "0 12 360" "1 12 360" "5 12 360" "1 7 100" "3 40 30"; do
  set -- $case
  first=$1 count=$2 frames=$3
  export RANGES="$work/ranges" FRAMES=$frames SLURM_ARRAY_TASK_MIN=$first SLURM_ARRAY_TASK_COUNT=$count
  : > "$RANGES"
  id=$first
  while [ "$id" -lt $(( first + count )) ]; do
    (cd "$work" && SLURM_ARRAY_TASK_ID=$id PATH="$work/bin:$PATH" sh "$recipe")
    id=$(( id + 1 ))
  done
  # Every frame once: expand the ranges and compare with 0..N-1.
  covered=$(awk -F: '{ for (f = $1; f < $2; ++f) print f }' "$RANGES" | sort -n | tr '\n' ' ')
  expected=$(seq 0 $(( frames - 1 )) | tr '\n' ' ')
  if [ "$covered" != "$expected" ]; then
    echo "array from $first, $count tasks, $frames frames: the ranges do not tile the frames:"
    cat "$RANGES"
    exit 1
  fi
  echo "array from $first, $count tasks, $frames frames: $(wc -l < "$RANGES") ranges, every frame once"
done
