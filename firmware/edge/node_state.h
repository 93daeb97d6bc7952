/* The node's state as every node file reads and counts it (node_state.c): the bottom layer of the
 * node's files (node.h lists them); not part of the node's API. */
#ifndef TVO_NODE_STATE_H
#define TVO_NODE_STATE_H

#include "node.h"

/** A decoded message and when it arrived. */
typedef struct {
    int channel;
    const tvo_lcm_session_t *session;          /* TVO_SESSION, else NULL */
    const tvo_lcm_unicycle_sample_t *unicycle; /* TVO_SAMPLE, else NULL */
    const tvo_lcm_chain_sample_t *chain;       /* TVO_CHAIN_SAMPLE, else NULL */
    const tvo_lcm_target_t *target;            /* TVO_TARGET, else NULL */
    uint64_t content_hash;                     /* a session message's, past its utime */
    int64_t now_us;                            /* clamped to the wire's range */
} tvo_node_input_t;

/** Adds one to a counter that saturates at INT32_MAX (signed overflow would be undefined). */
void tvo_node_count(int32_t *counter);
/** Counts a refusal under its wire status and keeps it as the last one (for the transport's log). */
void tvo_node_count_refusal(tvo_node_t *node, int32_t wire_status);
/** The running slot (the state says whether it runs). */
tvo_node_session_t *tvo_node_running_slot(tvo_node_t *node);

#endif /* TVO_NODE_STATE_H */
