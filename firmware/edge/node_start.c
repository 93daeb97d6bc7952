/*
 * A session from a START, built whole in a spare slot before anything changes (lcm_types/README.md
 * "Sessions"): the wire's checks (session_codec.c), the problem, the schedule of its clock mode and
 * the plant's controller; the running session is not touched, so a refused START cannot disturb it.
 */
#include "node_start.h"

#include <string.h>

/* Nothing gathered yet: no robot heard, no joint command computed (the robots at rest). */
static void gathering_start(tvo_node_gathering_t *g)
{
    memset(g, 0, sizeof(*g));
    g->last_step = -1;
    for (int r = 0; r < TVO_MAX_ROBOTS; ++r) {
        g->known[r].sequence = -1;
        g->heard[r] = -1;
    }
    g->commands[0].sequence = -1;
    g->commands[1].sequence = -1;
}

tvo_status_t tvo_node_build_session(tvo_node_session_t *s, const tvo_lcm_session_t *msg, uint64_t content_hash,
                                    int64_t now_us, tvo_session_reject_t *why)
{
    memset(s, 0, sizeof(*s));
    tvo_session_timing_t timing;
    tvo_status_t st = tvo_session_decode_timing(msg, &timing, why);
    if (st != TVO_OK) {
        return st;
    }
    const tvo_edge_controller_ops_t *ops = tvo_edge_controller_ops(timing.plant_kind);
    const tvo_schedule_ops_t *clock = tvo_schedule_ops(timing.clock_source);
    if (ops == NULL || clock == NULL) {
        why->status = TVO_ERR_PARAM;
        why->param = (ops == NULL) ? TVO_SESSION_PARAM_PLANT_KIND : TVO_SESSION_PARAM_CLOCK_SOURCE;
        return TVO_ERR_PARAM;
    }
    tvo_problem_desc_t desc;
    st = tvo_session_decode_problem(msg, &desc, why);
    if (st == TVO_OK) {
        tvo_problem_culprit_t culprit;
        st = tvo_problem_init(&s->problem, &desc, ops->relative_degree(msg), &culprit);
        if (st != TVO_OK) { /* the core names the entry it refused */
            why->status = st;
            why->param = TVO_SESSION_PARAM_OBJECTIVE;
            why->part = tvo_session_part_from_problem(culprit.part);
            why->index = culprit.index;
        }
    }
    if (st != TVO_OK) {
        return st;
    }
    tvo_schedule_start(&s->schedule, clock, &timing, msg, now_us);
    s->controller.ops = ops;
    const uint32_t epoch_tick = tvo_schedule_tick(&s->schedule, s->schedule.anchor.epoch_schedule_us);
    st = ops->init(&s->controller, msg, &s->problem.objective, epoch_tick, why);
    if (st != TVO_OK) {
        return st;
    }
    gathering_start(&s->gathering);
    s->session_id = msg->session_id;
    s->content_hash = content_hash;
    return TVO_OK;
}
