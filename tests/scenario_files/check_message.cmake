# Runs tvo_sim once (no firmware: every case here ends before a session) and checks its exit code
# and that its output holds the expected text, literally (cmake -P script).
#
#   -DSIM=<tvo_sim> -DSIM_ARGS=<|-list of arguments> -DEXPECT_EXIT=<code>
#   [-DEXPECT_STDERR=<text>] [-DEXPECT_STDOUT=<text>]
if(NOT SIM OR NOT DEFINED EXPECT_EXIT)
  message(FATAL_ERROR "check_message: SIM and EXPECT_EXIT are required")
endif()
string(REPLACE "|" ";" SIM_ARGS "${SIM_ARGS}")
execute_process(COMMAND ${SIM} --lcm-url memq:// ${SIM_ARGS}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
message(STATUS "exit code: ${rc}\n--- stdout\n${out}--- stderr\n${err}---")
if(NOT rc STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit code ${EXPECT_EXIT}, got '${rc}'")
endif()
foreach(stream stdout stderr)
  string(TOUPPER "EXPECT_${stream}" expect_var)
  set(text "${out}")
  if(stream STREQUAL "stderr")
    set(text "${err}")
  endif()
  if(DEFINED ${expect_var})
    string(FIND "${text}" "${${expect_var}}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${stream} does not hold: ${${expect_var}}")
    endif()
  endif()
endforeach()
