# Runs tvo_firmware_node and plant_client side by side on LCM_URL and checks the client's final error.
# Usage: cmake -DNODE=... -DCLIENT=... -DLCM_URL=... -DDURATION_S=... -DMAX_ERROR_M=... -DBOOT_FILE=...
#        -P run_plant_client.cmake
foreach(var NODE CLIENT LCM_URL DURATION_S MAX_ERROR_M BOOT_FILE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_plant_client.cmake: -D${var}=... is required")
  endif()
endforeach()
# Two COMMANDs run at once (as a pipeline: the node's stdout, which is empty, feeds the client's stdin).
# The node exits after the client's STOP; TIMEOUT ends both if either hangs.
execute_process(
  COMMAND ${NODE} --lcm-url ${LCM_URL} --boot-file ${BOOT_FILE}
  COMMAND ${CLIENT} ${LCM_URL} ${DURATION_S}
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  RESULTS_VARIABLE codes
  TIMEOUT 90)
message(STATUS "plant_client: ${out}")
message(STATUS "stderr: ${err}")
if(NOT codes STREQUAL "0;0")
  message(FATAL_ERROR "exit codes (node;client) '${codes}', expected '0;0'")
endif()
if(NOT out MATCHES "final_error_m=([0-9.eE+-]+)")
  message(FATAL_ERROR "plant_client printed no final_error_m")
endif()
set(final_error ${CMAKE_MATCH_1})
# CMake compares as doubles (LESS parses both sides as real numbers).
if(NOT final_error LESS MAX_ERROR_M)
  message(FATAL_ERROR "plant_client did not converge: final error ${final_error} m, bound ${MAX_ERROR_M} m")
endif()
message(STATUS "converged: final error ${final_error} m < ${MAX_ERROR_M} m")
