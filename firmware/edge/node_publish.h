/* What the node says (node_publish.c): not part of the node's API (node.h lists the node's files). */
#ifndef TVO_NODE_PUBLISH_H
#define TVO_NODE_PUBLISH_H

#include "node_state.h"

/** The ack of a session message, naming the session that runs after it. */
void tvo_node_publish_ack(tvo_node_t *node, const tvo_lcm_session_t *msg, const tvo_session_reject_t *why);
/**
 * A period's answer: `cmd` to every robot the node drives, stamped `stamp`; then, if the answered
 * sequence is a multiple of the session's telemetry_every, one telemetry per driven robot
 * (predicted: robots the period predicted). Counts the safe stops and speed mismatches it carries.
 */
void tvo_node_publish_answer(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                             const tvo_step_stamp_t *stamp, int32_t predicted);
/** The node's own safe stop (the CLOCK_NODE timer's): to every driven robot, no telemetry. */
void tvo_node_publish_own_stop(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                               const tvo_step_stamp_t *stamp);
/** The node's announcement (node_status_t) at now_us; the next is due a state's period later. */
void tvo_node_announce(tvo_node_t *node, int64_t now_us);

#endif /* TVO_NODE_PUBLISH_H */
