# The complete example of host/README.md's "Your own scenario" is a valid scenario file: its first yaml
# block is written to OUT_DIR/my.yaml and `tvo_sim --scenario my.yaml --dry-run` must accept it,
# two robots and its 16 s (cmake -P script).
#
#   -DSIM=<tvo_sim> -DREADME=<host/README.md> -DOUT_DIR=<dir>
file(READ ${README} text)
string(FIND "${text}" "### Your own scenario" at)
if(at EQUAL -1)
  message(FATAL_ERROR "README.md has no section 'Your own scenario'")
endif()
string(SUBSTRING "${text}" ${at} -1 text)
string(FIND "${text}" "```yaml\n" begin)
if(begin EQUAL -1)
  message(FATAL_ERROR "README.md's 'Your own scenario' has no yaml block")
endif()
math(EXPR begin "${begin} + 8")
string(SUBSTRING "${text}" ${begin} -1 text)
string(FIND "${text}" "```" end)
string(SUBSTRING "${text}" 0 ${end} example)
file(MAKE_DIRECTORY ${OUT_DIR})
file(WRITE ${OUT_DIR}/my.yaml "${example}")
execute_process(COMMAND ${SIM} --scenario ${OUT_DIR}/my.yaml --dry-run --lcm-url memq:// --out-dir ${OUT_DIR}/out
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "exit code: ${rc}\n${out}${err}")
if(NOT rc STREQUAL "0" OR NOT out MATCHES "2 robot\\(s\\), lockstep, h = 10000 us, 1600 periods")
  message(FATAL_ERROR "README.md's example scenario was not accepted as written")
endif()
