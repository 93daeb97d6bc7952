# The node's sources (transport-independent: sessions, schedule, codecs, protocol names), listed once
# for every program that runs the node: tvo_firmware_node on the host, the PIL program on the board.
set(tvo_edge_dir ${CMAKE_CURRENT_LIST_DIR})
set(tvo_edge_node_sources
  ${tvo_edge_dir}/node.c
  ${tvo_edge_dir}/node_sessions.c
  ${tvo_edge_dir}/node_start.c
  ${tvo_edge_dir}/node_period.c
  ${tvo_edge_dir}/node_publish.c
  ${tvo_edge_dir}/node_state.c
  ${tvo_edge_dir}/schedule.c
  ${tvo_edge_dir}/schedule_plant_clock.c
  ${tvo_edge_dir}/schedule_node_clock.c
  ${tvo_edge_dir}/session_codec.c
  ${tvo_edge_dir}/step_codec.c
  ${tvo_edge_dir}/edge_controller.c
  ${tvo_edge_dir}/channels.c
  ${tvo_edge_dir}/wire_status.c)
# The authenticated link in front of the node (auth_link.c; link tvo_auth, which brings Mbed TLS).
set(tvo_edge_auth_link_sources ${tvo_edge_dir}/auth_link.c)
# The node's sources see the core's public API only (tvo_core does not export firmware/src).
