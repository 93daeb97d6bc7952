# A scenario file runs exactly like a built-in one (cmake -P script): `tools/scenario FILE` (no
# build: TVO_DEMO_NO_BUILD, TVO_BUILD_DIR) writes every output, and tvo_sim running the same file as
# a built-in by its name gives the same summary and a byte-identical run.csv. Without BUILTIN the
# file is copied into a scenario folder of its own ($TVO_SCENARIO_DIR); with BUILTIN=NAME the
# built-in of that name is run from the default folder.
#
#   -DSCENARIO_TOOL=<tools/scenario> -DBUILD_DIR=<build> -DSIM=<tvo_sim> -DFIRMWARE=<node>
#   -DLCM_URL=<url> -DOUT_DIR=<dir> -DFILE=<file.yaml> [-DBUILTIN=<name>] [-DCHECKS=<|-list>]
cmake_minimum_required(VERSION 3.19)
include(${CMAKE_CURRENT_LIST_DIR}/../closed_loop/json_checks.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/../closed_loop/compare_runs.cmake)

foreach(var SCENARIO_TOOL BUILD_DIR SIM FIRMWARE LCM_URL OUT_DIR FILE)
  if(NOT ${var})
    message(FATAL_ERROR "file_like_builtin: ${var} is required")
  endif()
endforeach()
string(REPLACE "|" ";" CHECKS "${CHECKS}")
file(REMOVE_RECURSE ${OUT_DIR})
get_filename_component(name ${FILE} NAME_WE)

function(run_checked what)
  string(REPLACE ";" " " shown "${ARGN}")
  message(STATUS "running (${what}): ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  message(STATUS "exit code: ${rc}\n--- stdout\n${out}--- stderr\n${err}---")
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "${what} failed with exit code '${rc}'")
  endif()
endfunction()

run_checked("tools/scenario FILE" ${CMAKE_COMMAND} -E env TVO_DEMO_NO_BUILD=1 TVO_BUILD_DIR=${BUILD_DIR}
  ${SCENARIO_TOOL} ${FILE} --lcm-url ${LCM_URL} --out-dir ${OUT_DIR}/file)
foreach(output run.csv run.lcmlog summary.json scenario.json run.png)
  if(NOT EXISTS ${OUT_DIR}/file/${output})
    message(FATAL_ERROR "tools/scenario ${FILE} wrote no ${output}")
  endif()
endforeach()

if(BUILTIN)
  run_checked("built-in ${BUILTIN}" ${SIM} --firmware ${FIRMWARE} --lcm-url ${LCM_URL}
    --scenario ${BUILTIN} --out-dir ${OUT_DIR}/builtin)
else()
  file(COPY ${FILE} DESTINATION ${OUT_DIR}/folder)
  run_checked("built-in ${name}" ${CMAKE_COMMAND} -E env TVO_SCENARIO_DIR=${OUT_DIR}/folder
    ${SIM} --firmware ${FIRMWARE} --lcm-url ${LCM_URL} --scenario ${name} --out-dir ${OUT_DIR}/builtin)
endif()
tvo_compare_runs(${OUT_DIR}/file ${OUT_DIR}/builtin "file and built-in differ")
if(CHECKS)
  tvo_json_checks(${OUT_DIR}/file/summary.json summary.json ${CHECKS})
endif()
