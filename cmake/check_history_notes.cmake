# SPDX-License-Identifier: MIT
# Fails if a tracked text file carries a numbered history note (the word session or issue
# followed by a number, an issue's number after "#", a session named by since, until, before
# or after): the tree describes the program as it is, history lives in `git log`. Lists the files with `git ls-files`; where ROOT is not a checkout (or -DGIT=OFF)
# it globs the same folders. Usage: cmake -DROOT=<source dir> [-DGIT=OFF] -P <this file>.
cmake_policy(VERSION 3.16)  # list() keeps empty elements: the blank lines count
set(folders README.md docs bench examples src include app python scripts tests cmake)
# Data files hold no prose.
set(data_ext "\\.(msh|vtu|vtk|mesh|csv|png|svg|jpg|gz|bin|exo|cgns|su2)$")

# Matched against the lower-cased line: session, sessions or issue followed by a number (with
# a space or a hyphen, and "#" or not between); "#" and one or two digits as an issue
# reference (not a colour code, an HTML entity, "$#" or an anchor); and the word session
# after since, until, before, after, this, last or previous.
set(word_start "(^|[^a-z0-9_])")
set(patterns
  "${word_start}sessions?[ -]#?[0-9]"
  "${word_start}issues?[ -]#?[0-9]"
  "(^|[^a-z0-9_&$%#/{'\"\\\\])#[0-9][0-9]?([^0-9a-z_]|$)"
  "${word_start}(since|until|before|after|this|last|previous) sessions?([^a-z]|$)")

set(files "")
if(NOT DEFINED GIT OR GIT)
  find_program(git_exe git)
  if(git_exe)
    execute_process(COMMAND ${git_exe} -C ${ROOT} -c core.quotepath=off ls-files -- ${folders}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE listed ERROR_QUIET)
    if(rc EQUAL 0 AND NOT listed STREQUAL "")
      string(REPLACE "\n" ";" listed "${listed}")
      foreach(f IN LISTS listed)
        if(NOT f STREQUAL "" AND EXISTS ${ROOT}/${f})
          list(APPEND files ${ROOT}/${f})
        endif()
      endforeach()
    endif()
  endif()
endif()
if(NOT files)
  foreach(folder IN LISTS folders)
    if(IS_DIRECTORY ${ROOT}/${folder})
      file(GLOB_RECURSE found ${ROOT}/${folder}/*)
      list(APPEND files ${found})
    elseif(EXISTS ${ROOT}/${folder})
      list(APPEND files ${ROOT}/${folder})
    endif()
  endforeach()
endif()

set(bad "")
set(checked 0)
set(found 0)
foreach(f IN LISTS files)
  string(TOLOWER "${f}" lower_name)
  if(lower_name MATCHES "${data_ext}" OR IS_DIRECTORY ${f})
    continue()
  endif()
  math(EXPR checked "${checked} + 1")
  file(READ ${f} text)
  string(TOLOWER "${text}" lower)
  set(hit FALSE)
  foreach(p IN LISTS patterns)
    if(lower MATCHES "${p}")
      set(hit TRUE)
    endif()
  endforeach()
  if(NOT hit)
    continue()
  endif()
  # Only now split into lines, for the line numbers. Brackets, semicolons and backslashes
  # would bend CMake's list splitting; none of the patterns needs them.
  string(REGEX REPLACE "[][;\\\\]" " " text "${text}")
  string(REGEX REPLACE "[][;\\\\]" " " lower "${lower}")
  string(REPLACE "\n" ";" lines "${text}")
  string(REPLACE "\n" ";" lower_lines "${lower}")
  set(number 0)
  foreach(line IN LISTS lower_lines)
    foreach(p IN LISTS patterns)
      if(line MATCHES "${p}")
        file(RELATIVE_PATH rel ${ROOT} ${f})
        list(GET lines ${number} shown)
        string(STRIP "${shown}" shown)
        math(EXPR line_number "${number} + 1")
        string(APPEND bad "${rel}:${line_number}: ${shown}\n")
        math(EXPR found "${found} + 1")
        break()
      endif()
    endforeach()
    math(EXPR number "${number} + 1")
  endforeach()
endforeach()
if(bad)
  message("${bad}")
  message(FATAL_ERROR "${found} numbered history notes in ${checked} files: describe the program as "
                      "it is (history lives in git log)")
endif()
message(STATUS "history notes: none in ${checked} files")
