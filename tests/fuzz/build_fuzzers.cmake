# SPDX-License-Identifier: BSD-3-Clause
# The fuzz_build test (a ctest fixture the fuzz_<target> tests require): configures and builds
# standalone/ (SOURCE) into BINARY with the clang++ named by CXX, for builds of lic3d made with
# another compiler. Later runs only rebuild what changed.
foreach(variable CXX SOURCE BINARY GENERATOR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "build_fuzzers.cmake needs -D${variable}=...")
  endif()
endforeach()
set(packages "Debian 12: apt-get install clang-14 libclang-rt-14-dev, or sh cmake/install-deps.sh")
find_program(compiler NAMES ${CXX} NO_CACHE)
if(NOT compiler)
  message(FATAL_ERROR "The fuzz targets need clang, and ${CXX} is not installed (${packages})")
endif()
if(NOT DEFINED WARNINGS_AS_ERRORS OR WARNINGS_AS_ERRORS STREQUAL "")
  set(WARNINGS_AS_ERRORS OFF)
endif()

# A folder configured with another compiler cannot be reconfigured with this one: start afresh.
if(EXISTS ${BINARY}/CMakeCache.txt)
  file(STRINGS ${BINARY}/CMakeCache.txt cached REGEX "^CMAKE_CXX_COMPILER:[A-Z]+=")
  string(REGEX REPLACE "^[^=]*=" "" cached "${cached}")
  if(NOT cached STREQUAL compiler)
    file(REMOVE_RECURSE ${BINARY})
  endif()
endif()

execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${BINARY} -G ${GENERATOR}
          -DCMAKE_CXX_COMPILER=${compiler} -DCMAKE_BUILD_TYPE=RelWithDebInfo
          -DLIC3D_WARNINGS_AS_ERRORS=${WARNINGS_AS_ERRORS}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "Configuring the fuzz targets with ${compiler} failed (${packages})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "Building the fuzz targets with ${compiler} failed")
endif()
