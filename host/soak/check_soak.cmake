# Runs tvo_soak once and checks its exit code and JSON figures (cmake -P script).
#   -DSOAK=<tvo_soak> -DJSON=<output file> -DSOAK_ARGS=<|-list of arguments>
#   -DCHECKS=<|-list of KEY<OP>VALUE>   OP is <, <=, >, >= or ==; KEY a number in the JSON
# Fails (FATAL_ERROR) on the first unmet expectation, after printing the run's output.
cmake_minimum_required(VERSION 3.19)   # string(JSON)
include(${CMAKE_CURRENT_LIST_DIR}/../../tests/closed_loop/json_checks.cmake)
if(NOT SOAK OR NOT JSON)
  message(FATAL_ERROR "check_soak: SOAK and JSON are required")
endif()
string(REPLACE "|" ";" SOAK_ARGS "${SOAK_ARGS}")
string(REPLACE "|" ";" CHECKS "${CHECKS}")

file(REMOVE ${JSON})
set(cmd ${SOAK} ${SOAK_ARGS} --json ${JSON})
string(REPLACE ";" " " shown "${cmd}")
message(STATUS "running: ${shown}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "exit code: ${rc}\n--- stdout\n${out}--- stderr\n${err}---")
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "expected exit code 0, got '${rc}'")
endif()

tvo_json_checks(${JSON} ${JSON} ${CHECKS})
