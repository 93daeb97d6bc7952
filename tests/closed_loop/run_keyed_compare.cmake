# A keyed bus changes nothing but the bytes on the wire (cmake -P script): tvo_sim and the
# tvo_firmware_node it spawns run once unkeyed and once with --key-file, with the same arguments, and
# the two runs must agree (summary.json but the wall-clock rate, run.csv byte for byte). Before that,
# a key file that others may read is refused by both programs, naming the fix (chmod 600).
#
#   -DSIM=<tvo_sim> -DFIRMWARE=<tvo_firmware_node> -DOUT_DIR=<dir> [-DLCM_URL=<url>] -DSIM_ARGS=<|-list>
cmake_minimum_required(VERSION 3.19)
include(${CMAKE_CURRENT_LIST_DIR}/run_sim.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/compare_runs.cmake)

if(NOT SIM OR NOT FIRMWARE OR NOT OUT_DIR)
  message(FATAL_ERROR "run_keyed_compare: SIM, FIRMWARE and OUT_DIR are required")
endif()
string(REPLACE "|" ";" SIM_ARGS "${SIM_ARGS}")
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})

# A test key (its value does not matter; a real one comes from tools/keygen), owner-only.
set(key ${OUT_DIR}/bus.key)
file(WRITE ${key} "00112233445566778899aabbccddeeff0123456789abcdeffedcba9876543210\n")

file(CHMOD ${key} PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ)
foreach(program SIM FIRMWARE)
  # tvo_sim checks it with its options (--dry-run: nothing runs); the node before it opens LCM.
  set(extra "")
  if(program STREQUAL "SIM")
    set(extra --dry-run)
  endif()
  execute_process(COMMAND ${${program}} --key-file ${key} --lcm-url memq:// ${extra}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 30)
  if(rc STREQUAL "0" OR NOT err MATCHES "chmod 600")
    message(FATAL_ERROR "${program} took a group-readable key file: exit '${rc}', stderr:\n${err}")
  endif()
endforeach()
file(CHMOD ${key} PERMISSIONS OWNER_READ OWNER_WRITE)

set(plain_args ${SIM_ARGS})
tvo_run_sim(${OUT_DIR}/plain rc out err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "the unkeyed run failed with exit code '${rc}'")
endif()
set(SIM_ARGS ${plain_args} --key-file ${key})
tvo_run_sim(${OUT_DIR}/keyed rc out err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "the keyed run failed with exit code '${rc}'")
endif()
# The node's counts at exit (unauthenticated=N replayed=N) and tvo_sim's own drops ("dropped N frame(s)").
if(err MATCHES "unauthenticated=[1-9]|replayed=[1-9]|dropped [1-9]")
  message(FATAL_ERROR "the keyed run dropped genuine frames:\n${err}")
endif()
tvo_compare_runs(${OUT_DIR}/plain ${OUT_DIR}/keyed "changed by the key")
