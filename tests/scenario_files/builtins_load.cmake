# Every built-in scenario file loads: `tvo_sim --scenario NAME --dry-run` accepts each file of the
# folder by its name, and `--list-scenarios` prints one line per file, its name then its whole
# description, and one line per file of a subfolder (host/scenarios/fleet/), its path then its
# description (cmake -P script). With SCENARIO_TOOL, `tools/scenario --list` without a build (an
# empty TVO_BUILD_DIR) must print the same lines and build nothing.
#
#   -DSIM=<tvo_sim> -DSCENARIO_DIR=<host/scenarios> [-DSCENARIO_TOOL=<tools/scenario> -DWORK=<dir>]
if(NOT SIM OR NOT SCENARIO_DIR)
  message(FATAL_ERROR "builtins_load: SIM and SCENARIO_DIR are required")
endif()
file(GLOB files ${SCENARIO_DIR}/*.yaml)
list(LENGTH files count)
if(count LESS 7)
  message(FATAL_ERROR "expected the seven built-in runs in ${SCENARIO_DIR}, found ${count} files")
endif()
file(GLOB subfolder_files ${SCENARIO_DIR}/*/*.yaml)
list(LENGTH subfolder_files subfolder_count)
math(EXPR listed_count "${count} + ${subfolder_count}")
execute_process(COMMAND ${SIM} --list-scenarios RESULT_VARIABLE rc OUTPUT_VARIABLE listing ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "--list-scenarios exited with '${rc}': ${err}")
endif()
string(REGEX MATCHALL "\n" newlines "${listing}")   # not a list of the lines: a description may hold ';'
list(LENGTH newlines line_count)
if(NOT line_count EQUAL listed_count)
  message(FATAL_ERROR "--list-scenarios printed ${line_count} lines for ${count} files and ${subfolder_count} "
                      "in subfolders:\n${listing}")
endif()
foreach(file IN LISTS subfolder_files)
  file(READ ${file} text)
  string(REGEX MATCH "\ndescription: \"([^\"\n]*)\"" line "${text}")
  set(description "${CMAKE_MATCH_1}")
  file(RELATIVE_PATH shown ${CMAKE_CURRENT_BINARY_DIR} ${file})   # as the path to give from here
  if(shown MATCHES "^\\.\\./")
    set(shown ${file})
  endif()
  string(FIND "${listing}" "${shown}  ${description}\n" at)
  if(at EQUAL -1 OR description STREQUAL "")
    message(FATAL_ERROR "--list-scenarios lacks '${shown}  ${description}':\n${listing}")
  endif()
  message(STATUS "ok: ${shown}: ${description}")
endforeach()
foreach(file IN LISTS files)
  get_filename_component(name ${file} NAME_WE)
  file(READ ${file} text)
  string(REGEX MATCH "\ndescription: \"([^\"\n]*)\"" line "${text}")
  set(description "${CMAKE_MATCH_1}")
  string(FIND "${listing}" "${name}" at)
  string(FIND "${listing}" "${description}" described)
  if(at EQUAL -1 OR described EQUAL -1 OR description STREQUAL "")
    message(FATAL_ERROR "--list-scenarios lacks '${name}' or its description '${description}':\n${listing}")
  endif()
  execute_process(COMMAND ${SIM} --scenario ${name} --dry-run --lcm-url memq://
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0" OR NOT out MATCHES "dry run: scenario ${name},")
    message(FATAL_ERROR "${name}: exit code '${rc}'\n${out}${err}")
  endif()
  message(STATUS "ok: ${name}: ${description}")
endforeach()

if(SCENARIO_TOOL)
  file(REMOVE_RECURSE ${WORK})
  file(MAKE_DIRECTORY ${WORK})
  execute_process(COMMAND ${CMAKE_COMMAND} -E env TVO_BUILD_DIR=${WORK} TVO_SCENARIO_DIR=${SCENARIO_DIR}
                          ${SCENARIO_TOOL} --list
                  RESULT_VARIABLE rc OUTPUT_VARIABLE tool_listing ERROR_VARIABLE err)
  file(GLOB built ${WORK}/*)
  if(NOT rc STREQUAL "0" OR NOT tool_listing STREQUAL listing OR built)
    message(FATAL_ERROR "tools/scenario --list without a build: exit '${rc}', wrote '${built}', printed\n"
                        "${tool_listing}${err}\nwhere tvo_sim lists\n${listing}")
  endif()
  message(STATUS "ok: tools/scenario --list without a build lists what tvo_sim lists")
endif()
