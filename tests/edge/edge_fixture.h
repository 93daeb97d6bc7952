/*
 * Shared helpers of the edge tests: a valid START message to edit (naming the fixture node's boot),
 * one robot's samples, and a recording publish callback for the node. Header-only (static inline), so each
 * test stays one translation unit plus the code under test.
 */
#ifndef TVO_EDGE_FIXTURE_H
#define TVO_EDGE_FIXTURE_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "unity.h"

#include "node.h"
#include "session_codec.h"
#include "step_codec.h"
#include "tvo/sample_clock.h"
#include "tvo/status.h"

/* The fixture session: h = 10 ms, tau = h / 2, watchdog 3 periods; its START is sent at EF_UTIME
 * (plant clock) with the epoch EF_EPOCH_LEAD later. */
#define EF_PERIOD_US 10000
#define EF_DELAY_US 5000
#define EF_WATCHDOG 3
#define EF_UTIME 5000000
#define EF_EPOCH_LEAD 300000
#define EF_EPOCH (EF_UTIME + EF_EPOCH_LEAD)
#define EF_SESSION_ID 4242
/* The fixture node's boot, and another (an earlier boot's, or another node's). */
#define EF_BOOT ((int64_t)7001)
#define EF_OTHER_BOOT ((int64_t)7000)

/* Values at and past the ends of the wire ranges. */
#define EF_TWO_POW_60 ((int64_t)1 << 60)

/* ------------------------------------------------------------------------------------------------
 * Assertions that name the statuses
 * --------------------------------------------------------------------------------------------- */

/* The core's count of refusals in a row (a lockstep session's watchdog counts them): the one part of a
 * controller a refused sample changes. */
static inline uint32_t ef_refusals_in_row(const tvo_edge_controller_t *ctl)
{
    const int chain = ctl->ops == tvo_edge_controller_ops(TVO_LCM_SESSION_T_PLANT_CHAIN);
    return chain ? ctl->u.chain.internal.loop.clock.refusals_in_row : ctl->u.unicycle.internal.loop.clock.refusals_in_row;
}

static inline void ef_copy_refusals_in_row(tvo_edge_controller_t *to, const tvo_edge_controller_t *from)
{
    to->ops->clock(to)->refusals_in_row = ef_refusals_in_row(from);
}

static inline void ef_assert_status(int expected, int actual, int line)
{
    if (expected != actual) {
        static char msg[160];
        (void)snprintf(msg, sizeof(msg), "expected status %d (%s), got %d (%s)", expected,
                       tvo_protocol_status_str((int32_t)expected), actual, tvo_protocol_status_str((int32_t)actual));
        UNITY_TEST_FAIL(line, msg);
    }
}
#define EF_ASSERT_STATUS(expected, actual) ef_assert_status((int)(expected), (int)(actual), __LINE__)

static inline void ef_assert_param(int expected, int actual, int line)
{
    if (expected != actual) {
        static char msg[160];
        (void)snprintf(msg, sizeof(msg), "expected bad_param %d (%s), got %d (%s)", expected,
                       tvo_protocol_param_str((int32_t)expected), actual, tvo_protocol_param_str((int32_t)actual));
        UNITY_TEST_FAIL(line, msg);
    }
}
#define EF_ASSERT_PARAM(expected, actual) ef_assert_param((int)(expected), (int)(actual), __LINE__)

/* ------------------------------------------------------------------------------------------------
 * Messages
 * --------------------------------------------------------------------------------------------- */

/** A target path y_d(t) = (x0 + vx t, y0). */
static inline void ef_line_path(tvo_lcm_path_t *path, double x0, double y0, double vx)
{
    memset(path, 0, sizeof(*path));
    path->kind = TVO_LCM_PATH_T_KIND_POLYNOMIAL;
    path->coeff[0][0] = x0;
    path->coeff[0][1] = vx;
    path->coeff[1][0] = y0;
}

/** A valid START of `robots` unicycles (robot r tracks a line at y = r), PLANT clock, no constraints,
 *  telemetry after every answer, naming EF_BOOT for every robot. */
static inline void ef_start(tvo_lcm_session_t *m, int32_t session_id, int32_t clock_source, int32_t robots)
{
    (void)tvo_protocol_default_start(m, 1); /* the paper's loop; the robots below are the fixture's */
    m->utime = EF_UTIME;
    m->session_id = session_id;
    for (int32_t r = 0; r < TVO_LCM_SESSION_T_MAX_ROBOTS; ++r) {
        m->node_boot_id[r] = EF_BOOT;
    }
    m->clock_source = clock_source;
    m->epoch_utime = EF_EPOCH;
    m->period_us = EF_PERIOD_US;
    m->delay_us = EF_DELAY_US;
    m->watchdog_periods = EF_WATCHDOG;
    m->telemetry_every = 1;
    m->speed_max_mps = 2.0;
    m->chain_relative_degree = 2;
    m->chain_gains[0] = 2.56;
    m->chain_gains[1] = 3.2;
    m->chain_input_max = 1000.0;
    m->robot_count = robots; /* any count: tests send refused ones too */
    for (int32_t r = 0; r < robots && r < TVO_LCM_SESSION_T_MAX_ROBOTS; ++r) {
        m->robot[r].initial_speed_mps = 0.0;
        m->robot[r].tracking_weight[0] = 1.0;
        m->robot[r].tracking_weight[1] = 1.0;
        ef_line_path(&m->robot[r].target, 0.5, (double)r, 0.2);
    }
    m->robot_radius_m = 0.1;
}

/** Robot `robot`'s sample: at rest at (0, robot) heading east, heading measured, speed not. */
static inline void ef_sample(tvo_lcm_unicycle_sample_t *m, int32_t session_id, int64_t utime, int32_t sequence,
                             int8_t robot)
{
    memset(m, 0, sizeof(*m));
    m->header.utime = utime;
    m->header.session_id = session_id;
    m->header.sequence = sequence;
    m->header.robot = robot;
    m->position_m[0] = 0.0;
    m->position_m[1] = (double)robot;
    m->heading_rad = 0.0f;
    m->speed_mps = 0.0f;
    m->has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING;
}

/** The node of boot EF_BOOT driving own_robot (-1: every robot), publishing into `rec` (0 on success). */
static inline int ef_node_init(tvo_node_t *node, int8_t own_robot, void *rec);

/* ------------------------------------------------------------------------------------------------
 * A recording publish callback
 * --------------------------------------------------------------------------------------------- */

#define EF_RECORD_CAPACITY 64

typedef struct {
    int channel;
    uint32_t length;
    uint8_t data[TVO_NODE_BUFFER_BYTES];
} ef_message_t;

typedef struct {
    ef_message_t message[EF_RECORD_CAPACITY];
    uint32_t count;      /* since the last ef_record_clear */
    uint32_t overflow;   /* messages that did not fit (a test bug: clear more often) */
} ef_record_t;

static inline void ef_record_publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    ef_record_t *rec = (ef_record_t *)context;
    if (rec->count >= EF_RECORD_CAPACITY || length > TVO_NODE_BUFFER_BYTES) {
        rec->overflow++;
        return;
    }
    ef_message_t *m = &rec->message[rec->count++];
    m->channel = channel;
    m->length = length;
    memcpy(m->data, data, length);
}

static inline int ef_node_init(tvo_node_t *node, int8_t own_robot, void *rec)
{
    return tvo_node_init(node, own_robot, EF_BOOT, ef_record_publish, rec);
}

static inline void ef_record_clear(ef_record_t *rec)
{
    rec->count = 0;
    rec->overflow = 0;
}

/** Messages published on channel since the last clear. */
static inline uint32_t ef_record_count(const ef_record_t *rec, int channel)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < rec->count; ++i) {
        n += (rec->message[i].channel == channel) ? 1u : 0u;
    }
    return n;
}

/** The k-th (0-based) message on channel since the last clear, or NULL. */
static inline const ef_message_t *ef_record_nth(const ef_record_t *rec, int channel, uint32_t k)
{
    for (uint32_t i = 0; i < rec->count; ++i) {
        if (rec->message[i].channel == channel) {
            if (k == 0u) {
                return &rec->message[i];
            }
            --k;
        }
    }
    return NULL;
}

#endif /* TVO_EDGE_FIXTURE_H */
