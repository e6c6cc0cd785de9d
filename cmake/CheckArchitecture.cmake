# SPDX-License-Identifier: BSD-3-Clause
# The architecture checks, run by ctest in script mode:
#   cmake -DSOURCE_DIR=<repo> -DCHECK=layers|file_size|licence -P cmake/CheckArchitecture.cmake
#
# layers: the engine's folders are layers, lowest first (engine/CMakeLists.txt). A file of the
# engine includes only files of its own layer and of layers below it, always by their layer path
# ("core/volume.h"); the shaders' shared headers (plain data, compiled by both GLSL and C++) and
# the generated SPIR-V headers are the only bare includes. The layers below gpu/ include no
# Vulkan header. Every engine file lies in a layer folder. The front ends (app/) lie in one
# folder per program; cli/, bench/ and viewer/ never include each other, and the command-line
# library options/ and the Python module include none of them.
# file_size: no source file (engine, app, shaders, paraview, tests) is longer than 700 lines.
# licence: every source, build and script file names its licence (LICENSE, BSD-3-Clause) by its
# SPDX identifier in its first lines.
cmake_minimum_required(VERSION 3.25)

set(layers core io lic gpu passes render loading jobs)
set(first_vulkan_layer 3)  # gpu
set(max_lines 700)

function(layer_rank path out)
  string(REGEX MATCH "^[a-z0-9_]+/" folder "${path}")
  string(REPLACE "/" "" folder "${folder}")
  list(FIND layers "${folder}" rank)
  set(${out} ${rank} PARENT_SCOPE)
endfunction()

set(problems "")
if(CHECK STREQUAL "layers")
  file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}/engine"
       "${SOURCE_DIR}/engine/*.h" "${SOURCE_DIR}/engine/*.cpp")
  file(GLOB shader_headers RELATIVE "${SOURCE_DIR}/shaders" "${SOURCE_DIR}/shaders/*.h")
  list(LENGTH files count)
  if(count EQUAL 0)
    message(FATAL_ERROR "no engine sources under ${SOURCE_DIR}/engine")
  endif()
  foreach(file ${files})
    layer_rank("${file}" own)
    if(own LESS 0)
      string(APPEND problems "engine/${file}: not in a layer folder (${layers})\n")
      continue()
    endif()
    file(STRINGS "${SOURCE_DIR}/engine/${file}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line ${lines})
      if(line MATCHES "#[ \t]*include[ \t]*\"([^\"]+)\"")
        set(target "${CMAKE_MATCH_1}")
        layer_rank("${target}" rank)
        if(rank LESS 0)
          if(NOT target IN_LIST shader_headers AND NOT target MATCHES "_spv\\.h$")
            string(APPEND problems "engine/${file}: includes \"${target}\": engine files are "
                                   "included by their layer path (core/, io/, ...)\n")
          endif()
        elseif(NOT EXISTS "${SOURCE_DIR}/engine/${target}")
          string(APPEND problems "engine/${file}: includes \"${target}\", which does not exist\n")
        elseif(rank GREATER own)
          list(GET layers ${own} own_name)
          string(APPEND problems "engine/${file}: includes \"${target}\" from a higher layer "
                                 "(${own_name}/ may include only itself and the layers below)\n")
        endif()
      elseif(line MATCHES "#[ \t]*include[ \t]*<(vulkan/[^>]+)>" AND own LESS first_vulkan_layer)
        string(APPEND problems "engine/${file}: includes <${CMAKE_MATCH_1}> below gpu/\n")
      endif()
    endforeach()
  endforeach()
  # The front ends: one folder per program over the command-line library (app/CMakeLists.txt).
  # Each may include the engine, the library options/ and its own folder; app/main.cpp (the lic3d
  # program) also hands commands to cli/ and bench/; python/ (the module) uses only options/, the
  # engine and its own files.
  set(programs options cli bench viewer python)
  set(allowed_options options)
  set(allowed_cli options cli)
  set(allowed_bench options bench)
  set(allowed_viewer options viewer)
  set(allowed_main options cli bench)
  set(allowed_python options python)
  file(GLOB_RECURSE app_files RELATIVE "${SOURCE_DIR}"
       "${SOURCE_DIR}/app/*.h" "${SOURCE_DIR}/app/*.cpp" "${SOURCE_DIR}/python/*.h"
       "${SOURCE_DIR}/python/*.cpp")
  foreach(file ${app_files})
    if(file STREQUAL "app/main.cpp")
      set(own main)
    elseif(file MATCHES "^python/")
      set(own python)
    elseif(file MATCHES "^app/([a-z]+)/[^/]+$" AND CMAKE_MATCH_1 IN_LIST programs)
      set(own ${CMAKE_MATCH_1})
    else()
      string(APPEND problems "${file}: not in a program folder of app/ (${programs})\n")
      continue()
    endif()
    file(STRINGS "${SOURCE_DIR}/${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(line ${lines})
      if(NOT line MATCHES "#[ \t]*include[ \t]*\"(([a-z0-9_]+)/)?[^\"]+\"")
        continue()
      endif()
      set(folder "${CMAKE_MATCH_2}")
      if(folder STREQUAL "")
        string(APPEND problems "${file}: ${line}: include front-end and engine files by their "
                               "folder (options/, cli/, core/, ...)\n")
      elseif(folder IN_LIST programs AND NOT folder IN_LIST allowed_${own})
        string(APPEND problems "${file}: ${line}: ${own} may include only ${allowed_${own}} "
                               "among the front ends' folders\n")
      elseif(NOT folder IN_LIST programs AND NOT folder IN_LIST layers)
        string(APPEND problems "${file}: ${line}: no such engine layer or front-end folder\n")
      endif()
    endforeach()
  endforeach()
elseif(CHECK STREQUAL "file_size")
  set(files "")
  foreach(folder engine app shaders paraview python tests)
    file(GLOB_RECURSE found RELATIVE "${SOURCE_DIR}"
         "${SOURCE_DIR}/${folder}/*.h" "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.cxx"
         "${SOURCE_DIR}/${folder}/*.comp" "${SOURCE_DIR}/${folder}/*.frag"
         "${SOURCE_DIR}/${folder}/*.vert" "${SOURCE_DIR}/${folder}/*.glsl")
    list(APPEND files ${found})
  endforeach()
  foreach(file ${files})
    file(READ "${SOURCE_DIR}/${file}" text)
    string(REGEX MATCHALL "\n" newlines "${text}")
    list(LENGTH newlines n)
    if(n GREATER max_lines)
      string(APPEND problems "${file}: ${n} lines (at most ${max_lines}: split it by job)\n")
    endif()
  endforeach()
elseif(CHECK STREQUAL "licence")
  file(GLOB files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/CMakeLists.txt" "${SOURCE_DIR}/.ci/*")
  foreach(folder engine app shaders paraview python tests cmake docs)
    file(GLOB_RECURSE found RELATIVE "${SOURCE_DIR}"
         "${SOURCE_DIR}/${folder}/*.h" "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.cxx"
         "${SOURCE_DIR}/${folder}/*.comp" "${SOURCE_DIR}/${folder}/*.frag"
         "${SOURCE_DIR}/${folder}/*.vert" "${SOURCE_DIR}/${folder}/*.glsl"
         "${SOURCE_DIR}/${folder}/*.cmake" "${SOURCE_DIR}/${folder}/CMakeLists.txt"
         "${SOURCE_DIR}/${folder}/*.sh" "${SOURCE_DIR}/${folder}/*.py"
         "${SOURCE_DIR}/${folder}/*.xml")
    list(APPEND files ${found})
  endforeach()
  foreach(file ${files})
    file(STRINGS "${SOURCE_DIR}/${file}" head LIMIT_COUNT 3)
    if(NOT head MATCHES "SPDX-License-Identifier: BSD-3-Clause")
      string(APPEND problems "${file}: no 'SPDX-License-Identifier: BSD-3-Clause' in its first lines\n")
    endif()
  endforeach()
else()
  message(FATAL_ERROR "CHECK must be layers, file_size or licence")
endif()

if(problems)
  message(FATAL_ERROR "architecture.${CHECK}:\n${problems}")
endif()
message(STATUS "architecture.${CHECK}: ok")
