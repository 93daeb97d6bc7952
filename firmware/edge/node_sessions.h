/* The session table (node_sessions.c): not part of the node's API (node.h lists the node's files). */
#ifndef TVO_NODE_SESSIONS_H
#define TVO_NODE_SESSIONS_H

#include "node_state.h"

/** 1 if a session message names this node's boot (node_boot_id of its robot, or of every robot). */
int tvo_node_names_this_boot(const tvo_node_t *node, const tvo_lcm_session_t *msg);
/** The event a session message naming this boot is, given what runs. */
tvo_node_event_t tvo_node_session_event(const tvo_node_t *node, const tvo_lcm_session_t *msg, uint64_t content_hash);
/** A sample's or target's event: of the running session (when idle, of any), or another's. */
tvo_node_event_t tvo_node_stream_event(const tvo_node_t *node, int32_t session_id, tvo_node_event_t own,
                                       tvo_node_event_t other);
/** The one place a message changes the node's state: its action, the table's next state, the ack. */
void tvo_node_dispatch(tvo_node_t *node, tvo_node_event_t event, const tvo_node_input_t *in);

#endif /* TVO_NODE_SESSIONS_H */
