# cmake -DFAST=<tvo_bench_host> -DONE_COPY=<tvo_bench_host_one_copy> -P shape_copies_agree.cmake
# The core's shape copies (firmware/src/shape.h) must compute what its one copy computes, bit for
# bit: both host benches run the four closed loops, and every problem's command digest must match.
foreach(var FAST ONE_COPY)
  if(NOT EXISTS "${${var}}")
    message(FATAL_ERROR "shape_copies_agree: ${var} (${${var}}) not found")
  endif()
endforeach()

foreach(var FAST ONE_COPY)
  execute_process(COMMAND "${${var}}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${${var}} FAILED (exit ${rc}):\n${out}")
  endif()
  string(REGEX MATCHALL "BENCH_DIGEST [a-z0-9_]+ [0-9]+" digests_${var} "${out}")
  list(LENGTH digests_${var} count)
  if(count LESS 4)
    message(FATAL_ERROR "${${var}} printed ${count} digests, not one per problem (4):\n${out}")
  endif()
endforeach()

if(NOT digests_FAST STREQUAL digests_ONE_COPY)
  message(FATAL_ERROR "the shape copies and the one copy computed different commands:\n"
                      "  with copies: ${digests_FAST}\n  one copy:    ${digests_ONE_COPY}")
endif()
message(STATUS "the same commands, bit for bit: ${digests_FAST}")
