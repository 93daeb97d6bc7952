# Builds tvo_bench for the microbit board (few steps) and runs it in QEMU; see CMakeLists.txt.
#   cmake -DFIRMWARE_DIR=<src> -DBINARY_DIR=<dir> -DTOOLCHAIN_FILE=<file> -DQEMU=<qemu-system-arm>
#         [-DGENERATOR=<gen>] -P bench_smoke.cmake
cmake_minimum_required(VERSION 3.16)
foreach(var FIRMWARE_DIR BINARY_DIR TOOLCHAIN_FILE QEMU)
  if(NOT ${var})
    message(FATAL_ERROR "bench_smoke.cmake: ${var} is required")
  endif()
endforeach()
if(NOT GENERATOR)
  set(GENERATOR "Unix Makefiles")
endif()
set(steps 20)

include("${CMAKE_CURRENT_LIST_DIR}/../cmake/run_command.cmake")

tvo_run("configure" QUIET ${CMAKE_COMMAND} -S ${FIRMWARE_DIR} -B ${BINARY_DIR} -G ${GENERATOR}
    -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN_FILE} -DTVO_BOARD=microbit -DCMAKE_BUILD_TYPE=Release
    -DTVO_LIMITS= -DTVO_BENCH_STEPS=${steps})
tvo_run("build" QUIET ${CMAKE_COMMAND} --build ${BINARY_DIR} --target tvo_bench --parallel 2)

execute_process(
  COMMAND ${QEMU} -M microbit -nographic -monitor none -semihosting-config enable=on,target=native
          -icount shift=0 -kernel ${BINARY_DIR}/apps/bench/tvo_bench.elf
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 300)
message(STATUS "QEMU microbit output:\n${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the bench exited with ${rc} under QEMU microbit")
endif()
# A figure is a positive instruction count, for every problem (the default limits fit its RAM).
foreach(problem unicycle obstacles4 formation2 chain_k3)
  if(NOT out MATCHES "BENCH ${problem} steps ${steps} min [1-9][0-9]* median [1-9][0-9]* max [1-9][0-9]* status 0\n")
    message(FATAL_ERROR "no figure line for ${problem}")
  endif()
endforeach()
if(NOT out MATCHES "BENCH_CONFIG [^\n]* instructions_per_tick 125/2\n")
  message(FATAL_ERROR "no BENCH_CONFIG line with TIMER0's 62.5 instructions per count")
endif()
