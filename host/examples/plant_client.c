/*
 * plant_client: an example plant for tvo_firmware_node in plain C, for a robot team to copy
 * (README.md, "Writing your own plant"). Its robot is an exact unicycle tracking an ellipse, in
 * lockstep (CLOCK_PLANT): the plant's clock drives time; it samples, waits for the answer, applies it.
 *
 *   plant_client [LCM_URL [DURATION_S]]     prints "final_error_m=<metres>"; exit 0 if the session ran
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>
#include <lcm/lcm.h>

#include "channels.h"     /* TVO_CHANNEL_*: the protocol's channel names */
#include "tvo_lcm_command_t.h"
#include "tvo_lcm_measurement_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"

#define PERIOD_US 10000     /* h: period j's command applies at EPOCH_US + j h */
#define DELAY_US 5000       /* tau: the sample for period j is taken at EPOCH_US + j h - tau */
#define EPOCH_US 1000000    /* plant time at which the target's t = 0 */
#define WATCHDOG_PERIODS 10 /* no command for this long: the robot stops itself */
#define PI 3.14159265358979323846

typedef struct {
    double x, y, heading, v, w;   /* the pose it measures; the command it holds (speed, turn rate) */
    int64_t now_us, applied_us;   /* plant time of that pose; when it last applied a command */
} robot_t;

typedef struct {
    int64_t session_id, sent, in_force; /* the newest sequence sent; that of the command in force */
    int answered, restart, has_next, acked;
    tvo_lcm_command_t next;             /* applies at next.utime */
    tvo_lcm_session_ack_t ack;
} plant_t;

static void hold_for(robot_t *r, double dt) /* exact arc (or line) under the held command */
{
    const double h1 = r->heading + r->w * dt;
    const int line = fabs(r->w) < 1e-9;
    r->x += line ? r->v * dt * cos(r->heading) : r->v / r->w * (sin(h1) - sin(r->heading));
    r->y += line ? r->v * dt * sin(r->heading) : -r->v / r->w * (cos(h1) - cos(r->heading));
    r->heading = h1;
}

static void advance_to(robot_t *r, plant_t *p, int64_t t_us) /* applies a due command on its instant */
{
    if (p->has_next && p->next.utime <= t_us) {
        const int64_t at = p->next.utime > r->now_us ? p->next.utime : r->now_us; /* never in the past */
        hold_for(r, (double)(at - r->now_us) * 1e-6);
        r->now_us = r->applied_us = at;
        r->v = p->next.speed_mps[0];
        r->w = p->next.turn_rate_radps[0];
        p->has_next = 0;
    }
    hold_for(r, (double)(t_us - r->now_us) * 1e-6);
    r->now_us = t_us;
    if (t_us - r->applied_us >= WATCHDOG_PERIODS * PERIOD_US) {
        r->v = r->w = 0.0; /* the node cannot act during silence in lockstep: stop yourself */
    }
}

static void on_command(const lcm_recv_buf_t *rb, const char *ch, const tvo_lcm_command_t *c, void *user)
{
    plant_t *p = user;
    (void)rb, (void)ch;
    if (c->session_id != p->session_id) return; /* another plant's */
    const int safe_stop = ((uint32_t)c->flags & TVO_LCM_COMMAND_T_FLAG_SAFE_STOP) != 0u;
    p->answered |= c->measurement_sequence == p->sent;
    p->restart |= c->status == TVO_LCM_COMMAND_T_STATUS_ERR_NO_SESSION; /* the node restarted: START again */
    /* Apply a computed answer (status 0) to a newer sequence we sent, or a safe stop at once. */
    if ((c->status == 0 && c->measurement_sequence <= p->sent && c->measurement_sequence > p->in_force) || safe_stop) {
        p->in_force = c->measurement_sequence > p->in_force ? c->measurement_sequence : p->in_force;
        p->next = *c, p->has_next = 1;
        p->next.utime = safe_stop ? 0 : c->utime; /* never put off stopping */
    }
}

static void on_ack(const lcm_recv_buf_t *rb, const char *ch, const tvo_lcm_session_ack_t *a, void *user)
{
    plant_t *p = user;
    (void)rb, (void)ch;
    if (a->session_id == p->session_id) p->ack = *a, p->acked = 1;
}

/* Publishes the session message every 100 ms until its ack arrives (the node may be starting). */
static int request(lcm_t *lcm, plant_t *p, tvo_lcm_session_t *s, int8_t action, int64_t utime)
{
    s->action = action;
    s->utime = utime;
    p->acked = 0;
    for (int tries = 0; tries < 100 && !(p->acked && p->ack.action == action); ++tries) {
        tvo_lcm_session_t_publish(lcm, TVO_CHANNEL_SESSION, s);
        lcm_handle_timeout(lcm, 100);
    }
    return p->acked && p->ack.action == action;
}

int main(int argc, char **argv)
{
    lcm_t *lcm = lcm_create(argc > 1 ? argv[1] : NULL);
    const int64_t steps = (int64_t)((argc > 2 ? atof(argv[2]) : 5.0) * 1e6) / PERIOD_US;
    if (lcm == NULL || steps < 1) return fprintf(stderr, "usage: plant_client [LCM_URL [DURATION_S]]\n"), 2;
    plant_t p = {.session_id = (int64_t)time(NULL) * 1000 + getpid() % 1000, .sent = -1, .in_force = -1};
    robot_t r = {.x = -1.0, .y = -2.0, .now_us = EPOCH_US, .applied_us = EPOCH_US}; /* at rest */
    tvo_lcm_command_t_subscription_t *cmds = tvo_lcm_command_t_subscribe(lcm, TVO_CHANNEL_COMMAND, on_command, &p);
    tvo_lcm_session_ack_t_subscription_t *acks =
        tvo_lcm_session_ack_t_subscribe(lcm, TVO_CHANNEL_SESSION_ACK, on_ack, &p);
    tvo_lcm_session_t s = {.session_id = p.session_id, .clock_source = TVO_LCM_SESSION_T_CLOCK_PLANT,
        .epoch_utime = EPOCH_US, .period_us = PERIOD_US, .delay_us = DELAY_US, .delay_compensation = 1,
        .watchdog_periods = WATCHDOG_PERIODS, .plant_kind = TVO_LCM_SESSION_T_PLANT_UNICYCLE,
        .velocity_source = TVO_LCM_SESSION_T_VELOCITY_FROM_POSE, .filter_tf_s = 0.05, .gain_kp = 40.0,
        .gain_kd = 13.0, .omega_max_radps = 2.0 * PI, .accel_max_mps2 = 15.0, .speed_max_mps = 5.0,
        .min_speed_mps = 0.05, .robot_count = 1};
    s.robot[0] = (tvo_lcm_robot_t){.tracking_weight = {1.0, 1.0}, .target = {.kind = TVO_LCM_PATH_T_KIND_ELLIPSE,
        .semi_axis_m = {3.0, 1.5}, .omega_radps = 2.0 * PI / 10.0}};
    if (!request(lcm, &p, &s, TVO_LCM_SESSION_T_ACTION_START, r.now_us) || p.ack.status != 0) {
        fprintf(stderr, "plant_client: START %s: %s, parameter %s, part %s, index %d\n",
                p.acked ? "refused" : "not acknowledged", tvo_protocol_status_str((int32_t)p.ack.status),
                tvo_protocol_param_str(p.ack.bad_param), tvo_protocol_part_str(p.ack.bad_part), p.ack.bad_index);
        return 1;
    }
    for (int64_t n = 0; n < steps; ++n) {
        advance_to(&r, &p, EPOCH_US + (n + 1) * PERIOD_US - DELAY_US); /* sample n serves period n + 1 */
        tvo_lcm_measurement_t m = {.utime = r.now_us, .session_id = p.session_id, .sequence = n, .robot_count = 1,
            .position_m = {{r.x, r.y}}, .heading_rad = {r.heading}, .speed_mps = {r.v}, .heading_valid = 1,
            .speed_valid = 1};
        p.sent = n, p.answered = 0;
        tvo_lcm_measurement_t_publish(lcm, TVO_CHANNEL_MEASUREMENT, &m);
        for (int waited_ms = 0; !p.answered && waited_ms < 1000; waited_ms += 10) {
            lcm_handle_timeout(lcm, 10); /* no answer within 1 s: hold, as for a lost sample */
        }
        if (p.restart) {
            advance_to(&r, &p, r.now_us); /* the safe stop first */
            p.restart = !request(lcm, &p, &s, TVO_LCM_SESSION_T_ACTION_START, r.now_us);
        }
        advance_to(&r, &p, EPOCH_US + (n + 1) * PERIOD_US);
    }
    const tvo_lcm_path_t *e = &s.robot[0].target; /* the ellipse, centred at 0: where it is now */
    const double phase = e->omega_radps * (double)(r.now_us - EPOCH_US) * 1e-6;
    printf("final_error_m=%.6g\n", hypot(r.x - e->semi_axis_m[0] * cos(phase), r.y - e->semi_axis_m[1] * sin(phase)));
    request(lcm, &p, &s, TVO_LCM_SESSION_T_ACTION_STOP, r.now_us);
    tvo_lcm_command_t_unsubscribe(lcm, cmds);
    tvo_lcm_session_ack_t_unsubscribe(lcm, acks);
    lcm_destroy(lcm);
    return 0;
}
