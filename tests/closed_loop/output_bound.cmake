# The bound tvo_sim puts on a run's files before it starts (--dry-run prints it) holds for a real run,
# and is not so loose that it refuses sensible runs (cmake -P script):
#   actual <= bound for run.csv and run.lcmlog, and bound <= MAX_SLACK x actual.
#
#   -DSIM=<tvo_sim> -DOUT_DIR=<dir> -DFIRMWARE=<tvo_firmware_node> -DLCM_URL=<url>
#   -DSIM_ARGS=<|-list of arguments> -DMAX_SLACK=<whole number>
cmake_minimum_required(VERSION 3.19)
include(${CMAKE_CURRENT_LIST_DIR}/run_sim.cmake)

if(NOT SIM OR NOT OUT_DIR OR NOT FIRMWARE OR NOT MAX_SLACK)
  message(FATAL_ERROR "output_bound: SIM, OUT_DIR, FIRMWARE and MAX_SLACK are required")
endif()
string(REPLACE "|" ";" SIM_ARGS "${SIM_ARGS}")
file(REMOVE_RECURSE ${OUT_DIR})

set(run_args ${SIM_ARGS})
set(SIM_ARGS ${run_args} --dry-run)
tvo_run_sim(${OUT_DIR} rc out err)
if(NOT rc STREQUAL "0" OR NOT out MATCHES "run\\.csv ([0-9]+), run\\.lcmlog ([0-9]+)")
  message(FATAL_ERROR "the dry run did not print its bound (exit code '${rc}')")
endif()
set(bound_csv ${CMAKE_MATCH_1})
set(bound_lcmlog ${CMAKE_MATCH_2})
if(EXISTS ${OUT_DIR})
  message(FATAL_ERROR "the dry run created ${OUT_DIR}")
endif()

set(SIM_ARGS ${run_args})
tvo_run_sim(${OUT_DIR} rc out err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "the run failed with exit code '${rc}'")
endif()
foreach(file csv lcmlog)
  file(SIZE ${OUT_DIR}/run.${file} actual)
  set(bound ${bound_${file}})
  math(EXPR loose "${actual} * ${MAX_SLACK}")
  if(actual GREATER bound)
    message(FATAL_ERROR "run.${file}: ${actual} bytes written, more than the bound of ${bound}")
  endif()
  if(bound GREATER loose)
    message(FATAL_ERROR "run.${file}: the bound of ${bound} bytes is more than ${MAX_SLACK} x the ${actual} written")
  endif()
  message(STATUS "ok: run.${file}: ${actual} bytes written, bound ${bound}")
endforeach()
