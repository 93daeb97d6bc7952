# Configures (first time, or when the toolchain file changed) and builds the on-target test project.
#   cmake -DSOURCE_DIR=tests/target -DBINARY_DIR=<dir> -DTOOLCHAIN_FILE=<file> -DUNITY_DIR=<dir>
#         [-DGENERATOR=<gen>] -P build_target.cmake
cmake_minimum_required(VERSION 3.16)
foreach(var SOURCE_DIR BINARY_DIR TOOLCHAIN_FILE UNITY_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "build_target.cmake: ${var} is required")
  endif()
endforeach()
if(NOT GENERATOR)
  set(GENERATOR "Unix Makefiles")
endif()
if(EXISTS "${BINARY_DIR}/CMakeCache.txt" AND "${TOOLCHAIN_FILE}" IS_NEWER_THAN "${BINARY_DIR}/CMakeCache.txt")
  file(REMOVE_RECURSE "${BINARY_DIR}")
endif()
cmake_host_system_information(RESULT jobs QUERY NUMBER_OF_LOGICAL_CORES)
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" -G "${GENERATOR}"
                        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN_FILE}"
                        "-DTVO_UNITY_DIR=${UNITY_DIR}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the target tests failed (exit ${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BINARY_DIR}" --parallel ${jobs} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the target tests failed (exit ${rc})")
endif()
