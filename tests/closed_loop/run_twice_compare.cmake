# Runs tvo_sim twice with the same arguments and requires identical results (cmake -P script):
# every key of summary.json but steps_per_s (wall clock) equal, and run.csv byte for byte.
#
#   -DSIM=<tvo_sim> -DOUT_DIR=<dir> [-DFIRMWARE=<tvo_firmware_node>] [-DLCM_URL=<url>]
#   -DSIM_ARGS=<|-list of arguments>
cmake_minimum_required(VERSION 3.19)   # string(JSON)
include(${CMAKE_CURRENT_LIST_DIR}/run_sim.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/compare_runs.cmake)

if(NOT SIM OR NOT OUT_DIR)
  message(FATAL_ERROR "run_twice_compare: SIM and OUT_DIR are required")
endif()
string(REPLACE "|" ";" SIM_ARGS "${SIM_ARGS}")
file(REMOVE_RECURSE ${OUT_DIR})

foreach(run a b)
  tvo_run_sim(${OUT_DIR}/${run} rc out err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "run ${run} failed with exit code '${rc}'")
  endif()
endforeach()

tvo_compare_runs(${OUT_DIR}/a ${OUT_DIR}/b "not deterministic")
