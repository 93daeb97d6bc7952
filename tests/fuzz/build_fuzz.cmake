# Configures and builds the fuzz harnesses (tests/fuzz) with clang into BINARY_DIR.
#   cmake -DSOURCE_DIR=<repo>/tests/fuzz -DBINARY_DIR=<dir> -DCLANG=<clang> -P build_fuzz.cmake
foreach(v SOURCE_DIR BINARY_DIR CLANG)
  if(NOT ${v})
    message(FATAL_ERROR "build_fuzz.cmake: ${v} is not set")
  endif()
endforeach()
if(NOT EXISTS ${BINARY_DIR}/CMakeCache.txt)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -G "Unix Makefiles"
                          -DCMAKE_C_COMPILER=${CLANG} -DCMAKE_BUILD_TYPE=RelWithDebInfo
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the fuzz harnesses failed (clang with libFuzzer: Debian clang-14, libclang-rt-14-dev)")
  endif()
endif()
include(ProcessorCount)
ProcessorCount(jobs)
# Only the harnesses and the seed writer: the project's `all` also has the host programs of
# firmware/apps/bench (from add_subdirectory(firmware)), which nothing fuzzes (the sanitized stage
# builds them with clang).
include(${SOURCE_DIR}/harnesses.cmake)
set(targets fuzz_make_seeds)
foreach(harness IN LISTS tvo_fuzz_harnesses)
  list(APPEND targets fuzz_${harness})
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} -j ${jobs} --target ${targets} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the fuzz harnesses failed")
endif()
