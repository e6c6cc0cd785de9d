# SPDX-License-Identifier: BSD-3-Clause
# One place for compiler warnings: every lic3d target calls lic3d_set_warnings().
function(lic3d_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion
                                           # `VkFooInfo info{VK_STRUCTURE_TYPE_FOO}` zeroes the
                                           # other members on purpose: the Vulkan idiom.
                                           -Wno-missing-field-initializers)
  # GCC 12 reports false -Wrestrict warnings inside std::string concatenation (GCC bug 105651).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(LIC3D_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
