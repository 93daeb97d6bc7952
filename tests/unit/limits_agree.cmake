# cmake -DDEFAULT=<test_limits> -DONE_ROBOT=<test_limits_one_robot> -P limits_agree.cmake
# A one-robot product's limits (firmware/cmake/tvo_one_robot_limits.cmake) change sizes, not results:
# test_limits against tvo_core and against tvo_core_one_robot must print the same command digest.
foreach(var DEFAULT ONE_ROBOT)
  if(NOT EXISTS "${${var}}")
    message(FATAL_ERROR "limits_agree: ${var} (${${var}}) not found")
  endif()
  execute_process(COMMAND "${${var}}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${${var}} FAILED (exit ${rc}):\n${out}")
  endif()
  string(REGEX MATCHALL "LIMITS_DIGEST [a-z_]+ [0-9a-f]+" digests_${var} "${out}")
  if(NOT digests_${var})
    message(FATAL_ERROR "${${var}} printed no LIMITS_DIGEST line:\n${out}")
  endif()
endforeach()
if(NOT digests_DEFAULT STREQUAL digests_ONE_ROBOT)
  message(FATAL_ERROR "the one-robot limits computed other commands:\n"
                      "  default limits:   ${digests_DEFAULT}\n  one-robot limits: ${digests_ONE_ROBOT}")
endif()
message(STATUS "the same commands, bit for bit: ${digests_DEFAULT}")
