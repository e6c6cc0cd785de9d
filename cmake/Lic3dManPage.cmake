# SPDX-License-Identifier: BSD-3-Clause
# Writes the man page of a lic3d program with help2man from the built binary's --help and
# --version; cmake/Lic3dInstall.cmake runs it at build time:
#   cmake -DHELP2MAN=<help2man> -DPROGRAM=<built binary> -DNAME=<the NAME line>
#         -DINCLUDE=<extra sections, .h2m> [-DCOMMANDS=devices,compute,...] -DOUTPUT=<page.1>
#         -P cmake/Lic3dManPage.cmake
# help2man runs the program by its bare name, found through PATH, so the page's usage lines say
# "lic3d" and not the build folder. With COMMANDS, the --help of each command (formatted by
# help2man too) becomes a subsection of a section COMMANDS.
cmake_minimum_required(VERSION 3.25)

get_filename_component(folder "${PROGRAM}" DIRECTORY)
get_filename_component(program "${PROGRAM}" NAME)
set(run ${CMAKE_COMMAND} -E env "PATH=${folder}:$ENV{PATH}" "${HELP2MAN}" --no-info)

file(READ "${INCLUDE}" sections)
if(COMMANDS)
  string(APPEND sections "[COMMANDS]\n")
  string(REPLACE "," ";" COMMANDS "${COMMANDS}")
  foreach(command IN LISTS COMMANDS)
    execute_process(COMMAND ${run} --version-string=0 "--help-option=${command} --help" ${program}
                    OUTPUT_VARIABLE page RESULT_VARIABLE status)
    string(FIND "${page}" ".SH DESCRIPTION\n" start)
    if(NOT status EQUAL 0 OR start LESS 0)
      message(FATAL_ERROR "help2man: no page for `${program} ${command} --help` (${status})")
    endif()
    # DESCRIPTION (the command's first line) and OPTIONS, under the command's own heading.
    string(SUBSTRING "${page}" ${start} -1 page)
    string(REPLACE ".SH DESCRIPTION\n" "" page "${page}")
    string(REPLACE ".SH OPTIONS\n" "" page "${page}")
    string(APPEND sections ".SS \"${program} ${command} [OPTIONS]\"\n${page}")
  endforeach()
endif()

get_filename_component(work "${OUTPUT}" DIRECTORY)
file(WRITE "${work}/${program}.h2m" "${sections}")
execute_process(COMMAND ${run} "--name=${NAME}" --section=1 "--include=${work}/${program}.h2m"
                        "--output=${OUTPUT}.tmp" ${program}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(REMOVE "${OUTPUT}.tmp")
  message(FATAL_ERROR "help2man failed on ${program} (${status})")
endif()
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
