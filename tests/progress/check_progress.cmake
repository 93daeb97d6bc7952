# Runs COMMAND twice (cmake -P script): output to a pipe, then under `script` (a pseudo-terminal).
#   -DSCRIPT=<util-linux script> -DCOMMAND=<|-list: program and arguments>
#   -DPROGRESS=<regex of the progress line's text> -DOUTPUT=<regex the program's own output matches>
# Piped: exit 0, OUTPUT present, neither PROGRESS nor the line-erase code ESC[K. On the terminal:
# exit 0, OUTPUT, PROGRESS and ESC[K all present. CI and TVO_PROGRESS are unset for both runs (they
# turn the line off), and TERM is set, so both runs differ only in being on a terminal.
foreach(var SCRIPT COMMAND PROGRESS OUTPUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_progress: -D${var}=... is required")
  endif()
endforeach()
string(REPLACE "|" ";" command "${COMMAND}")
string(ASCII 27 esc)
set(erase "${esc}\\[K")
set(env ${CMAKE_COMMAND} -E env --unset=CI --unset=TVO_PROGRESS TERM=xterm)

function(fail_with why out)
  string(REPLACE "${esc}" "<ESC>" shown "${out}")
  message(FATAL_ERROR "${why}\n--- output\n${shown}\n---")
endfunction()

execute_process(COMMAND ${env} ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(piped "${out}${err}")
if(NOT rc STREQUAL "0")
  fail_with("piped run: exit code ${rc}" "${piped}")
endif()
if(NOT piped MATCHES "${OUTPUT}")
  fail_with("piped run: its own output ('${OUTPUT}') is missing" "${piped}")
endif()
if(piped MATCHES "${erase}" OR piped MATCHES "${PROGRESS}")
  fail_with("piped run: a progress line appeared on a pipe" "${piped}")
endif()

# script -e: exit with the command's code; -c takes one shell command line.
string(REPLACE ";" " " command_line "${command}")
execute_process(COMMAND ${env} ${SCRIPT} -qec "${command_line}" /dev/null
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(tty "${out}${err}")
if(NOT rc STREQUAL "0")
  fail_with("terminal run: exit code ${rc}" "${tty}")
endif()
if(NOT tty MATCHES "${OUTPUT}")
  fail_with("terminal run: its own output ('${OUTPUT}') is missing" "${tty}")
endif()
if(NOT tty MATCHES "${erase}" OR NOT tty MATCHES "${PROGRESS}")
  fail_with("terminal run: no progress line ('${PROGRESS}' after ESC[K)" "${tty}")
endif()
message(STATUS "progress: none on a pipe, shown on a terminal")
