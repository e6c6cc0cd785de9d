# SPDX-License-Identifier: BSD-3-Clause
# What `cmake --install` puts under share/, next to bin/lic3d, bin/lic3d-view (app/), the ParaView
# plugin (paraview/) and the Python module (python/):
#   share/doc/lic3d/                      README.md, LICENSE, docs/*.md, docs/examples/, the
#                                         ParaView script, the two real fields of assets/data
#                                         with their provenance and licences
#   share/man/man1/                       lic3d.1.gz, lic3d-view.1.gz: help2man, from the
#                                         built binaries' --help
#   share/bash-completion/completions/    lic3d, lic3d-view (assets/completion/lic3d.bash)
#   share/applications/lic3d-view.desktop and its icon, share/icons/hicolor/256x256/apps/lic3d.png
# No headers and no libraries: nothing outside this build links lic3d.

set(source ${CMAKE_SOURCE_DIR})

# Documentation, laid out as in the repository so that its links hold.
install(FILES ${source}/README.md ${source}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The Debian packages add share/doc/<package>/copyright and changelog.gz (Lic3dPackaging.cmake).
file(GLOB doc_pages CONFIGURE_DEPENDS ${source}/docs/*.md)
install(FILES ${doc_pages} ${source}/docs/paraview_lic3d.py
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
install(DIRECTORY ${source}/docs/examples DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs
        USE_SOURCE_PERMISSIONS)
if(EXISTS ${source}/assets/data/LICENSES)
  install(DIRECTORY ${source}/assets/data DESTINATION ${CMAKE_INSTALL_DOCDIR}/assets)
endif()

# Man pages, made at build time from the programs' own --help (cmake/Lic3dManPage.cmake), so they
# never disagree with it.
find_program(LIC3D_HELP2MAN help2man)
if(NOT LIC3D_HELP2MAN)
  message(STATUS "help2man not found: no man pages (cmake/install-deps.sh installs it)")
elseif(CMAKE_CROSSCOMPILING OR CMAKE_CXX_FLAGS MATCHES "-fsanitize")
  message(STATUS "No man pages: help2man would run programs built for another machine or with "
                 "sanitizers")
else()
  set(man_pages "")
  set(lic3d_name "3D Line Integral Convolution of vector fields with Vulkan")
  set(lic3d_commands "devices,compute,render,render2d,bench")
  set(lic3d-view_name "the lic3d desktop app: the LIC volume of a vector field in a window")
  set(lic3d-view_commands "")
  # Installed compressed, as Debian wants them (gzip -9n: no name or time stamp in the file).
  find_program(LIC3D_GZIP gzip)
  foreach(program lic3d lic3d-view)
    if(NOT TARGET ${program})
      continue()
    endif()
    set(page ${CMAKE_BINARY_DIR}/man/${program}.1)
    set(compressed "")
    set(compress "")
    if(LIC3D_GZIP)
      set(compressed ${page}.gz)
      set(compress COMMAND ${LIC3D_GZIP} -9nfk ${page})
    endif()
    add_custom_command(
      OUTPUT ${page} ${compressed}
      COMMAND ${CMAKE_COMMAND} -DHELP2MAN=${LIC3D_HELP2MAN} -DPROGRAM=$<TARGET_FILE:${program}>
              "-DNAME=${${program}_name}" "-DCOMMANDS=${${program}_commands}"
              -DINCLUDE=${source}/assets/man/${program}.h2m -DOUTPUT=${page}
              -P ${source}/cmake/Lic3dManPage.cmake
      ${compress}
      DEPENDS ${program} ${source}/assets/man/${program}.h2m ${source}/cmake/Lic3dManPage.cmake
      COMMENT "Writing the man page ${program}.1 (help2man)"
      VERBATIM)
    if(LIC3D_GZIP)
      list(APPEND man_pages ${compressed})
    else()
      list(APPEND man_pages ${page})
    endif()
  endforeach()
  add_custom_target(lic3d_man_pages ALL DEPENDS ${man_pages})
  install(FILES ${man_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()

# Bash completion, loaded on demand by bash-completion under the command's name.
set(completions ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
install(FILES ${source}/assets/completion/lic3d.bash DESTINATION ${completions} RENAME lic3d)
if(TARGET lic3d-view)
  install(FILES ${source}/assets/completion/lic3d.bash DESTINATION ${completions}
          RENAME lic3d-view)
  install(FILES ${source}/assets/desktop/lic3d-view.desktop
          DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
  # Made by `lic3d render --grid 96 --width 256 --height 256 --look streamlines` (the PNG carries
  # that session).
  install(FILES ${source}/assets/icons/lic3d.png
          DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/256x256/apps)
endif()
