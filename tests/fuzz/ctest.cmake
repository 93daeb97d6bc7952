# CTest registration of the fuzz harnesses (included by the top-level CMakeLists.txt): fuzz_build
# builds them with clang into <build>/fuzz (a CTest fixture, like target_build), then fuzz_<harness>
# replays the seed corpus (tests/fuzz/corpus/<harness>: seeds and past crashes, so each is a
# regression test) and fuzzes for TVO_FUZZ_SECONDS. A run passes when no invariant breaks; how many
# inputs it tries depends on the machine, what it asserts does not.
find_program(TVO_FUZZ_CLANG NAMES clang-14 clang)
if(NOT TVO_FUZZ_CLANG)
  message(FATAL_ERROR "clang not found: install the Debian packages clang-14 libclang-rt-14-dev (or run tools/setup)")
endif()
set(TVO_FUZZ_SECONDS 20 CACHE STRING "Seconds each fuzz harness runs in tools/test")
set(tvo_fuzz_bin ${CMAKE_BINARY_DIR}/fuzz)
add_test(NAME fuzz_build
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_CURRENT_LIST_DIR} -DBINARY_DIR=${tvo_fuzz_bin}
          -DCLANG=${TVO_FUZZ_CLANG} -P ${CMAKE_CURRENT_LIST_DIR}/build_fuzz.cmake)
set_tests_properties(fuzz_build PROPERTIES FIXTURES_SETUP tvo_fuzz_harnesses LABELS fuzz TIMEOUT 900)
include(${CMAKE_CURRENT_LIST_DIR}/harnesses.cmake)
foreach(harness IN LISTS tvo_fuzz_harnesses)
  add_test(NAME fuzz_${harness}
    COMMAND ${CMAKE_COMMAND} -DHARNESS=${tvo_fuzz_bin}/fuzz_${harness} -DSEEDS=${CMAKE_CURRENT_LIST_DIR}/corpus/${harness}
            -DWORK=${tvo_fuzz_bin}/run/${harness} -DSECONDS=${TVO_FUZZ_SECONDS}
            -P ${CMAKE_CURRENT_LIST_DIR}/run_fuzz.cmake)
  set_tests_properties(fuzz_${harness} PROPERTIES FIXTURES_REQUIRED tvo_fuzz_harnesses LABELS fuzz TIMEOUT 300)
endforeach()
