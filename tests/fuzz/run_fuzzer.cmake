# SPDX-License-Identifier: BSD-3-Clause
# Runs one libFuzzer target for SECONDS (or $ENV{LIC3D_FUZZ_SECONDS} when set) from the seeds in
# SEEDS, writing new inputs and crash reproducers under WORK (emptied first), never into the
# committed corpus. Fails on any finding, naming each reproducer and how to replay it. What the
# targets print (the command line's help and messages) is discarded; libFuzzer's own reports stay.
foreach(variable FUZZER SEEDS WORK SECONDS)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_fuzzer.cmake needs -D${variable}=...")
  endif()
endforeach()
if(DEFINED ENV{LIC3D_FUZZ_SECONDS})
  set(SECONDS $ENV{LIC3D_FUZZ_SECONDS})
endif()
if(NOT EXISTS ${FUZZER})
  message(FATAL_ERROR "${FUZZER} is missing (was fuzz_build run? ctest runs it first)")
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/corpus ${WORK}/artifacts)
# libFuzzer stops itself after SECONDS; the process limit is for a fuzzer that does not.
math(EXPR limit "${SECONDS} + 120")
execute_process(
  COMMAND ${FUZZER} -max_total_time=${SECONDS} -rss_limit_mb=1024 -timeout=5 -max_len=4096
          -close_fd_mask=3 -print_final_stats=1 -artifact_prefix=${WORK}/artifacts/ ${WORK}/corpus ${SEEDS}
  TIMEOUT ${limit}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(GLOB findings ${WORK}/artifacts/*)
  if(NOT findings)
    message(FATAL_ERROR "${FUZZER} failed (${status}) and wrote no reproducer")
  endif()
  # NOTICE prints the lines as they are, so the paths can be copied whole.
  set(report "${FUZZER} failed (${status}). Reproducers (removed by the next run of this test):")
  foreach(finding ${findings})
    string(APPEND report "\n  ${finding}")
  endforeach()
  list(GET findings 0 first)
  message(NOTICE "${report}\nReplay one: ${FUZZER} ${first}")
  message(FATAL_ERROR "the fuzzer found an input that crashes, leaks, hangs or runs out of memory: reproducers above")
endif()
