# The UDP ports of every test that talks LCM, handed out here and nowhere else. Each test takes its own
# (the URLs are ttl=0: nothing leaves the host), so `ctest -j` runs them side by side; and each build
# tree takes its own block, so two trees testing at once (a fresh clone beside a working tree) do not
# hear each other: Linux delivers a multicast datagram to every socket bound to its port, whatever
# group the socket joined.
set(TVO_TEST_LCM_PORT_BLOCK 200)
set(TVO_TEST_LCM_PORT_BASE "" CACHE STRING
  "First UDP port of this tree's LCM tests (empty: a block in 10000..49999 chosen by the build folder's path)")
if(TVO_TEST_LCM_PORT_BASE STREQUAL "")
  string(MD5 tvo_tree_hash "${CMAKE_BINARY_DIR}")
  string(SUBSTRING "${tvo_tree_hash}" 0 6 tvo_tree_hash)
  math(EXPR tvo_lcm_port_base "10000 + (0x${tvo_tree_hash} % 200) * ${TVO_TEST_LCM_PORT_BLOCK}")
elseif(TVO_TEST_LCM_PORT_BASE MATCHES "^[0-9]+$" AND TVO_TEST_LCM_PORT_BASE GREATER_EQUAL 1024
       AND TVO_TEST_LCM_PORT_BASE LESS_EQUAL 65000)
  set(tvo_lcm_port_base ${TVO_TEST_LCM_PORT_BASE})
else()
  message(FATAL_ERROR "TVO_TEST_LCM_PORT_BASE must be empty or a port number in 1024 .. 65000, got '${TVO_TEST_LCM_PORT_BASE}'")
endif()
set_property(GLOBAL PROPERTY TVO_TEST_LCM_PORT_FIRST ${tvo_lcm_port_base})
set_property(GLOBAL PROPERTY TVO_TEST_LCM_PORT_NEXT ${tvo_lcm_port_base})
message(STATUS "LCM tests: UDP ports ${tvo_lcm_port_base} on (TVO_TEST_LCM_PORT_BASE)")

# tvo_test_lcm_port(<var> [COUNT n]): the first of n (default 1) consecutive ports no other test has.
function(tvo_test_lcm_port var)
  cmake_parse_arguments(P "" "COUNT" "" ${ARGN})
  if(NOT P_COUNT)
    set(P_COUNT 1)
  endif()
  get_property(first GLOBAL PROPERTY TVO_TEST_LCM_PORT_FIRST)
  get_property(port GLOBAL PROPERTY TVO_TEST_LCM_PORT_NEXT)
  math(EXPR next "${port} + ${P_COUNT}")
  math(EXPR end "${first} + ${TVO_TEST_LCM_PORT_BLOCK}")
  if(next GREATER end)
    message(FATAL_ERROR "the LCM tests need more than ${TVO_TEST_LCM_PORT_BLOCK} ports: widen TVO_TEST_LCM_PORT_BLOCK")
  endif()
  set_property(GLOBAL PROPERTY TVO_TEST_LCM_PORT_NEXT ${next})
  set(${var} ${port} PARENT_SCOPE)
endfunction()

# tvo_test_lcm_url(<var>): an LCM URL on a port of its own, on loopback only.
function(tvo_test_lcm_url var)
  tvo_test_lcm_port(port)
  set(${var} "udpm://239.255.76.67:${port}?ttl=0" PARENT_SCOPE)
endfunction()
