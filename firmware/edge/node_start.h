/* A session from a START (node_start.c): not part of the node's API (node.h lists the node's files). */
#ifndef TVO_NODE_START_H
#define TVO_NODE_START_H

#include "node.h"

/** Builds a session from a START into `s` (the spare slot; the running one is not touched). */
tvo_status_t tvo_node_build_session(tvo_node_session_t *s, const tvo_lcm_session_t *msg, uint64_t content_hash,
                                    int64_t now_us, tvo_session_reject_t *why);

#endif /* TVO_NODE_START_H */
