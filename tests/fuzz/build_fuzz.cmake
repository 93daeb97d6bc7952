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
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} -j ${jobs} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the fuzz harnesses failed")
endif()
