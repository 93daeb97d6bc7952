# Runs tvo_sim once and checks its exit code, its stderr and its JSON summary (cmake -P script).
#
#   -DSIM=<tvo_sim> -DOUT_DIR=<dir> [-DFIRMWARE=<tvo_firmware_node>] [-DLCM_URL=<url>]
#   -DSIM_ARGS=<|-list of extra arguments>
#   -DEXPECT_EXIT=<code>            exact exit code (default 0)
#   -DEXPECT_EXIT_NONZERO=ON        any non-zero exit code instead
#   -DEXPECT_STDERR=<regex>         stderr must match
#   -DEXPECT_STDOUT=<regex>         stdout (the summary table) must match
#   -DCHECKS=<|-list of KEY<OP>VALUE>  OP is <, <=, >, >= or ==; KEY a number in summary.json
#   -DEXPECT_FILES=<|-list of names in OUT_DIR that must exist and be non-empty>
# Fails (FATAL_ERROR) on the first unmet expectation, after printing the run's output.
cmake_minimum_required(VERSION 3.19)   # string(JSON)
include(${CMAKE_CURRENT_LIST_DIR}/json_checks.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/run_sim.cmake)

if(NOT SIM OR NOT OUT_DIR)
  message(FATAL_ERROR "run_sim_check: SIM and OUT_DIR are required")
endif()
# Lists arrive '|'-separated (a ';' would split the cmake -P command line).
foreach(var SIM_ARGS CHECKS EXPECT_FILES)
  string(REPLACE "|" ";" ${var} "${${var}}")
endforeach()
if(NOT DEFINED EXPECT_EXIT)
  set(EXPECT_EXIT 0)
endif()

file(REMOVE_RECURSE ${OUT_DIR})
tvo_run_sim(${OUT_DIR} rc out err)

if(EXPECT_EXIT_NONZERO)
  if(rc STREQUAL "0" OR NOT rc MATCHES "^[0-9]+$")
    message(FATAL_ERROR "expected a non-zero exit code, got '${rc}'")
  endif()
elseif(NOT rc STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit code ${EXPECT_EXIT}, got '${rc}'")
endif()

if(DEFINED EXPECT_STDERR AND NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_STDERR}'")
endif()
if(DEFINED EXPECT_STDOUT AND NOT out MATCHES "${EXPECT_STDOUT}")
  message(FATAL_ERROR "stdout does not match '${EXPECT_STDOUT}'")
endif()

foreach(name IN LISTS EXPECT_FILES)
  if(NOT EXISTS ${OUT_DIR}/${name})
    message(FATAL_ERROR "missing output ${OUT_DIR}/${name}")
  endif()
  file(SIZE ${OUT_DIR}/${name} size)
  if(size EQUAL 0)
    message(FATAL_ERROR "empty output ${OUT_DIR}/${name}")
  endif()
endforeach()

if(CHECKS)
  tvo_json_checks(${OUT_DIR}/summary.json summary.json ${CHECKS})
endif()
