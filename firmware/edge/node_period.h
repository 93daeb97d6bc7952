/* A period of the running session (node_period.c): not part of the node's API (node.h lists the node's
 * files). */
#ifndef TVO_NODE_PERIOD_H
#define TVO_NODE_PERIOD_H

#include "node_state.h"

/** A sample of the running session: gathered, or, the period's last robot's, the period served. */
void tvo_node_serve_sample(tvo_node_t *node, const tvo_node_input_t *in);
/** A streamed target sample of the running session: TVO_OK if taken. */
tvo_status_t tvo_node_take_target(tvo_node_t *node, const tvo_node_input_t *in);
/** The CLOCK_NODE timer at now_us (the core counts missed periods; its stop is published); returns
 *  the running schedule's next deadline. */
int64_t tvo_node_serve_timer(tvo_node_t *node, int64_t now_us);

#endif /* TVO_NODE_PERIOD_H */
