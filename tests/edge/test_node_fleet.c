/*
 * Sessions of several robots (firmware/edge/node_period.c): one sample per robot and period, gathered
 * per robot; the period's last robot's sample steps it. Every node of a fleet (own_robot k) computes
 * the rows a node driving every robot computes from the same samples, bit for bit (with the fleet
 * build, test_node_fleet_fleet: 8 robots); a missing sample is predicted along the arcs of the node's
 * own joint commands (tau of the one before, h - tau of the last); a late one becomes the base of the
 * next prediction; strays and reordering cost at most a prediction; a robot never heard, or heard too
 * long ago, is not invented; a refused period keeps nothing (the session byte for byte); a bad sample
 * of another robot is refused and counted, unanswered.
 */
#include "edge_fixture.h"

#define H_S (EF_PERIOD_US * 1e-6)
#define TAU_S (EF_DELAY_US * 1e-6)
#define N TVO_NODE_MAX_ROBOTS /* a fleet of as many robots as the build drives */

void setUp(void);
void tearDown(void);

static tvo_node_t node;          /* drives every robot */
static ef_record_t rec;
static uint8_t wire[16384];
static int32_t robots;           /* of the running session */
static tvo_lcm_session_t start;

/* The node's own announcements are not the subject here. */
static void record(void *context, int channel, const uint8_t *data, uint32_t length)
{
    if (channel != TVO_NODE_CH_NODE) {
        ef_record_publish(context, channel, data, length);
    }
}

static void start_node(tvo_node_t *n, int8_t own_robot, ef_record_t *r, int32_t count, int32_t clock)
{
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(n, own_robot, EF_BOOT, record, r));
    ef_start(&start, EF_SESSION_ID, clock, count);
    const int len = tvo_lcm_session_t_encode(wire, 0, (int)sizeof(wire), &start);
    TEST_ASSERT_TRUE(len > 0);
    ef_record_clear(r);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, tvo_node_handle(n, TVO_NODE_CH_SESSION, wire, (uint32_t)len, 0));
    TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(r, TVO_NODE_CH_SESSION_ACK));
    TEST_ASSERT_NOT_NULL(tvo_node_session(n));
    ef_record_clear(r);
}

void setUp(void)
{
    robots = 2;
    start_node(&node, -1, &rec, robots, TVO_LCM_SESSION_T_CLOCK_PLANT);
}
void tearDown(void) {}

/* Robot r's pose at sample n: moving so that the law's commands change from period to period. */
static void pose(int32_t r, int64_t n, double *x, double *y, float *heading)
{
    *x = 0.01 * (double)n + 0.3 * (double)r;
    *y = (double)r + 0.002 * (double)(n * n) * (r % 2 == 0 ? 1.0 : -1.0);
    *heading = (float)(0.05 * (double)n * (r % 2 == 0 ? 1.0 : 0.5));
}

static int64_t stamp(int64_t n)
{
    return EF_EPOCH + (n + 1) * EF_PERIOD_US - EF_DELAY_US;
}

static void sample_of(int32_t r, int64_t n, tvo_lcm_unicycle_sample_t *s)
{
    ef_sample(s, EF_SESSION_ID, stamp(n), (int32_t)n, (int8_t)r);
    pose(r, n, &s->position_m[0], &s->position_m[1], &s->heading_rad);
}

static int send_to(tvo_node_t *n, const tvo_lcm_unicycle_sample_t *s, int64_t now_us)
{
    const int len = tvo_lcm_unicycle_sample_t_encode(wire, 0, (int)sizeof(wire), s);
    TEST_ASSERT_TRUE(len > 0);
    return tvo_node_handle(n, TVO_NODE_CH_SAMPLE, wire, (uint32_t)len, now_us);
}

static void send_sample(int32_t r, int64_t n)
{
    tvo_lcm_unicycle_sample_t s;
    sample_of(r, n, &s);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_to(&node, &s, 0));
}

/* The k-th command published since the last clear, decoded. */
static tvo_lcm_unicycle_command_t command_nth(const ef_record_t *r, uint32_t k)
{
    tvo_lcm_unicycle_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    const ef_message_t *m = ef_record_nth(r, TVO_NODE_CH_COMMAND, k);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, "no such command");
    if (m != NULL) {
        TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_unicycle_command_t_decode(m->data, 0, (int)m->length, &cmd));
    }
    return cmd;
}

static tvo_lcm_telemetry_t telemetry_nth(const ef_record_t *r, uint32_t k)
{
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    const ef_message_t *m = ef_record_nth(r, TVO_NODE_CH_TELEMETRY, k);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, "no such telemetry");
    if (m != NULL) {
        TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_telemetry_t_decode(m->data, 0, (int)m->length, &tel));
    }
    return tel;
}

/* The node's answer to period n (every robot's command and telemetry, robot order), the samples of
 * the robots in `lost` (a bit per robot) not sent; checks the answer's shape. */
typedef struct {
    tvo_lcm_unicycle_command_t cmd[TVO_MAX_ROBOTS];
    tvo_lcm_telemetry_t tel[TVO_MAX_ROBOTS];
} answer_t;

static void period(int64_t n, uint32_t lost, answer_t *out)
{
    ef_record_clear(&rec);
    for (int32_t r = 0; r < robots; ++r) {
        if ((lost & (1u << r)) == 0u) {
            send_sample(r, n);
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, rec.overflow);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)robots, ef_record_count(&rec, TVO_NODE_CH_COMMAND));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)robots, ef_record_count(&rec, TVO_NODE_CH_TELEMETRY));
    double speed[TVO_MAX_ROBOTS], turn[TVO_MAX_ROBOTS];
    for (int32_t r = 0; r < robots; ++r) {
        out->cmd[r] = command_nth(&rec, (uint32_t)r);
        out->tel[r] = telemetry_nth(&rec, (uint32_t)r);
        TEST_ASSERT_EQUAL_INT(r, out->cmd[r].header.robot);
        TEST_ASSERT_EQUAL_INT(r, out->tel[r].header.robot);
        TEST_ASSERT_EQUAL_INT32((int32_t)n, out->cmd[r].header.measurement_sequence);
        TEST_ASSERT_EQUAL_INT(out->cmd[0].header.status, out->cmd[r].header.status); /* one header for all */
        TEST_ASSERT_EQUAL_INT(out->cmd[0].header.flags, out->cmd[r].header.flags);
        TEST_ASSERT_EQUAL_INT64(out->cmd[0].header.utime, out->cmd[r].header.utime);
        speed[r] = (double)out->cmd[r].speed_mps;
        turn[r] = (double)out->cmd[r].turn_rate_radps;
    }
    for (int32_t r = 0; r < robots; ++r) {
        TEST_ASSERT_TRUE(tvo_joint_digest(speed, turn, robots) == (uint64_t)out->tel[r].joint_digest);
        TEST_ASSERT_EQUAL_INT(out->tel[0].predicted_robots, out->tel[r].predicted_robots);
    }
}

static void arc(double *x, double *y, double *heading, double v, double w, double dt)
{
    if (fabs(w) < 1e-9) {
        *x += v * cos(*heading) * dt;
        *y += v * sin(*heading) * dt;
    } else {
        *x += v / w * (sin(*heading + w * dt) - sin(*heading));
        *y += v / w * (cos(*heading) - cos(*heading + w * dt));
        *heading += w * dt;
    }
}

/* ------------------------------------------------------------------------------------------------ */

/* N nodes, each driving one robot, and one driving all, on the same samples in robot order: every
 * node's command is the central node's row for its robot, byte for byte, every digest the same. */
static void test_every_node_of_a_fleet_computes_the_central_nodes_rows_bit_for_bit(void)
{
    static tvo_node_t members[N];
    static ef_record_t member_rec[N];
    robots = N;
    start_node(&node, -1, &rec, N, TVO_LCM_SESSION_T_CLOCK_PLANT);
    for (int8_t k = 0; k < N; ++k) {
        start_node(&members[k], k, &member_rec[k], N, TVO_LCM_SESSION_T_CLOCK_PLANT);
    }
    int moved = 0;
    for (int64_t n = 0; n < 25; ++n) {
        ef_record_clear(&rec);
        for (int k = 0; k < N; ++k) {
            ef_record_clear(&member_rec[k]);
        }
        for (int32_t r = 0; r < N; ++r) {
            tvo_lcm_unicycle_sample_t s;
            sample_of(r, n, &s);
            TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_to(&node, &s, 0));
            for (int k = 0; k < N; ++k) {
                TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_to(&members[k], &s, 0));
            }
        }
        TEST_ASSERT_EQUAL_UINT32((uint32_t)N, ef_record_count(&rec, TVO_NODE_CH_COMMAND));
        const tvo_lcm_telemetry_t central_tel = telemetry_nth(&rec, 0u);
        TEST_ASSERT_EQUAL_INT(0, central_tel.predicted_robots);
        for (int k = 0; k < N; ++k) {
            TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&member_rec[k], TVO_NODE_CH_COMMAND));
            TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&member_rec[k], TVO_NODE_CH_TELEMETRY));
            const ef_message_t *want = ef_record_nth(&rec, TVO_NODE_CH_COMMAND, (uint32_t)k);
            const ef_message_t *got = ef_record_nth(&member_rec[k], TVO_NODE_CH_COMMAND, 0u);
            TEST_ASSERT_NOT_NULL(want);
            TEST_ASSERT_NOT_NULL(got);
            TEST_ASSERT_EQUAL_UINT32(want->length, got->length);
            TEST_ASSERT_EQUAL_MEMORY(want->data, got->data, want->length);
            const ef_message_t *want_tel = ef_record_nth(&rec, TVO_NODE_CH_TELEMETRY, (uint32_t)k);
            const ef_message_t *got_tel = ef_record_nth(&member_rec[k], TVO_NODE_CH_TELEMETRY, 0u);
            TEST_ASSERT_NOT_NULL(want_tel);
            TEST_ASSERT_NOT_NULL(got_tel);
            TEST_ASSERT_EQUAL_MEMORY(want_tel->data, got_tel->data, want_tel->length);
            const tvo_lcm_unicycle_command_t cmd = command_nth(&member_rec[k], 0u);
            EF_ASSERT_STATUS(TVO_OK, cmd.header.status);
            TEST_ASSERT_EQUAL_INT(k, cmd.header.robot);
            moved |= (k == N - 1 && cmd.speed_mps != 0.0f);
        }
    }
    TEST_ASSERT_TRUE(moved); /* the last robot was driven, not held at rest */
    TEST_ASSERT_EQUAL_INT32(25, node.counters.accepted);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.predicted);
}

static void test_a_missing_sample_is_predicted_along_the_nodes_commands(void)
{
    answer_t answer[9];
    for (int64_t n = 0; n < 6; ++n) {
        period(n, 0u, &answer[n]);
        EF_ASSERT_STATUS(TVO_OK, answer[n].cmd[0].header.status);
    }
    period(6, 1u, &answer[6]); /* robot 0's sample of period 6 lost */
    EF_ASSERT_STATUS(TVO_OK, answer[6].cmd[0].header.status);
    TEST_ASSERT_EQUAL_INT(1, answer[6].tel[0].predicted_robots);
    TEST_ASSERT_EQUAL_INT32(1, node.counters.predicted);
    /* Robot 0 at sample 5, along the command answering 4 for tau, then the one answering 5 for h - tau. */
    double x = 0.0, y = 0.0, heading = 0.0;
    float h32 = 0.0f;
    pose(0, 5, &x, &y, &h32);
    heading = (double)h32;
    arc(&x, &y, &heading, (double)answer[4].cmd[0].speed_mps, (double)answer[4].cmd[0].turn_rate_radps, TAU_S);
    arc(&x, &y, &heading, (double)answer[5].cmd[0].speed_mps, (double)answer[5].cmd[0].turn_rate_radps, H_S - TAU_S);
    const tvo_step_robot_state_t *p = &node.work.rows.predicted[0];
    TEST_ASSERT_NULL(node.work.rows.sample[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, x, p->position_m[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, y, p->position_m[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, heading, p->heading_rad);
    TEST_ASSERT_TRUE(answer[5].cmd[0].speed_mps != 0.0f); /* a real motion was predicted */
    /* The core got it, rounded once to its scalar. */
    TEST_ASSERT_TRUE(node.work.measurement.unicycle.position_m[0][0] == (tvo_real_t)p->position_m[0]);
    /* The late sample of period 6 replaces the prediction as the base of the next one. */
    ef_record_clear(&rec);
    send_sample(0, 6);
    TEST_ASSERT_EQUAL_UINT32(0u, rec.count); /* another robot's: unanswered */
    double lx = 0.0, ly = 0.0, lh = 0.0;
    pose(0, 6, &lx, &ly, &h32);
    lh = (double)h32;
    const tvo_step_robot_state_t *known = &tvo_node_session(&node)->gathering.known[0];
    TEST_ASSERT_TRUE(known->position_m[0] == lx && known->position_m[1] == ly && known->sequence == 6);
    period(7, 1u, &answer[7]);
    arc(&lx, &ly, &lh, (double)answer[5].cmd[0].speed_mps, (double)answer[5].cmd[0].turn_rate_radps, TAU_S);
    arc(&lx, &ly, &lh, (double)answer[6].cmd[0].speed_mps, (double)answer[6].cmd[0].turn_rate_radps, H_S - TAU_S);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, lx, node.work.rows.predicted[0].position_m[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, ly, node.work.rows.predicted[0].position_m[1]);
    TEST_ASSERT_EQUAL_INT(1, answer[7].tel[0].predicted_robots);
    /* Heard again: measured. */
    period(8, 0u, &answer[8]);
    TEST_ASSERT_EQUAL_INT(0, answer[8].tel[0].predicted_robots);
    TEST_ASSERT_EQUAL_INT32(2, node.counters.predicted);
}

static void test_a_robot_never_heard_or_heard_too_long_ago_is_not_invented(void)
{
    answer_t a;
    period(0, 1u, &a); /* robot 0 never heard */
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT, a.cmd[0].header.status);
    TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)a.cmd[0].header.flags);
    TEST_ASSERT_TRUE(a.cmd[0].speed_mps == 0.0f && a.cmd[1].speed_mps == 0.0f);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.accepted); /* the core never stepped */
    TEST_ASSERT_EQUAL_INT32(1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT]);
    period(1, 0u, &a); /* heard: steps */
    EF_ASSERT_STATUS(TVO_OK, a.cmd[0].header.status);
    TEST_ASSERT_EQUAL_INT32(1, node.counters.accepted);
    /* Silent for watchdog_periods periods: predicted; one more: not. */
    for (int64_t n = 2; n < 2 + EF_WATCHDOG; ++n) {
        period(n, 1u, &a);
        EF_ASSERT_STATUS(TVO_OK, a.cmd[0].header.status);
        TEST_ASSERT_EQUAL_INT(1, a.tel[0].predicted_robots);
    }
    period(2 + EF_WATCHDOG, 1u, &a);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT, a.cmd[0].header.status);
    TEST_ASSERT_EQUAL_INT(0, a.tel[0].predicted_robots);
}

static void test_a_stray_ahead_costs_at_most_one_prediction_and_reordering_one_too(void)
{
    answer_t a;
    period(0, 0u, &a);
    period(1, 0u, &a);
    /* A stray far ahead after the genuine sample of period 2: it replaces it, is not used (robot 0
     * predicted), and gives way to the next genuine sample. */
    ef_record_clear(&rec);
    send_sample(0, 2);
    tvo_lcm_unicycle_sample_t stray;
    sample_of(0, 1000, &stray);
    (void)send_to(&node, &stray, 0);
    send_sample(1, 2);
    TEST_ASSERT_EQUAL_INT(1, telemetry_nth(&rec, 0u).predicted_robots);
    period(3, 0u, &a);
    EF_ASSERT_STATUS(TVO_OK, a.cmd[0].header.status);
    TEST_ASSERT_EQUAL_INT(0, a.tel[0].predicted_robots);
    /* A stray before the genuine sample: the genuine one replaces it, nothing is predicted. */
    ef_record_clear(&rec);
    sample_of(0, 4000, &stray);
    (void)send_to(&node, &stray, 0);
    send_sample(0, 4);
    send_sample(1, 4);
    TEST_ASSERT_EQUAL_INT(0, telemetry_nth(&rec, 0u).predicted_robots);
    /* Reordered: robot 0's sample of 6 before its sample of 5. The newer is kept: 5 is predicted,
     * 6 measured. */
    ef_record_clear(&rec);
    send_sample(0, 6);
    send_sample(0, 5);
    send_sample(1, 5);
    TEST_ASSERT_EQUAL_INT(1, telemetry_nth(&rec, 0u).predicted_robots);
    EF_ASSERT_STATUS(TVO_OK, command_nth(&rec, 0u).header.status);
    ef_record_clear(&rec);
    send_sample(1, 6);
    TEST_ASSERT_EQUAL_INT(0, telemetry_nth(&rec, 0u).predicted_robots);
    EF_ASSERT_STATUS(TVO_OK, command_nth(&rec, 0u).header.status);
}

/* The session, byte for byte, without the controller's scratch and the anchor's votes and streak. */
static tvo_node_session_t before;
static void keep_session(void)
{
    memcpy(&before, tvo_node_session(&node), sizeof(before));
    tvo_edge_controller_clear_scratch(&before.controller);
}
static void assert_session_kept(int line)
{
    static tvo_node_session_t after;
    memcpy(&after, tvo_node_session(&node), sizeof(after));
    tvo_edge_controller_clear_scratch(&after.controller);
    before.schedule.votes = after.schedule.votes;
    before.schedule.vote_value = after.schedule.vote_value;
    ef_copy_refusals_in_row(&before.controller, &after.controller); /* the streak rule */
    before.schedule.clock.plant.vote_period = after.schedule.clock.plant.vote_period;
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&before, &after, sizeof(before), line, "the session changed");
}
#define ASSERT_SESSION_KEPT() assert_session_kept(__LINE__)

static void test_a_refused_period_keeps_nothing_of_what_it_gathered(void)
{
    answer_t a;
    period(0, 0u, &a);
    period(1, 0u, &a);
    /* Robot 0's sample of 2 is gathered; robot 1's (the trigger) is refused by the schedule (a
     * stamp 20 s ahead) and then by the core (not finite): each period keeps nothing, robot 0's
     * sample stays for the genuine trigger, which then needs no prediction. */
    ef_record_clear(&rec);
    send_sample(0, 2);
    keep_session();
    TEST_ASSERT_EQUAL_UINT8(1u, before.gathering.has_pending[0]);
    tvo_lcm_unicycle_sample_t trigger;
    sample_of(1, 2, &trigger);
    trigger.header.utime += 20000000;
    (void)send_to(&node, &trigger, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, command_nth(&rec, 0u).header.status);
    ASSERT_SESSION_KEPT();
    ef_record_clear(&rec);
    sample_of(1, 2, &trigger);
    trigger.position_m[1] = (double)NAN;
    (void)send_to(&node, &trigger, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE, command_nth(&rec, 0u).header.status);
    TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)command_nth(&rec, 1u).header.flags);
    ASSERT_SESSION_KEPT();
    /* A period refused with a prediction in it keeps neither the prediction nor the commands. */
    period(3, 1u, &a); /* predicted robot 0, committed */
    keep_session();
    ef_record_clear(&rec);
    sample_of(1, 4, &trigger);
    trigger.position_m[0] = (double)INFINITY;
    (void)send_to(&node, &trigger, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE, command_nth(&rec, 0u).header.status);
    TEST_ASSERT_EQUAL_INT(1, telemetry_nth(&rec, 0u).predicted_robots);
    ASSERT_SESSION_KEPT();
    ef_record_clear(&rec);
    send_sample(1, 4);
    EF_ASSERT_STATUS(TVO_OK, command_nth(&rec, 0u).header.status);
}

static void test_a_bad_sample_of_another_robot_is_refused_counted_and_unanswered(void)
{
    answer_t a;
    period(0, 0u, &a);
    keep_session();
    tvo_lcm_unicycle_sample_t s;
    const tvo_lcm_node_counters_t counters = node.counters;
    ef_record_clear(&rec);
    sample_of(0, 1, &s);
    s.position_m[0] = (double)NAN;
    (void)send_to(&node, &s, 0);
    sample_of(0, 1, &s);
    s.has |= TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    s.speed_mps = INFINITY;
    (void)send_to(&node, &s, 0);
    sample_of(0, 1, &s);
    s.heading_rad = NAN; /* has a heading: read */
    (void)send_to(&node, &s, 0);
    sample_of(0, 1, &s);
    s.header.sequence = -1;
    (void)send_to(&node, &s, 0);
    sample_of(0, 1, &s);
    s.header.utime = EF_TWO_POW_60 + 1;
    (void)send_to(&node, &s, 0);
    sample_of(0, 1, &s);
    s.header.robot = (int8_t)robots;
    (void)send_to(&node, &s, 0);
    TEST_ASSERT_EQUAL_UINT32(0u, rec.count);
    TEST_ASSERT_EQUAL_INT32(counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE] + 3,
                            node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE]);
    TEST_ASSERT_EQUAL_INT32(counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP] + 2,
                            node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP]);
    TEST_ASSERT_EQUAL_INT32(counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION] + 1,
                            node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION]);
    ASSERT_SESSION_KEPT(); /* none was gathered */
    /* Another session's: ignored, counted. */
    sample_of(0, 1, &s);
    s.header.session_id = EF_SESSION_ID + 1;
    (void)send_to(&node, &s, 0);
    TEST_ASSERT_EQUAL_INT32(counters.other_session + 1, node.counters.other_session);
    ASSERT_SESSION_KEPT();
    /* Without robot 0's sample of 1, the period predicts it. */
    ef_record_clear(&rec);
    send_sample(1, 1);
    TEST_ASSERT_EQUAL_INT(1, telemetry_nth(&rec, 0u).predicted_robots);
}

static void test_a_node_clock_session_predicts_nothing(void)
{
    robots = 2;
    start_node(&node, -1, &rec, robots, TVO_LCM_SESSION_T_CLOCK_NODE);
    /* The START arrived at node time 0 (offset -EF_UTIME); period j's apply instant on the node's
     * clock is EF_EPOCH - EF_UTIME + j h: samples of period j arrive 4 ms before it. */
    const int64_t offset = -EF_UTIME;
    for (int64_t j = 1; j <= 3; ++j) {
        const int64_t arrival = EF_EPOCH + offset + j * EF_PERIOD_US - 4000;
        ef_record_clear(&rec);
        for (int32_t r = 0; r < robots; ++r) {
            tvo_lcm_unicycle_sample_t s;
            sample_of(r, j, &s);
            s.header.utime = arrival - offset - 1000;
            if (!(j == 3 && r == 0)) {
                (void)send_to(&node, &s, arrival);
            }
        }
        const tvo_lcm_unicycle_command_t cmd = command_nth(&rec, 0u);
        EF_ASSERT_STATUS(j == 3 ? TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT : TVO_OK, cmd.header.status);
    }
    TEST_ASSERT_EQUAL_INT32(0, node.counters.predicted);
}

static void test_a_node_of_one_robot_publishes_its_row_only(void)
{
    static tvo_node_t member;
    static ef_record_t member_rec;
    start_node(&member, 0, &member_rec, robots, TVO_LCM_SESSION_T_CLOCK_PLANT);
    for (int64_t n = 0; n < 3; ++n) {
        ef_record_clear(&member_rec);
        for (int32_t r = 0; r < robots; ++r) {
            tvo_lcm_unicycle_sample_t s;
            sample_of(r, n, &s);
            (void)send_to(&member, &s, 0);
            /* Robot 0's sample is not the period's last: it steps nothing, even at the node of robot 0. */
            TEST_ASSERT_EQUAL_UINT32(r + 1 < robots ? 0u : 2u, member_rec.count);
        }
        const tvo_lcm_unicycle_command_t cmd = command_nth(&member_rec, 0u);
        TEST_ASSERT_EQUAL_INT(0, cmd.header.robot);
        EF_ASSERT_STATUS(TVO_OK, cmd.header.status);
        TEST_ASSERT_EQUAL_INT(0, telemetry_nth(&member_rec, 0u).header.robot);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_node_of_a_fleet_computes_the_central_nodes_rows_bit_for_bit);
    RUN_TEST(test_a_missing_sample_is_predicted_along_the_nodes_commands);
    RUN_TEST(test_a_robot_never_heard_or_heard_too_long_ago_is_not_invented);
    RUN_TEST(test_a_stray_ahead_costs_at_most_one_prediction_and_reordering_one_too);
    RUN_TEST(test_a_refused_period_keeps_nothing_of_what_it_gathered);
    RUN_TEST(test_a_bad_sample_of_another_robot_is_refused_counted_and_unanswered);
    RUN_TEST(test_a_node_clock_session_predicts_nothing);
    RUN_TEST(test_a_node_of_one_robot_publishes_its_row_only);
    return UNITY_END();
}
