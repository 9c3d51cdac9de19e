# The layering check must refuse what it is there to refuse: a tree with an upward include, a
# sideways include between the robots, a driver in task code and a thread in pure code, each
# named with its file and line; and pass the same tree without them.
#   cmake -DCHECK=cmake/CheckLayers.cmake -DWORK=<dir> -P check_layers_test.cmake
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE "${WORK}")
function(put path text)
  file(WRITE "${WORK}/${path}" "${text}\n")
endfunction()
put(common/include/colag/common/a.hpp "#pragma once\n#include <cstdint>")
put(platform/dds/include/colag/platform/dds/t.hpp "#pragma once\n#include \"colag/common/a.hpp\"")
put(uav_fw/include/colag/uav/m.hpp "#pragma once")
put(ugv_fw/src/ok.cpp "#include <cmath>\n#include \"colag/common/a.hpp\"")

function(check expect_ok)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${WORK} -P ${CHECK}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(out "${out}${err}")
  if(expect_ok AND NOT rc EQUAL 0)
    message(FATAL_ERROR "a clean tree was refused:\n${out}")
  endif()
  if(NOT expect_ok AND rc EQUAL 0)
    message(FATAL_ERROR "a tree that breaks the layering passed:\n${out}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

check(TRUE)
put(ugv_fw/src/bad.cpp "// up, sideways, a thread\n#include \"colag/platform/dds/t.hpp\"\n#include \"colag/uav/m.hpp\"\n#include <thread>")
put(common/src/up.cpp "#include \"colag/uav/m.hpp\"")
check(FALSE)
foreach(expected
    "ugv_fw/src/bad.cpp:2: includes \"colag/platform/dds/t.hpp\""
    "ugv_fw/src/bad.cpp:3: includes \"colag/uav/m.hpp\""
    "ugv_fw/src/bad.cpp:4: includes <thread>"
    "common/src/up.cpp:1: includes \"colag/uav/m.hpp\""
    "layers: 4 include")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected \"${expected}\" in:\n${out}")
  endif()
endforeach()
message(STATUS "layers test: PASS")
