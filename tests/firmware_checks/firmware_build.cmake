# Configures firmware/ as a standalone project (optionally with a cross toolchain file), builds the
# control core tvo_core (warnings are errors there), and optionally checks it for allocator use and
# links the allocation probe against it.
#
#   cmake -DFIRMWARE_DIR=<src> -DBINARY_DIR=<dir> [-DTOOLCHAIN_FILE=<file>] [-DGENERATOR=<gen>]
#         [-DC_COMPILER=<cc>] [-DTVO_DOUBLE=ON] [-DCHECK_ALLOCATOR=ON] [-DPROBE_DIR=<probe project>]
#         [-DBUILD_TYPE=Release|MinSizeRel] [-DFOOTPRINT_TOOL=tools/footprint.py]
#         [-DLIMITS=<size limits, e.g. TVO_MAX_OUTPUT_DIM=2,TVO_MAX_EQUALITIES=2>]
#         -P firmware_build.cmake
# With a probe and FOOTPRINT_TOOL, writes <dir>/footprint.json: the core's flash and RAM in the
# probe's --gc-sections link and the worst-case stack of one controller step; and
# <dir>/footprint_tracking.json, the same for a one-robot tracking firmware (tracking_probe.c) with
# the pose velocity source, and footprint_tracking_both_sources.json with either source.
cmake_minimum_required(VERSION 3.16)
include("${CMAKE_CURRENT_LIST_DIR}/check_no_allocator.cmake")

foreach(var FIRMWARE_DIR BINARY_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "firmware_build.cmake: ${var} is required")
  endif()
endforeach()
if(NOT GENERATOR)
  set(GENERATOR "Unix Makefiles")
endif()
if(TVO_DOUBLE)
  set(TVO_DOUBLE ON)
else()
  set(TVO_DOUBLE OFF)
endif()
cmake_host_system_information(RESULT jobs QUERY NUMBER_OF_LOGICAL_CORES)

include("${CMAKE_CURRENT_LIST_DIR}/../cmake/run_command.cmake")

if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()
set(common_args -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DTVO_DOUBLE=${TVO_DOUBLE})
list(APPEND common_args "-DTVO_LIMITS=${LIMITS}")
if(TOOLCHAIN_FILE)
  if(NOT EXISTS "${TOOLCHAIN_FILE}")
    message(FATAL_ERROR "toolchain file ${TOOLCHAIN_FILE} not found")
  endif()
  list(APPEND common_args "-DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN_FILE}")
elseif(C_COMPILER)
  list(APPEND common_args "-DCMAKE_C_COMPILER=${C_COMPILER}")
endif()

# A toolchain file is read only when a build folder is first configured: start afresh if it changed.
if(TOOLCHAIN_FILE AND EXISTS "${BINARY_DIR}/CMakeCache.txt"
   AND "${TOOLCHAIN_FILE}" IS_NEWER_THAN "${BINARY_DIR}/CMakeCache.txt")
  message(STATUS "${TOOLCHAIN_FILE} changed: removing ${BINARY_DIR}")
  file(REMOVE_RECURSE "${BINARY_DIR}")
endif()

# 1. firmware/ on its own, as a cross build would configure it
tvo_run("configure firmware" "${CMAKE_COMMAND}" -S "${FIRMWARE_DIR}" -B "${BINARY_DIR}" ${common_args}
    -DTVO_STACK_USAGE=ON)
tvo_run("build tvo_core" "${CMAKE_COMMAND}" --build "${BINARY_DIR}" --target tvo_core --parallel ${jobs})

load_cache("${BINARY_DIR}" READ_WITH_PREFIX SUB_ CMAKE_NM CMAKE_SIZE CMAKE_OBJDUMP CMAKE_C_COMPILER)
set(core_lib "${BINARY_DIR}/libtvo_core.a")
if(NOT EXISTS "${core_lib}")
  message(FATAL_ERROR "${core_lib} was not produced")
endif()
message(STATUS "built ${core_lib} with ${SUB_CMAKE_C_COMPILER}")

# Fails if the library or program links an allocator.
function(tvo_require_no_allocator file)
  tvo_find_allocator_symbols(found "${SUB_CMAKE_NM}" "${file}")
  if(found)
    string(REPLACE ";" ", " found "${found}")
    message(FATAL_ERROR "allocator symbols in ${file}: ${found}")
  endif()
  message(STATUS "no allocator symbols in ${file}")
endfunction()

# 2. no allocator in the core library
if(CHECK_ALLOCATOR)
  tvo_require_no_allocator("${core_lib}")
endif()

# 3. the probe: a --gc-sections link of the whole core, then the same check on the ELF, plus the
#    negative control (a program calling malloc must be caught by the same check)
if(PROBE_DIR)
  set(probe_bin "${BINARY_DIR}/probe")
  tvo_run("configure probe" "${CMAKE_COMMAND}" -S "${PROBE_DIR}" -B "${probe_bin}" ${common_args}
      "-DTVO_CORE_LIBRARY=${core_lib}" "-DTVO_FIRMWARE_INCLUDE_DIR=${FIRMWARE_DIR}/include")
  tvo_run("build probe" "${CMAKE_COMMAND}" --build "${probe_bin}" --parallel ${jobs})

  foreach(probe alloc_probe tracking_probe tracking_probe_both_sources)
    tvo_require_no_allocator("${probe_bin}/${probe}.elf")
  endforeach()

  tvo_find_allocator_symbols(found "${SUB_CMAKE_NM}" "${probe_bin}/alloc_canary.elf")
  if(NOT found)
    message(FATAL_ERROR "self-test FAILED: no allocator found in alloc_canary.elf, which calls malloc: the check is broken")
  endif()
  string(REPLACE ";" ", " found "${found}")
  message(STATUS "self-test passed: alloc_canary.elf (calls malloc) is caught: ${found}")

  if(SUB_CMAKE_SIZE)
    message(STATUS "size of the linked probe (core + libm + newlib-nano startup), for information:")
    execute_process(COMMAND "${SUB_CMAKE_SIZE}" "${probe_bin}/alloc_probe.elf")
    message(STATUS "size of libtvo_core.a (all objects, before --gc-sections), for information:")
    execute_process(COMMAND "${SUB_CMAKE_SIZE}" --totals "${core_lib}")
  endif()
endif()
if(PROBE_DIR AND FOOTPRINT_TOOL)
  tvo_run("footprint" "${FOOTPRINT_TOOL}" --core-dir "${BINARY_DIR}/CMakeFiles/tvo_core.dir"
      --map "${probe_bin}/alloc_probe.map" --elf "${probe_bin}/alloc_probe.elf" --objdump "${SUB_CMAKE_OBJDUMP}" --root tvo_controller_step --root tvo_chain_controller_step
      --json "${BINARY_DIR}/footprint.json")
  # A one-robot tracking firmware: what a board links when it adds tracking terms only (with the
  # pose velocity source, and with both sources).
  foreach(probe tracking_probe tracking_probe_both_sources)
    string(REPLACE "_probe" "" json_name "footprint_${probe}")
    tvo_run("footprint of ${probe}" "${FOOTPRINT_TOOL}" --core-dir "${BINARY_DIR}/CMakeFiles/tvo_core.dir"
        --map "${probe_bin}/${probe}.map" --elf "${probe_bin}/${probe}.elf" --objdump "${SUB_CMAKE_OBJDUMP}"
        --root tvo_controller_step --json "${BINARY_DIR}/${json_name}.json")
  endforeach()
endif()
message(STATUS "firmware build check passed")
