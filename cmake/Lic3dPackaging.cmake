# SPDX-License-Identifier: BSD-3-Clause
# Debian packages of what `cmake --install` installs, made by `cpack -G DEB` in the build folder
# (README.md, "Install"), for /usr:
#   lic3d           the programs, the Python module, man pages, bash completion, the desktop
#                   entry and icon, the documentation: every install rule without a component
#   lic3d-paraview  the ParaView plugin, in a package of its own because it needs ParaView (about
#                   1.4 GB), which the rest does not
# Any other install component becomes a package lic3d-<component>, except "development"
# (ParaView's client-server library, which the install removes again: paraview/CMakeLists.txt).
# The dependencies are what dpkg-shlibdeps finds the ELF files link, plus a Vulkan driver.
# tests/package_test.sh builds the packages, installs them into a scratch root and runs lic3d.

set(LIC3D_PACKAGE_CONTACT "the lic3d developers <lic3d@invalid>" CACHE STRING
    "Maintainer field of the Debian packages: Name <address>")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lic3d)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "${LIC3D_PACKAGE_CONTACT}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)

set(CPACK_DEB_COMPONENT_INSTALL ON)
get_cmake_property(CPACK_COMPONENTS_ALL COMPONENTS)
list(REMOVE_ITEM CPACK_COMPONENTS_ALL development)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # lic3d_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

set(CPACK_DEBIAN_LIC3D_PACKAGE_NAME lic3d)
set(CPACK_COMPONENT_LIC3D_DESCRIPTION
    "lic3d shows the inside of 3D vector fields with Line Integral Convolution
(LIC): a Vulkan compute pass follows the streamline through every voxel and
smears a noise volume along it; a graphics pass draws the LIC volume as
alpha-blended slices. It reads VTK, VTI, NRRD and raw files and runs on any
Vulkan device, Mesa's lavapipe (CPU) included.

This package holds the command-line program lic3d (pictures, LIC volumes,
2D LIC, animations, benchmarks; no display needed), the desktop app
lic3d-view, the Python module lic3d where it was built, their man pages and
the documentation with two real example fields.")
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_NAME lic3d-paraview)
set(CPACK_COMPONENT_PARAVIEW_DESCRIPTION
    "The ParaView plugin Lic3D: its filter 3D LIC computes LIC on image data
with the lic3d engine, one piece per process under mpirun pvbatch. Load
/usr/${LIC3D_PLUGIN_DESTINATION}/Lic3D.so
in ParaView (Tools > Manage Plugins) or name its folder in PV_PLUGIN_PATH.")
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_ENHANCES paraview)

# lic3d (the programs and the plugin) does nothing without a Vulkan driver; Mesa's runs anywhere.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "mesa-vulkan-drivers | vulkan-icd")
# CPack finds the ELF files with `file` and asks dpkg-shlibdeps (dpkg-dev) for their packages.
find_program(LIC3D_DPKG_SHLIBDEPS dpkg-shlibdeps)
find_program(LIC3D_FILE file)
if(LIC3D_DPKG_SHLIBDEPS AND LIC3D_FILE)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
else()
  # Without them: what the ELF files link on Debian 12, written out.
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libc6, libgcc-s1, libstdc++6, libvulkan1")
  set(CPACK_DEBIAN_LIC3D_PACKAGE_DEPENDS
      "${CPACK_DEBIAN_PACKAGE_DEPENDS}, libglfw3, libstb0, libpng16-16, zlib1g")
  if(LIC3D_WITH_OPENVDB)  # lic3d writes .vdb (engine/CMakeLists.txt)
    string(APPEND CPACK_DEBIAN_LIC3D_PACKAGE_DEPENDS ", libopenvdb10.0, libtbb12, libimath-3-1-29")
  endif()
  set(CPACK_DEBIAN_PARAVIEW_PACKAGE_DEPENDS "${CPACK_DEBIAN_PACKAGE_DEPENDS}, zlib1g, paraview")
endif()
# ffmpeg encodes --video; the Python module needs numpy.
set(CPACK_DEBIAN_LIC3D_PACKAGE_SUGGESTS ffmpeg)
if(TARGET Lic3D)
  string(APPEND CPACK_DEBIAN_LIC3D_PACKAGE_SUGGESTS ", lic3d-paraview")
endif()
if(TARGET lic3d_python)
  set(CPACK_DEBIAN_LIC3D_PACKAGE_RECOMMENDS python3-numpy)
endif()

# `cpack --config CPackSourceConfig.cmake`: the sources without build folders or Git's.
set(CPACK_SOURCE_GENERATOR TGZ)
set(CPACK_SOURCE_IGNORE_FILES "/build/" "/\\\\.git/" "/\\\\.gl/")

include(CPack)
