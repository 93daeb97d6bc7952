/* The fleet link in front of the node: per-robot samples in, the joint measurement to the node, the
 * own robot's row and the joint command's digest out (fleet_link.h). */
#include "fleet_link.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "channels.h"
#include "tvo_lcm_telemetry_t.h"

/* The longest prediction, in periods, whatever the session's watchdog (bounds the loop). */
#define TVO_FLEET_MAX_PREDICT_PERIODS 1000
/* Below this turn rate (rad/s) an arc is integrated as a straight line (its limit). */
#define TVO_FLEET_STRAIGHT_RADPS 1e-9

#if TVO_FLEET_MAX_ROBOTS > TVO_LCM_FLEET_SAMPLE_T_MAX_ROBOTS || TVO_FLEET_MAX_ROBOTS > TVO_LCM_FLEET_COMMAND_T_MAX_ROBOTS
#error "the fleet messages must name every robot the node's measurement carries"
#endif

int tvo_fleet_channel_name(int channel, int32_t robot, char *out, size_t size)
{
    const char *base = channel == TVO_FLEET_CH_SAMPLE        ? TVO_CHANNEL_FLEET_SAMPLE
                       : channel == TVO_FLEET_CH_COMMAND     ? TVO_CHANNEL_FLEET_COMMAND
                       : channel == TVO_FLEET_CH_SESSION_ACK ? TVO_CHANNEL_SESSION_ACK
                       : channel == TVO_FLEET_CH_TELEMETRY   ? TVO_CHANNEL_TELEMETRY
                                                             : NULL;
    if (base == NULL || out == NULL || robot < 0 || robot >= TVO_FLEET_MAX_ROBOTS) {
        return -1;
    }
    const int written = snprintf(out, size, "%s_R%d", base, (int)robot);
    return (written > 0 && (size_t)written < size) ? 0 : -1;
}

int tvo_fleet_link_channel_name(void *context, int channel, char *out, size_t size)
{
    const tvo_fleet_link_t *link = (const tvo_fleet_link_t *)context;
    if (link == NULL || out == NULL) {
        return -1;
    }
    if (channel >= TVO_FLEET_CH_SAMPLE && channel <= TVO_FLEET_CH_TELEMETRY) {
        return tvo_fleet_channel_name(channel, link->own_robot, out, size);
    }
    const char *name = tvo_node_channel_name(channel);
    const int written = (name != NULL) ? snprintf(out, size, "%s", name) : -1;
    return (written > 0 && (size_t)written < size) ? 0 : -1;
}

static uint64_t fnv_double(uint64_t hash, double value)
{
    uint64_t bits = 0u;
    memcpy(&bits, &value, sizeof(bits));
    for (int b = 0; b < 8; ++b) {
        hash ^= (bits >> (8 * b)) & 0xffu;
        hash *= 0x100000001b3ull;
    }
    return hash;
}

uint64_t tvo_fleet_digest(const tvo_fleet_joint_command_t *command, int32_t robot_count)
{
    uint64_t hash = 0xcbf29ce484222325ull;
    if (command == NULL) {
        return 0u;
    }
    for (int32_t r = 0; r < robot_count && r < TVO_FLEET_MAX_ROBOTS; ++r) {
        hash = fnv_double(hash, command->speed_mps[r]);
        hash = fnv_double(hash, command->turn_rate_radps[r]);
    }
    return hash;
}

static void reset(tvo_fleet_link_t *link, int64_t session_id)
{
    link->session_id = session_id;
    link->last_step = -1;
    link->answering = -1;
    link->predicted = 0;
    for (int r = 0; r < TVO_FLEET_MAX_ROBOTS; ++r) {
        link->known[r].sequence = -1;
        link->known_measured[r] = 0u;
        link->has_pending[r] = 0u;
    }
    for (int k = 0; k < 2; ++k) {
        memset(&link->commands[k], 0, sizeof(link->commands[k]));
        link->commands[k].sequence = -1;
    }
}

static void take_answer(void *context, const tvo_step_stamp_t *stamp, uint32_t wire_flags, const tvo_command_t *command);
static void publish_from_node(void *context, int channel, const uint8_t *data, uint32_t length);

int tvo_fleet_link_init(tvo_fleet_link_t *link, tvo_node_t *node, int32_t own_robot,
                        tvo_node_publish_fn transport_publish, void *transport_context)
{
    if (link == NULL || node == NULL || transport_publish == NULL || own_robot < 0 ||
        own_robot >= TVO_FLEET_MAX_ROBOTS) {
        return -1;
    }
    memset(link, 0, sizeof(*link));
    link->own_robot = own_robot;
    link->transport_publish = transport_publish;
    link->transport_context = transport_context;
    reset(link, -1);
    tvo_node_init(node, publish_from_node, link);
    return tvo_node_set_answer(node, take_answer, link);
}

/* ---- prediction -------------------------------------------------------------------------------- */

/* The joint command in force during the period after sample `sequence` (zero-order hold); NULL: at rest. */
static const tvo_fleet_joint_command_t *in_force(const tvo_fleet_link_t *link, int64_t sequence)
{
    for (int k = 0; k < 2; ++k) {
        if (link->commands[k].sequence >= 0 && link->commands[k].sequence <= sequence) {
            return &link->commands[k];
        }
    }
    /* Older than both kept: the oldest kept is the nearest (only after a long silence of the own robot). */
    return link->commands[1].sequence >= 0 ? &link->commands[1]
           : link->commands[0].sequence >= 0 ? &link->commands[0]
                                             : NULL;
}

/* Exact unicycle arc over dt_s under (v, omega) held. */
static void arc(tvo_fleet_robot_t *robot, double speed_mps, double turn_radps, double dt_s)
{
    const double theta = robot->heading_rad;
    if (fabs(turn_radps) < TVO_FLEET_STRAIGHT_RADPS) {
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
static void predict_period(const tvo_fleet_link_t *link, int r, tvo_fleet_robot_t *robot, double period_s,
                           double delay_s)
{
    const tvo_fleet_joint_command_t *before = in_force(link, robot->sequence - 1);
    const tvo_fleet_joint_command_t *after = in_force(link, robot->sequence);
    arc(robot, before != NULL ? before->speed_mps[r] : 0.0, before != NULL ? before->turn_rate_radps[r] : 0.0, delay_s);
    arc(robot, after != NULL ? after->speed_mps[r] : 0.0, after != NULL ? after->turn_rate_radps[r] : 0.0,
        period_s - delay_s);
    robot->sequence += 1;
}

/* ---- publishing ---------------------------------------------------------------------------------- */

static void publish_out(tvo_fleet_link_t *link, int channel, int length)
{
    if (length > 0) {
        link->transport_publish(link->transport_context, channel, link->buffer, (uint32_t)length);
    }
}

/* A fleet command: the own robot's row of `rows` with the whole joint command's digest. */
static void publish_row(tvo_fleet_link_t *link, const tvo_step_stamp_t *stamp, int32_t status, uint32_t wire_flags,
                        const tvo_fleet_joint_command_t *rows)
{
    tvo_lcm_fleet_command_t *out = &link->out;
    const int32_t robots = stamp->robot_count <= TVO_FLEET_MAX_ROBOTS ? (int32_t)stamp->robot_count : 0;
    memset(out, 0, sizeof(*out));
    out->utime = stamp->utime;
    out->session_id = stamp->session_id;
    out->measurement_sequence = stamp->sequence;
    out->robot = link->own_robot;
    out->robot_count = robots;
    out->status = status;
    out->flags = (int32_t)wire_flags;
    if (link->own_robot < robots) {
        out->speed_mps = rows->speed_mps[link->own_robot];
        out->turn_rate_radps = rows->turn_rate_radps[link->own_robot];
    }
    out->joint_digest = (int64_t)tvo_fleet_digest(rows, robots);
    out->predicted = (stamp->sequence == link->answering) ? link->predicted : 0;
    for (int32_t r = 0; r < robots; ++r) {
        out->joint_speed_mps[r] = rows->speed_mps[r];
        out->joint_turn_rate_radps[r] = rows->turn_rate_radps[r];
    }
    publish_out(link, TVO_FLEET_CH_COMMAND, tvo_lcm_fleet_command_t_encode(link->buffer, 0, TVO_NODE_BUFFER_BYTES, out));
}

/* The node's answer (tvo_node_answer_fn): kept as the joint command in force when the robots will
 * follow it (a computed command or a safe stop), then published as the own robot's row with the digest. */
static void take_answer(void *context, const tvo_step_stamp_t *stamp, uint32_t wire_flags, const tvo_command_t *command)
{
    tvo_fleet_link_t *link = (tvo_fleet_link_t *)context;
    const int32_t status = tvo_step_wire_status(&stamp->why);
    tvo_fleet_joint_command_t rows;
    memset(&rows, 0, sizeof(rows));
    for (uint8_t r = 0; r < stamp->robot_count && r < TVO_FLEET_MAX_ROBOTS; ++r) {
        rows.speed_mps[r] = (double)command->speed_mps[r];
        rows.turn_rate_radps[r] = (double)command->turn_rate_radps[r];
    }
    const int in_step = link->answering >= 0 && stamp->sequence == link->answering;
    const int followed = status == TVO_LCM_COMMAND_T_STATUS_OK || (wire_flags & TVO_LCM_COMMAND_T_FLAG_SAFE_STOP) != 0u;
    if (in_step) {
        link->answered_ok = (uint8_t)(status == TVO_LCM_COMMAND_T_STATUS_OK);
    }
    if (followed && stamp->robot_count > 0 && stamp->robot_count <= TVO_FLEET_MAX_ROBOTS) {
        link->commands[1] = link->commands[0];
        link->commands[0] = rows;
        link->commands[0].sequence = in_step ? link->answering : (link->last_step >= 0 ? link->last_step : 0);
    }
    publish_row(link, stamp, status, wire_flags, &rows);
}

/* The node's publisher (tvo_node_publish_fn): its ack and telemetry, renamed for the own robot. */
static void publish_from_node(void *context, int channel, const uint8_t *data, uint32_t length)
{
    tvo_fleet_link_t *link = (tvo_fleet_link_t *)context;
    if (channel == TVO_NODE_CH_SESSION_ACK || channel == TVO_NODE_CH_TELEMETRY) {
        link->transport_publish(link->transport_context,
                                channel == TVO_NODE_CH_SESSION_ACK ? TVO_FLEET_CH_SESSION_ACK : TVO_FLEET_CH_TELEMETRY,
                                data, length);
    }
}

/* ---- receiving ----------------------------------------------------------------------------------- */

static int sample_valid(const tvo_lcm_fleet_sample_t *s)
{
    const int finite = isfinite(s->position_m[0]) && isfinite(s->position_m[1]) &&
                       (!s->heading_valid || isfinite(s->heading_rad)) && (!s->speed_valid || isfinite(s->speed_mps));
    return finite && s->robot_count >= 1 && s->robot_count <= TVO_FLEET_MAX_ROBOTS && s->robot >= 0 &&
           s->robot < s->robot_count && tvo_schedule_wire_time_ok(s->sequence) && tvo_schedule_wire_time_ok(s->utime);
}

static void state_of(const tvo_lcm_fleet_sample_t *s, tvo_fleet_robot_t *robot)
{
    robot->position_m[0] = s->position_m[0];
    robot->position_m[1] = s->position_m[1];
    robot->heading_rad = s->heading_valid ? s->heading_rad : 0.0;
    robot->speed_mps = s->speed_valid ? s->speed_mps : 0.0;
    robot->sequence = s->sequence;
}

/* No joint measurement could be built (a robot never heard, or unheard too long): the command in
 * force, HOLDING, with the wire's ERR_NO_MEASUREMENT, and a telemetry of the same answer (the plant awaits both). */
static void answer_unheard(tvo_fleet_link_t *link, const tvo_lcm_fleet_sample_t *own, int64_t delay_us)
{
    const tvo_step_stamp_t stamp = {own->utime + delay_us, own->session_id, own->sequence,
                                    {TVO_NODE_OK, TVO_OK, TVO_REASON_NO_MEASUREMENT}, (uint8_t)own->robot_count};
    const int32_t status = tvo_step_wire_status(&stamp.why);
    const uint32_t flags = TVO_LCM_COMMAND_T_FLAG_HOLDING;
    const tvo_fleet_joint_command_t *held = in_force(link, own->sequence);
    tvo_fleet_joint_command_t rows;
    memset(&rows, 0, sizeof(rows));
    if (held != NULL) {
        rows = *held;
    }
    link->unheard_steps += 1u;
    publish_row(link, &stamp, status, flags, &rows);
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    tel.utime = stamp.utime;
    tel.session_id = stamp.session_id;
    tel.measurement_sequence = stamp.sequence;
    tel.status = status;
    tel.flags = (int32_t)flags;
    publish_out(link, TVO_FLEET_CH_TELEMETRY, tvo_lcm_telemetry_t_encode(link->buffer, 0, TVO_NODE_BUFFER_BYTES, &tel));
}

/* The own robot's sample n: the joint measurement from the others' samples of n, or their
 * predictions; the node steps with it; the states are kept only if the node took the step. */
static void step(tvo_fleet_link_t *link, tvo_node_t *node, const tvo_lcm_fleet_sample_t *own, int64_t now_us)
{
    const tvo_node_session_t *s = tvo_node_session(node);
    const int running = s != NULL && s->session_id == own->session_id;
    const int64_t n = own->sequence;
    const int32_t robots = own->robot_count; /* own is the link's rx: a transport re-entering it may reuse it */
    tvo_fleet_robot_t next[TVO_FLEET_MAX_ROBOTS];
    int32_t predicted = 0;
    uint32_t robot_periods = 0u;
    int heard_all = 1;
    if (running) {
        const double period_s = (double)s->schedule.timing.period_us * 1e-6;
        const double delay_s = (double)s->schedule.timing.delay_us * 1e-6;
        int64_t span = (int64_t)s->schedule.timing.watchdog_periods;
        span = span < TVO_FLEET_MAX_PREDICT_PERIODS ? span : TVO_FLEET_MAX_PREDICT_PERIODS;
        for (int32_t r = 0; r < robots; ++r) {
            next[r] = link->known[r];
            if (r == link->own_robot) {
                state_of(own, &next[r]);
                continue;
            }
            /* A sample stamped more than a period ahead is a stray: it would hold back the genuine ones. */
            if (link->has_pending[r] && link->pending[r].sequence > n + 1) {
                link->has_pending[r] = 0u;
            }
            /* A sample of an earlier period than n (its own robot's step was missed) is still news. */
            if (link->has_pending[r] && link->pending[r].sequence <= n && link->pending[r].sequence > next[r].sequence) {
                state_of(&link->pending[r], &next[r]);
            }
            if (next[r].sequence == n) {
                continue;
            }
            if (next[r].sequence < 0 || next[r].sequence > n || n - next[r].sequence > span) {
                heard_all = 0;
                break;
            }
            predicted += 1;
            while (next[r].sequence < n) {
                predict_period(link, (int)r, &next[r], period_s, delay_s);
                robot_periods += 1u;
            }
        }
    }
    if (running && !heard_all) {
        answer_unheard(link, own, s->schedule.timing.delay_us);
        return;
    }
    tvo_step_measurement_t *joint = &link->joint;
    memset(joint, 0, sizeof(*joint));
    joint->utime = own->utime;
    joint->session_id = own->session_id;
    joint->sequence = own->sequence;
    joint->robot_count = robots;
    joint->heading_valid = own->heading_valid ? 1u : 0u;
    joint->speed_valid = own->speed_valid ? 1u : 0u;
    for (int32_t r = 0; r < robots; ++r) {
        tvo_step_robot_sample_t *sample = &joint->robot[r];
        const tvo_fleet_robot_t *robot = running ? &next[r] : NULL;
        if (robot == NULL) { /* no session of this id: the node answers for itself (NO_SESSION, other session) */
            if (r == link->own_robot) {
                sample->position_m[0] = own->position_m[0];
                sample->position_m[1] = own->position_m[1];
            }
            continue;
        }
        sample->position_m[0] = robot->position_m[0];
        sample->position_m[1] = robot->position_m[1];
        sample->heading_rad = robot->heading_rad;
        sample->speed_mps = robot->speed_mps;
    }
    link->answering = n;
    link->predicted = predicted;
    link->answered_ok = 0u;
    (void)tvo_node_measure(node, joint, now_us);
    const int stepped = running && link->answered_ok;
    link->answering = -1;
    if (!stepped) {
        return; /* refused: nothing of the samples is kept, as the node keeps nothing of a refused one */
    }
    link->predictions += robot_periods;
    link->last_step = n;
    for (int32_t r = 0; r < robots; ++r) {
        link->known[r] = next[r];
        link->known_measured[r] = (uint8_t)(next[r].sequence == n && (r == link->own_robot ||
                                            (link->has_pending[r] && link->pending[r].sequence == n)));
        if (link->has_pending[r] && link->pending[r].sequence <= n) {
            link->has_pending[r] = 0u;
        }
    }
}

/* Another robot's sample: kept for its period, or, late for a period already stepped, taken as that
 * robot's state there if it was predicted (the next prediction starts from it). */
static void gather(tvo_fleet_link_t *link, const tvo_lcm_fleet_sample_t *sample)
{
    const int32_t r = sample->robot;
    if (sample->sequence > link->last_step) {
        if (!link->has_pending[r] || sample->sequence > link->pending[r].sequence) {
            link->pending[r] = *sample;
            link->has_pending[r] = 1u;
        }
        return;
    }
    link->samples_late += 1u;
    if (sample->sequence == link->known[r].sequence && !link->known_measured[r]) {
        state_of(sample, &link->known[r]);
        link->known_measured[r] = 1u;
    }
}

int tvo_fleet_link_receive(tvo_fleet_link_t *link, tvo_node_t *node, int channel, const uint8_t *data,
                           uint32_t length, int64_t now_us)
{
    if (link == NULL || node == NULL || data == NULL) {
        return 0;
    }
    if (channel == TVO_NODE_CH_SESSION || channel == TVO_NODE_CH_TARGET) {
        return tvo_node_handle(node, channel, data, length, now_us);
    }
    if (channel != TVO_FLEET_CH_SAMPLE) {
        return 0;
    }
    tvo_lcm_fleet_sample_t *sample = &link->rx;
    if (tvo_lcm_fleet_sample_t_decode(data, 0, (int)length, sample) != (int)length || !sample_valid(sample)) {
        link->samples_refused += 1u;
        return 0;
    }
    const tvo_node_session_t *s = tvo_node_session(node);
    const int ours = s != NULL && s->session_id == sample->session_id;
    if (ours && link->session_id != sample->session_id) {
        reset(link, sample->session_id);
    }
    if (sample->robot != link->own_robot) {
        if (!ours || sample->robot_count != (int32_t)s->schedule.timing.robot_count) {
            link->samples_refused += 1u;
            return 0;
        }
        link->samples_taken += 1u;
        gather(link, sample);
        return channel;
    }
    link->samples_taken += 1u;
    step(link, node, sample, now_us);
    return channel;
}
