/*
 * A period of the running session (lcm_types/README.md "Timing", "Sessions"): samples arrive one robot
 * at a time and are kept per robot; the period's last robot's sample (robot robot_count - 1: a plant
 * sends a period's samples in robot order) steps it, with every robot's sample of that sequence, a
 * robot without one predicted (CLOCK_PLANT) along the exact unicycle arc of the joint commands this
 * node computed. Every node of a fleet and a node that drives every robot step on the same sample
 * with the same rows, so, without loss, they compute the same joint command bit for bit.
 *
 * The period's step is the core's transaction; the node vets only its schedule and the wire, and
 * keeps what the period gathered (the robots' states, the joint command the next prediction follows)
 * only when the core committed the period, as its outcome says: a refused period keeps nothing.
 */
#include "node_period.h"

#include "node_publish.h"

#include <math.h>
#include <string.h>

/* The longest prediction, in periods, whatever the session's watchdog (bounds the loop). */
#define NODE_MAX_PREDICT_PERIODS 1000
/* Below this turn rate (rad/s) an arc is integrated as a straight line (its limit). */
#define NODE_STRAIGHT_RADPS 1e-9

/* ---- gathering ---------------------------------------------------------------------------------- */

/* Another robot's sample: kept for its period (the newest; a stray more than a period ahead of it gives
 * way, so it cannot hold back the genuine stream), or, late for a period already stepped, taken as that
 * robot's state there if it was predicted (the next prediction starts from it). */
static void gather(tvo_node_gathering_t *g, const tvo_lcm_unicycle_sample_t *sample)
{
    const int32_t r = sample->header.robot;
    const int64_t sequence = sample->header.sequence;
    if (sequence > g->last_step) {
        const int64_t pending = g->pending[r].header.sequence;
        if (!g->has_pending[r] || sequence > pending || pending > sequence + 1) {
            g->pending[r] = *sample;
            g->has_pending[r] = 1u;
        }
        return;
    }
    if (sequence == g->known[r].sequence && !g->known_measured[r]) {
        tvo_step_state_of(sample, &g->known[r]);
        g->known_measured[r] = 1u;
        g->heard[r] = sequence > g->heard[r] ? sequence : g->heard[r];
    }
}

/* The joint command in force during the period after sample `sequence` (zero-order hold); NULL: at rest. */
static const tvo_node_joint_command_t *in_force(const tvo_node_gathering_t *g, int64_t sequence)
{
    for (int k = 0; k < 2; ++k) {
        if (g->commands[k].sequence >= 0 && g->commands[k].sequence <= sequence) {
            return &g->commands[k];
        }
    }
    /* Older than both kept: the oldest kept is the nearest (only after a long silence of the trigger). */
    return g->commands[1].sequence >= 0 ? &g->commands[1] : g->commands[0].sequence >= 0 ? &g->commands[0] : NULL;
}

/* Exact unicycle arc over dt_s under (v, omega) held. */
static void arc(tvo_step_robot_state_t *robot, double speed_mps, double turn_radps, double dt_s)
{
    const double theta = robot->heading_rad;
    if (fabs(turn_radps) < NODE_STRAIGHT_RADPS) {
        robot->position_m[0] += speed_mps * cos(theta) * dt_s;
        robot->position_m[1] += speed_mps * sin(theta) * dt_s;
    } else {
        const double next = theta + turn_radps * dt_s;
        robot->position_m[0] += speed_mps / turn_radps * (sin(next) - sin(theta));
        robot->position_m[1] += speed_mps / turn_radps * (cos(theta) - cos(next));
        robot->heading_rad = next;
    }
    robot->speed_mps = speed_mps;
}

/* Robot r from its sample m to m + 1: sample m is taken tau before the apply instant of the command
 * answering m, so the command answering m - 1 holds for tau, then the one answering m for h - tau. */
static void predict_period(const tvo_node_gathering_t *g, int r, tvo_step_robot_state_t *robot, double period_s,
                           double delay_s)
{
    const tvo_node_joint_command_t *before = in_force(g, robot->sequence - 1);
    const tvo_node_joint_command_t *after = in_force(g, robot->sequence);
    arc(robot, before != NULL ? before->speed_mps[r] : 0.0, before != NULL ? before->turn_rate_radps[r] : 0.0, delay_s);
    arc(robot, after != NULL ? after->speed_mps[r] : 0.0, after != NULL ? after->turn_rate_radps[r] : 0.0,
        period_s - delay_s);
    robot->sequence += 1;
}

/*
 * The rows of period n (the trigger's sequence) into the node's work: each robot's sample of n, or its
 * state predicted to n from the newest it has (CLOCK_PLANT, its newest sample at most watchdog_periods
 * periods old); work->unheard when a robot has neither. Reads the session, changes nothing of it.
 */
static void gather_rows(const tvo_node_session_t *s, const tvo_lcm_unicycle_sample_t *trigger, tvo_node_period_work_t *work)
{
    const tvo_node_gathering_t *g = &s->gathering;
    const tvo_session_timing_t *timing = &s->schedule.timing;
    const int64_t n = trigger->header.sequence;
    const int predicts = timing->clock_source == TVO_LCM_SESSION_T_CLOCK_PLANT;
    const int64_t span = timing->watchdog_periods < NODE_MAX_PREDICT_PERIODS ? (int64_t)timing->watchdog_periods
                                                                             : NODE_MAX_PREDICT_PERIODS;
    const double period_s = (double)timing->period_us * 1e-6;
    const double delay_s = (double)timing->delay_us * 1e-6;
    work->predicted = 0;
    work->unheard = 0;
    for (uint8_t r = 0; r < timing->robot_count; ++r) {
        tvo_step_robot_state_t *next = &work->next[r];
        work->rows.sample[r] = NULL;
        work->measured[r] = 0u;
        work->heard[r] = g->heard[r];
        if (r + 1u == timing->robot_count) {
            work->rows.sample[r] = trigger;
            tvo_step_state_of(trigger, next);
            work->measured[r] = 1u;
            work->heard[r] = n;
            continue;
        }
        *next = g->known[r];
        if (g->has_pending[r]) {
            const tvo_lcm_unicycle_sample_t *p = &g->pending[r];
            if (p->header.sequence == n) {
                work->rows.sample[r] = p;
                tvo_step_state_of(p, next);
                work->measured[r] = 1u;
                work->heard[r] = n;
                continue;
            }
            if (p->header.sequence < n && p->header.sequence > next->sequence) {
                tvo_step_state_of(p, next); /* an earlier period's sample (its step was missed) is still news */
                work->heard[r] = p->header.sequence;
            }
        }
        const int64_t heard = work->heard[r];
        if (!predicts || heard < 0 || next->sequence < 0 || next->sequence > n || n - heard > span) {
            work->unheard = 1; /* never heard, heard too long ago, or no prediction on the node's clock */
            return;
        }
        work->predicted += 1;
        while (next->sequence < n) {
            predict_period(g, (int)r, next, period_s, delay_s);
        }
        work->rows.predicted[r] = *next;
    }
}

/* A committed period: the rows become the robots' known states, the joint command the one the next
 * prediction follows, and the samples it used (or passed) are done with. */
static void gathering_commit(tvo_node_session_t *s, const tvo_node_period_work_t *work, const tvo_edge_command_t *cmd,
                             int64_t n)
{
    tvo_node_gathering_t *g = &s->gathering;
    const uint8_t robots = s->schedule.timing.robot_count;
    for (uint8_t r = 0; r < robots; ++r) {
        g->known[r] = work->next[r];
        g->known_measured[r] = work->measured[r];
        g->heard[r] = work->heard[r];
        if (g->has_pending[r] && g->pending[r].header.sequence <= n) {
            g->has_pending[r] = 0u;
        }
    }
    g->commands[1] = g->commands[0];
    memset(&g->commands[0], 0, sizeof(g->commands[0]));
    s->controller.ops->rows(cmd, robots, g->commands[0].speed_mps, g->commands[0].turn_rate_radps);
    g->commands[0].sequence = n;
    g->last_step = n;
}

/* ---- the period's step -------------------------------------------------------------------------- */

/* The core's answer, as its returned status and command say it. */
typedef struct {
    tvo_edge_mark_t mark;                      /* the command's flags, outcome and reason */
    int took_sample;                           /* the core committed the period (took its measurement) */
} node_answer_t;

/* The one reading of what the core returned: it took the period's sample if it committed the period
 * (applied, or the speed mismatch's stop, whose measurement it accepted), as the command's outcome says. */
static node_answer_t core_answer(const tvo_node_session_t *s, tvo_status_t error, const tvo_edge_command_t *cmd)
{
    node_answer_t answer;
    answer.mark = s->controller.ops->mark(cmd);
    answer.took_sample = error == TVO_OK && (answer.mark.outcome == TVO_OUTCOME_APPLIED ||
                                             answer.mark.reason == TVO_REASON_SPEED_MISMATCH);
    return answer;
}

/* What one attempt to serve the period on a schedule came to. */
typedef struct {
    tvo_step_why_t why;                        /* the edge's refusal, the core's error, or the command's reason */
    tvo_schedule_placement_t placement;
    uint32_t apply_tick;                       /* the core's tick of placement.apply_us (when stepped) */
    int stepped;                               /* the core stepped: work->command is its answer */
    node_answer_t answer;                      /* the core's (when stepped; else took_sample 0) */
} node_attempt_t;

/* The period passed every check, the core's included, and only its law could not serve it (a target
 * sample not there yet). When the core's answer is its watchdog's stop, its check (which changes
 * nothing) says whether the measurement itself passed. */
static int law_refused(tvo_node_session_t *s, const tvo_node_period_work_t *work, const node_attempt_t *attempt)
{
    const tvo_reason_t r = attempt->why.reason;
    if (!attempt->stepped || attempt->why.error != TVO_OK) {
        return 0;
    }
    if (r == TVO_REASON_TARGET_NOT_READY || r == TVO_REASON_NUMERIC || r == TVO_REASON_NOT_POSITIVE_DEFINITE) {
        return 1;
    }
    tvo_reason_t checked = TVO_REASON_NONE;
    return r == TVO_REASON_WATCHDOG &&
           s->controller.ops->check(&s->controller, &work->measurement, attempt->apply_tick, &checked) == TVO_OK &&
           checked == TVO_REASON_NONE;
}

/* The node's checks of the period judged on `schedule` (the wire's and its schedule's, then whether every
 * robot has a row), then the core's step, a transaction that checks the rest once. */
static void attempt_period(tvo_node_t *node, tvo_node_session_t *s, const tvo_schedule_t *schedule,
                           const tvo_lcm_sample_header_t *header, const tvo_edge_samples_t *samples, int64_t now_us,
                           node_attempt_t *attempt)
{
    tvo_node_period_work_t *work = &node->work;
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    const tvo_step_why_t none = {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE};
    attempt->stepped = 0;
    attempt->why = none;
    memset(&attempt->answer, 0, sizeof(attempt->answer));
    attempt->why.node = tvo_schedule_place(schedule, header, now_us, &attempt->placement);
    if (attempt->why.node == TVO_NODE_OK && work->unheard) {
        attempt->why.node = TVO_NODE_ROBOT_UNHEARD;
    }
    if (attempt->why.node == TVO_NODE_OK) {
        const uint32_t stamp_tick = tvo_schedule_tick(schedule, attempt->placement.stamp_us);
        attempt->why.node = ops->measurement(&s->controller, samples, schedule->timing.robot_count, stamp_tick,
                                             &work->measurement);
    }
    if (attempt->why.node != TVO_NODE_OK) {
        return;
    }
    /* The core's step is a transaction: the barrier's s0 included (its objective's start rule). */
    attempt->apply_tick = tvo_schedule_tick(schedule, attempt->placement.apply_us);
    attempt->why.error = ops->step(&s->controller, &work->measurement, attempt->apply_tick, &work->command);
    attempt->answer = core_answer(s, attempt->why.error, &work->command);
    attempt->why.reason = attempt->answer.mark.reason;
    attempt->stepped = 1;
}

/* The refusal's answer, stamped no earlier than the sample: the core's, whoever refused (the core's
 * step, or the node's checks, which hand the core the refusal): the command in force, or the core's
 * watchdog's stop, which the answer then says. Nothing of the period is kept. */
static void refuse_period(tvo_node_t *node, tvo_node_session_t *s, const tvo_lcm_sample_header_t *header,
                          const node_attempt_t *attempt, int64_t now_us)
{
    tvo_node_period_work_t *work = &node->work;
    tvo_step_stamp_t stamp = {s->schedule.ops->refusal_utime(&s->schedule, header, now_us), s->session_id,
                              header->sequence, attempt->why};
    node_answer_t answer = attempt->answer;
    if (!attempt->stepped) {
        /* an initialised session: TVO_OK */
        answer = core_answer(s, s->controller.ops->refuse(&s->controller, &work->command), &work->command);
    }
    if (answer.mark.outcome == TVO_OUTCOME_STOPPED) {
        const tvo_step_why_t stopped = {TVO_NODE_OK, TVO_OK, answer.mark.reason};
        stamp.why = stopped;
    }
    /* Counted under the status its answer carries (node_counters_t.refused); last_refusal keeps why,
     * which a stop does not say. */
    tvo_node_count_refusal(node, tvo_step_wire_status(&stamp.why));
    node->last_refusal = tvo_step_wire_status(&attempt->why);
    tvo_node_publish_answer(node, s, &work->command, &stamp, work->unheard ? 0 : work->predicted);
}

/*
 * One answer per period. It is judged on the schedule's anchor in force; if refused, its vote may
 * carry a re-anchor (schedule.h: refused samples that agree), and it is judged again on the moved
 * anchor, computed in a copy of the schedule. The move is committed, by one assignment, only if the
 * period then passes every check, the core's included (its law may still refuse it): nothing of a
 * failed trial is undone, because nothing of it was kept.
 */
static void serve_period(tvo_node_t *node, tvo_node_session_t *s, const tvo_node_input_t *in)
{
    tvo_node_period_work_t *work = &node->work;
    const tvo_lcm_sample_header_t *header = (in->unicycle != NULL) ? &in->unicycle->header : &in->chain->header;
    const tvo_edge_samples_t samples = {&work->rows, in->chain};
    work->predicted = 0;
    work->unheard = 0;
    if (in->unicycle != NULL) {
        gather_rows(s, in->unicycle, work);
    }
    node_attempt_t attempt;
    attempt_period(node, s, &s->schedule, header, &samples, in->now_us, &attempt);
    if (!attempt.answer.took_sample) {
        tvo_schedule_t moved = s->schedule;
        if (s->schedule.ops->vote(&s->schedule, header, &attempt.why, in->now_us, &moved.anchor)) {
            attempt_period(node, s, &moved, header, &samples, in->now_us, &attempt);
            if (attempt.answer.took_sample || law_refused(s, work, &attempt)) {
                s->schedule.anchor = moved.anchor;
            }
        }
    }
    if (!attempt.answer.took_sample) {
        refuse_period(node, s, header, &attempt, in->now_us);
        return;
    }
    tvo_node_count(&node->counters.accepted);
    for (int32_t k = 0; k < work->predicted; ++k) {
        tvo_node_count(&node->counters.predicted);
    }
    tvo_schedule_accept(&s->schedule, &attempt.placement, header->sequence);
    gathering_commit(s, work, &work->command, header->sequence);
    const tvo_step_stamp_t stamp = {attempt.placement.apply_us - s->schedule.anchor.offset_us, s->session_id,
                                    header->sequence, attempt.why};
    tvo_node_publish_answer(node, s, &work->command, &stamp, work->predicted);
}

/* A sample's own checks on arrival, for one that does not step the period: its plant, its robot, its
 * times, its values. (The period's last robot's is judged by the schedule and the core, in that order.) */
static tvo_node_status_t check_on_arrival(const tvo_node_session_t *s, const tvo_node_input_t *in)
{
    const tvo_lcm_sample_header_t *header = (in->unicycle != NULL) ? &in->unicycle->header : &in->chain->header;
    if (in->channel != s->controller.ops->sample_channel) {
        return TVO_NODE_WRONG_PLANT;
    }
    if (header->robot < 0 || header->robot >= (int32_t)s->schedule.timing.robot_count) {
        return TVO_NODE_WRONG_ROBOT;
    }
    if (header->sequence < 0) {
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* unanswered: an answer echoing it would read as the node's own stop (-1) */
    }
    if (header->robot + 1 == (int32_t)s->schedule.timing.robot_count) {
        return TVO_NODE_OK; /* the period's last robot: it steps the period */
    }
    if (!tvo_schedule_wire_time_ok(header->utime)) {
        return TVO_NODE_IMPLAUSIBLE_STAMP;
    }
    return tvo_step_unicycle_sample_finite(in->unicycle) ? TVO_NODE_OK : TVO_NODE_NOT_FINITE;
}

void tvo_node_serve_sample(tvo_node_t *node, const tvo_node_input_t *in)
{
    tvo_node_session_t *s = tvo_node_running_slot(node);
    const tvo_node_status_t check = check_on_arrival(s, in);
    if (check != TVO_NODE_OK) {
        const tvo_step_why_t why = {check, TVO_OK, TVO_REASON_NONE};
        tvo_node_count_refusal(node, tvo_step_wire_status(&why)); /* refused, not answered on its own */
        return;
    }
    const tvo_lcm_sample_header_t *header = (in->unicycle != NULL) ? &in->unicycle->header : &in->chain->header;
    if (header->robot + 1 < (int32_t)s->schedule.timing.robot_count) {
        gather(&s->gathering, in->unicycle); /* another robot's: a unicycle's (a chain has one robot) */
        return;
    }
    serve_period(node, s, in);
}

/* ---- streamed targets --------------------------------------------------------------------------- */

/* A sample is taken if newer than the last of its robot and stamped no later than the clock mode allows
 * (one stray from beyond the next period would hold back every genuine one after it: it costs a period
 * or two). */
tvo_status_t tvo_node_take_target(tvo_node_t *node, const tvo_node_input_t *in)
{
    tvo_node_session_t *s = tvo_node_running_slot(node);
    const tvo_schedule_t *schedule = &s->schedule;
    const tvo_lcm_target_t *msg = in->target;
    tvo_step_why_t answer = {tvo_schedule_wire_time_ok(msg->header.utime) ? TVO_NODE_OK : TVO_NODE_IMPLAUSIBLE_STAMP,
                             TVO_OK, TVO_REASON_NONE};
    const int64_t stamp_us = (answer.node == TVO_NODE_OK) ? msg->header.utime + schedule->anchor.offset_us : 0;
    if (answer.node == TVO_NODE_OK && stamp_us > schedule->ops->latest_target_us(schedule, in->now_us)) {
        answer.node = TVO_NODE_IMPLAUSIBLE_STAMP;
    }
    /* The objective's time of the sample, in ticks (us) since the epoch, from 64-bit times: a
     * uint32 tick would alias a sample 2^32 us old with one from the future. */
    const int64_t since_epoch_us = (answer.node == TVO_NODE_OK) ? stamp_us - schedule->anchor.epoch_schedule_us : 0;
    if (answer.node == TVO_NODE_OK && since_epoch_us < -schedule->timing.period_us) {
        answer.error = TVO_ERR_BEFORE_EPOCH; /* more than a period before the epoch */
    }
    if (answer.node == TVO_NODE_OK && answer.error == TVO_OK) {
        /* A sample from the period before the epoch (a plant samples its target with its first sample,
         * at epoch - tau) is carried forward to the epoch: the objective's time starts there. */
        const int64_t carry_us = since_epoch_us < 0 ? -since_epoch_us : 0;
        answer.error = tvo_step_target_from_lcm_carried(msg, schedule->timing.robot_count,
                                                        (uint64_t)(since_epoch_us + carry_us), (double)carry_us * 1e-6,
                                                        &s->problem);
    }
    node->last_target_status = tvo_step_wire_status(&answer);
    if (node->last_target_status != TVO_LCM_COMMAND_HEADER_T_STATUS_OK) {
        tvo_node_count(&node->counters.targets_refused);
        return TVO_ERR_PARAM; /* not taken */
    }
    return TVO_OK;
}

/* ---- the CLOCK_NODE timer ----------------------------------------------------------------------- */

int64_t tvo_node_serve_timer(tvo_node_t *node, int64_t now_us)
{
    tvo_node_session_t *s = tvo_node_running_slot(node);
    tvo_schedule_t *schedule = &s->schedule;
    int64_t period = 0;
    if (schedule->ops->take_missed(schedule, now_us, &period)) {
        /* The core counts the missed periods and its watchdog decides; its stop is published, stamped
         * now, every period until a sample is served. */
        tvo_edge_command_t *cmd = &node->work.command;
        const uint32_t apply_tick = tvo_schedule_tick(schedule, tvo_schedule_apply_us(schedule, period));
        tvo_step_why_t why = {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE};
        why.error = s->controller.ops->miss(&s->controller, apply_tick, cmd);
        const node_answer_t answer = core_answer(s, why.error, cmd);
        why.reason = answer.mark.reason;
        if (answer.mark.outcome == TVO_OUTCOME_STOPPED) {
            const tvo_step_stamp_t stamp = {tvo_schedule_plant_utime(schedule, now_us), s->session_id, -1, why};
            tvo_node_publish_own_stop(node, s, cmd, &stamp);
        }
    }
    return schedule->ops->next_deadline(schedule);
}
