# SPDX-License-Identifier: BSD-3-Clause
# Every C++ source is formatted by the repository's .clang-format, run by ctest in script mode:
#   cmake -DSOURCE_DIR=<repo> -DCLANG_FORMAT=<clang-format-14> -P cmake/CheckFormat.cmake
# Fix a failure with: clang-format-14 -i <the files named>.
cmake_minimum_required(VERSION 3.25)

set(files "")
foreach(folder engine app shaders paraview python tests)
  file(GLOB_RECURSE found "${SOURCE_DIR}/${folder}/*.h" "${SOURCE_DIR}/${folder}/*.cpp"
       "${SOURCE_DIR}/${folder}/*.cxx")
  list(APPEND files ${found})
endforeach()
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror --style=file ${files}
                WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE status ERROR_VARIABLE report)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "style.clang_format: these sources are not formatted by .clang-format "
                      "(clang-format-14 -i FILE fixes them):\n${report}")
endif()
list(LENGTH files count)
message(STATUS "style.clang_format: ${count} files formatted")
