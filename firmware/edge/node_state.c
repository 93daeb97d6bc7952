/*
 * The node's state as every node file reads and counts it (node_state.h): the counters, the running
 * session. It calls no other node file, so the files above it form layers, not a cycle.
 */
#include "node_state.h"

void tvo_node_count(int32_t *counter)
{
    if (*counter < INT32_MAX) {
        ++*counter;
    }
}

void tvo_node_count_refusal(tvo_node_t *node, int32_t wire_status)
{
    const uint32_t slot = (uint32_t)wire_status < (uint32_t)TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS ? (uint32_t)wire_status : 0u;
    tvo_node_count(&node->counters.refused[slot]);
    node->last_refusal = wire_status;
}

tvo_node_session_t *tvo_node_running_slot(tvo_node_t *node)
{
    return &node->slot[node->running];
}

const tvo_node_session_t *tvo_node_session(const tvo_node_t *node)
{
    return (node != NULL && node->state == TVO_NODE_RUNNING) ? &node->slot[node->running] : NULL;
}

const tvo_lcm_node_counters_t *tvo_node_counters(const tvo_node_t *node)
{
    return node != NULL ? &node->counters : NULL;
}

int tvo_node_stop_requested(const tvo_node_t *node)
{
    return node != NULL && node->stop_requested;
}
