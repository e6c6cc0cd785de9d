# SPDX-License-Identifier: BSD-3-Clause
# Runs the libFuzzer targets one after another within ONE time box: SECONDS (or
# $ENV{LIC3D_FUZZ_SECONDS} when set) for all of them together, shared equally. Each starts from
# its seeds in SEEDS/<target>, writing new inputs and crash reproducers under WORK/<target>
# (emptied first), never into the committed corpus. Every target runs even after one fails; the
# test fails on any finding, naming each reproducer and how to replay it. What the targets print
# (the command line's help and messages) is discarded; libFuzzer's own reports stay.
# Each target's scratch files (the inputs it writes for the readers, tests/fuzz/fuzz_support.h)
# go to WORK/<target>/scratch through TMPDIR, and the test fails if a target leaves a scratch
# folder in /dev/shm or /tmp, or (when it ends normally) in its own scratch folder.
#   FUZZERS: a list of target names; FUZZER_DIR: the folder with fuzz_<target> in it.
#   RUNS (optional): run each target for this many inputs instead of the time box.
foreach(variable FUZZERS FUZZER_DIR SEEDS WORK SECONDS)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_fuzzer.cmake needs -D${variable}=...")
  endif()
endforeach()
if(DEFINED ENV{LIC3D_FUZZ_SECONDS})
  set(SECONDS $ENV{LIC3D_FUZZ_SECONDS})
endif()
string(REPLACE "," ";" FUZZERS "${FUZZERS}")
list(LENGTH FUZZERS count)
math(EXPR share "${SECONDS} / ${count}")
if(share LESS 1)
  set(share 1)
endif()
# libFuzzer stops itself after its share; the process limit is for a fuzzer that does not.
math(EXPR limit "${share} + 120")
if(DEFINED RUNS)
  set(budget -runs=${RUNS})
else()
  set(budget -max_total_time=${share})
endif()

# Scratch folders outside the build folder, as they are before the targets run.
function(scratch_outside result)
  file(GLOB found LIST_DIRECTORIES true /dev/shm/lic3d-fuzz-* /tmp/lic3d-fuzz-*)
  set(${result} "${found}" PARENT_SCOPE)
endfunction()
scratch_outside(outside_before)

set(failed "")
foreach(target ${FUZZERS})
  set(fuzzer ${FUZZER_DIR}/fuzz_${target})
  if(NOT EXISTS ${fuzzer})
    message(FATAL_ERROR "${fuzzer} is missing (was fuzz_build run? ctest runs it first)")
  endif()
  set(work ${WORK}/${target})
  file(REMOVE_RECURSE ${work})
  file(MAKE_DIRECTORY ${work}/corpus ${work}/artifacts ${work}/scratch)
  set(ENV{TMPDIR} ${work}/scratch)
  if(DEFINED RUNS)
    message(STATUS "fuzz_${target}: ${RUNS} runs")
  else()
    message(STATUS "fuzz_${target}: ${share} s")
  endif()
  execute_process(
    COMMAND ${fuzzer} ${budget} -rss_limit_mb=1024 -timeout=5 -max_len=4096
            -close_fd_mask=3 -print_final_stats=1 -artifact_prefix=${work}/artifacts/
            ${work}/corpus ${SEEDS}/${target}
    TIMEOUT ${limit}
    RESULT_VARIABLE status)
  # A target that ends normally removes its scratch folder.
  file(GLOB left LIST_DIRECTORIES true ${work}/scratch/*)
  if(status EQUAL 0 AND left)
    list(APPEND failed ${target})
    message(NOTICE "${fuzzer} ended normally and left its scratch folder: ${left}")
  endif()
  if(NOT status EQUAL 0)
    list(APPEND failed ${target})
    file(GLOB findings ${work}/artifacts/*)
    if(NOT findings)
      message(NOTICE "${fuzzer} failed (${status}) and wrote no reproducer")
      continue()
    endif()
    # NOTICE prints the lines as they are, so the paths can be copied whole.
    set(report "${fuzzer} failed (${status}). Reproducers (removed by the next run of this test):")
    foreach(finding ${findings})
      string(APPEND report "\n  ${finding}")
    endforeach()
    list(GET findings 0 first)
    message(NOTICE "${report}\nReplay one: ${fuzzer} ${first}")
  endif()
endforeach()
scratch_outside(outside_after)
if(outside_before)
  list(REMOVE_ITEM outside_after ${outside_before})
endif()
if(outside_after)
  string(REPLACE ";" "\n  " left "${outside_after}")
  message(FATAL_ERROR "the fuzzers left scratch folders outside the build folder:\n  ${left}")
endif()
if(failed)
  message(FATAL_ERROR "the fuzzers of ${failed} found an input that crashes, leaks, hangs or runs "
                      "out of memory (reproducers above), or failed to run or to remove its scratch")
endif()
