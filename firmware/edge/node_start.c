/*
 * A session from a START, built whole in a spare slot before anything changes (lcm_types/README.md
 * "Sessions"): the wire's checks (session_codec.c), the problem, the schedule of its clock mode and
 * the plant's controller; the running session is not touched, so a refused START cannot disturb it.
 */
#include "node_private.h"

#include <string.h>

#include "internal/constraints.h"

/* A refused problem's culprit entry, where tvo_problem_init names only the part: the first robot whose
 * tracking weight, or the first obstacle that (with those before it) the core's own term init refuses;
 * -1 if none alone is to blame. A refusal's cold path. */
static int32_t problem_culprit(const tvo_problem_desc_t *desc, const tvo_barrier_t *barrier, int32_t part)
{
    if (part == TVO_LCM_SESSION_ACK_T_PART_ROBOTS) {
        for (uint8_t r = 0; r < desc->robot_count && r < TVO_MAX_ROBOTS; ++r) {
            tvo_tracking_term_t term;
            if (tvo_tracking_init(&term, &desc->target[r], desc->tracking_weight[r], (uint8_t)(2u * r)) != TVO_OK) {
                return (int32_t)r;
            }
        }
    } else if (part == TVO_LCM_SESSION_ACK_T_PART_OBSTACLES) {
        for (uint8_t count = 1u; count <= desc->obstacle_count && count <= TVO_MAX_OBSTACLES; ++count) {
            tvo_free_space_term_t term;
            if (tvo_free_space_term_init(&term, barrier, 0u, desc->robot_radius_m, desc->obstacle, count) != TVO_OK) {
                return (int32_t)count - 1; /* a bad disk, or the later of an overlapping pair */
            }
        }
    }
    return -1;
}

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
        uint8_t problem_part = 0;
        st = tvo_problem_init(&s->problem, &desc, ops->relative_degree(msg), &problem_part);
        if (st != TVO_OK) {
            why->status = st;
            why->param = TVO_SESSION_PARAM_OBJECTIVE;
            why->part = tvo_session_part_from_problem(problem_part);
            why->index = problem_culprit(&desc, &s->problem.barrier, why->part);
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
