# Runs one harness: the seeds (and past crashes) first, then fuzzing for SECONDS; new inputs go to
# WORK/corpus, a crash to WORK/crash-*, never into the source tree.
#   cmake -DHARNESS=<exe> -DSEEDS=<dir> -DWORK=<dir> -DSECONDS=<n> -P run_fuzz.cmake
file(MAKE_DIRECTORY ${WORK}/corpus)
execute_process(COMMAND ${HARNESS} -max_total_time=${SECONDS} -timeout=20 -rss_limit_mb=4096
                        -print_final_stats=1 -artifact_prefix=${WORK}/ ${WORK}/corpus ${SEEDS}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "stat::number_of_executed_units: *[0-9]+" runs "${err}")
string(REGEX MATCH "cov: [0-9]+ ft: [0-9]+" coverage "${err}")
message("${HARNESS}: ${runs}; ${coverage}")
if(NOT rc EQUAL 0)
  message("${err}")
  message(FATAL_ERROR "fuzzing failed (exit ${rc}); the input that broke it is in ${WORK}/ (crash-*); replay it with\n"
                      "  ${HARNESS} <that file>\nand add it to ${SEEDS} as a regression test once fixed")
endif()
