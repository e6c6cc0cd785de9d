# SPDX-License-Identifier: BSD-3-Clause
# GLSL -> SPIR-V at build time with glslangValidator, embedded as C arrays.
#
# lic3d_add_shaders(<target> SOURCES a.comp b.vert ...) creates an INTERFACE target whose
# include directory holds one header per shader, `<name>_<stage>_spv.h`, defining
# `const uint32_t <name>_<stage>_spv[]`. A source written `file.frag:variant:DEFINE` is compiled
# once more with -DDEFINE into `<name>_<variant>_<stage>_spv.h`. glslang's --depfile records
# #include dependencies, so editing a shared header recompiles every shader that includes it.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(lic3d_add_shaders target)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  foreach(entry ${ARG_SOURCES})
    string(REPLACE ":" ";" parts ${entry})
    list(GET parts 0 src)
    list(LENGTH parts count)
    get_filename_component(name ${src} NAME_WE)
    get_filename_component(ext ${src} EXT)
    string(SUBSTRING ${ext} 1 -1 stage)
    set(defines)
    if(count EQUAL 3)
      list(GET parts 1 variant)
      list(GET parts 2 define)
      set(name ${name}_${variant})
      set(defines -D${define})
    endif()
    set(var ${name}_${stage}_spv)
    set(header ${out_dir}/${var}.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.3 --quiet -I${CMAKE_CURRENT_SOURCE_DIR}
              ${defines} --depfile ${header}.d --vn ${var} -o ${header}
              ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      MAIN_DEPENDENCY ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPFILE ${header}.d
      COMMENT "glslang ${entry}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${target}_compile DEPENDS ${headers})
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE ${out_dir})
  add_dependencies(${target} ${target}_compile)
endfunction()
