# The layering rule, checked at every build (cmake -P, no other tools): a folder includes only
# the folders below it, and pure code includes no OS, thread, I/O, DDS or OpenCV header.
#
#   cmake -DSOURCE_DIR=<tree> [-DSTAMP=<file>] -P cmake/CheckLayers.cmake
#
# Every `#include "..."` of every source and header is resolved to a file of the tree (next to
# the including file first, then under any include/ folder of the tree); includes that resolve
# to no file of the tree (generated IDL headers) are not checked. Both files are then placed by
# the first row of the table below whose folder prefixes their path, and the include must land
# in a folder the including row allows. A violation prints "file:line: ..." and fails.

cmake_minimum_required(VERSION 3.25)

# place | the folders it may include from
set(colag_layer_rules
  "common/|common/"
  "hal/include/|common/ hal/include/"
  "hal/scripted/|common/ hal/include/ hal/scripted/"
  "hal/|common/ hal/"
  "platform/include/|common/ hal/include/ platform/include/"
  "platform/|common/ hal/include/ platform/"
  "board/|common/ hal/include/ platform/ board/"
  "ugv_fw/app/|common/ hal/ platform/ board/ ugv_fw/"
  "ugv_fw/|common/ hal/include/ platform/include/ ugv_fw/include/ ugv_fw/src/"
  "uav_fw/app/|common/ hal/ platform/ board/ uav_fw/"
  "uav_fw/|common/ hal/include/ platform/include/ uav_fw/include/ uav_fw/src/"
  "sim/|common/ hal/ platform/ board/ ugv_fw/include/ ugv_fw/src/ uav_fw/include/ uav_fw/src/ sim/"
  "tools/|common/ hal/ platform/ board/ ugv_fw/ uav_fw/ sim/ tools/"
  "tests/|common/ hal/ platform/ board/ ugv_fw/ uav_fw/ sim/ tools/ tests/")

# Pure code (the firmware's tasks, common/, the HAL's interfaces): the standard library and Eigen
# only, and of the standard library nothing that does I/O or owns threads.
set(colag_pure_places common/ hal/include/ ugv_fw/include/ ugv_fw/src/ uav_fw/include/ uav_fw/src/)
set(colag_impure_std thread mutex shared_mutex condition_variable future stop_token fstream
    iostream filesystem cstdio csignal ctime)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<tree> [-DSTAMP=<file>] -P CheckLayers.cmake")
endif()
get_filename_component(root "${SOURCE_DIR}" ABSOLUTE)

set(folders common hal platform board ugv_fw uav_fw sim tools tests)
set(files "")
foreach(folder ${folders})
  file(GLOB_RECURSE found RELATIVE "${root}" "${root}/${folder}/*.cpp" "${root}/${folder}/*.hpp"
       "${root}/${folder}/*.h")
  list(APPEND files ${found})
endforeach()
list(FILTER files EXCLUDE REGEX "^tests/fuzz/corpus/")
list(FILTER files EXCLUDE REGEX "^tests/data/")

# Where each header can be reached from: its path below the nearest include/ folder.
foreach(f ${files})
  if(f MATCHES "/include/(.+)$")
    set("hdr_${CMAKE_MATCH_1}" "${f}")
  endif()
endforeach()

function(place_of path out_place out_allowed)
  foreach(rule ${colag_layer_rules})
    string(REPLACE "|" ";" parts "${rule}")
    list(GET parts 0 prefix)
    string(FIND "${path}" "${prefix}" at)
    if(at EQUAL 0)
      list(GET parts 1 allowed)
      string(REPLACE " " ";" allowed "${allowed}")
      set(${out_place} "${prefix}" PARENT_SCOPE)
      set(${out_allowed} "${allowed}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out_place} "" PARENT_SCOPE)
  set(${out_allowed} "" PARENT_SCOPE)
endfunction()

function(starts_with_any path prefixes out)
  foreach(p ${prefixes})
    string(FIND "${path}" "${p}" at)
    if(at EQUAL 0)
      set(${out} TRUE PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} FALSE PARENT_SCOPE)
endfunction()

# The line number of `line` in file `f`, for messages.
function(line_of f line out)
  file(READ "${root}/${f}" content)
  string(FIND "${content}" "${line}" at)
  string(SUBSTRING "${content}" 0 ${at} before)
  string(REGEX MATCHALL "\n" newlines "${before}")
  list(LENGTH newlines n)
  math(EXPR n "${n} + 1")
  set(${out} ${n} PARENT_SCOPE)
endfunction()

set(violations 0)
set(checked 0)
foreach(f ${files})
  place_of("${f}" place allowed)
  if(NOT place)
    continue()
  endif()
  starts_with_any("${f}" "${colag_pure_places}" pure)
  get_filename_component(dir "${f}" DIRECTORY)
  file(STRINGS "${root}/${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
  foreach(line ${lines})
    if(NOT line MATCHES "#[ \t]*include[ \t]*([<\"])([^>\"]+)[>\"]")
      continue()
    endif()
    set(kind "${CMAKE_MATCH_1}")
    set(name "${CMAKE_MATCH_2}")
    math(EXPR checked "${checked} + 1")
    if(kind STREQUAL "<")
      if(pure)
        string(REGEX MATCH "^[a-z_]+$" std_name "${name}")
        list(FIND colag_impure_std "${name}" impure)
        if(NOT name MATCHES "^Eigen/" AND (NOT std_name OR NOT impure EQUAL -1))
          line_of("${f}" "${line}" lineno)
          message(NOTICE "${f}:${lineno}: includes <${name}>: ${place} is pure code "
                                 "(the standard library without I/O or threads, and Eigen)")
          math(EXPR violations "${violations} + 1")
        endif()
      endif()
      continue()
    endif()
    set(target "")
    if(dir AND EXISTS "${root}/${dir}/${name}")
      file(RELATIVE_PATH target "${root}" "${root}/${dir}/${name}")
    elseif(DEFINED "hdr_${name}")
      set(target "${hdr_${name}}")
    endif()
    if(NOT target)
      continue()  # generated (IDL) or outside the tree
    endif()
    starts_with_any("${target}" "${allowed}" ok)
    string(REPLACE ";" " " allowed_text "${allowed}")
    if(NOT ok)
      line_of("${f}" "${line}" lineno)
      message(NOTICE "${f}:${lineno}: includes \"${name}\" (${target}): ${place} may use "
                             "only ${allowed_text}")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()

list(LENGTH files count)
if(violations GREATER 0)
  message(FATAL_ERROR "layers: ${violations} include(s) break the layering (README.md, Layout)")
endif()
message(STATUS "layers: ${count} files, ${checked} includes, every arrow points down")
if(STAMP)
  file(WRITE "${STAMP}" "ok\n")
endif()
