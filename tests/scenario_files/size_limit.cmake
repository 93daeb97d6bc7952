# A scenario file larger than the limit is refused before it is parsed; one at the limit loads. The
# limit is read from its one definition, kMaxScenarioFileBytes in host/src/scenario_file.hpp
# (cmake -P script).
#
#   -DSIM=<tvo_sim> -DHEADER=<scenario_file.hpp> -DBASE=<a valid scenario file> -DOUT_DIR=<dir>
foreach(var SIM HEADER BASE OUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "size_limit: ${var} is required")
  endif()
endforeach()
file(STRINGS ${HEADER} limit_line REGEX "kMaxScenarioFileBytes = [0-9]+;")
string(REGEX MATCH "kMaxScenarioFileBytes = ([0-9]+)" _ "${limit_line}")
set(limit ${CMAKE_MATCH_1})
if(NOT limit)
  message(FATAL_ERROR "no kMaxScenarioFileBytes in ${HEADER}")
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
# A valid file padded with comment bytes to exactly the limit, and the same plus one byte.
file(READ ${BASE} text)
string(LENGTH "${text}" base_length)
math(EXPR pad "${limit} - ${base_length} - 1")
string(REPEAT "#" ${pad} comment)
file(WRITE ${OUT_DIR}/at_limit.yaml "${text}${comment}\n")
file(WRITE ${OUT_DIR}/over_limit.yaml "${text}${comment}#\n")
file(SIZE ${OUT_DIR}/at_limit.yaml at_size)
if(NOT at_size EQUAL limit)
  message(FATAL_ERROR "at_limit.yaml is ${at_size} bytes, not ${limit}")
endif()

execute_process(COMMAND ${SIM} --lcm-url memq:// --scenario ${OUT_DIR}/at_limit.yaml --dry-run
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
message(STATUS "at the limit: exit code ${rc}\n${out}${err}")
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "a file of exactly ${limit} bytes was refused")
endif()
execute_process(COMMAND ${SIM} --lcm-url memq:// --scenario ${OUT_DIR}/over_limit.yaml --dry-run
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
message(STATUS "over the limit: exit code ${rc}\n${out}${err}")
math(EXPR over "${limit} + 1")
set(expected "${OUT_DIR}/over_limit.yaml:1:1: the file is ${over} bytes, over the limit of ${limit} bytes for a scenario file (refused before parsing)")
if(NOT rc STREQUAL "2")
  message(FATAL_ERROR "expected exit code 2, got '${rc}'")
endif()
string(FIND "${err}" "${expected}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "stderr does not hold: ${expected}")
endif()
