# SPDX-License-Identifier: MIT
# check_history_notes.cmake flags every numbered history note in a tree of sample files and
# nothing else. Usage: cmake -DROOT=<source dir> -DWORK=<scratch dir> -P <this file>.
cmake_policy(VERSION 3.16)
# Built from pieces so that this file holds no note itself.
set(s "session")
set(i "issue")
set(h "#")
set(S "Session")
set(notes
  "The rows of ${s} 14 follow."
  "### The weight loop (${s} 20)"
  "| case | before (${s} 13) | after |"
  "Until ${s}-14 the coarse operators stayed."
  "as in ${s}s 4 and 10"
  "Against ${i} ${h}3's goals:"
  "## What is left (${i} 5)"
  "still short of ${h}3's 0.34"
  "(see ${h}12)"
  "Before the rule of this ${s} it took 8 iterations."
  "// 29 vs 44 (${S} 17)")
set(fine
  "step 3 of the loop, eq. 10, §5.2, Table 1, paper 003, Fig. 8"
  "#include <vector>"
  "color: #333333; fill: #1f77b4; stroke: #000"
  "see [Flat edges](#flat-edges) and [Layers](DESIGN.md#1-layers)"
  "&#123; and \${#array} and $# and printf(\"%#04x\")"
  "A Session object; one session per mesh; MorphSession"
  "# 01 · Rotate the inner circle"
  "issues are tracked elsewhere; a session of work")
file(REMOVE_RECURSE ${WORK})
string(REPLACE ";" "\n" body "${notes}")
file(WRITE ${WORK}/docs/notes.md "title\n\n${body}\n")
string(REPLACE ";" "\n" body "${fine}")
file(WRITE ${WORK}/src/fine.cpp "${body}\n")
file(WRITE ${WORK}/README.md "Nothing to see.\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK} -DGIT=OFF -P ${ROOT}/cmake/check_history_notes.cmake
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "the check passed a tree with history notes:\n${out}")
endif()
list(LENGTH notes count)
math(EXPR last "${count} + 2")
foreach(line RANGE 3 ${last})
  if(NOT out MATCHES "docs/notes.md:${line}: ")
    message(FATAL_ERROR "line ${line} of the notes was not flagged:\n${out}")
  endif()
endforeach()
if(out MATCHES "fine.cpp|README.md|notes.md:[12]: ")
  message(FATAL_ERROR "the check flagged legitimate text:\n${out}")
endif()
file(REMOVE ${WORK}/docs/notes.md)
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK} -DGIT=OFF -P ${ROOT}/cmake/check_history_notes.cmake
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the check failed a tree without history notes:\n${out}")
endif()
message(STATUS "history notes check: ok")
