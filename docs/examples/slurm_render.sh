#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# A turntable of N frames split over a Slurm job array, one frame range per task (docs/BATCH.md).
# Submit from the folder that holds flow.vti; Slurm opens the log before this script runs, so
# the log folder must exist first:
#   mkdir -p logs && sbatch slurm_render.sh
# Any --array range works (0-11, 1-12, 5-16): the task's place in it comes from
# SLURM_ARRAY_TASK_MIN. A requeued task renders only the frames it had not finished.
#SBATCH --array=0-11
#SBATCH --gpus=1
#SBATCH --output=logs/render_%a.log
set -eu
N=${FRAMES:-360}                         # frames in the whole animation
FIRST=${SLURM_ARRAY_TASK_MIN:-0}
TASKS=${SLURM_ARRAY_TASK_COUNT:-12}
PER=$(( (N + TASKS - 1) / TASKS ))       # frames per task, rounded up
A=$(( (SLURM_ARRAY_TASK_ID - FIRST) * PER ))
B=$(( A + PER < N ? A + PER : N ))
[ "$A" -lt "$N" ] || exit 0              # more tasks than frames
mkdir -p frames
lic3d render --field flow.vti --width 1920 --height 1080 --color magnitude \
  --turntable "$N" --frames "$A:$B" --skip-existing -o 'frames/flow_%04d.png'
