/*
 * Cost of one keyed period on the board, the real receive path under qemu -icount shift=0
 * (tools/bench): a signed sample frame goes into tvo_auth_link_receive (the frame's checks, the
 * verify, the node's decoding, gathering and schedule, the core's step, the command encoded, signed
 * and handed to the transport, and after every telemetry_every-th period the telemetry the same
 * way), bracketed by the cycle counter. The plant is outside the bracket: it signs the samples, and
 * moves its robots along exact unicycle arcs under the commands the node published.
 *
 *   unicycle  one robot tracking the bench's ellipse (bench_problems.h's "unicycle"), a node that
 *             drives every robot (own robot -1): one verify, one step, one command per period.
 *   fleet8    robot 7's node of an 8-robot fleet on formation8 (a ring of distance bounds): per period
 *             the 8 robots' samples in robot order (8 verifies, the last one steps), its one command.
 *             The other robots move under the joint command of a second node (every robot's, not
 *             measured) that hears the same samples: both evaluate the same joint law.
 * Both run CLOCK_PLANT lockstep at h = 10 ms with the default telemetry rate (telemetry_every 0: every
 * 10th period here), BENCH_PERIODS periods, every one of which must be a computed command (status 0).
 *
 * Prints "PERIOD <name> periods <n> mean <instr> median <instr> min <instr> max <instr> telemetry_every
 * <k> announce <instr>": the mean over a whole number of telemetry cycles is the figure (it carries the
 * telemetry at its rate; the median is a period without it); announce is the node's status messages
 * (tvo_node_poll: one a second while running) per period, outside the period's figure. Then
 * "PERIOD_DONE". A problem the build's limits cannot hold prints "PERIOD_SKIP <name>". After the
 * unicycle run, "FORGED <kind> instr <n>": what each kind of forged frame costs the node (see forged_frames).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "auth_link.h"
#include "board.h"
#include "channels.h"
#include "node.h"
#include "tvo/defaults.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

#define BENCH_PERIODS 400u
#define PERIOD_US TVO_DEFAULT_PERIOD_US /* the session's h and tau: tvo_protocol_default_start's */
#define DELAY_US TVO_DEFAULT_DELAY_US
#define START_UTIME 1000000
#define EPOCH_UTIME (START_UTIME + 200000)
#define FLEET_ROBOTS 8
#define BOOT_ID 5
#define PI_D 3.14159265358979323846

int main(void);

typedef struct {
    double x_m, y_m, heading_rad, speed_mps, turn_rate_radps;
} robot_t;

static tvo_node_t node;          /* the node measured (keyed) */
static tvo_auth_link_t link;
static tvo_node_t driver;        /* fleet8: every robot's node, whose commands move the other robots */
static tvo_auth_t plant;
static tvo_lcm_session_t start;
static robot_t robots[FLEET_ROBOTS];
static uint8_t frame[TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES];
static uint32_t period_ticks[BENCH_PERIODS];
static uint32_t computed;        /* commands of the measured node with status 0 */
static uint32_t refused;         /* commands of the measured node with another status */
static uint64_t announce_ticks;
static const uint8_t key[TVO_AUTH_KEY_BYTES] = {9, 8, 7, 6, 5, 4, 3, 2, 1, 0, 11, 12, 13, 14, 15, 16,
                                                17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32};

static void fail(const char *what)
{
    tvo_board_puts("PERIOD_ERROR ");
    tvo_board_puts(what);
    tvo_board_puts("\n");
    tvo_board_exit(1);
}

/* A command of the measured node (its frame signed; the message is what precedes the trailer). */
static void take_command(const uint8_t *data, uint32_t length)
{
    tvo_lcm_unicycle_command_t command;
    if (length < TVO_AUTH_TRAILER_BYTES ||
        tvo_lcm_unicycle_command_t_decode(data, 0, (int)(length - TVO_AUTH_TRAILER_BYTES), &command) < 0) {
        fail("a command that does not decode");
    }
    if (command.header.status == 0) {
        ++computed;
        robot_t *r = &robots[command.header.robot];
        r->speed_mps = command.speed_mps;
        r->turn_rate_radps = command.turn_rate_radps;
    } else {
        ++refused;
    }
}

static void measured_transport(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    if (channel == TVO_NODE_CH_COMMAND) {
        take_command(data, length);
    }
}

/* fleet8: the joint command from the node that drives every robot (its robot 7 is the measured node's). */
static void driver_publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    tvo_lcm_unicycle_command_t command;
    if (channel == TVO_NODE_CH_COMMAND && tvo_lcm_unicycle_command_t_decode(data, 0, (int)length, &command) >= 0 &&
        command.header.status == 0 && command.header.robot < FLEET_ROBOTS - 1) {
        robots[command.header.robot].speed_mps = command.speed_mps;
        robots[command.header.robot].turn_rate_radps = command.turn_rate_radps;
    }
}

/* The exact unicycle arc over dt_s under the robot's command. */
static void move(robot_t *r, double dt_s)
{
    const double w = r->turn_rate_radps;
    const double v = r->speed_mps;
    const double h0 = r->heading_rad;
    if (fabs(w) < 1e-9) {
        r->x_m += v * dt_s * cos(h0);
        r->y_m += v * dt_s * sin(h0);
    } else {
        r->x_m += v / w * (sin(h0 + w * dt_s) - sin(h0));
        r->y_m -= v / w * (cos(h0 + w * dt_s) - cos(h0));
    }
    r->heading_rad = atan2(sin(h0 + w * dt_s), cos(h0 + w * dt_s));
}

/* The paper's loop (tvo_protocol_default_start), lockstep, at 2 m/s: the bench's session. */
static void session_defaults(int32_t robot_count)
{
    (void)tvo_protocol_default_start(&start, robot_count); /* 1 .. FLEET_ROBOTS: in range */
    start.utime = START_UTIME;
    start.session_id = 77;
    for (int32_t r = 0; r < robot_count; ++r) {
        start.node_boot_id[r] = BOOT_ID;
    }
    start.epoch_utime = EPOCH_UTIME;
    start.speed_max_mps = 2.0;
}

/* bench_problems.h's "unicycle": an ellipse (3 m x 1.5 m, one turn in 10 s), the robot from (-1, -2). */
static void unicycle_session(void)
{
    session_defaults(1);
    tvo_lcm_path_t *path = &start.robot[0].target;
    path->kind = TVO_LCM_PATH_T_KIND_ELLIPSE;
    path->semi_axis_m[0] = 3.0;
    path->semi_axis_m[1] = 1.5;
    path->omega_radps = 2.0 * PI_D / 10.0;
    memset(robots, 0, sizeof(robots));
    robots[0].x_m = -1.0;
    robots[0].y_m = -2.0;
}

#if TVO_MAX_ROBOTS >= FLEET_ROBOTS && TVO_MAX_DISTANCE_BOUNDS >= FLEET_ROBOTS
/* bench_problems.h's "formation8": points on a circle of 2 m turning at 0.2 rad/s, a ring of distance
 * bounds between neighbours (0.5 to 1.5 times their spacing), each robot 0.3 m off its point. */
static void formation8_session(void)
{
    session_defaults(FLEET_ROBOTS);
    const double spacing_m = 2.0 * 2.0 * sin(PI_D / FLEET_ROBOTS);
    memset(robots, 0, sizeof(robots));
    for (int32_t r = 0; r < FLEET_ROBOTS; ++r) {
        const double phase = 2.0 * PI_D * r / FLEET_ROBOTS;
        tvo_lcm_path_t *path = &start.robot[r].target;
        path->kind = TVO_LCM_PATH_T_KIND_CIRCLE;
        path->semi_axis_m[0] = 2.0;
        path->omega_radps = 0.2;
        path->phase_rad = phase;
        robots[r].x_m = 2.3 * cos(phase);
        robots[r].y_m = 2.3 * sin(phase);
        robots[r].heading_rad = phase + 0.5 * PI_D;
        start.distance[r].robot_a = r;
        start.distance[r].robot_b = (r + 1) % FLEET_ROBOTS;
        start.distance[r].min_m = 0.5 * spacing_m;
        start.distance[r].max_m = 1.5 * spacing_m;
    }
    start.distance_count = FLEET_ROBOTS;
}
#endif

/* The plant's frame of robot r's sample of period n (signed), its length. */
static uint32_t sample_frame(int32_t r, uint32_t n)
{
    tvo_lcm_unicycle_sample_t sample;
    memset(&sample, 0, sizeof(sample));
    sample.header.utime = EPOCH_UTIME + (int64_t)n * PERIOD_US + PERIOD_US - DELAY_US;
    sample.header.session_id = start.session_id;
    sample.header.sequence = (int32_t)n;
    sample.header.robot = (int8_t)r;
    sample.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    sample.position_m[0] = robots[r].x_m;
    sample.position_m[1] = robots[r].y_m;
    sample.heading_rad = (float)robots[r].heading_rad;
    sample.speed_mps = (float)robots[r].speed_mps;
    const int bytes = tvo_lcm_unicycle_sample_t_encode(frame, 0, (int)sizeof(frame), &sample);
    size_t signed_length = 0u;
    if (bytes <= 0 || tvo_auth_sign(&plant, TVO_CHANNEL_SAMPLE, frame, (size_t)bytes, sizeof(frame), &signed_length) !=
                          TVO_AUTH_OK) {
        fail("sample encode");
    }
    return (uint32_t)signed_length;
}

/* Insertion sort of a copy, for the median: bounded, no library. */
static uint32_t median_ticks(const uint32_t *values, uint32_t count)
{
    static uint32_t sorted[BENCH_PERIODS];
    for (uint32_t i = 0u; i < count && i < BENCH_PERIODS; ++i) {
        const uint32_t v = values[i];
        uint32_t j = i;
        while (j > 0u && sorted[j - 1u] > v) {
            sorted[j] = sorted[j - 1u];
            --j;
        }
        sorted[j] = v;
    }
    return sorted[count / 2u];
}

static uint32_t instructions(uint64_t ticks)
{
    return (uint32_t)((ticks * TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM) / TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN);
}

/* Runs BENCH_PERIODS keyed periods of the session in `start` on a node of own_robot; prints the line. */
static void run(const char *name, int8_t own_robot, int32_t robot_count)
{
    computed = 0u;
    refused = 0u;
    announce_ticks = 0u;
    if (tvo_auth_init(&plant, key, TVO_AUTH_SENDER_PLANT, 1000u) != TVO_AUTH_OK ||
        tvo_auth_link_init(&link, key, own_robot >= 0 ? TVO_AUTH_SENDER_FLEET_NODE + (uint32_t)own_robot : TVO_AUTH_SENDER_NODE,
                           BOOT_ID, measured_transport, NULL) != TVO_AUTH_OK ||
        tvo_node_init(&node, own_robot, BOOT_ID, tvo_auth_link_publish, &link) != 0) {
        fail("set-up");
    }
    const int fleet = own_robot >= 0;
    if (fleet && tvo_node_init(&driver, -1, BOOT_ID, driver_publish, NULL) != 0) {
        fail("driver set-up");
    }
    int64_t now_us = 1000;
    (void)tvo_node_poll(&node, now_us);
    const int bytes = tvo_lcm_session_t_encode(frame, 0, (int)sizeof(frame), &start);
    size_t signed_length = 0u;
    if (bytes <= 0 || tvo_auth_sign(&plant, TVO_CHANNEL_SESSION, frame, (size_t)bytes, sizeof(frame), &signed_length) !=
                          TVO_AUTH_OK) {
        fail("start encode");
    }
    (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SESSION, frame, (uint32_t)signed_length, now_us);
    if (fleet) {
        (void)tvo_node_handle(&driver, TVO_NODE_CH_SESSION, frame, (uint32_t)bytes, now_us);
    }
    if (tvo_node_session(&node) == NULL || (fleet && tvo_node_session(&driver) == NULL)) {
        fail("the START was refused");
    }
    const uint32_t telemetry_every = tvo_node_session(&node)->schedule.timing.telemetry_every;
    for (uint32_t n = 0u; n < BENCH_PERIODS; ++n) {
        /* Period n: the robots are sampled tau before its apply instant ... */
        for (int32_t r = 0; r < robot_count; ++r) {
            move(&robots[r], (double)(PERIOD_US - DELAY_US) * 1e-6);
        }
        now_us += PERIOD_US;
        uint64_t ticks = 0u;
        for (int32_t r = 0; r < robot_count; ++r) {
            const uint32_t length = sample_frame(r, n);
            if (fleet) { /* the driver first: its commands apply with the measured node's */
                (void)tvo_node_handle(&driver, TVO_NODE_CH_SAMPLE, frame, length - TVO_AUTH_TRAILER_BYTES, now_us);
            }
            const uint32_t t0 = tvo_board_cycle_counter_read();
            (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SAMPLE, frame, length, now_us);
            const uint32_t t1 = tvo_board_cycle_counter_read();
            ticks += tvo_board_cycle_counter_elapsed(t0, t1);
        }
        period_ticks[n] = (uint32_t)ticks;
        const uint32_t t0 = tvo_board_cycle_counter_read();
        (void)tvo_node_poll(&node, now_us);
        announce_ticks += tvo_board_cycle_counter_elapsed(t0, tvo_board_cycle_counter_read());
        /* ... and move on to the next sampling instant under the commands that apply now. */
        for (int32_t r = 0; r < robot_count; ++r) {
            move(&robots[r], (double)DELAY_US * 1e-6);
        }
    }
    if (computed != BENCH_PERIODS || refused != 0u || telemetry_every == 0u || BENCH_PERIODS % telemetry_every != 0u) {
        tvo_board_puts("PERIOD_ERROR ");
        tvo_board_puts(name);
        tvo_board_puts(" computed ");
        tvo_board_put_u32(computed);
        tvo_board_puts(" refused ");
        tvo_board_put_u32(refused);
        tvo_board_puts("\n");
        tvo_board_exit(1);
    }
    uint64_t sum = 0u;
    uint32_t min = UINT32_MAX;
    uint32_t max = 0u;
    for (uint32_t n = 0u; n < BENCH_PERIODS; ++n) {
        sum += period_ticks[n];
        min = period_ticks[n] < min ? period_ticks[n] : min;
        max = period_ticks[n] > max ? period_ticks[n] : max;
    }
    tvo_board_puts("PERIOD ");
    tvo_board_puts(name);
    tvo_board_puts(" periods ");
    tvo_board_put_u32(BENCH_PERIODS);
    tvo_board_puts(" mean ");
    tvo_board_put_u32(instructions((sum + BENCH_PERIODS / 2u) / BENCH_PERIODS));
    tvo_board_puts(" median ");
    tvo_board_put_u32(instructions(median_ticks(period_ticks, BENCH_PERIODS)));
    tvo_board_puts(" min ");
    tvo_board_put_u32(instructions(min));
    tvo_board_puts(" max ");
    tvo_board_put_u32(instructions(max));
    tvo_board_puts(" telemetry_every ");
    tvo_board_put_u32(telemetry_every);
    tvo_board_puts(" announce ");
    tvo_board_put_u32(instructions((announce_ticks + BENCH_PERIODS / 2u) / BENCH_PERIODS));
    tvo_board_puts("\n");
}

/* What a forged frame costs the node, by kind, through the same link while the session runs (after the
 * unicycle run): a sample with a forged tag from the plant's sender id (a verify), from an unknown
 * sender, cut short, with another fingerprint, and a replay of the plant's last sample. The median of
 * FORGED_REPEATS each: "FORGED <kind> instr <n>". Each must be dropped. */
#define FORGED_REPEATS 33u
static void forged_frames(void)
{
    static const char *const names[5] = {"forged_tag", "unknown_sender", "cut_short", "other_fingerprint", "replay"};
    static uint8_t genuine[sizeof(frame)];
    static uint32_t ticks[FORGED_REPEATS];
    const uint32_t length = sample_frame(0, BENCH_PERIODS - 1u); /* a sample of a period the node has served */
    memcpy(genuine, frame, length);
    (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SAMPLE, frame, length, 0); /* now a replay */
    for (uint32_t kind = 0u; kind < 5u; ++kind) {
        for (uint32_t i = 0u; i < FORGED_REPEATS; ++i) {
            memcpy(frame, genuine, length);
            uint8_t *trailer = frame + length - TVO_AUTH_TRAILER_BYTES;
            uint32_t n = length;
            if (kind <= 1u) {
                const uint32_t sender = kind == 1u ? 0x10000u + i : TVO_AUTH_SENDER_PLANT;
                trailer[0] = (uint8_t)(sender >> 24);
                trailer[1] = (uint8_t)(sender >> 16);
                trailer[2] = (uint8_t)(sender >> 8);
                trailer[3] = (uint8_t)sender;
                trailer[4] = 0x40u; /* a counter far above the plant's */
                trailer[11] = (uint8_t)i;
                trailer[12] ^= 0x01u;
            } else if (kind == 2u) {
                n = length - 1u;
            } else if (kind == 3u) {
                frame[0] ^= 0x5au;
            }
            const uint32_t drops = link.drops;
            const uint32_t t0 = tvo_board_cycle_counter_read();
            (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SAMPLE, frame, n, 0);
            ticks[i] = tvo_board_cycle_counter_elapsed(t0, tvo_board_cycle_counter_read());
            if (link.drops != drops + 1u) {
                fail("a forged frame was not dropped");
            }
        }
        tvo_board_puts("FORGED ");
        tvo_board_puts(names[kind]);
        tvo_board_puts(" instr ");
        tvo_board_put_u32(instructions(median_ticks(ticks, FORGED_REPEATS)));
        tvo_board_puts("\n");
    }
}

int main(void)
{
    if (tvo_node_check_buffer() != 0) {
        fail("node buffer");
    }
    tvo_board_cycle_counter_start();
    unicycle_session();
    run("unicycle", -1, 1);
    forged_frames();
#if TVO_MAX_ROBOTS >= FLEET_ROBOTS && TVO_MAX_DISTANCE_BOUNDS >= FLEET_ROBOTS
    formation8_session();
    run("fleet8", FLEET_ROBOTS - 1, FLEET_ROBOTS);
#else
    tvo_board_puts("PERIOD_SKIP fleet8\n");
#endif
    tvo_board_puts("PERIOD_DONE\n");
    tvo_board_exit(0);
}
