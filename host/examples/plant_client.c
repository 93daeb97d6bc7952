/*
 * plant_client: an example plant for tvo_firmware_node in plain C, for a robot team to copy
 * (lcm_types/README.md, "Writing your own plant", rules 1-6). Its robot is an exact unicycle tracking an
 * ellipse, in lockstep (CLOCK_PLANT): the plant's clock drives time; it samples, waits for the answer,
 * applies it.
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
#include "tvo/defaults.h" /* the paper's loop: the values a START sends */
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

#define PERIOD_US TVO_DEFAULT_PERIOD_US /* h: period j's command applies at EPOCH_US + j h */
#define DELAY_US TVO_DEFAULT_DELAY_US   /* tau: the sample for period j is taken at EPOCH_US + j h - tau */
#define EPOCH_US 1000000                /* plant time at which the target's t = 0 */
#define WATCHDOG_PERIODS TVO_DEFAULT_WATCHDOG_PERIODS /* no command for this long: the robot stops itself */
#define PI 3.14159265358979323846

typedef struct {
    double x, y, heading, v, w;   /* the pose it measures; the command it holds (speed, turn rate) */
    int64_t now_us, applied_us;   /* plant time of that pose; when it last applied a command */
} robot_t;

typedef struct {
    int32_t session_id, sent, in_force; /* the newest sequence sent; that of the command in force */
    int answered, acked, running_seen;
    int64_t boot_id, node_utime;        /* rule 1: the node's boot, from its announcements */
    int restart;                        /* rule 5: the node restarted or lost the session */
    tvo_lcm_unicycle_command_t next;    /* applies at next.header.utime */
    int has_next;
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
    if (p->has_next && p->next.header.utime <= t_us) {
        const int64_t at = p->next.header.utime > r->now_us ? p->next.header.utime : r->now_us; /* never in the past */
        hold_for(r, (double)(at - r->now_us) * 1e-6);
        r->now_us = r->applied_us = at;
        r->v = (double)p->next.speed_mps;
        r->w = (double)p->next.turn_rate_radps;
        p->has_next = 0;
    }
    hold_for(r, (double)(t_us - r->now_us) * 1e-6);
    r->now_us = t_us;
    if (t_us - r->applied_us >= WATCHDOG_PERIODS * PERIOD_US) {
        r->v = r->w = 0.0; /* rule 5: the node cannot act during silence in lockstep: stop yourself */
    }
}

static void on_node(const lcm_recv_buf_t *rb, const char *ch, const tvo_lcm_node_status_t *s, void *user)
{
    plant_t *p = user;
    (void)rb, (void)ch;
    if (s->protocol_version != TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION || s->own_robot != -1) return;
    if (p->boot_id != 0 && s->boot_id > p->boot_id) p->restart = 1; /* a new boot: our session is gone */
    if (s->boot_id == p->boot_id && s->state == TVO_LCM_NODE_STATUS_T_STATE_RUNNING && s->session_id == p->session_id)
        p->running_seen = 1, p->node_utime = s->utime;
    else if (s->boot_id == p->boot_id && s->state == TVO_LCM_NODE_STATUS_T_STATE_IDLE && p->running_seen &&
             s->utime > p->node_utime)
        p->restart = 1; /* it ran ours and now runs nothing */
    if (p->boot_id == 0 || s->boot_id > p->boot_id) p->boot_id = s->boot_id;
}

static void on_command(const lcm_recv_buf_t *rb, const char *ch, const tvo_lcm_unicycle_command_t *c, void *user)
{
    plant_t *p = user;
    const tvo_lcm_command_header_t *h = &c->header;
    (void)rb, (void)ch;
    if (h->session_id != p->session_id || h->robot != 0) return; /* another plant's */
    const int safe_stop = ((uint32_t)h->flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0u;
    p->answered |= h->measurement_sequence == p->sent;
    const int newer_ours = h->measurement_sequence <= p->sent && h->measurement_sequence > p->in_force;
    /* Apply a computed answer (status 0) to a newer sequence we sent, or a safe stop at once. */
    if ((h->status == 0 && newer_ours) || safe_stop) {
        if (newer_ours) p->in_force = h->measurement_sequence; /* a safe stop of a stray's must not hide ours */
        p->next = *c, p->has_next = 1;
        p->next.header.utime = safe_stop ? 0 : h->utime; /* never put off stopping */
    }
}

static void on_ack(const lcm_recv_buf_t *rb, const char *ch, const tvo_lcm_session_ack_t *a, void *user)
{
    plant_t *p = user;
    (void)rb, (void)ch;
    if (a->session_id == p->session_id && a->boot_id == p->boot_id) p->ack = *a, p->acked = 1;
}

/* Rules 1, 2 and 6: the session message names the node's boot, repeated every 100 ms until acked. */
static int request(lcm_t *lcm, plant_t *p, tvo_lcm_session_t *s, int8_t action, int64_t utime)
{
    for (int waited = 0; p->boot_id == 0 && waited < 50; ++waited) lcm_handle_timeout(lcm, 100); /* rule 1 */
    s->action = action;
    s->utime = utime;
    s->node_boot_id[0] = p->boot_id;
    p->acked = 0, p->restart = 0, p->running_seen = 0;
    for (int tries = 0; tries < 100 && p->boot_id != 0 && !(p->acked && p->ack.action == action); ++tries) {
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
    plant_t p = {.session_id = (int32_t)((time(NULL) * 1000 + getpid() % 1000) & 0x7fffffff), .sent = -1, .in_force = -1};
    robot_t r = {.x = -1.0, .y = -2.0, .now_us = EPOCH_US, .applied_us = EPOCH_US}; /* at rest */
    tvo_lcm_node_status_t_subscription_t *nodes = tvo_lcm_node_status_t_subscribe(lcm, TVO_CHANNEL_NODE, on_node, &p);
    tvo_lcm_unicycle_command_t_subscription_t *cmds =
        tvo_lcm_unicycle_command_t_subscribe(lcm, TVO_CHANNEL_COMMAND, on_command, &p);
    /* LCM drops past 30 queued messages per subscription, silently: a plant of many robots lifts that. */
    tvo_lcm_unicycle_command_t_subscription_set_queue_capacity(cmds, 0);
    tvo_lcm_session_ack_t_subscription_t *acks =
        tvo_lcm_session_ack_t_subscribe(lcm, TVO_CHANNEL_SESSION_ACK, on_ack, &p);
    /* The paper's loop for one robot, lockstep (tvo/defaults.h: h, tau, the watchdog, the gains, the limits). */
    tvo_lcm_session_t s;
    (void)tvo_protocol_default_start(&s, 1); /* one robot: in range */
    s.session_id = p.session_id;
    s.epoch_utime = EPOCH_US;
    s.robot[0].target = (tvo_lcm_path_t){.kind = TVO_LCM_PATH_T_KIND_ELLIPSE, .semi_axis_m = {3.0, 1.5},
                                         .omega_radps = 2.0 * PI / 10.0};
    if (!request(lcm, &p, &s, TVO_LCM_SESSION_T_ACTION_START, r.now_us) || p.ack.status != 0) {
        fprintf(stderr, "plant_client: START %s: %s, parameter %s, part %s, index %d\n",
                p.acked ? "refused" : (p.boot_id != 0 ? "not acknowledged" : "no node announced itself"),
                tvo_protocol_status_str((int32_t)p.ack.status), tvo_protocol_param_str(p.ack.bad_param),
                tvo_protocol_part_str(p.ack.bad_part), p.ack.bad_index);
        tvo_lcm_node_status_t_unsubscribe(lcm, nodes);
        tvo_lcm_unicycle_command_t_unsubscribe(lcm, cmds);
        tvo_lcm_session_ack_t_unsubscribe(lcm, acks);
        lcm_destroy(lcm);
        return 1;
    }
    for (int32_t n = 0; n < steps; ++n) {
        advance_to(&r, &p, EPOCH_US + (n + 1) * PERIOD_US - DELAY_US); /* rule 3: sample n serves period n + 1 */
        tvo_lcm_unicycle_sample_t m = {.header = {.utime = r.now_us, .session_id = p.session_id, .sequence = n},
            .has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED,
            .position_m = {r.x, r.y}, .heading_rad = (float)remainder(r.heading, 2.0 * PI), .speed_mps = (float)r.v};
        p.sent = n, p.answered = 0;
        tvo_lcm_unicycle_sample_t_publish(lcm, TVO_CHANNEL_SAMPLE, &m);
        for (int waited_ms = 0; !p.answered && !p.restart && waited_ms < 1000; waited_ms += 10) {
            lcm_handle_timeout(lcm, 10); /* no answer within 1 s: hold, as for a lost sample */
        }
        if (p.restart) { /* rule 5: stop the robot, START a new session naming the node's current boot */
            r.v = r.w = 0.0, p.has_next = 0;
            s.session_id = p.session_id = (p.session_id + 1) & 0x7fffffff;
            if (!request(lcm, &p, &s, TVO_LCM_SESSION_T_ACTION_START, r.now_us)) break;
        }
        advance_to(&r, &p, EPOCH_US + (n + 1) * PERIOD_US);
    }
    const tvo_lcm_path_t *e = &s.robot[0].target; /* the ellipse, centred at 0: where it is now */
    const double phase = e->omega_radps * (double)(r.now_us - EPOCH_US) * 1e-6;
    printf("final_error_m=%.6g\n", hypot(r.x - e->semi_axis_m[0] * cos(phase), r.y - e->semi_axis_m[1] * sin(phase)));
    request(lcm, &p, &s, TVO_LCM_SESSION_T_ACTION_STOP, r.now_us); /* rule 6 */
    tvo_lcm_node_status_t_unsubscribe(lcm, nodes);
    tvo_lcm_unicycle_command_t_unsubscribe(lcm, cmds);
    tvo_lcm_session_ack_t_unsubscribe(lcm, acks);
    lcm_destroy(lcm);
    return 0;
}
