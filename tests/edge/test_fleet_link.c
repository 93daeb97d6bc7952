/*
 * The fleet link in front of the node (fleet_link.c): a node of a 2-robot fleet fed per-robot samples
 * must compute the very command a central node computes from the joint measurement; a missing sample
 * is predicted along the arcs of the node's own joint commands (tau of the one before, h - tau of the
 * last); a late one becomes the base of the next prediction; a robot never heard is not invented.
 */
#include "edge_fixture.h"
#include "fleet_link.h"

#define ROBOTS 2
#define OWN 1
#define H_S (EF_PERIOD_US * 1e-6)
#define TAU_S (EF_DELAY_US * 1e-6)

static tvo_node_t central;
static ef_record_t central_rec;
static tvo_node_t member;
static tvo_fleet_link_t link;
static ef_record_t member_rec;
static uint8_t wire[4096];

void setUp(void)
{
    tvo_node_init(&central, ef_record_publish, &central_rec);
    ef_record_clear(&central_rec);
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_link_init(&link, &member, OWN, ef_record_publish, &member_rec));
    ef_record_clear(&member_rec);
    tvo_lcm_session_t start;
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, ROBOTS);
    const int n = tvo_lcm_session_t_encode(wire, 0, (int)sizeof(wire), &start);
    TEST_ASSERT_TRUE(n > 0);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, tvo_node_handle(&central, TVO_NODE_CH_SESSION, wire, (uint32_t)n, 0));
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, tvo_fleet_link_receive(&link, &member, TVO_NODE_CH_SESSION, wire,
                                                                      (uint32_t)n, 0));
    TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&member_rec, TVO_FLEET_CH_SESSION_ACK));
    ef_record_clear(&member_rec);
    ef_record_clear(&central_rec);
}
void tearDown(void) {}

/* Robot r's pose at sample n: moving so that the law's commands change from period to period. */
static void pose(int32_t r, int64_t n, double *x, double *y, double *heading)
{
    *x = 0.01 * (double)n + 0.3 * (double)r;
    *y = (double)r + 0.002 * (double)(n * n) * (r == 0 ? 1.0 : -1.0);
    *heading = 0.05 * (double)n * (r == 0 ? 1.0 : 0.5);
}

static int64_t stamp(int64_t n)
{
    return EF_EPOCH + (n + 1) * EF_PERIOD_US - EF_DELAY_US;
}

static void sample_of(int32_t r, int64_t n, tvo_lcm_fleet_sample_t *s)
{
    memset(s, 0, sizeof(*s));
    s->utime = stamp(n);
    s->session_id = EF_SESSION_ID;
    s->sequence = n;
    s->robot = r;
    s->robot_count = ROBOTS;
    pose(r, n, &s->position_m[0], &s->position_m[1], &s->heading_rad);
    s->heading_valid = 1;
}

static void send_sample(int32_t r, int64_t n)
{
    tvo_lcm_fleet_sample_t s;
    sample_of(r, n, &s);
    const int len = tvo_lcm_fleet_sample_t_encode(wire, 0, (int)sizeof(wire), &s);
    TEST_ASSERT_TRUE(len > 0);
    TEST_ASSERT_EQUAL_INT(TVO_FLEET_CH_SAMPLE, tvo_fleet_link_receive(&link, &member, TVO_FLEET_CH_SAMPLE, wire,
                                                                      (uint32_t)len, 0));
}

static void central_step(int64_t n, tvo_lcm_command_t *out)
{
    tvo_lcm_measurement_t m;
    ef_measurement(&m, EF_SESSION_ID, stamp(n), n, ROBOTS);
    for (int32_t r = 0; r < ROBOTS; ++r) {
        pose(r, n, &m.position_m[r][0], &m.position_m[r][1], &m.heading_rad[r]);
    }
    const int len = tvo_lcm_measurement_t_encode(wire, 0, (int)sizeof(wire), &m);
    ef_record_clear(&central_rec);
    (void)tvo_node_handle(&central, TVO_NODE_CH_MEASUREMENT, wire, (uint32_t)len, 0);
    const ef_message_t *c = ef_record_nth(&central_rec, TVO_NODE_CH_COMMAND, 0);
    if (c == NULL) {
        TEST_FAIL_MESSAGE("no central command");
        return;
    }
    TEST_ASSERT_EQUAL_INT((int)c->length, tvo_lcm_command_t_decode(c->data, 0, (int)c->length, out));
}

/* The member's answer to its own sample n (others' first if `others`), decoded. */
static void member_step(int64_t n, int others, tvo_lcm_fleet_command_t *out)
{
    ef_record_clear(&member_rec);
    if (others) {
        send_sample(0, n);
    }
    send_sample(OWN, n);
    TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&member_rec, TVO_FLEET_CH_COMMAND));
    TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&member_rec, TVO_FLEET_CH_TELEMETRY));
    const ef_message_t *c = ef_record_nth(&member_rec, TVO_FLEET_CH_COMMAND, 0);
    if (c == NULL) {
        TEST_FAIL_MESSAGE("no fleet command");
        return;
    }
    TEST_ASSERT_EQUAL_INT((int)c->length, tvo_lcm_fleet_command_t_decode(c->data, 0, (int)c->length, out));
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

static void test_digest_and_channel_names(void)
{
    tvo_fleet_joint_command_t c;
    memset(&c, 0, sizeof(c));
    c.speed_mps[0] = 1.0;
    c.turn_rate_radps[0] = -0.5;
    c.speed_mps[1] = 7.0; /* past robot_count: not digested */
    /* FNV-1a 64 over the 16 bytes of (1.0, -0.5), least significant byte first (computed apart). */
    TEST_ASSERT_TRUE(tvo_fleet_digest(&c, 1) == 0x2c18cbea19d5b735ull);
    c.turn_rate_radps[0] = nextafter(-0.5, 0.0);
    TEST_ASSERT_TRUE(tvo_fleet_digest(&c, 1) != 0x2c18cbea19d5b735ull);
    char name[TVO_FLEET_CHANNEL_NAME_BYTES];
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_channel_name(TVO_FLEET_CH_SAMPLE, 2, name, sizeof(name)));
    TEST_ASSERT_EQUAL_STRING("TVO_FLEET_SAMPLE_R2", name);
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_channel_name(TVO_FLEET_CH_SESSION_ACK, 0, name, sizeof(name)));
    TEST_ASSERT_EQUAL_STRING("TVO_SESSION_ACK_R0", name);
    TEST_ASSERT_EQUAL_INT(-1, tvo_fleet_channel_name(TVO_FLEET_CH_SAMPLE, TVO_FLEET_MAX_ROBOTS, name, sizeof(name)));
    TEST_ASSERT_EQUAL_INT(-1, tvo_fleet_channel_name(TVO_NODE_CH_COMMAND, 0, name, sizeof(name)));
    TEST_ASSERT_EQUAL_INT(-1, tvo_fleet_link_init(&link, &member, TVO_FLEET_MAX_ROBOTS, ef_record_publish, &member_rec));
}

static void test_member_computes_the_central_command(void)
{
    for (int64_t n = 0; n < 20; ++n) {
        tvo_lcm_command_t want;
        tvo_lcm_fleet_command_t got;
        central_step(n, &want);
        member_step(n, 1, &got);
        TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, want.status);
        EF_ASSERT_STATUS(want.status, got.status);
        TEST_ASSERT_EQUAL_INT(0, got.predicted);
        TEST_ASSERT_EQUAL_INT(OWN, got.robot);
        TEST_ASSERT_TRUE(got.speed_mps == want.speed_mps[OWN] && got.turn_rate_radps == want.turn_rate_radps[OWN]);
        tvo_fleet_joint_command_t rows;
        memset(&rows, 0, sizeof(rows));
        for (int32_t r = 0; r < want.robot_count; ++r) {
            rows.speed_mps[r] = want.speed_mps[r];
            rows.turn_rate_radps[r] = want.turn_rate_radps[r];
        }
        TEST_ASSERT_TRUE((uint64_t)got.joint_digest == tvo_fleet_digest(&rows, want.robot_count));
        TEST_ASSERT_TRUE(got.utime == want.utime && got.flags == want.flags);
    }
}

static void test_missing_sample_is_predicted_along_the_nodes_commands(void)
{
    tvo_lcm_fleet_command_t answer[8];
    for (int64_t n = 0; n < 6; ++n) {
        member_step(n, 1, &answer[n]);
        TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, answer[n].status);
    }
    member_step(6, 0, &answer[6]); /* robot 0's sample of period 6 lost */
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, answer[6].status);
    TEST_ASSERT_EQUAL_INT(1, answer[6].predicted);
    double x = 0.0, y = 0.0, heading = 0.0;
    pose(0, 5, &x, &y, &heading);
    arc(&x, &y, &heading, answer[4].joint_speed_mps[0], answer[4].joint_turn_rate_radps[0], TAU_S);
    arc(&x, &y, &heading, answer[5].joint_speed_mps[0], answer[5].joint_turn_rate_radps[0], H_S - TAU_S);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, x, link.joint.robot[0].position_m[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, y, link.joint.robot[0].position_m[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, heading, link.joint.robot[0].heading_rad);
    TEST_ASSERT_TRUE(x != 0.0 && answer[5].joint_speed_mps[0] != 0.0); /* a real motion was predicted */
    /* The late sample of period 6 replaces the prediction as the base of the next one. */
    send_sample(0, 6);
    TEST_ASSERT_EQUAL_UINT32(1u, link.samples_late);
    double lx = 0.0, ly = 0.0, lh = 0.0;
    pose(0, 6, &lx, &ly, &lh);
    TEST_ASSERT_TRUE(link.known[0].position_m[0] == lx && link.known[0].position_m[1] == ly);
    member_step(7, 0, &answer[7]);
    arc(&lx, &ly, &lh, answer[5].joint_speed_mps[0], answer[5].joint_turn_rate_radps[0], TAU_S);
    arc(&lx, &ly, &lh, answer[6].joint_speed_mps[0], answer[6].joint_turn_rate_radps[0], H_S - TAU_S);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, lx, link.joint.robot[0].position_m[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, ly, link.joint.robot[0].position_m[1]);
    TEST_ASSERT_EQUAL_INT(1, answer[7].predicted);
}

static void test_a_robot_never_heard_is_not_invented(void)
{
    tvo_lcm_fleet_command_t got;
    member_step(0, 0, &got);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_ERR_NO_MEASUREMENT, got.status);
    TEST_ASSERT_TRUE(((uint32_t)got.flags & TVO_LCM_COMMAND_T_FLAG_HOLDING) != 0u);
    TEST_ASSERT_TRUE(got.speed_mps == 0.0 && got.turn_rate_radps == 0.0);
    TEST_ASSERT_EQUAL_INT32(0, member.counters.accepted); /* the node never stepped */
    TEST_ASSERT_EQUAL_UINT32(1u, link.unheard_steps);
    member_step(1, 1, &got); /* heard: steps */
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, got.status);
    TEST_ASSERT_EQUAL_INT32(1, member.counters.accepted);
}

static void test_a_stray_from_the_future_costs_one_period(void)
{
    tvo_lcm_fleet_command_t got;
    member_step(0, 1, &got);
    member_step(1, 1, &got);
    ef_record_clear(&member_rec);
    send_sample(0, 1000); /* a stray far ahead: kept until the next step, then dropped */
    member_step(2, 0, &got);
    TEST_ASSERT_EQUAL_INT(1, got.predicted);
    member_step(3, 1, &got); /* the genuine sample is used again */
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, got.status);
    TEST_ASSERT_EQUAL_INT(0, got.predicted);
}

static void test_bad_samples_are_refused(void)
{
    tvo_lcm_fleet_sample_t s;
    sample_of(0, 0, &s);
    s.position_m[1] = (double)NAN;
    int len = tvo_lcm_fleet_sample_t_encode(wire, 0, (int)sizeof(wire), &s);
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_link_receive(&link, &member, TVO_FLEET_CH_SAMPLE, wire, (uint32_t)len, 0));
    sample_of(0, 0, &s);
    s.robot = ROBOTS; /* not a robot of the session */
    len = tvo_lcm_fleet_sample_t_encode(wire, 0, (int)sizeof(wire), &s);
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_link_receive(&link, &member, TVO_FLEET_CH_SAMPLE, wire, (uint32_t)len, 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_link_receive(&link, &member, TVO_FLEET_CH_SAMPLE, wire, 3u, 0));
    TEST_ASSERT_EQUAL_UINT32(3u, link.samples_refused);
    TEST_ASSERT_EQUAL_UINT32(0u, member_rec.count); /* unanswered */
}

/* An answer that must never be called (its node refuses it). */
static void test_answer_unused(void *context, const tvo_step_stamp_t *stamp, uint32_t wire_flags, const tvo_command_t *command)
{
    (void)context;
    (void)stamp;
    (void)wire_flags;
    (void)command;
    TEST_FAIL_MESSAGE("an answer the node refused was called");
}

/* A START to a node (the fleet link's if link_node is its node): its ack's status and bad_param. */
static void start_answer(tvo_lcm_session_t *start, tvo_fleet_link_t *via, tvo_node_t *node, ef_record_t *rec,
                         int channel, tvo_lcm_session_ack_t *ack)
{
    const int n = tvo_lcm_session_t_encode(wire, 0, (int)sizeof(wire), start);
    TEST_ASSERT_TRUE(n > 0);
    ef_record_clear(rec);
    if (via != NULL) {
        (void)tvo_fleet_link_receive(via, node, TVO_NODE_CH_SESSION, wire, (uint32_t)n, 0);
    } else {
        (void)tvo_node_handle(node, TVO_NODE_CH_SESSION, wire, (uint32_t)n, 0);
    }
    const ef_message_t *m = ef_record_nth(rec, channel, 0);
    if (m == NULL) {
        TEST_FAIL_MESSAGE("no ack");
        return;
    }
    TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_session_ack_t_decode(m->data, 0, (int)m->length, ack));
}

static void test_a_node_with_an_answer_drives_unicycles_only(void)
{
    tvo_lcm_session_t start;
    ef_start(&start, EF_SESSION_ID + 1, TVO_LCM_SESSION_T_CLOCK_PLANT, ROBOTS);
    start.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
    tvo_lcm_session_ack_t ack;
    start_answer(&start, &link, &member, &member_rec, TVO_FLEET_CH_SESSION_ACK, &ack);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_ERR_PARAM, ack.status);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PARAM_PLANT_KIND, ack.bad_param);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.running_session_id); /* the running session runs on */
    start_answer(&start, NULL, &central, &central_rec, TVO_NODE_CH_SESSION_ACK, &ack);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, ack.status); /* a node answering in command_t takes it */
    /* ... and cannot be given an answer while it runs that chain session (its commands are not rows). */
    TEST_ASSERT_EQUAL_INT(-1, tvo_node_set_answer(&central, test_answer_unused, NULL));
}

#if TVO_FLEET_MAX_ROBOTS > TVO_WIRE_MAX_ROBOTS
/* A node answering through a test's sink: the joint command it computed, every robot's row. */
static tvo_fleet_joint_command_t sunk;
static int32_t sunk_status;
static void sink(void *context, const tvo_step_stamp_t *stamp, uint32_t wire_flags, const tvo_command_t *command)
{
    (void)context;
    (void)wire_flags;
    sunk_status = tvo_step_wire_status(&stamp->why);
    memset(&sunk, 0, sizeof(sunk));
    for (uint8_t r = 0; r < stamp->robot_count; ++r) {
        sunk.speed_mps[r] = (double)command->speed_mps[r];
        sunk.turn_rate_radps[r] = (double)command->turn_rate_radps[r];
    }
}
#endif

static void test_a_fleet_of_more_robots_than_the_wire_carries(void)
{
#if TVO_FLEET_MAX_ROBOTS > TVO_WIRE_MAX_ROBOTS
    enum { N = TVO_FLEET_MAX_ROBOTS };
    static tvo_fleet_link_t big;
    static tvo_node_t big_node, reference;
    static ef_record_t big_rec, reference_rec;
    TEST_ASSERT_EQUAL_INT(0, tvo_fleet_link_init(&big, &big_node, N - 1, ef_record_publish, &big_rec));
    tvo_node_init(&reference, ef_record_publish, &reference_rec);
    TEST_ASSERT_EQUAL_INT(0, tvo_node_set_answer(&reference, sink, NULL));
    TEST_ASSERT_EQUAL_UINT8(N, tvo_node_max_robots(&big_node));
    TEST_ASSERT_EQUAL_UINT8(TVO_WIRE_MAX_ROBOTS, tvo_node_max_robots(&central));
    tvo_lcm_session_t start;
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, N);
    tvo_lcm_session_ack_t ack;
    /* A node answering in command_t cannot carry them: refused, naming the robot count. */
    tvo_node_init(&central, ef_record_publish, &central_rec);
    start_answer(&start, NULL, &central, &central_rec, TVO_NODE_CH_SESSION_ACK, &ack);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_ERR_PARAM, ack.status);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PARAM_ROBOT_COUNT, ack.bad_param);
    /* target_t carries the wire's robots: streamed targets are refused, naming the first robot. */
    start.robot[2].target.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    start_answer(&start, &big, &big_node, &big_rec, TVO_FLEET_CH_SESSION_ACK, &ack);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_ERR_DIMENSION, ack.status);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, ack.bad_param);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_ROBOTS, ack.bad_part);
    TEST_ASSERT_EQUAL_INT32(2, ack.bad_index);
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, N);
    start_answer(&start, &big, &big_node, &big_rec, TVO_FLEET_CH_SESSION_ACK, &ack);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, ack.status);
    start_answer(&start, NULL, &reference, &reference_rec, TVO_NODE_CH_SESSION_ACK, &ack);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, ack.status);
    int moved_beyond_the_wire = 0;
    for (int64_t n = 0; n < 12; ++n) {
        tvo_step_measurement_t joint;
        memset(&joint, 0, sizeof(joint));
        joint.utime = stamp(n);
        joint.session_id = EF_SESSION_ID;
        joint.sequence = n;
        joint.robot_count = N;
        joint.heading_valid = 1u;
        ef_record_clear(&big_rec);
        for (int32_t r = 0; r < N; ++r) { /* the own robot (N - 1) last: its sample steps the node */
            tvo_lcm_fleet_sample_t sample;
            sample_of(r, n, &sample);
            sample.robot_count = N;
            const int len = tvo_lcm_fleet_sample_t_encode(wire, 0, (int)sizeof(wire), &sample);
            TEST_ASSERT_EQUAL_INT(TVO_FLEET_CH_SAMPLE,
                                  tvo_fleet_link_receive(&big, &big_node, TVO_FLEET_CH_SAMPLE, wire, (uint32_t)len, 0));
            pose(r, n, &joint.robot[r].position_m[0], &joint.robot[r].position_m[1], &joint.robot[r].heading_rad);
        }
        ef_record_clear(&reference_rec);
        TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_MEASUREMENT, tvo_node_measure(&reference, &joint, 0));
        TEST_ASSERT_NULL(ef_record_nth(&reference_rec, TVO_NODE_CH_COMMAND, 0)); /* answered, not in command_t */
        tvo_lcm_fleet_command_t got;
        const ef_message_t *c = ef_record_nth(&big_rec, TVO_FLEET_CH_COMMAND, 0);
        const ef_message_t *t = ef_record_nth(&big_rec, TVO_FLEET_CH_TELEMETRY, 0);
        if (c == NULL || t == NULL) {
            TEST_FAIL_MESSAGE("no fleet command or telemetry");
            return;
        }
        TEST_ASSERT_EQUAL_INT((int)c->length, tvo_lcm_fleet_command_t_decode(c->data, 0, (int)c->length, &got));
        TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, got.status);
        TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, sunk_status);
        TEST_ASSERT_EQUAL_INT32(N, got.robot_count);
        for (int32_t r = 0; r < N; ++r) {
            TEST_ASSERT_TRUE(got.joint_speed_mps[r] == sunk.speed_mps[r] &&
                             got.joint_turn_rate_radps[r] == sunk.turn_rate_radps[r]);
            moved_beyond_the_wire |= r >= TVO_WIRE_MAX_ROBOTS && sunk.speed_mps[r] != 0.0;
        }
        TEST_ASSERT_TRUE((uint64_t)got.joint_digest == tvo_fleet_digest(&sunk, N));
        TEST_ASSERT_TRUE(got.speed_mps == sunk.speed_mps[N - 1]);
        tvo_lcm_telemetry_t tel;
        TEST_ASSERT_EQUAL_INT((int)t->length, tvo_lcm_telemetry_t_decode(t->data, 0, (int)t->length, &tel));
        TEST_ASSERT_EQUAL_INT32(0, tel.dim); /* the law's vectors do not fit telemetry_t: not carried */
        TEST_ASSERT_EQUAL_INT32(TVO_LCM_COMMAND_T_STATUS_OK, tel.status);
    }
    TEST_ASSERT_TRUE(moved_beyond_the_wire);
#else
    TEST_IGNORE_MESSAGE("this build's fleets fit the wire (test_fleet_link_fleet runs the larger build)");
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_digest_and_channel_names);
    RUN_TEST(test_member_computes_the_central_command);
    RUN_TEST(test_missing_sample_is_predicted_along_the_nodes_commands);
    RUN_TEST(test_a_robot_never_heard_is_not_invented);
    RUN_TEST(test_a_stray_from_the_future_costs_one_period);
    RUN_TEST(test_bad_samples_are_refused);
    RUN_TEST(test_a_node_with_an_answer_drives_unicycles_only);
    RUN_TEST(test_a_fleet_of_more_robots_than_the_wire_carries);
    return UNITY_END();
}
