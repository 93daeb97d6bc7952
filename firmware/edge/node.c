/* The firmware node's transport-independent logic; see node.h and README.md ("Sessions", "Timing"). */
#include "node.h"

#include <string.h>

#include "tvo/sample_clock.h"

_Static_assert(TVO_STATUS_COUNT <= TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS, "node_counters_t.refused has a slot per status");

/* CLOCK_NODE: a stamp may lead the node's clock by at most half a period (clock offset, jitter). */
#define NODE_FUTURE_TOLERANCE_DIVISOR 2
/* CLOCK_NODE, before the first accepted measurement: this many refused measurements in a row that
 * agree (within a quarter period) on the plant's clock re-anchor the offset the START gave. */
#define NODE_ANCHOR_VOTES 3u
/* CLOCK_PLANT: the first sample must be stamped within this long after the later of the START and
 * the epoch (or within watchdog_periods periods, if longer). */
#define NODE_FIRST_SAMPLE_WINDOW_US 1000000
#define NODE_ANCHOR_AGREEMENT_DIVISOR 4

int tvo_node_check_buffer(void)
{
    tvo_lcm_command_t command;
    tvo_lcm_telemetry_t telemetry;
    tvo_lcm_session_ack_t ack;
    memset(&command, 0, sizeof(command));
    memset(&telemetry, 0, sizeof(telemetry));
    memset(&ack, 0, sizeof(ack));
    const int fits = tvo_lcm_command_t_encoded_size(&command) <= TVO_NODE_BUFFER_BYTES &&
                     tvo_lcm_telemetry_t_encoded_size(&telemetry) <= TVO_NODE_BUFFER_BYTES &&
                     tvo_lcm_session_ack_t_encoded_size(&ack) <= TVO_NODE_BUFFER_BYTES;
    return fits ? 0 : -1;
}

void tvo_node_init(tvo_node_t *node, tvo_node_publish_fn publish, void *publish_context)
{
    if (node == NULL) {
        return;
    }
    memset(node, 0, sizeof(*node));
    node->publish = publish;
    node->publish_context = publish_context;
}

const tvo_node_session_t *tvo_node_session(const tvo_node_t *node)
{
    return (node != NULL && node->has_session) ? &node->slot[node->running] : NULL;
}

static tvo_node_session_t *running_session(tvo_node_t *node)
{
    return node->has_session ? &node->slot[node->running] : NULL;
}

/* Counters saturate: a long run never overflows one (signed overflow would be undefined). */
static void count(int32_t *counter)
{
    if (*counter < INT32_MAX) {
        ++*counter;
    }
}

static int64_t clamp_time(int64_t t)
{
    return t < 0 ? 0 : (t > TVO_WIRE_TIME_MAX_US ? TVO_WIRE_TIME_MAX_US : t);
}

static int wire_time_ok(int64_t t)
{
    return t >= 0 && t <= TVO_WIRE_TIME_MAX_US;
}

/* The core's uint32 tick of a schedule time (wrapping, like the board's free-running counter). */
static uint32_t schedule_tick(int64_t t_us)
{
    return (uint32_t)(uint64_t)t_us;
}

static void publish_encoded(tvo_node_t *node, int channel, int length)
{
    if (length > 0 && node->publish != NULL) {
        node->publish(node->publish_context, channel, node->buffer, (uint32_t)length);
    }
}

static void publish_ack(tvo_node_t *node, const tvo_lcm_session_t *msg, const tvo_session_reject_t *why)
{
    const tvo_node_session_t *s = tvo_node_session(node);
    tvo_session_ack(msg, why, s != NULL ? s->session_id : -1, &node->last_ack);
    node->acks++;
    publish_encoded(node, TVO_NODE_CH_SESSION_ACK,
                    tvo_lcm_session_ack_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &node->last_ack));
}

/* A command and the telemetry that follows it. */
static void publish_step(tvo_node_t *node, tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                         const tvo_step_stamp_t *stamp, int64_t now_us)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    const uint32_t flags = ops->flags(cmd);
    if ((flags & TVO_FLAG_SAFE_STOP) != 0u) {
        count(&node->counters.safe_stops);
    }
    if ((flags & TVO_FLAG_SPEED_MISMATCH) != 0u) {
        count(&node->counters.speed_mismatch);
    }
    tvo_lcm_command_t out;
    ops->command_to_lcm(cmd, stamp, &out);
    publish_encoded(node, TVO_NODE_CH_COMMAND, tvo_lcm_command_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &out));
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    ops->telemetry_to_lcm(&s->controller, &s->problem, &tel);
    tvo_step_telemetry_stamp(stamp, flags, &tel);
    tel.node_time_us = (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE) ? now_us : 0;
    tel.counters = node->counters;
    publish_encoded(node, TVO_NODE_CH_TELEMETRY,
                    tvo_lcm_telemetry_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &tel));
}

/* ---- sessions ---------------------------------------------------------------------------------- */

/* Builds a session from a START into `s` (the spare slot); the running one is not touched. */
static tvo_status_t build_session(tvo_node_session_t *s, const tvo_lcm_session_t *msg, uint64_t content_hash,
                                  int64_t now_us, tvo_session_reject_t *why)
{
    memset(s, 0, sizeof(*s));
    tvo_status_t st = tvo_session_decode_timing(msg, &s->timing, why);
    if (st != TVO_OK) {
        return st;
    }
    const tvo_edge_controller_ops_t *ops = tvo_edge_controller_ops(s->timing.plant_kind);
    if (ops == NULL) {
        why->status = TVO_ERR_PARAM;
        why->param = TVO_PARAM_PLANT_KIND;
        return TVO_ERR_PARAM;
    }
    tvo_problem_desc_t desc;
    st = tvo_session_decode_problem(msg, &desc, why);
    if (st == TVO_OK) {
        uint8_t problem_part = 0;
        st = tvo_problem_init(&s->problem, &desc, ops->relative_degree(msg), &problem_part);
        if (st != TVO_OK) {
            why->status = st;
            why->param = TVO_PARAM_OBJECTIVE;
            why->part = tvo_session_part_from_problem(problem_part);
            why->index = -1;
        }
    }
    if (st != TVO_OK) {
        return st;
    }
    /* CLOCK_NODE: the plant's clock maps onto the node's through this START's arrival (its transit
     * counts as age). Both times are within the wire range, so nothing here can overflow. */
    s->offset_us = (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE) ? now_us - msg->utime : 0;
    s->epoch_schedule_us = s->timing.epoch_utime + s->offset_us;
    s->controller.ops = ops;
    st = ops->init(&s->controller, msg, &s->problem.objective, schedule_tick(s->epoch_schedule_us), why);
    if (st != TVO_OK) {
        return st;
    }
    s->session_id = msg->session_id;
    s->content_hash = content_hash;
    s->start_utime = msg->utime;
    return TVO_OK;
}

static void on_start(tvo_node_t *node, const tvo_lcm_session_t *msg, uint64_t content_hash, int64_t now_us)
{
    tvo_session_reject_t why = {TVO_OK, TVO_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    const tvo_node_session_t *running = tvo_node_session(node);
    if (running != NULL && msg->session_id == running->session_id) {
        /* The plant repeats START until acked: the same content is answered again, not restarted. */
        tvo_session_timing_t timing;
        tvo_session_reject_t repeat_why = why;
        if (content_hash != running->content_hash) {
            why.status = TVO_ERR_SESSION_CONFLICT;
        } else if (running->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_PLANT && !running->has_accepted &&
                   msg->utime > running->start_utime &&
                   tvo_session_decode_timing(msg, &timing, &repeat_why) == TVO_OK) {
            /* Stamped with the plant's clock now (a utime a fresh START could have): the first sample's
             * window starts from it. A repeat is acked 0 either way: the session runs. */
            node->slot[node->running].start_utime = msg->utime;
        }
        publish_ack(node, msg, &why);
        return;
    }
    const uint8_t spare = node->has_session ? (uint8_t)(1u - node->running) : node->running;
    if (build_session(&node->slot[spare], msg, content_hash, now_us, &why) == TVO_OK) {
        node->running = spare;
        node->has_session = 1;
        node->stop_requested = 0;
        memset(&node->counters, 0, sizeof(node->counters));
        node->last_target_status = TVO_OK;
    }
    publish_ack(node, msg, &why);
}

static void on_session(tvo_node_t *node, const tvo_lcm_session_t *msg, uint64_t content_hash, int64_t now_us)
{
    tvo_session_reject_t why = {TVO_OK, TVO_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    if (msg->action == TVO_LCM_SESSION_T_ACTION_START) {
        on_start(node, msg, content_hash, now_us);
        return;
    }
    if (msg->action == TVO_LCM_SESSION_T_ACTION_STOP) {
        const tvo_node_session_t *running = tvo_node_session(node);
        if (running != NULL && msg->session_id == running->session_id) {
            node->has_session = 0;
            node->stop_requested = 1;
        } else {
            why.status = TVO_ERR_NO_SESSION; /* not ours to obey: whatever runs, runs on */
        }
    } else {
        why.status = TVO_ERR_PARAM;
    }
    publish_ack(node, msg, &why);
}

/* ---- measurements ------------------------------------------------------------------------------ */

/* Period index of schedule time t: the smallest j >= 0 with epoch + j h > t (the next apply instant). */
static int64_t next_period_after(const tvo_node_session_t *s, int64_t t_us)
{
    const int64_t since = t_us - s->epoch_schedule_us;
    return since < 0 ? 0 : since / s->timing.period_us + 1;
}

static int64_t apply_instant(const tvo_node_session_t *s, int64_t period)
{
    return s->epoch_schedule_us + period * s->timing.period_us;
}

/* CLOCK_PLANT: from the epoch to stamp + tau, plus half a period, so that its quotient by h is the
 * period whose apply instant is nearest (a sample stamped then serves it; negative: before the epoch).
 * Wire times: no overflow. */
static int64_t plant_to_apply_us(const tvo_node_session_t *s, int64_t stamp_us)
{
    return stamp_us + s->timing.delay_us - s->epoch_schedule_us + s->timing.period_us / 2;
}

/* CLOCK_PLANT, before the first accepted measurement: what the node knows of the plant's clock, the
 * later of the START (or its repeat, or the samples' vote) and the epoch. */
static int64_t first_sample_anchor(const tvo_node_session_t *s)
{
    return s->start_utime > s->epoch_schedule_us ? s->start_utime : s->epoch_schedule_us;
}

/* ... and the latest stamp a first sample may carry. */
static int64_t first_sample_deadline(const tvo_node_session_t *s)
{
    const int64_t h = s->timing.period_us;
    const int64_t window = (int64_t)s->timing.watchdog_periods * h > NODE_FIRST_SAMPLE_WINDOW_US
                               ? (int64_t)s->timing.watchdog_periods * h
                               : NODE_FIRST_SAMPLE_WINDOW_US;
    return first_sample_anchor(s) + window; /* wire times and a window of at most 2^30 us: no overflow */
}

/*
 * Which period the measurement serves and when that period's command applies (schedule clock), or
 * why it cannot serve any. Only wire-range-checked values enter the arithmetic.
 */
static tvo_status_t schedule_measurement(const tvo_node_session_t *s, const tvo_lcm_measurement_t *msg,
                                         int64_t now_us, int64_t *period, int64_t *stamp_us)
{
    if (!wire_time_ok(msg->utime) || !wire_time_ok(msg->sequence)) {
        return TVO_ERR_IMPLAUSIBLE_STAMP;
    }
    const int64_t h = s->timing.period_us;
    *stamp_us = msg->utime + s->offset_us;
    if (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE) {
        if (*stamp_us > now_us + h / NODE_FUTURE_TOLERANCE_DIVISOR) {
            return TVO_ERR_IMPLAUSIBLE_STAMP; /* from the future by the node's own clock */
        }
        const int64_t next = next_period_after(s, now_us);
        *period = (s->has_accepted && next <= s->last_period) ? s->last_period + 1 : next;
        return TVO_OK; /* the age against the apply instant: the controller's check */
    }
    /* CLOCK_PLANT: the period whose apply instant is nearest to stamp + tau. */
    const int64_t to_apply = plant_to_apply_us(s, *stamp_us);
    if (to_apply < 0) {
        return TVO_ERR_IMPLAUSIBLE_STAMP; /* before the epoch */
    }
    *period = to_apply / h;
    if (!s->has_accepted) {
        /* The first sample anchors the sequence: it must follow the START (or the epoch) closely (a
         * stray from far ahead would otherwise anchor it), and its period lie within the controller's
         * clock span. */
        return (*stamp_us <= first_sample_deadline(s) && *period * h <= (int64_t)TVO_MAX_TICK_SPAN)
                   ? TVO_OK
                   : TVO_ERR_IMPLAUSIBLE_STAMP;
    }
    if (*period <= s->last_period) {
        return TVO_ERR_OUT_OF_ORDER; /* a duplicate, or older than the last accepted */
    }
    if (msg->sequence - s->last_sequence != *period - s->last_period) {
        return TVO_ERR_IMPLAUSIBLE_STAMP; /* stamp and sequence disagree: a stray, or a wild number */
    }
    return TVO_OK;
}

/* The refusal's answer, stamped no earlier than the measurement: the core's answer if it stepped
 * (`stepped`: the command in force, or its watchdog's stop), else the command in force; in CLOCK_PLANT,
 * where the plant's samples are the only clock, a safe stop after watchdog_periods refusals in a row.
 * Nothing of the message is kept. */
static void refuse_measurement(tvo_node_t *node, tvo_node_session_t *s, const tvo_lcm_measurement_t *msg,
                               tvo_status_t reason, const tvo_edge_command_t *stepped, int64_t now_us)
{
    count(&node->counters.refused[(uint32_t)reason < (uint32_t)TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS ? reason : 0]);
    node->last_refusal = reason;
    tvo_step_stamp_t stamp = {clamp_time(msg->utime), s->session_id, msg->sequence, reason, s->timing.robot_count};
    if (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE) {
        const int64_t plant_now = clamp_time(now_us - s->offset_us);
        stamp.utime = stamp.utime > plant_now ? stamp.utime : plant_now;
    }
    tvo_edge_command_t cmd;
    if (s->refused_in_row < UINT32_MAX) {
        s->refused_in_row++;
    }
    if (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_PLANT && s->refused_in_row >= s->timing.watchdog_periods) {
        (void)s->controller.ops->safe_stop(&s->controller, &cmd);
        stamp.status = TVO_ERR_WATCHDOG;
    } else if (stepped != NULL) {
        cmd = *stepped;
    } else {
        s->controller.ops->holding(&s->controller, &cmd);
    }
    publish_step(node, s, &cmd, &stamp, now_us);
}

/* A measurement when no session runs: a safe stop that tells the plant to START again. */
static void answer_without_session(tvo_node_t *node, const tvo_lcm_measurement_t *msg)
{
    count(&node->counters.refused[TVO_ERR_NO_SESSION]);
    node->last_refusal = TVO_ERR_NO_SESSION;
    tvo_lcm_command_t out;
    memset(&out, 0, sizeof(out));
    out.utime = clamp_time(msg->utime);
    out.session_id = msg->session_id;
    out.measurement_sequence = msg->sequence;
    out.robot_count = (msg->robot_count >= 1 && msg->robot_count <= TVO_MAX_ROBOTS) ? msg->robot_count : 0;
    out.status = (int32_t)TVO_ERR_NO_SESSION;
    out.flags = (int32_t)TVO_FLAG_SAFE_STOP;
    publish_encoded(node, TVO_NODE_CH_COMMAND, tvo_lcm_command_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &out));
}

/* One vote of a refused measurement for `implied` (agreeing within `tolerance` with the ones before);
 * 1 once NODE_ANCHOR_VOTES in a row agree. */
static int vote(tvo_node_session_t *s, int64_t implied, int64_t tolerance)
{
    const int64_t gap = implied - s->anchor_candidate_us;
    if (s->anchor_votes == 0u || gap > tolerance || gap < -tolerance) {
        s->anchor_candidate_us = implied;
        s->anchor_votes = 1u;
        return 0;
    }
    if (++s->anchor_votes < NODE_ANCHOR_VOTES) {
        return 0;
    }
    s->anchor_votes = 0u;
    return 1;
}

/*
 * Recovery from a wrong anchor, by measurements that agree with each other (a lone stray cannot do
 * it: it takes NODE_ANCHOR_VOTES in a row). Returns 1 if it re-anchored.
 * CLOCK_NODE, before tracking starts: the START's transit is taken as the offset's error, but a START
 * can be much slower than a measurement (2 kB against 0.4 kB on a serial link), which makes every
 * measurement look early (or stale) for the whole session; refused measurements whose own transit,
 * taken as zero, agree on one offset re-anchor the schedule to it. Once tracking started the offset is
 * fixed (the objective's time is counting).
 * CLOCK_PLANT, while tracking: if a stray was taken as the anchor of the sequence numbering (it came
 * first, or its stamp and sequence happened to agree), the genuine samples disagree with it ever
 * after; samples ahead of the last served period that agree on their own numbering adopt it.
 * CLOCK_PLANT, before tracking: a plant that could not be served within the first-sample window (its
 * robot inside an obstacle, its target stream late) would be refused ever after; samples past the
 * window that agree on their own numbering move the window to the last of them. Like the others, the
 * move stands only if the node's checks then pass that sample; if only the step refuses it (a target
 * sample not there yet), the move stands: it anchors nothing, it admits what follows.
 */
static int reanchor(tvo_node_session_t *s, const tvo_lcm_measurement_t *msg, tvo_status_t refusal, int64_t now_us)
{
    const int in_range = wire_time_ok(msg->utime) && wire_time_ok(msg->sequence) &&
                         msg->robot_count == (int32_t)s->timing.robot_count;
    const int64_t h = s->timing.period_us;
    if (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE) {
        if (!in_range || s->has_accepted ||
            (refusal != TVO_ERR_IMPLAUSIBLE_STAMP && refusal != TVO_ERR_STALE && refusal != TVO_ERR_FUTURE_STAMP)) {
            s->anchor_votes = 0u;
            return 0;
        }
        const int64_t implied = now_us - msg->utime;
        if (!vote(s, implied, h / NODE_ANCHOR_AGREEMENT_DIVISOR)) {
            return 0;
        }
        const int64_t epoch_schedule = s->timing.epoch_utime + implied;
        if (tvo_sample_clock_rebase(s->controller.ops->clock(&s->controller), schedule_tick(epoch_schedule)) != TVO_OK) {
            return 0;
        }
        s->offset_us = implied;
        s->epoch_schedule_us = epoch_schedule;
        return 1;
    }
    if (!in_range || refusal != TVO_ERR_IMPLAUSIBLE_STAMP) {
        s->anchor_votes = 0u;
        return 0;
    }
    const int64_t to_apply = plant_to_apply_us(s, msg->utime); /* in range */
    const int64_t period = to_apply / h;
    const int votes = to_apply >= 0 &&
                      (s->has_accepted ? period > s->last_period
                                       : msg->utime > first_sample_deadline(s) && period * h <= (int64_t)TVO_MAX_TICK_SPAN);
    if (!votes) {
        s->anchor_votes = 0u;
        return 0;
    }
    if (!vote(s, msg->sequence - period, 0)) {
        return 0;
    }
    if (s->has_accepted) {
        s->last_sequence = msg->sequence - (period - s->last_period); /* the samples' own numbering */
    } else {
        s->start_utime = msg->utime; /* the first-sample window starts from the plant's samples */
    }
    return 1;
}

/* Everything the node checks of a measurement before the step: its period, stamp and apply instant
 * on the schedule's clock, and the core measurement (the core's step checks the rest, once). */
static tvo_status_t vet_measurement(tvo_node_session_t *s, const tvo_lcm_measurement_t *msg, int64_t now_us,
                                    int64_t *period, int64_t *apply_us, tvo_edge_measurement_t *meas)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    int64_t stamp_us = 0;
    *apply_us = 0;
    tvo_status_t st = (msg->robot_count == (int32_t)s->timing.robot_count) ? TVO_OK : TVO_ERR_DIMENSION;
    if (st == TVO_OK) {
        st = schedule_measurement(s, msg, now_us, period, &stamp_us);
    }
    if (st != TVO_OK) {
        return st;
    }
    *apply_us = apply_instant(s, *period);
    if (!wire_time_ok(*apply_us - s->offset_us)) {
        return TVO_ERR_IMPLAUSIBLE_STAMP; /* its command could not be stamped on the wire */
    }
    if (*apply_us - stamp_us > (int64_t)TVO_MAX_TICK_SPAN) {
        return TVO_ERR_STALE; /* older than the controller's ticks span: as uint32 it could look fresh */
    }
    if (s->has_accepted && (*period - s->last_period) > (int64_t)TVO_MAX_TICK_SPAN / s->timing.period_us) {
        return TVO_ERR_STALE; /* a silence longer than the clock spans: START a new session */
    }
    return ops->measurement(&s->controller, msg, s->timing.robot_count, schedule_tick(stamp_us), meas);
}

/* The node's vetting, the slack rule on the first accepted sample, and the core's step (a transaction).
 * On a refusal *stepped says whether cmd holds the core's answer. */
static tvo_status_t serve_measurement(tvo_node_session_t *s, const tvo_lcm_measurement_t *msg, int64_t now_us,
                                      int64_t *period, int64_t *apply_us, tvo_edge_command_t *cmd, int *stepped)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    tvo_edge_measurement_t meas;
    *stepped = 0;
    tvo_status_t st = vet_measurement(s, msg, now_us, period, apply_us, &meas);
    if (st != TVO_OK) {
        return st;
    }
    /* The paper's slack rule takes the first accepted sample as the state at t = 0; undone if the step
     * refuses it, so a refused first sample leaves the rule for the next one. */
    const uint8_t slack_was_chosen = s->problem.slack_chosen;
    const tvo_barrier_t barrier_before = s->problem.barrier;
    if (!slack_was_chosen) {
        tvo_real_t y[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};
        ops->positions(&meas, s->timing.robot_count, y);
        (void)tvo_problem_choose_slack(&s->problem, y, TVO_R(0.0));
    }
    st = ops->step(&s->controller, &meas, schedule_tick(*apply_us), cmd);
    *stepped = 1;
    if (st != TVO_OK) {
        s->problem.barrier = barrier_before;
        s->problem.slack_chosen = slack_was_chosen;
    }
    return st;
}

/* The sample passed every check, the core's included, and only its law could not serve it (a target
 * sample not there yet). */
static int law_refused(tvo_status_t st)
{
    return st == TVO_ERR_TARGET_NOT_READY || st == TVO_ERR_NUMERIC || st == TVO_ERR_NOT_POSITIVE_DEFINITE;
}

static void on_measurement(tvo_node_t *node, const tvo_lcm_measurement_t *msg, int64_t now_us)
{
    tvo_node_session_t *s = running_session(node);
    if (s == NULL) {
        answer_without_session(node, msg);
        return;
    }
    if (msg->session_id != s->session_id) {
        count(&node->counters.other_session); /* another plant's: not ours to answer */
        return;
    }
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    int64_t period = 0;
    int64_t apply_us = 0;
    tvo_edge_command_t cmd;
    int stepped = 0;
    tvo_status_t st = serve_measurement(s, msg, now_us, &period, &apply_us, &cmd, &stepped);
    if (st != TVO_OK) {
        /* A re-anchor stands only if the measurement that completed the vote then passes every check
         * (its law may still refuse it): one refused for another reason too (not finite, say) must
         * leave the anchor as it was. */
        const int64_t offset = s->offset_us;
        const int64_t epoch_schedule = s->epoch_schedule_us;
        const int64_t last_sequence = s->last_sequence;
        const int64_t start_utime = s->start_utime;
        const uint32_t epoch_tick = schedule_tick(epoch_schedule);
        if (reanchor(s, msg, st, now_us)) {
            st = serve_measurement(s, msg, now_us, &period, &apply_us, &cmd, &stepped); /* on the corrected anchor */
            if (st != TVO_OK && !(stepped && law_refused(st))) {
                s->offset_us = offset;
                s->epoch_schedule_us = epoch_schedule;
                s->last_sequence = last_sequence;
                s->start_utime = start_utime;
                (void)tvo_sample_clock_rebase(ops->clock(&s->controller), epoch_tick);
            }
        }
    }
    if (st != TVO_OK) {
        refuse_measurement(node, s, msg, st, stepped ? &cmd : NULL, now_us);
        return;
    }
    count(&node->counters.accepted);
    s->has_accepted = 1;
    s->last_period = period;
    s->last_sequence = msg->sequence;
    s->refused_in_row = 0;
    s->next_miss_period = period + 1;
    const tvo_step_stamp_t stamp = {apply_us - s->offset_us, s->session_id, msg->sequence, st, s->timing.robot_count};
    publish_step(node, s, &cmd, &stamp, now_us);
}

/* ---- streamed targets -------------------------------------------------------------------------- */

/* The latest stamp (schedule clock) a streamed target sample may carry: the node's now plus half a
 * period (CLOCK_NODE), or the apply instant of the period after the last accepted one (CLOCK_PLANT;
 * before the first, after the one a sample stamped at the first sample's anchor would serve, which
 * the plant's samples move when its stream starts late). So one stray costs at most a period or two. */
static int64_t latest_plausible_target_us(const tvo_node_session_t *s, int64_t now_us)
{
    const int64_t h = s->timing.period_us;
    if (s->timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE) {
        return now_us + h / NODE_FUTURE_TOLERANCE_DIVISOR;
    }
    if (s->has_accepted) {
        return apply_instant(s, s->last_period + 1);
    }
    /* The anchor is a wire time no earlier than the epoch: a period >= 0. */
    const int64_t anchor_period = plant_to_apply_us(s, first_sample_anchor(s)) / h;
    return apply_instant(s, anchor_period + 1);
}

static void on_target(tvo_node_t *node, const tvo_lcm_target_t *msg, int64_t now_us)
{
    tvo_node_session_t *s = running_session(node);
    if (s == NULL) {
        return;
    }
    if (msg->session_id != s->session_id) {
        count(&node->counters.other_session);
        return;
    }
    tvo_status_t st = wire_time_ok(msg->utime) ? TVO_OK : TVO_ERR_IMPLAUSIBLE_STAMP;
    if (st == TVO_OK && msg->utime + s->offset_us > latest_plausible_target_us(s, now_us)) {
        /* A sample from beyond the next period would hold back every genuine one after it (a
         * streamed target takes only newer samples): one stray costs a period or two at most. */
        st = TVO_ERR_IMPLAUSIBLE_STAMP;
    }
    /* The objective's time of the sample, in ticks (us) since the epoch, from 64-bit times: a
     * uint32 tick would alias a sample 2^32 us old with one from the future. */
    const int64_t since_epoch_us = (st == TVO_OK) ? msg->utime + s->offset_us - s->epoch_schedule_us : 0;
    if (st == TVO_OK && since_epoch_us < 0) {
        st = TVO_ERR_OUT_OF_ORDER; /* before the epoch */
    }
    const uint64_t objective_ticks = (uint64_t)since_epoch_us;
    if (st == TVO_OK) {
        st = tvo_step_target_from_lcm(msg, s->timing.robot_count, objective_ticks, &s->problem);
    }
    node->last_target_status = st;
    if (st != TVO_OK) {
        count(&node->counters.targets_refused);
    }
}

/* ---- entry points ------------------------------------------------------------------------------ */

int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length, int64_t now_us)
{
    if (node == NULL) {
        return 0;
    }
    if (data == NULL || length > (uint32_t)INT32_MAX) {
        count(&node->counters.undecodable);
        return 0;
    }
    now_us = clamp_time(now_us);
    const int size = (int)length;
    switch (channel) {
    case TVO_NODE_CH_SESSION:
        if (tvo_lcm_session_t_decode(data, 0, size, &node->rx.session) != size) {
            break; /* malformed, or bytes past the message: not what a sender of this message sends */
        }
        on_session(node, &node->rx.session, tvo_session_content_hash(data, length), now_us);
        return channel;
    case TVO_NODE_CH_MEASUREMENT:
        if (tvo_lcm_measurement_t_decode(data, 0, size, &node->rx.measurement) != size) {
            break;
        }
        on_measurement(node, &node->rx.measurement, now_us);
        return channel;
    case TVO_NODE_CH_TARGET:
        if (tvo_lcm_target_t_decode(data, 0, size, &node->rx.target) != size) {
            break;
        }
        on_target(node, &node->rx.target, now_us);
        return channel;
    default:
        return 0; /* not a channel the node takes (its own outputs, or unknown) */
    }
    count(&node->counters.undecodable);
    return 0;
}

int64_t tvo_node_poll(tvo_node_t *node, int64_t now_us)
{
    tvo_node_session_t *s = (node != NULL) ? running_session(node) : NULL;
    if (s == NULL || s->timing.clock_source != TVO_LCM_SESSION_T_CLOCK_NODE || !s->has_accepted) {
        return TVO_NODE_NO_DEADLINE; /* the watchdog is armed by the first accepted measurement */
    }
    now_us = clamp_time(now_us);
    /* The periods since the last served one passed without a measurement. The core counts them all in
     * one call (every period since its last application) and its watchdog decides; it cannot stop the
     * robots before watchdog_periods have passed, so the node need not call it sooner. */
    const int64_t first_due = s->last_period + (int64_t)s->timing.watchdog_periods;
    const int64_t miss_period = s->next_miss_period > first_due ? s->next_miss_period : first_due;
    const int64_t due_period = next_period_after(s, now_us) - 1; /* the last apply instant at or before now */
    if (due_period >= miss_period) {
        /* A stop is published, stamped now, every period until a measurement is served. */
        tvo_edge_command_t cmd;
        const tvo_status_t st = s->controller.ops->miss(&s->controller, schedule_tick(apply_instant(s, due_period)), &cmd);
        s->next_miss_period = due_period + 1;
        if ((s->controller.ops->flags(&cmd) & TVO_FLAG_SAFE_STOP) != 0u) {
            const tvo_step_stamp_t stamp = {clamp_time(now_us - s->offset_us), s->session_id, -1, st,
                                            s->timing.robot_count};
            publish_step(node, s, &cmd, &stamp, now_us);
        }
        return apply_instant(s, s->next_miss_period);
    }
    return apply_instant(s, miss_period);
}
