# SPDX-License-Identifier: BSD-3-Clause
# Debian packages of what `cmake --install` installs, made by `cpack -G DEB` in the build folder
# (README.md, "Install"), for /usr:
#   lic3d           the programs, the Python module, man pages, bash completion, the desktop
#                   entry and icon, the documentation: every install rule without a component
#   lic3d-paraview  the ParaView plugin, in a package of its own because it needs ParaView (about
#                   1.4 GB), which the rest does not
#   python3-lic3d   the Python module (component python), Debian's name for it: it depends on the
#                   Python version it is built for, which the programs do not
# Any other install component becomes a package lic3d-<component>, except "development"
# (ParaView's client-server library, which the install removes again: paraview/CMakeLists.txt).
# The dependencies are what dpkg-shlibdeps finds the ELF files link, plus a Vulkan driver.
# Each package carries Debian's copyright file (machine-readable, from assets/debian/copyright.in
# and LICENSE) and changelog (assets/debian/changelog). The programs link the shared zlib, libpng
# and pugixml where LIC3D_STATIC_SYSTEM_LIBRARIES is OFF (the ci preset): lintian rejects
# statically linked copies. tests/package_test.sh builds the packages, runs lintian on them,
# installs them into a scratch root and runs lic3d.

# The Maintainer field: Debian's DEBFULLNAME and DEBEMAIL where set (as dch takes them), else the
# project's placeholder. Packagers set LIC3D_PACKAGE_MAINTAINER="Name <address>".
set(maintainer "lic3d developers <lic3d@example.org>")
if(DEFINED ENV{DEBEMAIL} AND "$ENV{DEBEMAIL}" MATCHES "<")
  set(maintainer "$ENV{DEBEMAIL}")
elseif(DEFINED ENV{DEBEMAIL} AND DEFINED ENV{DEBFULLNAME})
  set(maintainer "$ENV{DEBFULLNAME} <$ENV{DEBEMAIL}>")
endif()
set(LIC3D_PACKAGE_MAINTAINER "${maintainer}" CACHE STRING
    "Maintainer field of the Debian packages: Name <address>")
if(NOT LIC3D_PACKAGE_MAINTAINER MATCHES "^[^<>@]+ <[^<>@ ]+@[^<>@ ]+\\.[^<>@ ]+>$")
  message(FATAL_ERROR "LIC3D_PACKAGE_MAINTAINER is '${LIC3D_PACKAGE_MAINTAINER}': Debian wants "
                      "'Name <user@host.domain>'")
endif()

# Debian's changelog of the packages: its latest entry is this version.
set(changelog ${CMAKE_SOURCE_DIR}/assets/debian/changelog)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${changelog}
             ${CMAKE_SOURCE_DIR}/assets/debian/copyright.in)
file(STRINGS ${changelog} latest LIMIT_COUNT 1)
if(NOT latest MATCHES "^lic3d \\(${PROJECT_VERSION}\\) ")
  message(FATAL_ERROR "The latest entry of ${changelog} is '${latest}', not version "
                      "${PROJECT_VERSION}: add an entry for it (dch -v ${PROJECT_VERSION})")
endif()
set(debian_doc ${CMAKE_BINARY_DIR}/debian)
file(MAKE_DIRECTORY ${debian_doc})
# gzip -9n, as Debian wants it: no name or time stamp in the file.
execute_process(COMMAND gzip -9nc INPUT_FILE ${changelog} OUTPUT_FILE ${debian_doc}/changelog.gz
                RESULT_VARIABLE gzip_result)
if(NOT gzip_result EQUAL 0)
  message(FATAL_ERROR "gzip -9n ${changelog} failed: ${gzip_result}")
endif()

# Debian's copyright file, machine-readable (DEP-5): the licence texts of LICENSE and of the VTK
# notice of assets/data, each line indented by one space and empty lines written " .".
function(lic3d_dep5_text out text)
  string(STRIP "${text}" text)
  string(REGEX REPLACE "[ \t]+\n" "\n" text "${text}")
  string(REPLACE "\n" "\n " text " ${text}")
  string(REPLACE "\n \n" "\n .\n" text "${text}")
  string(REPLACE "\n \n" "\n .\n" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()
file(READ ${CMAKE_SOURCE_DIR}/LICENSE license)
if(NOT license MATCHES "Copyright \\(c\\) ([0-9-]+), ([^\n]+)\n")
  message(FATAL_ERROR "No 'Copyright (c) YEAR, HOLDER' line in LICENSE")
endif()
set(LIC3D_COPYRIGHT "${CMAKE_MATCH_1} ${CMAKE_MATCH_2}")
string(FIND "${license}" "Redistribution" at)
string(SUBSTRING "${license}" ${at} -1 license)
lic3d_dep5_text(LIC3D_LICENSE_TEXT "${license}")
file(READ ${CMAKE_SOURCE_DIR}/assets/data/LICENSES/pyvista-vtk-data_Copyright_VTK-BSD.txt vtk)
string(FIND "${vtk}" "Redistribution" at)
string(SUBSTRING "${vtk}" ${at} -1 vtk)
string(REGEX REPLACE "=+\\*/[ \t\n]*$" "" vtk "${vtk}")
lic3d_dep5_text(LIC3D_VTK_LICENSE_TEXT "${vtk}")
configure_file(${CMAKE_SOURCE_DIR}/assets/debian/copyright.in ${debian_doc}/copyright @ONLY)

# Each package's /usr/share/doc/<package>/: copyright and changelog.gz. In the packages only
# (EXCLUDE_FROM_ALL leaves them to an install of the component, which is what cpack does).
set(package_components lic3d)
set(package_names lic3d)
if(TARGET Lic3D)
  list(APPEND package_components paraview)
  list(APPEND package_names lic3d-paraview)
endif()
if(TARGET lic3d_python)
  list(APPEND package_components python)
  list(APPEND package_names python3-lic3d)
endif()
foreach(component name IN ZIP_LISTS package_components package_names)
  install(FILES ${debian_doc}/copyright ${debian_doc}/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${name} COMPONENT ${component} EXCLUDE_FROM_ALL)
endforeach()

if(LIC3D_STATIC_SYSTEM_LIBRARIES)
  message(STATUS "LIC3D_STATIC_SYSTEM_LIBRARIES is ON: Debian packages made from this build carry "
                 "their own zlib and libpng, which lintian rejects (configure with OFF for them)")
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lic3d)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "${LIC3D_PACKAGE_MAINTAINER}")
# Left at CPack's default, so that CPackDeb does not put the one summary above every package's
# own (the first line of each description below).
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${CMAKE_PROJECT_NAME} built using CMake")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)

set(CPACK_DEB_COMPONENT_INSTALL ON)
get_cmake_property(CPACK_COMPONENTS_ALL COMPONENTS)
list(REMOVE_ITEM CPACK_COMPONENTS_ALL development)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # lic3d_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SOURCE lic3d)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

set(CPACK_DEBIAN_LIC3D_PACKAGE_NAME lic3d)
set(CPACK_DEBIAN_LIC3D_DESCRIPTION
    "3D Line Integral Convolution of vector fields with Vulkan
lic3d shows the inside of 3D vector fields with Line Integral Convolution
(LIC): a Vulkan compute pass follows the streamline through every voxel and
smears a noise volume along it; a graphics pass draws the LIC volume as
alpha-blended slices. It reads VTK, VTI, NRRD and raw files and runs on any
Vulkan device, Mesa's lavapipe (CPU) included.

This package holds the command-line program lic3d (pictures, LIC volumes,
2D LIC, animations, benchmarks; no display needed), the desktop app
lic3d-view, their man pages and the documentation with two real example
fields.")
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_NAME lic3d-paraview)
set(CPACK_DEBIAN_PARAVIEW_DESCRIPTION
    "ParaView plugin for 3D Line Integral Convolution with Vulkan
The ParaView plugin Lic3D: its filter 3D LIC computes LIC on image data
with the lic3d engine, one piece per process under mpirun pvbatch. Load
/usr/${LIC3D_PLUGIN_DESTINATION}/Lic3D.so
in ParaView (Tools > Manage Plugins) or name its folder in PV_PLUGIN_PATH.")
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_ENHANCES paraview)
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-lic3d)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_DEBIAN_PYTHON_DESCRIPTION
    "Python module for 3D Line Integral Convolution with Vulkan
The Python module lic3d computes Line Integral Convolution of 3D vector
fields given as numpy arrays with the lic3d engine, on any Vulkan device,
Mesa's lavapipe (CPU) included, and renders pictures of the LIC volume: the
same parameters and results as the command-line program lic3d.")

# Every package does nothing without a Vulkan driver; Mesa's runs anywhere. The Python module is
# built for one Python version (its file name says which) and works on numpy arrays.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "mesa-vulkan-drivers | vulkan-icd")
set(python_depends "")
if(TARGET lic3d_python)
  math(EXPR next_minor "${LIC3D_PYTHON_VERSION_MINOR} + 1")
  set(next "${LIC3D_PYTHON_VERSION_MAJOR}.${next_minor}")
  set(python_depends ", python3 (>= ${LIC3D_PYTHON_VERSION}), python3 (<< ${next}), python3-numpy")
endif()
# CPack finds the ELF files with `file` and asks dpkg-shlibdeps (dpkg-dev) for their packages,
# which it adds to these.
find_program(LIC3D_DPKG_SHLIBDEPS dpkg-shlibdeps)
find_program(LIC3D_FILE file)
if(LIC3D_DPKG_SHLIBDEPS AND LIC3D_FILE)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "${CPACK_DEBIAN_PACKAGE_DEPENDS}${python_depends}")
else()
  # Without them: what the ELF files link on Debian 12, written out.
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
         ", libc6, libgcc-s1, libstdc++6, libvulkan1, libpng16-16, zlib1g")
  if(NOT LIC3D_STATIC_SYSTEM_LIBRARIES)
    string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libpugixml1v5")
  endif()
  set(CPACK_DEBIAN_LIC3D_PACKAGE_DEPENDS "${CPACK_DEBIAN_PACKAGE_DEPENDS}, libglfw3, libstb0")
  if(LIC3D_WITH_OPENVDB)  # lic3d writes .vdb (engine/CMakeLists.txt)
    string(APPEND CPACK_DEBIAN_LIC3D_PACKAGE_DEPENDS ", libopenvdb10.0, libtbb12, libimath-3-1-29")
  endif()
  set(CPACK_DEBIAN_PARAVIEW_PACKAGE_DEPENDS "${CPACK_DEBIAN_PACKAGE_DEPENDS}, paraview")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "${CPACK_DEBIAN_PACKAGE_DEPENDS}${python_depends}")
endif()
# ffmpeg encodes --video.
set(CPACK_DEBIAN_LIC3D_PACKAGE_SUGGESTS ffmpeg)
if(TARGET Lic3D)
  string(APPEND CPACK_DEBIAN_LIC3D_PACKAGE_SUGGESTS ", lic3d-paraview")
endif()
if(TARGET lic3d_python)
  string(APPEND CPACK_DEBIAN_LIC3D_PACKAGE_SUGGESTS ", python3-lic3d")
endif()

# `cpack --config CPackSourceConfig.cmake`: the sources without build folders or Git's.
set(CPACK_SOURCE_GENERATOR TGZ)
set(CPACK_SOURCE_IGNORE_FILES "/build/" "/\\\\.git/" "/\\\\.gl/")

include(CPack)
