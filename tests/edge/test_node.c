/*
 * The node (firmware/edge/node*.c) through its raw-bytes entry, as a transport drives it: encoded
 * messages and the node's clock (a plain int64 passed in) in, encoded acks, commands, telemetry and
 * announcements out through a recording publish callback, decoded with the generated
 * tvo_lcm_*_decode. A one-robot session (robot 0's sample steps every period, exactly as v2's joint
 * measurement did): the session table with the boot check, CLOCK_PLANT and CLOCK_NODE timing (the
 * timer included), "nothing from a refused message is kept" (byte comparison of the running session
 * before and after), counters, announcements, the telemetry rate, the slack rule, and one test per
 * integer-from-the-wire site at its extremes (the test_node_ubsan variant runs them all under UBSan
 * and ASan). Sessions of several robots (gathering, prediction): test_node_fleet.c. The contract:
 * lcm_types/README.md "Sessions", "Timing".
 */
#include <float.h>

#include "edge_fixture.h"

#include "tvo/target.h"

void setUp(void);
void tearDown(void);

#define H ((int64_t)EF_PERIOD_US)
#define TAU ((int64_t)EF_DELAY_US)
#define W ((int64_t)EF_WATCHDOG)
#define SEQ0 ((int64_t)1000)            /* the plant's sequence of period 0 */
#define OTHER_ID ((int32_t)777)
#define NODE_T0 ((int64_t)7000000)      /* node clock when the CLOCK_NODE START arrives */
#define OFFSET (NODE_T0 - EF_UTIME)     /* node clock minus plant clock */

static tvo_node_t node;
static ef_record_t rec;                 /* everything the node publishes but its announcements */
static ef_record_t announcements;       /* its node_status_t on TVO_NODE */
static uint8_t wire[16384];
static tvo_lcm_session_t start;
static tvo_node_session_t snapshot;
static tvo_lcm_node_counters_t snapshot_counters;
static uint8_t snapshot_running;
static tvo_lcm_telemetry_t last_telemetry;

static void record(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    ef_record_publish(channel == TVO_NODE_CH_NODE ? &announcements : &rec, channel, data, length);
}

void setUp(void)
{
    ef_record_clear(&rec);
    ef_record_clear(&announcements);
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(&node, -1, EF_BOOT, record, NULL));
}

void tearDown(void) {}

/* ------------------------------------------------------------------------------------------------
 * Sending and reading
 * --------------------------------------------------------------------------------------------- */

static int send_session(const tvo_lcm_session_t *m, int64_t now_us)
{
    const int n = tvo_lcm_session_t_encode(wire, 0, (int)sizeof(wire), m);
    TEST_ASSERT_TRUE(n > 0);
    return tvo_node_handle(&node, TVO_NODE_CH_SESSION, wire, (uint32_t)n, now_us);
}

static int send_sample(const tvo_lcm_unicycle_sample_t *m, int64_t now_us)
{
    const int n = tvo_lcm_unicycle_sample_t_encode(wire, 0, (int)sizeof(wire), m);
    TEST_ASSERT_TRUE(n > 0);
    return tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, wire, (uint32_t)n, now_us);
}

static int send_chain_sample(const tvo_lcm_chain_sample_t *m, int64_t now_us)
{
    const int n = tvo_lcm_chain_sample_t_encode(wire, 0, (int)sizeof(wire), m);
    TEST_ASSERT_TRUE(n > 0);
    return tvo_node_handle(&node, TVO_NODE_CH_CHAIN_SAMPLE, wire, (uint32_t)n, now_us);
}

static int send_target(const tvo_lcm_target_t *m, int64_t now_us)
{
    const int n = tvo_lcm_target_t_encode(wire, 0, (int)sizeof(wire), m);
    TEST_ASSERT_TRUE(n > 0);
    return tvo_node_handle(&node, TVO_NODE_CH_TARGET, wire, (uint32_t)n, now_us);
}

/* The only ack published since the last clear. */
static tvo_lcm_session_ack_t the_ack(int line)
{
    tvo_lcm_session_ack_t ack;
    memset(&ack, 0, sizeof(ack));
    UNITY_TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&rec, TVO_NODE_CH_SESSION_ACK), line, "acks published");
    UNITY_TEST_ASSERT_EQUAL_UINT32(1u, rec.count, line, "an ack comes alone");
    const ef_message_t *m = ef_record_nth(&rec, TVO_NODE_CH_SESSION_ACK, 0);
    if (m == NULL) {
        UNITY_TEST_FAIL(line, "no ack");
        return ack;
    }
    UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_session_ack_t_decode(m->data, 0, (int)m->length, &ack), line,
                                "ack decodes");
    UNITY_TEST_ASSERT_EQUAL_INT64(EF_BOOT, ack.boot_id, line, "the ack names the node's boot");
    UNITY_TEST_ASSERT_EQUAL_INT(-1, ack.own_robot, line, "and its robot: every robot");
    return ack;
}
#define THE_ACK() the_ack(__LINE__)

/* The only command published since the last clear, and the telemetry that follows it (in
 * last_telemetry), which must carry the command's header. */
static tvo_lcm_unicycle_command_t the_command(int line)
{
    tvo_lcm_unicycle_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    UNITY_TEST_ASSERT_EQUAL_UINT32(0u, rec.overflow, line, "recorder overflow");
    UNITY_TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&rec, TVO_NODE_CH_COMMAND), line, "commands published");
    UNITY_TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&rec, TVO_NODE_CH_TELEMETRY), line, "telemetry published");
    UNITY_TEST_ASSERT_EQUAL_UINT32(2u, rec.count, line, "messages published");
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_COMMAND, rec.message[0].channel, line, "the command comes first");
    const ef_message_t *m = &rec.message[0];
    UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_unicycle_command_t_decode(m->data, 0, (int)m->length, &cmd),
                                line, "command decodes");
    m = &rec.message[1];
    memset(&last_telemetry, 0, sizeof(last_telemetry));
    UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_telemetry_t_decode(m->data, 0, (int)m->length, &last_telemetry),
                                line, "telemetry decodes");
    UNITY_TEST_ASSERT_EQUAL_INT64(cmd.header.utime, last_telemetry.header.utime, line, "telemetry utime");
    UNITY_TEST_ASSERT_EQUAL_INT64(cmd.header.session_id, last_telemetry.header.session_id, line, "telemetry session");
    UNITY_TEST_ASSERT_EQUAL_INT64(cmd.header.measurement_sequence, last_telemetry.header.measurement_sequence, line,
                                  "telemetry sequence");
    UNITY_TEST_ASSERT_EQUAL_INT(cmd.header.robot, last_telemetry.header.robot, line, "telemetry robot");
    UNITY_TEST_ASSERT_EQUAL_INT(0, cmd.header.robot, line, "robot 0's command");
    UNITY_TEST_ASSERT_EQUAL_INT(cmd.header.status, last_telemetry.header.status, line, "telemetry status");
    UNITY_TEST_ASSERT_EQUAL_INT(cmd.header.flags, last_telemetry.header.flags, line, "telemetry flags");
    UNITY_TEST_ASSERT_EQUAL_INT(0, last_telemetry.predicted_robots, line, "one robot: nothing predicted");
    const double speed = (double)cmd.speed_mps, turn = (double)cmd.turn_rate_radps;
    UNITY_TEST_ASSERT(tvo_joint_digest(&speed, &turn, 1) == (uint64_t)last_telemetry.joint_digest, line,
                      "telemetry digest is the command's");
    UNITY_TEST_ASSERT(isfinite(cmd.speed_mps) && isfinite(cmd.turn_rate_radps), line, "finite command");
    return cmd;
}
#define THE_COMMAND() the_command(__LINE__)

static void expect_nothing_published(int line)
{
    UNITY_TEST_ASSERT_EQUAL_UINT32(0u, rec.count, line, "nothing should be published");
}
#define EXPECT_NOTHING_PUBLISHED() expect_nothing_published(__LINE__)

static void expect_safe_stop(const tvo_lcm_unicycle_command_t *cmd, int line)
{
    UNITY_TEST_ASSERT(((uint32_t)cmd->header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0u, line, "SAFE_STOP flag");
    UNITY_TEST_ASSERT(cmd->speed_mps == 0.0f && cmd->turn_rate_radps == 0.0f, line, "v = omega = 0");
}
#define EXPECT_SAFE_STOP(cmd) expect_safe_stop(&(cmd), __LINE__)

/* ------------------------------------------------------------------------------------------------
 * "Nothing of a refused message is kept": the running session, byte for byte
 * --------------------------------------------------------------------------------------------- */

/* A copy of the session without the controller's scratch (its work: written before it is
 * read, meaning nothing between steps, like the stack frame it replaces). */
static tvo_node_session_t *session_without_scratch(const tvo_node_session_t *session)
{
    static tvo_node_session_t copy;
    memcpy(&copy, session, sizeof(copy));
    tvo_edge_controller_clear_scratch(&copy.controller);
    return &copy;
}

static void take_snapshot(void)
{
    const tvo_node_session_t *s = tvo_node_session(&node);
    TEST_ASSERT_NOT_NULL_MESSAGE(s, "no session to snapshot");
    memcpy(&snapshot, session_without_scratch(s), sizeof(snapshot));
    memcpy(&snapshot_counters, &node.counters, sizeof(snapshot_counters));
    snapshot_running = node.running;
}

/* The counters alone (a node that runs nothing). */
static void take_snapshot_of_counters(void)
{
    memcpy(&snapshot_counters, &node.counters, sizeof(snapshot_counters));
}

/* The running session is the snapshot's, byte for byte, but for the CLOCK_PLANT refusal streak, the
 * anchor votes and the controller's scratch. */
static void assert_session_kept(int line)
{
    const tvo_node_session_t *running = tvo_node_session(&node);
    UNITY_TEST_ASSERT_NOT_NULL(running, line, "the session should still run");
    const tvo_node_session_t *s = session_without_scratch(running);
    const tvo_schedule_t *before = &snapshot.schedule;
    const tvo_schedule_t *after = &s->schedule;
    const int clock_node = after->ops->clock_source == TVO_LCM_SESSION_T_CLOCK_NODE;
    UNITY_TEST_ASSERT_EQUAL_UINT8(snapshot_running, node.running, line, "running slot");
    if (!clock_node) {
        ef_copy_refusals_in_row(&snapshot.controller, &s->controller); /* the streak rule */
    }
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&snapshot.controller, &s->controller, sizeof(s->controller), line,
                                   "controller changed");
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&snapshot.problem, &s->problem, sizeof(s->problem), line, "problem changed");
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&before->timing, &after->timing, sizeof(after->timing), line, "timing changed");
    UNITY_TEST_ASSERT_EQUAL_INT64(before->last_period, after->last_period, line, "last_period changed");
    UNITY_TEST_ASSERT_EQUAL_INT64(before->anchor.last_sequence, after->anchor.last_sequence, line,
                                  "last_sequence changed");
    if (clock_node) {
        UNITY_TEST_ASSERT_EQUAL_INT64(before->clock.node.next_miss_period, after->clock.node.next_miss_period, line,
                                      "next_miss_period changed");
    }
    UNITY_TEST_ASSERT_EQUAL_INT64(before->anchor.offset_us, after->anchor.offset_us, line, "offset changed");
    UNITY_TEST_ASSERT_EQUAL_UINT8(before->has_accepted, after->has_accepted, line, "has_accepted changed");
    tvo_node_session_t expected;
    memcpy(&expected, &snapshot, sizeof(expected));
    if (!clock_node) {
        expected.schedule.clock.plant.vote_period = after->clock.plant.vote_period;       /* the vote's */
    }
    /* The one thing a refused measurement may leave (README "Timing"): a vote on the plant's clock or
     * numbering. */
    expected.schedule.vote_value = after->vote_value;
    expected.schedule.votes = after->votes;
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&expected, s, sizeof(expected), line, "session changed");
}
#define ASSERT_SESSION_KEPT() assert_session_kept(__LINE__)

/* ... and not even a counter moved (a repeated START). */
static void assert_session_and_counters_kept(int line)
{
    assert_session_kept(line);
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&snapshot_counters, &node.counters, sizeof(node.counters), line,
                                   "counters changed");
}
#define ASSERT_SESSION_AND_COUNTERS_KEPT() assert_session_and_counters_kept(__LINE__)

/* ------------------------------------------------------------------------------------------------
 * Sessions and the plant's schedule
 * --------------------------------------------------------------------------------------------- */

static int64_t plant_apply(int64_t j)
{
    return EF_EPOCH + j * H;
}

/* CLOCK_PLANT: the genuine sample for period j, stamped apply - tau, numbered by period. */
static void plant_meas(tvo_lcm_unicycle_sample_t *m, int64_t j)
{
    ef_sample(m, EF_SESSION_ID, plant_apply(j) - TAU, (int32_t)(SEQ0 + j), 0);
}

/* CLOCK_NODE: period j's apply instant on the node's clock. */
static int64_t node_apply(int64_t j)
{
    return EF_EPOCH + OFFSET + j * H;
}

/* CLOCK_NODE: a sample for period j arrives 4 ms before A_j, sampled 1 ms before it arrives. */
static int64_t node_arrival(int64_t j)
{
    return node_apply(j) - 4000;
}
static void node_meas(tvo_lcm_unicycle_sample_t *m, int64_t j, int32_t sequence)
{
    ef_sample(m, EF_SESSION_ID, node_arrival(j) - OFFSET - 1000, sequence, 0);
}

static void start_session(int32_t id, int32_t clock_source, int64_t now_us)
{
    ef_start(&start, id, clock_source, 1);
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, send_session(&start, now_us));
    const tvo_lcm_session_ack_t ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_OK, ack.status);
    TEST_ASSERT_EQUAL_INT64(id, ack.running_session_id);
}

/* Sends a measurement and expects it accepted, answered for apply instant utime. */
static tvo_lcm_unicycle_command_t expect_accepted(const tvo_lcm_unicycle_sample_t *m, int64_t now_us, int64_t utime, int line)
{
    ef_record_clear(&rec);
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(m, now_us), line, "handled");
    const tvo_lcm_unicycle_command_t cmd = the_command(line);
    ef_assert_status(TVO_OK, cmd.header.status, line);
    UNITY_TEST_ASSERT_EQUAL_INT64(utime, cmd.header.utime, line, "command utime: the apply instant");
    UNITY_TEST_ASSERT_EQUAL_INT64(m->header.sequence, cmd.header.measurement_sequence, line, "sequence echoed");
    UNITY_TEST_ASSERT_EQUAL_INT64(m->header.session_id, cmd.header.session_id, line, "session echoed");
    UNITY_TEST_ASSERT(((uint32_t)cmd.header.flags & (TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP)) == 0u, line,
                      "neither holding nor stopping");
    return cmd;
}
#define EXPECT_ACCEPTED(m, now, utime) expect_accepted(&(m), (now), (utime), __LINE__)

/*
 * Sends a measurement of the running session and expects it refused for `reason` (holding) or,
 * when reason is TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, answered with a safe stop; the running session is kept byte for
 * byte unless it is a safe stop. The answer's utime is never before the measurement's stamp:
 * CLOCK_PLANT the stamp itself, CLOCK_NODE the later of the stamp and now (plant clock).
 */
static tvo_lcm_unicycle_command_t expect_refused(const tvo_lcm_unicycle_sample_t *m, int64_t now_us, int32_t reason, int line)
{
    const tvo_node_session_t *s = tvo_node_session(&node);
    UNITY_TEST_ASSERT_NOT_NULL(s, line, "no session");
    const int clock_node = s->schedule.timing.clock_source == TVO_LCM_SESSION_T_CLOCK_NODE;
    const int64_t offset = s->schedule.anchor.offset_us;
    take_snapshot();
    const int32_t refused_before = node.counters.refused[reason];
    ef_record_clear(&rec);
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(m, now_us), line, "handled");
    const tvo_lcm_unicycle_command_t cmd = the_command(line);
    ef_assert_status((int)reason, cmd.header.status, line);
    UNITY_TEST_ASSERT_EQUAL_INT64(m->header.sequence, cmd.header.measurement_sequence, line, "sequence echoed");
    UNITY_TEST_ASSERT_EQUAL_INT64(m->header.session_id, cmd.header.session_id, line, "session echoed");
    const int64_t stamp = m->header.utime < 0 ? 0 : (m->header.utime > EF_TWO_POW_60 ? EF_TWO_POW_60 : m->header.utime);
    if (clock_node) {
        int64_t now = now_us < 0 ? 0 : (now_us > EF_TWO_POW_60 ? EF_TWO_POW_60 : now_us);
        now -= offset;
        now = now < 0 ? 0 : (now > EF_TWO_POW_60 ? EF_TWO_POW_60 : now);
        UNITY_TEST_ASSERT_EQUAL_INT64(stamp > now ? stamp : now, cmd.header.utime, line, "refusal utime");
    } else {
        UNITY_TEST_ASSERT_EQUAL_INT64(stamp, cmd.header.utime, line, "refusal utime is the measurement's");
    }
    /* Counted once, under the status the answer carries (node_counters_t.refused). */
    UNITY_TEST_ASSERT_EQUAL_INT32(refused_before + 1, node.counters.refused[reason], line, "refusal counted");
    if (reason == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG) {
        expect_safe_stop(&cmd, line); /* last_refusal: the why behind the stop */
        return cmd;
    }
    UNITY_TEST_ASSERT_EQUAL_INT(reason, node.last_refusal, line, "last_refusal");
    UNITY_TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)cmd.header.flags, line, "HOLDING, nothing else");
    assert_session_kept(line);
    return cmd;
}
#define EXPECT_REFUSED(m, now, reason) expect_refused(&(m), (now), (reason), __LINE__)

/* A fresh node running a CLOCK_PLANT session with periods 1..accepted accepted. */
static void plant_session_after(int64_t accepted)
{
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    for (int64_t j = 1; j <= accepted; ++j) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j));
    }
}

/* A fresh node running a CLOCK_NODE session (START at NODE_T0) with periods 1..accepted accepted. */
static void node_session_after(int64_t accepted)
{
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, NODE_T0);
    for (int64_t j = 1; j <= accepted; ++j) {
        tvo_lcm_unicycle_sample_t m;
        node_meas(&m, j, (int32_t)j);
        (void)EXPECT_ACCEPTED(m, node_arrival(j), node_apply(j) - OFFSET);
    }
}

/* ------------------------------------------------------------------------------------------------
 * The session table
 * --------------------------------------------------------------------------------------------- */

static void test_start_when_idle_runs_the_session_and_acks_ok(void)
{
    TEST_ASSERT_NULL(tvo_node_session(&node));
    TEST_ASSERT_EQUAL_INT64(TVO_LCM_NODE_STATUS_T_IDLE_PERIOD_US, tvo_node_poll(&node, 0)); /* the next announcement */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, send_session(&start, 0));
    const tvo_lcm_session_ack_t ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_OK, ack.status);
    TEST_ASSERT_EQUAL_INT64(EF_UTIME, ack.utime);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.session_id);
    TEST_ASSERT_EQUAL_INT8(TVO_LCM_SESSION_T_ACTION_START, ack.action);
    TEST_ASSERT_EQUAL_INT32(0, ack.bad_param);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_NONE, ack.bad_part);
    TEST_ASSERT_EQUAL_INT32(-1, ack.bad_index);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.running_session_id);
    const tvo_node_session_t *s = tvo_node_session(&node);
    TEST_ASSERT_NOT_NULL(s);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, s->session_id);
    TEST_ASSERT_EQUAL_INT64(0, s->schedule.anchor.offset_us); /* CLOCK_PLANT: the plant's clock is the schedule's */
    TEST_ASSERT_EQUAL_UINT32(1u, node.acks);
    TEST_ASSERT_EQUAL_INT(0, tvo_node_stop_requested(&node));
    TEST_ASSERT_EQUAL_INT32(1, node.counters.sessions);
    /* CLOCK_PLANT has no timer: the next deadline is the running node's next announcement. */
    TEST_ASSERT_EQUAL_INT64(TVO_LCM_NODE_STATUS_T_RUNNING_PERIOD_US, tvo_node_poll(&node, 0));
}

static void test_start_with_a_new_id_replaces_the_running_session(void)
{
    plant_session_after(2);
    TEST_ASSERT_EQUAL_INT32(2, node.counters.accepted);
    ef_start(&start, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.period_us = 2 * H; /* another schedule */
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    const tvo_lcm_session_ack_t ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_OK, ack.status);
    TEST_ASSERT_EQUAL_INT64(OTHER_ID, ack.running_session_id);
    TEST_ASSERT_EQUAL_INT64(OTHER_ID, tvo_node_session(&node)->session_id);
    TEST_ASSERT_EQUAL_INT32(2, node.counters.accepted); /* counters are the node's, since it started */
    TEST_ASSERT_EQUAL_INT32(2, node.counters.sessions);
    /* The old one's samples are another session's now. */
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    ef_record_clear(&rec);
    (void)send_sample(&m, 0);
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(1, node.counters.other_session);
    /* The new session starts its own schedule: period 1 of h = 20 ms. */
    ef_sample(&m, OTHER_ID, EF_EPOCH + 2 * H - TAU, 5, 0);
    (void)EXPECT_ACCEPTED(m, 0, EF_EPOCH + 2 * H);
}

/* Edits of a START that make it invalid, with the ack they must get. */
typedef struct {
    const char *what;
    int32_t status;  /* command_t.STATUS_* */
    int32_t param;   /* session_ack_t.PARAM_* */
    int32_t part;
    int32_t index;
} refusal_t;

static void make_invalid(tvo_lcm_session_t *m, int which)
{
    switch (which) {
    case 0: m->period_us = 0; break;
    case 1: m->gain_kp = -1.0; break;
    case 2: m->epoch_utime = m->utime + (int64_t)TVO_MAX_TICK_SPAN + 1; break;
    case 3:
        m->distance_count = 1;
        m->distance[0].robot_b = 5;
        break;
    case 4:
        m->halfspace_count = 1;
        m->barrier.relaxation_degree = 1; /* below k + 1: the core's barrier refuses it */
        break;
    case 5: m->gain_kp = 3e38; break; /* a float, but past the sampling's reach (and the law's range) */
    case 6: m->robot[0].target.coeff[0][3] = 1e30; break; /* acked before, then every step failed */
    case 7: m->robot[0].target.coeff[1][0] = 2e4; break; /* the target starts beyond the workspace */
    case 8:
        m->obstacle_count = 1;
        m->obstacle[0].center_m[0] = 1e5;
        m->obstacle[0].radius_m = 0.5;
        break;
    case 9:
        m->halfspace_count = 1;
        m->halfspace[0].normal[0] = 1.0;
        m->halfspace[0].normal_rate[1] = 3.14159;
        m->halfspace[0].bound_m = 1.0;
        m->halfspace[0].bound_rate_mps = -1e6; /* the fuzzer's -inf telemetry came from such a wall */
        break;
    case 10: /* robot 1's weight is negative: the ack names robot 1 */
        m->robot_count = 2;
        ef_line_path(&m->robot[1].target, 0.5, 1.0, 0.2);
        m->robot[1].tracking_weight[0] = 1.0;
        m->robot[1].tracking_weight[1] = -1.0;
        break;
    case 11: /* obstacle 2 overlaps obstacle 0: the ack names the later of the pair */
        m->obstacle_count = 3;
        m->obstacle[0].center_m[0] = 3.0;
        m->obstacle[0].center_m[1] = 3.0;
        m->obstacle[0].radius_m = 0.5;
        m->obstacle[1].center_m[0] = -3.0;
        m->obstacle[1].center_m[1] = 3.0;
        m->obstacle[1].radius_m = 0.5;
        m->obstacle[2].center_m[0] = 3.4;
        m->obstacle[2].center_m[1] = 3.0;
        m->obstacle[2].radius_m = 0.5;
        break;
    default: m->robot[0].target.kind = 9; break;
    }
}

static const refusal_t invalid_starts[] = {
    {"period 0", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_PERIOD, TVO_LCM_SESSION_ACK_T_PART_NONE, -1},
    {"negative gain", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_GAINS, TVO_LCM_SESSION_ACK_T_PART_NONE, -1},
    {"epoch beyond the span", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_EPOCH, TVO_LCM_SESSION_ACK_T_PART_NONE, -1},
    {"distance robot 5", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_DISTANCE, 0},
    {"relaxation degree 1", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_BARRIER, -1},
    {"gain 3e38", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_GAINS, TVO_LCM_SESSION_ACK_T_PART_NONE, -1},
    {"target coefficient 1e30", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 0},
    {"target 2e4 m out", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 0},
    {"obstacle 1e5 m out", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, 0},
    {"wall moving at 1e6 m/s", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, 0},
    {"robot 1's weight -1", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 1},
    {"obstacles 0 and 2 overlap", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, 2},
    {"target kind 9", TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 0},
};

static void test_refused_start_while_running_changes_nothing(void)
{
    for (int which = 0; which < (int)(sizeof(invalid_starts) / sizeof(invalid_starts[0])); ++which) {
        for (int same_id = 0; same_id < 2; ++same_id) {
            setUp();
            plant_session_after(2);
            take_snapshot();
            const uint8_t stop_requested = node.stop_requested;
            ef_start(&start, same_id ? EF_SESSION_ID : OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
            make_invalid(&start, which);
            ef_record_clear(&rec);
            (void)send_session(&start, 0);
            const tvo_lcm_session_ack_t ack = THE_ACK();
            const refusal_t *r = &invalid_starts[which];
            /* The running id with other (here: invalid) content is a conflict before it is invalid. */
            TEST_ASSERT_EQUAL_INT_MESSAGE(same_id ? TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_SESSION_CONFLICT : r->status, ack.status, r->what);
            if (!same_id) {
                EF_ASSERT_PARAM(r->param, ack.bad_param);
                TEST_ASSERT_EQUAL_INT32(r->part, ack.bad_part);
                TEST_ASSERT_EQUAL_INT32(r->index, ack.bad_index);
            }
            TEST_ASSERT_EQUAL_INT64(start.session_id, ack.session_id);
            TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.running_session_id);
            ASSERT_SESSION_AND_COUNTERS_KEPT();
            TEST_ASSERT_EQUAL_UINT8(stop_requested, node.stop_requested);
            /* The old session answers on, on its own schedule. */
            tvo_lcm_unicycle_sample_t m;
            plant_meas(&m, 3);
            (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
        }
    }
}

static void test_refused_start_when_idle_leaves_the_node_idle(void)
{
    for (int which = 0; which < (int)(sizeof(invalid_starts) / sizeof(invalid_starts[0])); ++which) {
        setUp();
        ef_start(&start, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        make_invalid(&start, which);
        (void)send_session(&start, 0);
        const tvo_lcm_session_ack_t ack = THE_ACK();
        EF_ASSERT_STATUS(invalid_starts[which].status, ack.status);
        EF_ASSERT_PARAM(invalid_starts[which].param, ack.bad_param);
        TEST_ASSERT_EQUAL_INT64(-1, ack.running_session_id);
        TEST_ASSERT_NULL(tvo_node_session(&node));
    }
}

static void test_repeated_start_is_acked_again_without_a_restart(void)
{
    for (int clock = TVO_LCM_SESSION_T_CLOCK_PLANT; clock <= TVO_LCM_SESSION_T_CLOCK_NODE; ++clock) {
        setUp();
        if (clock == TVO_LCM_SESSION_T_CLOCK_PLANT) {
            plant_session_after(2);
        } else {
            node_session_after(2);
        }
        const tvo_lcm_session_ack_t first = node.last_ack;
        take_snapshot();
        ef_start(&start, EF_SESSION_ID, clock, 1);
        start.utime = EF_UTIME + 150000; /* sent again later: only the utime differs */
        ef_record_clear(&rec);
        (void)send_session(&start, NODE_T0 + 999999);
        const tvo_lcm_session_ack_t ack = THE_ACK();
        EF_ASSERT_STATUS(first.status, ack.status);
        TEST_ASSERT_EQUAL_INT64(start.utime, ack.utime); /* echoes the repeat */
        TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.running_session_id);
        TEST_ASSERT_EQUAL_INT32(first.bad_param, ack.bad_param);
        TEST_ASSERT_EQUAL_INT32(first.bad_part, ack.bad_part);
        TEST_ASSERT_EQUAL_INT32(first.bad_index, ack.bad_index);
        ASSERT_SESSION_AND_COUNTERS_KEPT(); /* no restart: schedule, offset, controller, counters */
    }
}

static void test_start_of_the_running_id_with_other_content_is_a_conflict(void)
{
    plant_session_after(2);
    take_snapshot();
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.gain_kp = 41.0;
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    const tvo_lcm_session_ack_t ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_SESSION_CONFLICT, ack.status);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.running_session_id);
    ASSERT_SESSION_AND_COUNTERS_KEPT();
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
}

/* A STOP of `id`, naming the node's boot for one robot (a plant's STOP names the boots as its START). */
static void stop_message(tvo_lcm_session_t *m, int32_t id)
{
    memset(m, 0, sizeof(*m));
    m->utime = EF_UTIME + 1000000;
    m->protocol_version = TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION;
    m->session_id = id;
    m->action = TVO_LCM_SESSION_T_ACTION_STOP;
    m->robot_count = 1;
    m->node_boot_id[0] = EF_BOOT;
}

static void test_stop_of_the_running_session_ends_it_and_a_start_begins_anew(void)
{
    plant_session_after(2);
    tvo_lcm_session_t stop;
    stop_message(&stop, EF_SESSION_ID);
    ef_record_clear(&rec);
    (void)send_session(&stop, 0);
    const tvo_lcm_session_ack_t ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_OK, ack.status);
    TEST_ASSERT_EQUAL_INT8(TVO_LCM_SESSION_T_ACTION_STOP, ack.action);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.session_id);
    TEST_ASSERT_EQUAL_INT64(-1, ack.running_session_id);
    TEST_ASSERT_NULL(tvo_node_session(&node));
    TEST_ASSERT_EQUAL_INT(1, tvo_node_stop_requested(&node));
    /* Its samples are now dropped unanswered (counted: idle). */
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    ef_record_clear(&rec);
    (void)send_sample(&m, 0);
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(1, node.counters.idle);
    /* The same START again (a plant that re-sends it) starts afresh. */
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    TEST_ASSERT_EQUAL_UINT8(0u, node.stop_requested);
    TEST_ASSERT_EQUAL_UINT8(0u, tvo_node_session(&node)->schedule.has_accepted);
    plant_meas(&m, 5);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(5));
}

static void test_stop_of_another_id_is_refused_and_the_session_runs_on(void)
{
    plant_session_after(2);
    take_snapshot();
    tvo_lcm_session_t stop;
    stop_message(&stop, OTHER_ID);
    ef_record_clear(&rec);
    (void)send_session(&stop, 0);
    tvo_lcm_session_ack_t ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_SESSION, ack.status);
    TEST_ASSERT_EQUAL_INT64(OTHER_ID, ack.session_id);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, ack.running_session_id);
    TEST_ASSERT_EQUAL_UINT8(0u, node.stop_requested);
    ASSERT_SESSION_AND_COUNTERS_KEPT();
    /* When idle: refused too, and nothing runs. */
    setUp();
    (void)send_session(&stop, 0);
    ack = THE_ACK();
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_SESSION, ack.status);
    TEST_ASSERT_EQUAL_INT64(-1, ack.running_session_id);
    TEST_ASSERT_EQUAL_UINT8(0u, node.stop_requested);
}

static void test_unknown_actions_are_refused_and_change_nothing(void)
{
    const int8_t bad[] = {INT8_MIN, -1, 0, TVO_LCM_SESSION_T_ACTION_STOP + 1, INT8_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        for (int running = 0; running < 2; ++running) {
            setUp();
            if (running) {
                plant_session_after(1);
                take_snapshot();
            }
            ef_start(&start, running ? EF_SESSION_ID : OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
            start.action = bad[i];
            ef_record_clear(&rec);
            (void)send_session(&start, 0);
            const tvo_lcm_session_ack_t ack = THE_ACK();
            EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, ack.status);
            TEST_ASSERT_EQUAL_INT8(bad[i], ack.action);
            TEST_ASSERT_EQUAL_INT64(running ? EF_SESSION_ID : -1, ack.running_session_id);
            if (running) {
                ASSERT_SESSION_AND_COUNTERS_KEPT();
            } else {
                TEST_ASSERT_NULL(tvo_node_session(&node));
            }
        }
    }
}

static void test_samples_and_targets_while_idle_are_dropped_and_counted(void)
{
    tvo_lcm_unicycle_sample_t m;
    ef_sample(&m, 31337, 123456, 17, 0);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(&m, 0));
    EXPECT_NOTHING_PUBLISHED(); /* no NO_SESSION stop: the plant learns a restart from TVO_NODE */
    TEST_ASSERT_EQUAL_INT32(1, node.counters.idle);
    tvo_lcm_target_t t;
    memset(&t, 0, sizeof(t));
    t.header.session_id = 31337;
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_TARGET, send_target(&t, 0));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(2, node.counters.idle);
    TEST_ASSERT_NULL(tvo_node_session(&node));
    /* ... and after a STOP ended the session, the same. */
    plant_session_after(1);
    tvo_lcm_session_t stop;
    ef_start(&stop, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    stop.action = TVO_LCM_SESSION_T_ACTION_STOP;
    (void)send_session(&stop, 0);
    TEST_ASSERT_NULL(tvo_node_session(&node));
    plant_meas(&m, 2);
    ef_record_clear(&rec);
    (void)send_sample(&m, 0);
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(3, node.counters.idle);
}

static void test_messages_of_another_session_are_ignored_and_counted(void)
{
    plant_session_after(2);
    take_snapshot();
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    m.header.session_id = OTHER_ID;
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(&m, 0));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(1, node.counters.other_session);
    tvo_lcm_target_t t;
    memset(&t, 0, sizeof(t));
    t.header.utime = plant_apply(2);
    t.header.session_id = OTHER_ID;
    t.header.robot = 0;
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_TARGET, send_target(&t, 0));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(2, node.counters.other_session);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.targets_refused);
    ASSERT_SESSION_KEPT();
    /* The genuine stream goes on. */
    m.header.session_id = EF_SESSION_ID;
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
    TEST_ASSERT_EQUAL_INT32(2, node.counters.other_session);
}

/* ------------------------------------------------------------------------------------------------
 * The session table (node.c) against lcm_types/README.md "Sessions", row by row
 * --------------------------------------------------------------------------------------------- */

/* What a row's message is sent to, and what it sends. */
typedef enum { ROW_IDLE, ROW_RUNNING_A } row_state_t;
typedef enum {
    SEND_START_VALID_NEW_ID,    /* a START of an id not running, that passes every check */
    SEND_START_INVALID,         /* a START of an id not running, that fails a check (period 0) */
    SEND_START_REPEAT,          /* the running START again, a later utime */
    SEND_START_OTHER_CONTENT,   /* the running id, another gain */
    SEND_STOP_RUNNING,          /* STOP of the running id */
    SEND_STOP_OTHER,            /* STOP of an id not running */
    SEND_OTHER_ACTION,          /* action 7 */
    SEND_START_OTHER_BOOT,      /* a valid START of a new id naming an earlier boot of the node */
    SEND_STOP_OTHER_BOOT,       /* STOP of the running id naming an earlier boot */
    SEND_SAMPLE_OWN,            /* a genuine sample of the running id (idle: of any id) */
    SEND_SAMPLE_OTHER,          /* a sample of another id */
    SEND_TARGET_OWN,            /* a target sample of the running id (idle: of any id) */
    SEND_TARGET_OTHER           /* a target sample of another id */
} row_message_t;

/* What the row says comes back. */
typedef enum { ANSWER_NONE, ANSWER_ACK, ANSWER_COMMAND } row_answer_t;
/* Which counter the row's message moves by one (the others stay). */
typedef enum { COUNTED_NONE, COUNTED_OTHER_SESSION, COUNTED_IDLE, COUNTED_WRONG_BOOT } row_counter_t;

typedef struct {
    const char *readme;         /* the README's row: "state | message | action | ack / answer" */
    row_state_t state;
    row_message_t message;
    tvo_node_event_t event;     /* what the node takes the message for */
    tvo_node_state_t after;     /* the node's state after it */
    row_answer_t answer;
    int32_t status;             /* the ack's or the command's status */
    int64_t running_after;      /* the ack's running_session_id: an id, or -1 */
    int kept;                   /* "nothing changes": the running session byte for byte, counters too */
    row_counter_t counted;      /* ... but for this counter */
} readme_row_t;

#define ID_A EF_SESSION_ID
#define ID_B OTHER_ID
#define ERR(name) TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_##name

static const readme_row_t readme_rows[] = {
    {"any (idle) | START, STOP or another action naming another boot | dropped | none (counted: wrong_boot)", ROW_IDLE,
     SEND_START_OTHER_BOOT, TVO_NODE_EVENT_WRONG_BOOT, TVO_NODE_IDLE, ANSWER_NONE, 0, -1, 0, COUNTED_WRONG_BOOT},
    {"any (running A) | START, STOP or another action naming another boot | dropped: A runs on | none (wrong_boot)",
     ROW_RUNNING_A, SEND_STOP_OTHER_BOOT, TVO_NODE_EVENT_WRONG_BOOT, TVO_NODE_RUNNING, ANSWER_NONE, 0, ID_A, 1,
     COUNTED_WRONG_BOOT},
    {"idle | START that passes every check | the session is built and runs | status 0, running_session_id = its id",
     ROW_IDLE, SEND_START_VALID_NEW_ID, TVO_NODE_EVENT_START, TVO_NODE_RUNNING, ANSWER_ACK, TVO_OK, ID_B, 0, COUNTED_NONE},
    {"running A | START of a new id B that passes every check | B replaces A | 0, running B", ROW_RUNNING_A,
     SEND_START_VALID_NEW_ID, TVO_NODE_EVENT_START, TVO_NODE_RUNNING, ANSWER_ACK, TVO_OK, ID_B, 0, COUNTED_NONE},
    {"any (idle) | START that fails a check | nothing changes | the status, bad_param ...; running -1", ROW_IDLE,
     SEND_START_INVALID, TVO_NODE_EVENT_START, TVO_NODE_IDLE, ANSWER_ACK, ERR(PARAM), -1, 0, COUNTED_NONE},
    {"any (running A) | START that fails a check | nothing changes: A keeps running | the status ...; running A",
     ROW_RUNNING_A, SEND_START_INVALID, TVO_NODE_EVENT_START, TVO_NODE_RUNNING, ANSWER_ACK, ERR(PARAM), ID_A, 1,
     COUNTED_NONE},
    {"running A | START of A, the same content (any utime) | nothing: a repeat | 0 again", ROW_RUNNING_A,
     SEND_START_REPEAT, TVO_NODE_EVENT_START_REPEAT, TVO_NODE_RUNNING, ANSWER_ACK, TVO_OK, ID_A, 1, COUNTED_NONE},
    {"running A | START of A with other content | refused | STATUS_ERR_SESSION_CONFLICT (17)", ROW_RUNNING_A,
     SEND_START_OTHER_CONTENT, TVO_NODE_EVENT_START_CONFLICT, TVO_NODE_RUNNING, ANSWER_ACK, ERR(SESSION_CONFLICT), ID_A,
     1, COUNTED_NONE},
    {"running A | STOP of A | the session ends | 0, running -1", ROW_RUNNING_A, SEND_STOP_RUNNING, TVO_NODE_EVENT_STOP,
     TVO_NODE_IDLE, ANSWER_ACK, TVO_OK, -1, 0, COUNTED_NONE},
    {"any (idle) | STOP of another id | ignored | STATUS_ERR_NO_SESSION (18)", ROW_IDLE, SEND_STOP_OTHER,
     TVO_NODE_EVENT_STOP_OTHER, TVO_NODE_IDLE, ANSWER_ACK, ERR(NO_SESSION), -1, 0, COUNTED_NONE},
    {"any (running A) | STOP of another id | ignored | STATUS_ERR_NO_SESSION (18)", ROW_RUNNING_A, SEND_STOP_OTHER,
     TVO_NODE_EVENT_STOP_OTHER, TVO_NODE_RUNNING, ANSWER_ACK, ERR(NO_SESSION), ID_A, 1, COUNTED_NONE},
    {"any (idle) | another action | ignored | STATUS_ERR_PARAM", ROW_IDLE, SEND_OTHER_ACTION, TVO_NODE_EVENT_OTHER_ACTION,
     TVO_NODE_IDLE, ANSWER_ACK, ERR(PARAM), -1, 0, COUNTED_NONE},
    {"any (running A) | another action | ignored | STATUS_ERR_PARAM", ROW_RUNNING_A, SEND_OTHER_ACTION,
     TVO_NODE_EVENT_OTHER_ACTION, TVO_NODE_RUNNING, ANSWER_ACK, ERR(PARAM), ID_A, 1, COUNTED_NONE},
    {"idle | sample | dropped | none (counted: idle)", ROW_IDLE, SEND_SAMPLE_OWN, TVO_NODE_EVENT_SAMPLE, TVO_NODE_IDLE,
     ANSWER_NONE, 0, -1, 0, COUNTED_IDLE},
    {"idle | target | dropped | none (counted: idle)", ROW_IDLE, SEND_TARGET_OWN, TVO_NODE_EVENT_TARGET, TVO_NODE_IDLE,
     ANSWER_NONE, 0, -1, 0, COUNTED_IDLE},
    {"running A | sample of another session id | ignored | none (counted: other_session)", ROW_RUNNING_A,
     SEND_SAMPLE_OTHER, TVO_NODE_EVENT_SAMPLE_OTHER, TVO_NODE_RUNNING, ANSWER_NONE, 0, ID_A, 1, COUNTED_OTHER_SESSION},
    {"running A | target of another session id | ignored | none (counted: other_session)", ROW_RUNNING_A,
     SEND_TARGET_OTHER, TVO_NODE_EVENT_TARGET_OTHER, TVO_NODE_RUNNING, ANSWER_NONE, 0, ID_A, 1, COUNTED_OTHER_SESSION},
    /* Transitions of the table that the README's table leaves to other sections: */
    {"(Timing) running A | the period's last robot's sample of A | served | command(s), telemetry at its rate",
     ROW_RUNNING_A, SEND_SAMPLE_OWN, TVO_NODE_EVENT_SAMPLE, TVO_NODE_RUNNING, ANSWER_COMMAND, TVO_OK, ID_A, 0,
     COUNTED_NONE},
    {"(Streamed targets) running A | target of A | taken (here refused: A's target is not streamed) | none",
     ROW_RUNNING_A, SEND_TARGET_OWN, TVO_NODE_EVENT_TARGET, TVO_NODE_RUNNING, ANSWER_NONE, 0, ID_A, 0, COUNTED_NONE},
};

static void send_row_message(row_message_t message)
{
    tvo_lcm_session_t msg;
    tvo_lcm_unicycle_sample_t m;
    tvo_lcm_target_t t;
    switch (message) {
    case SEND_START_VALID_NEW_ID:
    case SEND_START_INVALID:
    case SEND_START_OTHER_BOOT:
        ef_start(&msg, ID_B, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.period_us = (message == SEND_START_INVALID) ? 0 : msg.period_us;
        msg.node_boot_id[0] = (message == SEND_START_OTHER_BOOT) ? EF_OTHER_BOOT : EF_BOOT;
        (void)send_session(&msg, 0);
        return;
    case SEND_START_REPEAT:
    case SEND_START_OTHER_CONTENT:
        ef_start(&msg, ID_A, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.utime += (message == SEND_START_REPEAT) ? 1000 : 0;
        msg.gain_kp += (message == SEND_START_OTHER_CONTENT) ? 1.0 : 0.0;
        (void)send_session(&msg, 0);
        return;
    case SEND_STOP_RUNNING:
    case SEND_STOP_OTHER:
    case SEND_STOP_OTHER_BOOT:
        stop_message(&msg, message == SEND_STOP_OTHER ? ID_B : ID_A);
        msg.node_boot_id[0] = (message == SEND_STOP_OTHER_BOOT) ? EF_OTHER_BOOT : EF_BOOT;
        (void)send_session(&msg, 0);
        return;
    case SEND_OTHER_ACTION:
        stop_message(&msg, ID_A);
        msg.action = 7;
        (void)send_session(&msg, 0);
        return;
    case SEND_SAMPLE_OWN:
    case SEND_SAMPLE_OTHER:
        plant_meas(&m, 2);
        m.header.session_id = (message == SEND_SAMPLE_OWN) ? ID_A : ID_B;
        (void)send_sample(&m, 0);
        return;
    case SEND_TARGET_OWN:
    case SEND_TARGET_OTHER:
        memset(&t, 0, sizeof(t));
        t.header.utime = EF_EPOCH;
        t.header.session_id = (message == SEND_TARGET_OWN) ? ID_A : ID_B;
        t.header.robot = 0;
        (void)send_target(&t, 0);
        return;
    default:
        TEST_FAIL_MESSAGE("unknown row message");
    }
}

/* Sends each row's message in its state and checks the row: what the node took it for, the table's
 * cell for it, the state after, the answer and the counters. Every reachable cell of the table is
 * some row's. */
static void test_each_readme_session_row_is_what_the_table_does(void)
{
    uint8_t covered[TVO_NODE_STATE_COUNT][TVO_NODE_EVENT_COUNT];
    memset(covered, 0, sizeof(covered));
    for (size_t i = 0; i < sizeof(readme_rows) / sizeof(readme_rows[0]); ++i) {
        const readme_row_t *row = &readme_rows[i];
        setUp();
        tvo_node_state_t before = TVO_NODE_IDLE;
        if (row->state == ROW_RUNNING_A) {
            plant_session_after(1);
            before = TVO_NODE_RUNNING;
        }
        take_snapshot_of_counters();
        if (row->state == ROW_RUNNING_A) {
            take_snapshot();
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(before, node.state, row->readme);
        ef_record_clear(&rec);
        send_row_message(row->message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(row->event, node.last_event, row->readme);
        TEST_ASSERT_EQUAL_INT_MESSAGE(row->after, node.state, row->readme);
        tvo_node_transition_info_t cell;
        TEST_ASSERT_TRUE_MESSAGE(tvo_node_transition_info(before, row->event, &cell), row->readme);
        TEST_ASSERT_TRUE_MESSAGE(cell.reachable, row->readme);
        TEST_ASSERT_TRUE_MESSAGE(row->after == cell.next_if_taken || row->after == cell.next_if_refused, row->readme);
        TEST_ASSERT_EQUAL_INT_MESSAGE(row->answer == ANSWER_ACK, cell.acked, row->readme);
        covered[before][row->event] = 1u;
        switch (row->answer) {
        case ANSWER_ACK: {
            const tvo_lcm_session_ack_t ack = THE_ACK();
            TEST_ASSERT_EQUAL_INT_MESSAGE(row->status, ack.status, row->readme);
            TEST_ASSERT_EQUAL_INT64_MESSAGE(row->running_after, ack.running_session_id, row->readme);
            if (row->message == SEND_START_INVALID) {
                EF_ASSERT_PARAM(TVO_LCM_SESSION_ACK_T_PARAM_PERIOD, ack.bad_param); /* the check that failed is named */
            }
            break;
        }
        case ANSWER_COMMAND: {
            const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
            TEST_ASSERT_EQUAL_INT_MESSAGE(row->status, cmd.header.status, row->readme);
            break;
        }
        case ANSWER_NONE:
        default:
            EXPECT_NOTHING_PUBLISHED();
            break;
        }
        const tvo_node_session_t *s = tvo_node_session(&node);
        TEST_ASSERT_EQUAL_INT64_MESSAGE(row->running_after, s != NULL ? s->session_id : -1, row->readme);
        snapshot_counters.other_session += (row->counted == COUNTED_OTHER_SESSION) ? 1 : 0;
        snapshot_counters.idle += (row->counted == COUNTED_IDLE) ? 1 : 0;
        snapshot_counters.wrong_boot += (row->counted == COUNTED_WRONG_BOOT) ? 1 : 0;
        if (row->kept) {
            ASSERT_SESSION_AND_COUNTERS_KEPT();
        } else if (row->counted != COUNTED_NONE) {
            TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&snapshot_counters, &node.counters, sizeof(node.counters), row->readme);
        }
        if (row->message == SEND_STOP_RUNNING) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(1, tvo_node_stop_requested(&node), row->readme);
        }
    }
    for (int state = 0; state < (int)TVO_NODE_STATE_COUNT; ++state) {
        for (int event = TVO_NODE_EVENT_NONE + 1; event < (int)TVO_NODE_EVENT_COUNT; ++event) {
            tvo_node_transition_info_t cell;
            TEST_ASSERT_TRUE(tvo_node_transition_info((tvo_node_state_t)state, (tvo_node_event_t)event, &cell));
            if (cell.reachable && !covered[state][event]) {
                static char text[96];
                (void)snprintf(text, sizeof(text), "table cell (state %d, event %d) is no row's", state, event);
                TEST_FAIL_MESSAGE(text);
            }
        }
    }
}

/* When idle no id runs: no message is a repeat, a conflict, a STOP of the running id or another
 * session's, and the table says those cells cannot arise. */
static void test_idle_cells_the_classification_cannot_reach_are_marked_so(void)
{
    const tvo_node_event_t unreachable[] = {TVO_NODE_EVENT_START_REPEAT, TVO_NODE_EVENT_START_CONFLICT,
                                            TVO_NODE_EVENT_STOP, TVO_NODE_EVENT_SAMPLE_OTHER,
                                            TVO_NODE_EVENT_TARGET_OTHER};
    for (size_t i = 0; i < sizeof(unreachable) / sizeof(unreachable[0]); ++i) {
        tvo_node_transition_info_t cell;
        TEST_ASSERT_TRUE(tvo_node_transition_info(TVO_NODE_IDLE, unreachable[i], &cell));
        TEST_ASSERT_EQUAL_UINT8(0u, cell.reachable);
    }
    /* Every message, whatever its id, when idle: START, STOP_OTHER, OTHER_ACTION, WRONG_BOOT, SAMPLE, TARGET. */
    const row_message_t all[] = {SEND_START_INVALID,    SEND_START_REPEAT,    SEND_START_OTHER_CONTENT,
                                 SEND_STOP_RUNNING,     SEND_STOP_OTHER,      SEND_OTHER_ACTION,
                                 SEND_START_OTHER_BOOT, SEND_STOP_OTHER_BOOT, SEND_SAMPLE_OWN,
                                 SEND_SAMPLE_OTHER,     SEND_TARGET_OWN,      SEND_TARGET_OTHER};
    for (size_t i = 0; i < sizeof(all) / sizeof(all[0]); ++i) {
        setUp();
        send_row_message(all[i]);
        tvo_node_transition_info_t cell;
        TEST_ASSERT_TRUE(tvo_node_transition_info(TVO_NODE_IDLE, node.last_event, &cell));
        TEST_ASSERT_EQUAL_UINT8(1u, cell.reachable);
    }
    tvo_node_transition_info_t cell;
    TEST_ASSERT_FALSE(tvo_node_transition_info(TVO_NODE_IDLE, TVO_NODE_EVENT_NONE, &cell));
    TEST_ASSERT_FALSE(tvo_node_transition_info(TVO_NODE_STATE_COUNT, TVO_NODE_EVENT_START, &cell));
    TEST_ASSERT_FALSE(tvo_node_transition_info(TVO_NODE_RUNNING, TVO_NODE_EVENT_COUNT, &cell));
}

/* ------------------------------------------------------------------------------------------------
 * CLOCK_PLANT timing
 * --------------------------------------------------------------------------------------------- */

static void test_plant_period_is_the_apply_instant_nearest_stamp_plus_tau(void)
{
    const int64_t jitters[] = {-H / 2, -2000, 0, 2000, H / 2 - 1};
    for (size_t i = 0; i < sizeof(jitters) / sizeof(jitters[0]); ++i) {
        setUp();
        start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, 3);
        m.header.utime += jitters[i];
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
        const tvo_node_session_t *s = tvo_node_session(&node);
        TEST_ASSERT_EQUAL_INT64(3, s->schedule.last_period);
        TEST_ASSERT_EQUAL_INT64(SEQ0 + 3, s->schedule.anchor.last_sequence);
        plant_meas(&m, 4);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(4));
    }
    /* Half a period later than the nominal stamp: the next period (and its sequence must say so). */
    setUp();
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    m.header.utime += H / 2;
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(4));
}

static void test_plant_age_outside_zero_to_h_is_refused_by_the_controller(void)
{
    /* tau = 0: a stamp after its apply instant (nearest grid point) is from the future. */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.delay_us = 0;
    (void)send_session(&start, 0);
    tvo_lcm_unicycle_sample_t m;
    ef_sample(&m, EF_SESSION_ID, plant_apply(3) + 3000, SEQ0 + 3, 0);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_FUTURE_STAMP);
    ef_sample(&m, EF_SESSION_ID, plant_apply(3), SEQ0 + 3, 0);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
    /* tau = h: a stamp more than a period before its apply instant is stale. */
    setUp();
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.delay_us = H;
    (void)send_session(&start, 0);
    ef_sample(&m, EF_SESSION_ID, plant_apply(3) - H - 4000, SEQ0 + 3, 0);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE);
    ef_sample(&m, EF_SESSION_ID, plant_apply(3) - H, SEQ0 + 3, 0);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
}

static void test_plant_duplicates_and_reordering_are_out_of_order(void)
{
    plant_session_after(1);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 1);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER); /* duplicate */
    plant_meas(&m, 3);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3)); /* a lost period: consistent stamp and sequence */
    plant_meas(&m, 2);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER); /* arrives late */
    plant_meas(&m, 0);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
    plant_meas(&m, 4);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(4));
}

/* Field by field (a struct's padding is not part of it). */
static void assert_same_command(const tvo_lcm_unicycle_command_t *a, const tvo_lcm_unicycle_command_t *b)
{
    TEST_ASSERT_EQUAL_INT64(a->header.utime, b->header.utime);
    TEST_ASSERT_EQUAL_INT64(a->header.session_id, b->header.session_id);
    TEST_ASSERT_EQUAL_INT64(a->header.measurement_sequence, b->header.measurement_sequence);
    TEST_ASSERT_EQUAL_INT32(a->header.robot, b->header.robot);
    TEST_ASSERT_EQUAL_MEMORY(&a->speed_mps, &b->speed_mps, sizeof(a->speed_mps));
    TEST_ASSERT_EQUAL_MEMORY(&a->turn_rate_radps, &b->turn_rate_radps, sizeof(a->turn_rate_radps));
    TEST_ASSERT_EQUAL_INT32(a->header.status, b->header.status);
    TEST_ASSERT_EQUAL_INT32(a->header.flags, b->header.flags);
}

static void test_plant_stray_stamps_cost_the_genuine_stream_nothing(void)
{
    /* A reference node sees the genuine stream only. */
    static tvo_lcm_unicycle_command_t reference[6];
    plant_session_after(0);
    for (int64_t j = 1; j <= 5; ++j) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        reference[j] = EXPECT_ACCEPTED(m, 0, plant_apply(j));
    }
    /* This one sees a stray after each genuine sample. */
    setUp();
    plant_session_after(0);
    for (int64_t j = 1; j <= 5; ++j) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        const tvo_lcm_unicycle_command_t cmd = EXPECT_ACCEPTED(m, 0, plant_apply(j));
        assert_same_command(&reference[j], &cmd);
        tvo_lcm_unicycle_sample_t stray;
        switch (j) {
        case 1: /* a stamp 20 s ahead with the next sequence */
            ef_sample(&stray, EF_SESSION_ID, plant_apply(2000), (int32_t)(SEQ0 + j + 1), 0);
            (void)EXPECT_REFUSED(stray, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
            break;
        case 2: /* a stamp in the past */
            ef_sample(&stray, EF_SESSION_ID, plant_apply(0) - TAU, (int32_t)(SEQ0 + j + 1), 0);
            (void)EXPECT_REFUSED(stray, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
            break;
        case 3: /* before the epoch */
            ef_sample(&stray, EF_SESSION_ID, EF_EPOCH - 10 * H, (int32_t)(SEQ0 + j + 1), 0);
            (void)EXPECT_REFUSED(stray, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
            break;
        case 4: /* the right stamp, a wild sequence */
            plant_meas(&stray, j + 1);
            stray.header.sequence = (int32_t)SEQ0 + (1 << 30);
            (void)EXPECT_REFUSED(stray, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
            break;
        default: /* garbage values of the right fingerprint */
            plant_meas(&stray, j + 1);
            stray.position_m[0] = (double)NAN;
            (void)EXPECT_REFUSED(stray, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE);
            break;
        }
    }
}

static void test_plant_huge_sequences_are_refused(void)
{
    plant_session_after(1);
    /* Negative ones are test_sample_sequence_extremes' (refused unanswered). */
    const int32_t bad[] = {(int32_t)SEQ0 + 2 + 1, (int32_t)SEQ0 + (1 << 30), INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        const int64_t j = 2 + (int64_t)i;
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        m.header.sequence = bad[i];
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
        /* A watchdog's worth of refusals would stop: keep below it with the genuine sample. */
        plant_meas(&m, j);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j));
    }
}

/* CLOCK_PLANT: a jump past the watchdog's span (from the last accepted period to j) is served once
 * three samples in a row agree on it: j and j + 1 refused, j + 2 served. */
static void plant_jump_to(int64_t j)
{
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, j);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    plant_meas(&m, j + 1);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    plant_meas(&m, j + 2);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 2));
}

static void test_plant_gap_with_consistent_sequence_is_accepted(void)
{
    plant_session_after(1);
    tvo_lcm_unicycle_sample_t m;
    /* A gap within the watchdog's span is served at once. */
    plant_meas(&m, 1 + EF_WATCHDOG);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(1 + EF_WATCHDOG));
    /* A longer one once three samples agree on it (a plant back from a silence it stopped itself in). */
    plant_jump_to(1 + EF_WATCHDOG + 7);
    const int64_t last = 1 + EF_WATCHDOG + 7 + 2;
    /* A gap beyond the controller's tick span is stale: the plant must START anew. */
    const int64_t beyond = last + (int64_t)TVO_MAX_TICK_SPAN / H + 1;
    plant_meas(&m, beyond);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE);
    plant_meas(&m, last + 1); /* ends the streak of refusals before the next jump's two */
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(last + 1));
    /* The longest gap the span holds, once three samples agree on it. */
    plant_jump_to(beyond - 3);
}

/* Issue 25's bound: one genuine sample stamped 20 s ahead with a sequence that agrees (a plant's clock
 * fault) costs its own refusal, not 20 s of safe stops; the stream after it is served at once. */
static void test_plant_one_sample_far_ahead_costs_one_refusal(void)
{
    plant_session_after(5);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 5 + 2000);
    const tvo_lcm_unicycle_command_t refused = EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    TEST_ASSERT_TRUE(((uint32_t)refused.header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING) != 0u);
    TEST_ASSERT_TRUE(((uint32_t)refused.header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) == 0u);
    for (int64_t j = 6; j < 6 + 50; ++j) {
        plant_meas(&m, j);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j));
    }
    /* Strays interleaved with the genuine stream never add up to a vote: each served sample ends the streak. */
    for (int64_t j = 56; j < 56 + 6; ++j) {
        plant_meas(&m, j + 2000);
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
        plant_meas(&m, j);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j));
    }
}

/* A refused sample's answer, whatever it is refused for (a streak of refusals answers with the safe
 * stop): its sequence echoed, held or stopped, and what it returns is that answer. */
static tvo_lcm_unicycle_command_t expect_refused_any(const tvo_lcm_unicycle_sample_t *m, int line)
{
    ef_record_clear(&rec);
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(m, 0), line, "handled");
    const tvo_lcm_unicycle_command_t cmd = the_command(line);
    UNITY_TEST_ASSERT(cmd.header.status != TVO_LCM_COMMAND_HEADER_T_STATUS_OK, line, "refused");
    UNITY_TEST_ASSERT_EQUAL_INT64(m->header.sequence, cmd.header.measurement_sequence, line, "sequence echoed");
    UNITY_TEST_ASSERT(((uint32_t)cmd.header.flags & (TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING |
                                                     TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP)) != 0u,
                      line, "held or stopped");
    return cmd;
}

/* node_counters_t: `refused` counts each refused sample once, under the command_header_t.status its
 * answer carries. The tester's sequence: 100 good samples, 14 NaN (a streak past the watchdog, answered
 * with safe stops, status 15), then good ones. Per answer, exactly the counter of its status rose by one
 * (accepted for status 0); before the fix the streak's stops were counted under the attempt's status. */
static void test_plant_each_refusal_is_counted_under_the_status_its_answer_carries(void)
{
    plant_session_after(0);
    int32_t stops = 0, not_finite = 0;
    for (int64_t j = 1; j <= 120; ++j) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        const int bad = j > 100 && j <= 114;
        if (bad) {
            m.position_m[0] = (double)NAN;
        }
        const tvo_lcm_node_counters_t before = node.counters;
        ef_record_clear(&rec);
        TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(&m, 0));
        const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
        const int32_t status = cmd.header.status;
        TEST_ASSERT_EQUAL_INT64(m.header.sequence, cmd.header.measurement_sequence);
        TEST_ASSERT_TRUE_MESSAGE(status >= 0 && status < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS, "status in a slot");
        if (bad) {
            TEST_ASSERT_TRUE_MESSAGE(status == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE ||
                                         status == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG,
                                     "a NaN sample: not finite, or the streak's safe stop");
        }
        if (status == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG) {
            TEST_ASSERT_TRUE(((uint32_t)cmd.header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0u);
            ++stops;
        }
        not_finite += status == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE;
        TEST_ASSERT_EQUAL_INT32(before.accepted + (status == TVO_LCM_COMMAND_HEADER_T_STATUS_OK ? 1 : 0),
                                node.counters.accepted);
        for (int32_t slot = 0; slot < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++slot) {
            const int32_t rose = node.counters.refused[slot] - before.refused[slot];
            char what[64];
            (void)snprintf(what, sizeof(what), "sample %d answered %d: refused[%d]", (int)j, (int)status, (int)slot);
            TEST_ASSERT_EQUAL_INT32_MESSAGE((status != 0 && slot == status) ? 1 : 0, rose, what);
        }
        if (status != 0 && status != TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG) {
            TEST_ASSERT_EQUAL_INT(status, node.last_refusal); /* a stop's last_refusal keeps the why behind it */
        }
    }
    TEST_ASSERT_EQUAL_INT32(W - 1, not_finite); /* the streak's first W - 1, then its stops */
    TEST_ASSERT_EQUAL_INT32(14 - (W - 1), stops);
    TEST_ASSERT_EQUAL_INT32(stops, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG]);
    TEST_ASSERT_EQUAL_INT32(not_finite, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE]);
}

/* Issue 39: after a jump past the watchdog's span, late or repeated samples arriving among the genuine
 * ones (a retry queue flushing: copies of samples already served, and of the genuine ones already
 * refused) cost their own refusal only: the genuine stream is served from its third sample whatever
 * their number (before the fix each copy restarted the vote: with 20 copies, served from the 22nd). */
static void test_plant_stale_copies_after_a_jump_do_not_restart_the_vote(void)
{
    const int copies[] = {0, 1, 5, 20};
    for (size_t c = 0; c < sizeof(copies) / sizeof(copies[0]); ++c) {
        setUp();
        plant_session_after(5);
        const int64_t j = 5 + W + 10; /* a jump past the watchdog's span */
        int sent = 0;
        for (int64_t k = 0; k < 2; ++k) {
            tvo_lcm_unicycle_sample_t genuine;
            plant_meas(&genuine, j + k);
            const tvo_lcm_unicycle_command_t cmd = expect_refused_any(&genuine, __LINE__);
            TEST_ASSERT_TRUE_MESSAGE(cmd.header.status == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP ||
                                         cmd.header.status == TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG,
                                     "a genuine sample before the vote carries: the jump (or the streak's stop)");
            /* Half the copies after each of the two refused genuine samples. */
            const int here = (k == 0) ? copies[c] / 2 : copies[c] - copies[c] / 2;
            for (int i = 0; i < here; ++i, ++sent) {
                tvo_lcm_unicycle_sample_t copy;
                if (sent % 2 == 0) {
                    plant_meas(&copy, 5 - (sent / 2) % 5); /* a copy of a sample served before the gap */
                } else {
                    plant_meas(&copy, j + (sent / 2) % (k + 1)); /* a copy of a genuine one already refused */
                }
                (void)expect_refused_any(&copy, __LINE__);
            }
        }
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j + 2);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 2)); /* the third genuine sample, for every count */
        plant_meas(&m, j + 3);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 3));
        /* ... and a copy after it costs its own refusal too: the stream goes on. */
        plant_meas(&m, j + 1);
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
        plant_meas(&m, j + 4);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 4));
    }
}

static void test_plant_watchdog_refusals_in_a_row_give_a_safe_stop_until_one_is_accepted(void)
{
    plant_session_after(2);
    tvo_lcm_unicycle_sample_t dup;
    plant_meas(&dup, 2);
    for (int64_t k = 1; k < W; ++k) {
        (void)EXPECT_REFUSED(dup, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
    }
    TEST_ASSERT_EQUAL_INT32(0, node.counters.safe_stops);
    tvo_lcm_unicycle_command_t cmd = EXPECT_REFUSED(dup, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG);
    TEST_ASSERT_EQUAL_INT64(SEQ0 + 2, cmd.header.measurement_sequence);
    TEST_ASSERT_EQUAL_INT32(1, node.counters.safe_stops);
    cmd = EXPECT_REFUSED(dup, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG); /* and on, until one is accepted */
    TEST_ASSERT_EQUAL_INT32(2, node.counters.safe_stops);
    TEST_ASSERT_EQUAL_INT32(W - 1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER]);
    TEST_ASSERT_EQUAL_INT32(2, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG]); /* the stops' status */
    /* The controller dropped to rest: it holds zero until a measurement is accepted. */
    const tvo_node_session_t *s = tvo_node_session(&node);
    TEST_ASSERT_TRUE(s->controller.u.unicycle.internal.held.speed_mps[0] == TVO_R(0.0));
    TEST_ASSERT_TRUE(s->controller.u.unicycle.internal.speed_state_mps[0] == TVO_R(0.0));
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
    TEST_ASSERT_EQUAL_UINT32(0u, ef_refusals_in_row(&tvo_node_session(&node)->controller));
    plant_meas(&dup, 3);
    (void)EXPECT_REFUSED(dup, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER); /* the count restarted */
}

/* Copies of served samples (a retry queue flushing), fewer than watchdog_periods in a row, cost their
 * refusals only: the next genuine samples are answered bit for bit as without them. (watchdog_periods
 * of them are the watchdog's stop: the test above; a link stuck on its last sample must stop.) */
static void test_plant_fewer_copies_than_the_watchdog_cost_their_refusals_only(void)
{
    tvo_lcm_unicycle_command_t without[2];
    for (int with_copies = 0; with_copies < 2; ++with_copies) {
        setUp();
        plant_session_after(6);
        tvo_lcm_unicycle_sample_t m;
        for (int64_t i = 0; with_copies && i < W - 1; ++i) {
            plant_meas(&m, 6 - i % 6); /* 6, 5, .., 1, 6, ..: the newest served and older ones */
            (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
        }
        TEST_ASSERT_EQUAL_INT32(0, node.counters.safe_stops);
        for (int64_t j = 7; j < 9; ++j) {
            plant_meas(&m, j);
            const tvo_lcm_unicycle_command_t cmd = EXPECT_ACCEPTED(m, 0, plant_apply(j));
            if (!with_copies) {
                without[j - 7] = cmd;
                continue;
            }
            TEST_ASSERT_EQUAL_INT64(without[j - 7].header.utime, cmd.header.utime);
            TEST_ASSERT_EQUAL_INT(without[j - 7].header.status, cmd.header.status);
            TEST_ASSERT_EQUAL_INT(without[j - 7].header.flags, cmd.header.flags);
            TEST_ASSERT_EQUAL_MEMORY(&without[j - 7].speed_mps, &cmd.speed_mps, sizeof(cmd.speed_mps));
            TEST_ASSERT_EQUAL_MEMORY(&without[j - 7].turn_rate_radps, &cmd.turn_rate_radps, sizeof(cmd.turn_rate_radps));
        }
    }
}

static void test_plant_wrong_robot_plant_and_non_finite_values_are_refused(void)
{
    plant_session_after(1);
    tvo_lcm_unicycle_sample_t m;
    /* A robot the session does not have: refused, counted, unanswered (it steps no period). */
    const int8_t robots[] = {INT8_MIN, -1, 1, INT8_MAX};
    for (size_t i = 0; i < sizeof(robots) / sizeof(robots[0]); ++i) {
        plant_meas(&m, 2);
        m.header.robot = robots[i];
        take_snapshot();
        ef_record_clear(&rec);
        TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(&m, 0));
        EXPECT_NOTHING_PUBLISHED();
        TEST_ASSERT_EQUAL_INT32((int32_t)i + 1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION]);
        ASSERT_SESSION_KEPT();
    }
    /* A chain's sample to a unicycle session: refused, counted under ERR_PARAM, unanswered. */
    tvo_lcm_chain_sample_t chain;
    memset(&chain, 0, sizeof(chain));
    chain.header = m.header;
    chain.header.robot = 0;
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_CHAIN_SAMPLE, send_chain_sample(&chain, 0));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM]);
    ASSERT_SESSION_KEPT();
    plant_meas(&m, 2);
    m.heading_rad = INFINITY;
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE);
    plant_meas(&m, 2);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(2));
}

/* ------------------------------------------------------------------------------------------------
 * CLOCK_NODE timing and the timer
 * --------------------------------------------------------------------------------------------- */

static void test_node_clock_offset_comes_from_the_start_and_commands_are_in_plant_time(void)
{
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, NODE_T0);
    const tvo_node_session_t *s = tvo_node_session(&node);
    TEST_ASSERT_EQUAL_INT64(OFFSET, s->schedule.anchor.offset_us);
    TEST_ASSERT_EQUAL_INT64(EF_EPOCH + OFFSET, s->schedule.anchor.epoch_schedule_us);
    /* Arriving 3 ms after A_0: serves period 1. */
    tvo_lcm_unicycle_sample_t m;
    const int64_t now = node_apply(0) + 3000;
    ef_sample(&m, EF_SESSION_ID, now - OFFSET - 1000, 42, 0);
    (void)EXPECT_ACCEPTED(m, now, node_apply(1) - OFFSET);
    /* Before the epoch: period 0 (if the sample is young enough for it). */
    setUp();
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, NODE_T0);
    const int64_t early = node_apply(0) - 6000;
    ef_sample(&m, EF_SESSION_ID, early - OFFSET - 1000, 7, 0);
    (void)EXPECT_ACCEPTED(m, early, node_apply(0) - OFFSET);
    /* A second sample before A_0 serves the next period, not the one already served (its stamp,
     * 1 ms ahead of the node's clock, is young enough for A_1). */
    const int64_t soon = node_apply(0) - 1000;
    ef_sample(&m, EF_SESSION_ID, node_apply(0) - OFFSET, 8, 0);
    (void)EXPECT_ACCEPTED(m, soon, node_apply(1) - OFFSET);
}

static void test_node_clock_sequence_is_only_echoed(void)
{
    node_session_after(1);
    tvo_lcm_unicycle_sample_t m;
    node_meas(&m, 2, 123456789); /* any sequence in range */
    (void)EXPECT_ACCEPTED(m, node_arrival(2), node_apply(2) - OFFSET);
    node_meas(&m, 3, 5);         /* even going back */
    (void)EXPECT_ACCEPTED(m, node_arrival(3), node_apply(3) - OFFSET);
}

static void test_node_clock_stamp_more_than_half_a_period_ahead_is_implausible(void)
{
    node_session_after(1);
    tvo_lcm_unicycle_sample_t m;
    const int64_t now = node_apply(1) + 1000;
    ef_sample(&m, EF_SESSION_ID, now - OFFSET + H / 2 + 1, 2, 0);
    (void)EXPECT_REFUSED(m, now, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    ef_sample(&m, EF_SESSION_ID, now - OFFSET + 20000000, 2, 0); /* 20 s ahead */
    (void)EXPECT_REFUSED(m, now, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    /* Exactly h/2 ahead: within the tolerance; A_2 = now + 9 ms is after it. */
    ef_sample(&m, EF_SESSION_ID, now - OFFSET + H / 2, 2, 0);
    (void)EXPECT_ACCEPTED(m, now, node_apply(2) - OFFSET);
    /* The genuine stream is not locked out by the stray. */
    node_meas(&m, 3, 3);
    (void)EXPECT_ACCEPTED(m, node_arrival(3), node_apply(3) - OFFSET);
}

static void test_node_clock_stale_and_repeated_stamps_are_refused(void)
{
    node_session_after(1);
    tvo_lcm_unicycle_sample_t m;
    /* Arriving at A_1 + 2 ms: serves A_2; sampled 1 ms after A_0 is 19 ms old there. */
    const int64_t now = node_apply(1) + 2000;
    ef_sample(&m, EF_SESSION_ID, node_apply(0) + 1000 - OFFSET, 2, 0);
    (void)EXPECT_REFUSED(m, now, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE);
    /* A sample stamped at A_2 itself (1 ms ahead of the node's clock) serves A_2 with age 0; the
     * same stamp again serves A_3 with age h, but is not newer than the last accepted one. */
    ef_sample(&m, EF_SESSION_ID, node_apply(2) - OFFSET, 2, 0);
    (void)EXPECT_ACCEPTED(m, node_apply(2) - 1000, node_apply(2) - OFFSET);
    (void)EXPECT_REFUSED(m, node_apply(2) - 500, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
    node_meas(&m, 3, 3);
    (void)EXPECT_ACCEPTED(m, node_arrival(3), node_apply(3) - OFFSET);
}

static void test_node_timer_has_no_deadline_before_the_first_accepted_measurement(void)
{
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, NODE_T0);
    const int64_t times[] = {0, NODE_T0, node_apply(0), node_apply(100), EF_TWO_POW_60, INT64_MAX, INT64_MIN};
    for (size_t i = 0; i < sizeof(times) / sizeof(times[0]); ++i) {
        const int64_t deadline = tvo_node_poll(&node, times[i]);
        TEST_ASSERT_EQUAL_INT64(node.next_announcement_us, deadline); /* no timer: only the next announcement */
    }
    tvo_lcm_unicycle_sample_t m;
    node_meas(&m, 1, 1);
    m.position_m[1] = (double)NAN;
    (void)EXPECT_REFUSED(m, node_arrival(1), TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE); /* a refusal does not arm it */
    ef_record_clear(&rec);
    const int64_t deadline = tvo_node_poll(&node, node_apply(50));
    TEST_ASSERT_EQUAL_INT64(node.next_announcement_us, deadline);
    EXPECT_NOTHING_PUBLISHED();
}

/* What tvo_node_poll answers when the timer's next deadline is `timer`: the earlier of it and the
 * node's next announcement (read after the poll, which may have announced). */
static int64_t with_announcement(int64_t timer)
{
    return timer < node.next_announcement_us ? timer : node.next_announcement_us;
}

/* The only message published since the last clear: a command, with no telemetry (the node's own stop). */
static tvo_lcm_unicycle_command_t the_own_stop(int line)
{
    tvo_lcm_unicycle_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    UNITY_TEST_ASSERT_EQUAL_UINT32(1u, rec.count, line, "one message: the stop, no telemetry");
    const ef_message_t *m = ef_record_nth(&rec, TVO_NODE_CH_COMMAND, 0);
    if (m == NULL) {
        UNITY_TEST_FAIL(line, "no command");
        return cmd;
    }
    UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_unicycle_command_t_decode(m->data, 0, (int)m->length, &cmd),
                                line, "command decodes");
    return cmd;
}

static void expect_timer_stop(int64_t now, int64_t next_deadline, int line)
{
    ef_record_clear(&rec);
    const int64_t deadline = tvo_node_poll(&node, now);
    const tvo_lcm_unicycle_command_t cmd = the_own_stop(line);
    ef_assert_status(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, cmd.header.status, line);
    UNITY_TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP, (uint32_t)cmd.header.flags, line, "flags");
    expect_safe_stop(&cmd, line);
    UNITY_TEST_ASSERT_EQUAL_INT64(-1, cmd.header.measurement_sequence, line, "the node's own stop answers nothing");
    UNITY_TEST_ASSERT_EQUAL_INT64(now - OFFSET, cmd.header.utime, line, "stamped now, in plant time");
    UNITY_TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, cmd.header.session_id, line, "session");
    UNITY_TEST_ASSERT_EQUAL_INT64(with_announcement(next_deadline), deadline, line, "next deadline");
}
#define EXPECT_TIMER_STOP(now, next) expect_timer_stop((now), (next), __LINE__)

static void expect_timer_quiet(int64_t now, int64_t deadline, int line)
{
    ef_record_clear(&rec);
    const int64_t answer = tvo_node_poll(&node, now);
    UNITY_TEST_ASSERT_EQUAL_INT64(with_announcement(deadline), answer, line, "deadline");
    expect_nothing_published(line);
}
#define EXPECT_TIMER_QUIET(now, deadline) expect_timer_quiet((now), (deadline), __LINE__)

static void test_node_timer_stops_at_last_apply_plus_watchdog_periods_then_every_period(void)
{
    node_session_after(2); /* last apply: A_2 */
    const int64_t due = node_apply(2 + W);
    EXPECT_TIMER_QUIET(node_arrival(2), due);
    EXPECT_TIMER_QUIET(node_apply(3), due);
    EXPECT_TIMER_QUIET(due - 1, due);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.safe_stops);
    EXPECT_TIMER_STOP(due, node_apply(3 + W));
    TEST_ASSERT_EQUAL_INT32(1, node.counters.safe_stops);
    EXPECT_TIMER_QUIET(due, node_apply(3 + W)); /* polled again at once: nothing more */
    EXPECT_TIMER_QUIET(node_apply(3 + W) - 1, node_apply(3 + W));
    EXPECT_TIMER_STOP(node_apply(3 + W), node_apply(4 + W));
    /* Polled late (the transport slept long): one stop, stamped now, the next deadline after now. */
    const int64_t late = node_apply(9 + W) + 1234;
    EXPECT_TIMER_STOP(late, node_apply(10 + W));
    TEST_ASSERT_EQUAL_INT32(3, node.counters.safe_stops);
    /* The controller is at rest; a refused measurement holds zero. */
    const tvo_node_session_t *s = tvo_node_session(&node);
    TEST_ASSERT_TRUE(s->controller.u.unicycle.internal.held.speed_mps[0] == TVO_R(0.0));
    /* Tracking resumes with the next accepted measurement, and the timer restarts from it. */
    tvo_lcm_unicycle_sample_t m;
    const int64_t j = 10 + W;
    node_meas(&m, j, 99);
    const tvo_lcm_unicycle_command_t cmd = EXPECT_ACCEPTED(m, node_arrival(j), node_apply(j) - OFFSET);
    TEST_ASSERT_TRUE(cmd.speed_mps != 0.0f || cmd.turn_rate_radps != 0.0f);
    EXPECT_TIMER_QUIET(node_arrival(j), node_apply(j + W));
    EXPECT_TIMER_STOP(node_apply(j + W), node_apply(j + W + 1));
}

static void test_node_timer_is_not_moved_by_refused_measurements(void)
{
    node_session_after(2);
    const int64_t due = node_apply(2 + W);
    tvo_lcm_unicycle_sample_t m;
    node_meas(&m, 3, 3);
    m.header.robot = 3;
    ef_record_clear(&rec);
    (void)send_sample(&m, node_arrival(3));
    EXPECT_NOTHING_PUBLISHED(); /* no robot of the session: refused on arrival, unanswered */
    node_meas(&m, 4, 4);
    m.position_m[0] = (double)NAN;
    (void)EXPECT_REFUSED(m, node_arrival(4), TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE);
    EXPECT_TIMER_QUIET(due - 1, due);
    EXPECT_TIMER_STOP(due, node_apply(3 + W));
}

static void test_plant_clock_sessions_have_no_timer(void)
{
    plant_session_after(2);
    const int64_t times[] = {0, plant_apply(3), plant_apply(1000), EF_TWO_POW_60};
    for (size_t i = 0; i < sizeof(times) / sizeof(times[0]); ++i) {
        EXPECT_TIMER_QUIET(times[i], TVO_NODE_NO_DEADLINE);
    }
}

static void test_stop_disarms_the_timer(void)
{
    node_session_after(2);
    tvo_lcm_session_t stop;
    stop_message(&stop, EF_SESSION_ID);
    (void)send_session(&stop, node_apply(3));
    EXPECT_TIMER_QUIET(node_apply(2 + W), TVO_NODE_NO_DEADLINE);
    EXPECT_TIMER_QUIET(node_apply(100), TVO_NODE_NO_DEADLINE);
}

/* ------------------------------------------------------------------------------------------------
 * Telemetry counters, undecodable input, the slack rule
 * --------------------------------------------------------------------------------------------- */

/* The latest announcement published since the last clear of `announcements`, decoded. */
static tvo_lcm_node_status_t latest_announcement(int line)
{
    tvo_lcm_node_status_t status;
    memset(&status, 0, sizeof(status));
    UNITY_TEST_ASSERT(announcements.count > 0u, line, "an announcement");
    if (announcements.count == 0u) {
        return status;
    }
    const ef_message_t *m = &announcements.message[announcements.count - 1u];
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_NODE, m->channel, line, "on TVO_NODE");
    UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_node_status_t_decode(m->data, 0, (int)m->length, &status), line,
                                "node_status_t decodes");
    return status;
}
#define LATEST_ANNOUNCEMENT() latest_announcement(__LINE__)

static void test_counters_count_every_kind_of_event_and_the_announcement_carries_them(void)
{
    plant_session_after(2);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 2);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER);
    plant_meas(&m, 3);
    m.position_m[0] = (double)NAN;
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE);
    plant_meas(&m, 3);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
    /* Malformed: garbage, truncated, padded, empty, NULL; the right length with another type's
     * fingerprint (a chain sample's bytes cut to a unicycle sample's length). */
    static const uint8_t garbage[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    plant_meas(&m, 3);
    const int n = tvo_lcm_unicycle_sample_t_encode(wire, 0, (int)sizeof(wire), &m);
    TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_SAMPLE), n);
    static uint8_t other_type[128];
    tvo_lcm_chain_sample_t chain;
    memset(&chain, 0, sizeof(chain));
    TEST_ASSERT_TRUE(tvo_lcm_chain_sample_t_encode(other_type, 0, (int)sizeof(other_type), &chain) > n);
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, garbage, sizeof(garbage), 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, wire, (uint32_t)n - 1u, 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, wire, (uint32_t)n + 1u, 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SESSION, garbage, sizeof(garbage), 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_TARGET, wire, 0u, 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, NULL, (uint32_t)n, 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, wire, UINT32_MAX, 0));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, TVO_NODE_CH_SAMPLE, other_type, (uint32_t)n, 0));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(8, node.counters.malformed);
    /* A transport's drops before the node (an authenticated link's). */
    tvo_node_count_drop(&node, TVO_NODE_DROP_MALFORMED);
    tvo_node_count_drop(&node, TVO_NODE_DROP_UNAUTHENTICATED);
    tvo_node_count_drop(&node, TVO_NODE_DROP_REPLAYED);
    tvo_node_count_drop(&node, TVO_NODE_DROP_REPLAYED);
    tvo_node_count_drop(&node, TVO_NODE_DROP_COUNT); /* not a drop: nothing */
    tvo_node_count_drop(NULL, TVO_NODE_DROP_REPLAYED);
    /* Not the node's channels (its own outputs, unknown numbers): not taken, counted as malformed (only a
     * serial link or a confused transport hands them to a node). */
    const int others[] = {TVO_NODE_CH_COMMAND, TVO_NODE_CH_TELEMETRY, TVO_NODE_CH_SESSION_ACK, TVO_NODE_CH_NODE,
                          TVO_NODE_CH_CHAIN_COMMAND, 0, -1, 10, 99, INT32_MIN};
    for (size_t i = 0; i < sizeof(others) / sizeof(others[0]); ++i) {
        TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(&node, others[i], wire, (uint32_t)n, 0));
    }
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(9 + (int32_t)(sizeof(others) / sizeof(others[0])), node.counters.malformed);
    /* Another session's; a target the session cannot take (its target is not streamed). */
    m.header.session_id = OTHER_ID;
    (void)send_sample(&m, 0);
    tvo_lcm_target_t t;
    memset(&t, 0, sizeof(t));
    t.header.utime = plant_apply(2);
    t.header.session_id = EF_SESSION_ID;
    t.header.robot = 0;
    (void)send_target(&t, 0);
    TEST_ASSERT_EQUAL_INT32(1, node.counters.targets_refused);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, node.last_target_status);
    /* A safe stop: watchdog_periods refusals in a row. */
    plant_meas(&m, 3);
    for (int64_t k = 0; k < W; ++k) {
        ef_record_clear(&rec);
        (void)send_sample(&m, 0);
    }
    plant_meas(&m, 4);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(4));
    /* The next announcement carries them (the START at node time 0 announced; the next is due 1 s later). */
    ef_record_clear(&announcements);
    (void)tvo_node_poll(&node, TVO_LCM_NODE_STATUS_T_RUNNING_PERIOD_US - 1);
    TEST_ASSERT_EQUAL_UINT32(0u, announcements.count);
    (void)tvo_node_poll(&node, TVO_LCM_NODE_STATUS_T_RUNNING_PERIOD_US);
    const tvo_lcm_node_status_t status = LATEST_ANNOUNCEMENT();
    TEST_ASSERT_EQUAL_MEMORY(tvo_node_counters(&node), &status.counters, sizeof(status.counters));
    const tvo_lcm_node_counters_t *c = &status.counters;
    TEST_ASSERT_EQUAL_INT32(4, c->accepted);
    TEST_ASSERT_EQUAL_INT32((int32_t)W, c->refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER]);
    TEST_ASSERT_EQUAL_INT32(1, c->refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG]); /* the streak's stop */
    TEST_ASSERT_EQUAL_INT32(1, c->refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE]);
    TEST_ASSERT_EQUAL_INT32(9 + (int32_t)(sizeof(others) / sizeof(others[0])), c->malformed);
    TEST_ASSERT_EQUAL_INT32(1, c->unauthenticated);
    TEST_ASSERT_EQUAL_INT32(2, c->replayed);
    TEST_ASSERT_EQUAL_INT32(1, c->other_session);
    TEST_ASSERT_EQUAL_INT32(1, c->safe_stops);
    TEST_ASSERT_EQUAL_INT32(1, c->targets_refused);
    TEST_ASSERT_EQUAL_INT32(0, c->speed_mismatch);
    TEST_ASSERT_EQUAL_INT32(0, c->wrong_boot);
    TEST_ASSERT_EQUAL_INT32(0, c->idle);
    TEST_ASSERT_EQUAL_INT32(0, c->predicted);
    TEST_ASSERT_EQUAL_INT32(1, c->sessions);
    int32_t refused = 0;
    for (int i = 0; i < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++i) {
        refused += c->refused[i];
    }
    TEST_ASSERT_EQUAL_INT32(2 + (int32_t)W, refused);
}

static void test_counters_count_speed_mismatch_steps(void)
{
    /* A plant that reports a speed beyond anything it was commanded (|v| <= speed_max = 2), yet
     * plausible (below 2 speed_max + 0.5); 10 m/s is refused, as the next test says. */
    plant_session_after(0);
    for (int64_t j = 1; j <= (int64_t)TVO_SPEED_MISMATCH_PERIODS + 1; ++j) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        m.has |= TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
        m.speed_mps = 4.0f;
        const tvo_lcm_unicycle_command_t cmd = EXPECT_ACCEPTED(m, 0, plant_apply(j));
        const int flagged = ((uint32_t)cmd.header.flags & TVO_FLAG_SPEED_MISMATCH) != 0u;
        TEST_ASSERT_EQUAL_INT(j >= (int64_t)TVO_SPEED_MISMATCH_PERIODS, flagged);
    }
    TEST_ASSERT_EQUAL_INT32(2, node.counters.speed_mismatch);
}

static void test_plant_implausible_measurements_are_refused_and_keep_nothing(void)
{
    /* The independent client's cases: a speed of 1e3 m/s, a position of 1e6 m, a heading of 1e6 rad,
     * each refused with its own status and nothing of it kept; the stream then goes on. */
    plant_session_after(2);
    for (int which = 0; which < 3; ++which) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, 3 + 2 * which);
        switch (which) {
        case 0:
            m.has |= TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
            m.speed_mps = (float)1e3;
            break;
        case 1: m.position_m[0] = 1e6; break;
        default: m.heading_rad = 1e6; break;
        }
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT);
        plant_meas(&m, 4 + 2 * which); /* the genuine stream goes on (and the watchdog's count restarts) */
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(4 + 2 * which));
    }
    TEST_ASSERT_EQUAL_INT32(3, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT]);
}

/* A START whose robot 0 streams its target and must stay in x <= 0.5 (a half-space). */
static void streamed_constrained_start(tvo_lcm_session_t *m)
{
    ef_start(m, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    m->robot[0].target.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    m->halfspace_count = 1;
    m->halfspace[0].robot = 0;
    m->halfspace[0].normal[0] = 1.0;
    m->halfspace[0].bound_m = 0.5;
}

static void target_at_epoch(tvo_lcm_target_t *t)
{
    memset(t, 0, sizeof(*t));
    t->header.utime = EF_EPOCH;
    t->header.session_id = EF_SESSION_ID;
    t->header.robot = 0;
    t->position_m[0] = 0.2;
}

static void test_slack_rule_is_undone_when_the_first_step_fails(void)
{
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    /* Reference: the target, then the first sample at x = 1 (violating x <= 0.5 by 0.5). */
    streamed_constrained_start(&start);
    (void)send_session(&start, 0);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_TARGET, send_target(&t, 0));
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 2);
    m.position_m[0] = 1.0;
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(2));
    const tvo_real_t reference_slack = tvo_node_session(&node)->problem.barrier.slack0;
    TEST_ASSERT_TRUE(reference_slack > TVO_R(0.0));

    /* Now a first sample at x = 2 whose step fails (no target sample yet), then as above. */
    setUp();
    (void)send_session(&start, 0);
    tvo_lcm_unicycle_sample_t first;
    plant_meas(&first, 1);
    first.position_m[0] = 2.0;
    ef_record_clear(&rec);
    (void)send_sample(&first, 0);
    const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_TARGET_NOT_READY, cmd.header.status);
    TEST_ASSERT_TRUE(cmd.header.utime >= first.header.utime);
    TEST_ASSERT_TRUE(((uint32_t)cmd.header.flags & (TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP)) != 0u);
    TEST_ASSERT_EQUAL_INT32(1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_TARGET_NOT_READY]);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.accepted);
    const tvo_node_session_t *s = tvo_node_session(&node);
    TEST_ASSERT_EQUAL_UINT8(0u, s->problem.slack_chosen);
    TEST_ASSERT_EQUAL_UINT8(0u, s->schedule.has_accepted);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(2));
    TEST_ASSERT_EQUAL_UINT8(1u, s->problem.slack_chosen);
    TEST_ASSERT_TRUE(s->problem.barrier.slack0 == reference_slack); /* chosen from x = 1, not x = 2 */
}

/* A session whose single robot streams its target (no constraints). */
static void streamed_session(int32_t clock_source, int64_t now_us)
{
    ef_start(&start, EF_SESSION_ID, clock_source, 1);
    start.robot[0].target.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    ef_record_clear(&rec);
    (void)send_session(&start, now_us);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
}

/* Issue 27: a target sampled with the first measurement, at epoch - tau, is taken, carried forward to
 * the epoch along its own Taylor series; one from more than a period before the epoch is refused. */
static void test_target_stamped_at_epoch_minus_tau_is_carried_to_the_epoch(void)
{
    streamed_session(TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    t.header.utime = EF_EPOCH - H - 1;
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER, node.last_target_status);
    t.header.utime = EF_EPOCH - TAU;
    t.position_m[0] = 1.0;
    t.velocity_mps[0] = 2.0;
    t.acceleration_mps2[0] = 0.5;
    t.jerk_mps3[0] = 0.25;
    t.position_m[1] = -1.0;
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    const tvo_target_t *target = &tvo_node_session(&node)->problem.target[0];
    TEST_ASSERT_NOT_NULL(target);
    const tvo_target_streamed_t *sample = &target->u.streamed;
    const double dt = (double)TAU * 1e-6;
    TEST_ASSERT_EQUAL_UINT64(0u, sample->stamp_ticks);
    TEST_ASSERT_EQUAL_FLOAT((float)(1.0 + 2.0 * dt + 0.25 * dt * dt + 0.25 * dt * dt * dt / 6.0), (float)sample->deriv[0][0]);
    TEST_ASSERT_EQUAL_FLOAT((float)(2.0 + 0.5 * dt + 0.125 * dt * dt), (float)sample->deriv[1][0]);
    TEST_ASSERT_EQUAL_FLOAT((float)(0.5 + 0.25 * dt), (float)sample->deriv[2][0]);
    TEST_ASSERT_EQUAL_FLOAT(0.25f, (float)sample->deriv[3][0]);
    TEST_ASSERT_EQUAL_FLOAT(-1.0f, (float)sample->deriv[0][1]);
    /* The first measurement, stamped at the same instant, is served with it. */
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 0);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(0));
}

/* ------------------------------------------------------------------------------------------------
 * More timing: the tick span, chain sessions, refusals by the controller's step
 * --------------------------------------------------------------------------------------------- */

static void test_plant_first_measurement_beyond_the_tick_span_is_implausible(void)
{
    /* Issue 9: an epoch 20 min before the first measurement. Every measurement says why, and after
     * watchdog_periods of them the answer is a safe stop. */
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    const int64_t twenty_minutes = (int64_t)20 * 60 * 1000000;
    for (int64_t k = 0; k < W + 1; ++k) {
        tvo_lcm_unicycle_sample_t m;
        ef_sample(&m, EF_SESSION_ID, EF_EPOCH + twenty_minutes + k * H - TAU, (int32_t)k, 0);
        (void)EXPECT_REFUSED(m, 0, k + 1 < W ? TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP : TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG);
    }
    /* Each counted under its answer's status: W - 1 holding, then 2 safe stops. */
    TEST_ASSERT_EQUAL_INT32((int32_t)W - 1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP]);
    TEST_ASSERT_EQUAL_INT32(2, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG]);
    /* The first sample anchors the sequence, so it must follow the later of the START and the epoch
     * within a second (or watchdog_periods periods if longer): the last period inside that window is
     * served, the next one is not. */
    const int64_t window = (W * H > 1000000) ? W * H : 1000000;
    const int64_t last = ((EF_UTIME > EF_EPOCH ? EF_UTIME : EF_EPOCH) + window - EF_EPOCH + TAU) / H;
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, last + 1);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG);
    plant_meas(&m, last);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(last));
}

/* A chain session's answer: one chain_command_t (robot 0) and its telemetry, decoded. */
static tvo_lcm_chain_command_t the_chain_command(int with_telemetry, int line)
{
    tvo_lcm_chain_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    UNITY_TEST_ASSERT_EQUAL_UINT32(with_telemetry ? 2u : 1u, rec.count, line, "messages published");
    UNITY_TEST_ASSERT_EQUAL_UINT32(0u, ef_record_count(&rec, TVO_NODE_CH_COMMAND), line, "no unicycle command");
    const ef_message_t *m = ef_record_nth(&rec, TVO_NODE_CH_CHAIN_COMMAND, 0);
    if (m == NULL) {
        UNITY_TEST_FAIL(line, "no chain command");
        return cmd;
    }
    UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_chain_command_t_decode(m->data, 0, (int)m->length, &cmd), line,
                                "chain command decodes");
    if (with_telemetry) {
        m = ef_record_nth(&rec, TVO_NODE_CH_TELEMETRY, 0);
        UNITY_TEST_ASSERT_NOT_NULL(m, line, "telemetry");
        if (m != NULL) {
            tvo_lcm_telemetry_t tel;
            UNITY_TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_telemetry_t_decode(m->data, 0, (int)m->length, &tel),
                                        line, "telemetry decodes");
            UNITY_TEST_ASSERT_EQUAL_INT(cmd.header.status, tel.header.status, line, "telemetry status");
            UNITY_TEST_ASSERT_EQUAL_INT64(cmd.header.utime, tel.header.utime, line, "telemetry utime");
            const double u0 = (double)cmd.input[0], u1 = (double)cmd.input[1];
            UNITY_TEST_ASSERT(tvo_joint_digest(&u0, &u1, 1) == (uint64_t)tel.joint_digest, line, "digest of u");
        }
    }
    return cmd;
}

static void test_chain_session_runs_through_the_node(void)
{
    for (int clock = TVO_LCM_SESSION_T_CLOCK_PLANT; clock <= TVO_LCM_SESSION_T_CLOCK_NODE; ++clock) {
        setUp();
        ef_start(&start, EF_SESSION_ID, clock, 1);
        start.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
        (void)send_session(&start, NODE_T0);
        EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
        const int node_clock = clock == TVO_LCM_SESSION_T_CLOCK_NODE;
        tvo_lcm_chain_command_t cmd;
        tvo_lcm_chain_sample_t c;
        for (int64_t j = 1; j <= 3; ++j) {
            tvo_lcm_unicycle_sample_t m;
            if (node_clock) {
                node_meas(&m, j, (int32_t)j);
            } else {
                plant_meas(&m, j);
            }
            memset(&c, 0, sizeof(c));
            c.header = m.header;
            c.position_m[0] = m.position_m[0];
            c.position_m[1] = m.position_m[1];
            const int64_t now = node_clock ? node_arrival(j) : 0;
            if (j == 2) {
                /* The session reads y' as measured (no filters): a sample without it is refused. */
                take_snapshot();
                ef_record_clear(&rec);
                TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_CHAIN_SAMPLE, send_chain_sample(&c, now));
                cmd = the_chain_command(1, __LINE__);
                EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_MISSING_FIELD, cmd.header.status);
                TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)cmd.header.flags);
                ASSERT_SESSION_KEPT();
                /* ... and a unicycle's sample: not this session's plant, refused unanswered. */
                ef_record_clear(&rec);
                (void)send_sample(&m, now);
                EXPECT_NOTHING_PUBLISHED();
                TEST_ASSERT_EQUAL_INT32(1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM]);
                /* ... and a position beyond the workspace (float32's largest): implausible, nothing kept. */
                tvo_lcm_chain_sample_t far = c;
                far.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
                far.position_m[1] = 3.4e38;
                take_snapshot();
                ef_record_clear(&rec);
                TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_CHAIN_SAMPLE, send_chain_sample(&far, now));
                cmd = the_chain_command(1, __LINE__);
                EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT, cmd.header.status);
                TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)cmd.header.flags);
                ASSERT_SESSION_KEPT();
            }
            c.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
            ef_record_clear(&rec);
            TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_CHAIN_SAMPLE, send_chain_sample(&c, now));
            cmd = the_chain_command(1, __LINE__);
            EF_ASSERT_STATUS(TVO_OK, cmd.header.status);
            TEST_ASSERT_EQUAL_INT64(node_clock ? node_apply(j) - OFFSET : plant_apply(j), cmd.header.utime);
            TEST_ASSERT_EQUAL_INT(c.header.sequence, cmd.header.measurement_sequence);
            TEST_ASSERT_EQUAL_INT(0, cmd.header.robot);
            TEST_ASSERT_TRUE(cmd.input[0] != 0.0f); /* the chain's u, x and y */
        }
        if (node_clock) {
            EXPECT_TIMER_QUIET(node_arrival(3), node_apply(3 + W));
            ef_record_clear(&rec);
            (void)tvo_node_poll(&node, node_apply(3 + W));
            cmd = the_chain_command(0, __LINE__); /* the node's own stop: no telemetry */
            TEST_ASSERT_EQUAL_INT(-1, cmd.header.measurement_sequence);
        } else {
            for (int64_t k = 1; k < W; ++k) {
                ef_record_clear(&rec);
                (void)send_chain_sample(&c, 0); /* a duplicate */
                cmd = the_chain_command(1, __LINE__);
                EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER, cmd.header.status);
                TEST_ASSERT_TRUE(cmd.input[0] != 0.0f); /* the chain's held u */
            }
            ef_record_clear(&rec);
            (void)send_chain_sample(&c, 0);
            cmd = the_chain_command(1, __LINE__);
        }
        EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, cmd.header.status);
        TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP, (uint32_t)cmd.header.flags);
        TEST_ASSERT_TRUE(cmd.input[0] == 0.0f && cmd.input[1] == 0.0f);
        TEST_ASSERT_TRUE(tvo_node_session(&node)->controller.u.chain.internal.held.u[0] == TVO_R(0.0));
    }
}

/* An uncompensated streamed-target session after periods 1 and 2, whose next target sample is
 * stamped at period 3's apply instant (the latest the node takes): the controller's check passes
 * measurement 3, its law (evaluated at the sample, tau before) then fails: the sample is its future. */
static void session_whose_law_fails_next(void)
{
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.delay_compensation = 0;
    start.robot[0].target.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    (void)send_target(&t, 0);
    for (int64_t j = 1; j <= 2; ++j) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j));
    }
    t.header.utime = plant_apply(3);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
}

/* A START that took 150 ms longer than the measurements (a slow serial link): every measurement
 * looks early by that much. NODE_ANCHOR_VOTES (3) of them in a row agree on the plant's clock, the
 * schedule re-anchors, and the third is accepted; a lone stray before them re-anchors nothing. */
static void test_node_clock_reanchors_on_agreeing_measurements_before_tracking(void)
{
    const int64_t start_delay = 150000;
    const int64_t offset = NODE_T0 - EF_UTIME; /* the true node-minus-plant clock offset */
    const int64_t latency = 100;
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, NODE_T0 + start_delay);
    tvo_lcm_unicycle_sample_t stray;
    ef_sample(&stray, EF_SESSION_ID, EF_EPOCH + 40 * H, 1000, 0);
    ef_record_clear(&rec);
    (void)send_sample(&stray, EF_EPOCH + offset + 40 * H - 500000);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, THE_COMMAND().header.status);
    for (int64_t k = 0; k < 6; ++k) {
        const int64_t sample = EF_EPOCH + (k + 1) * H - TAU;
        tvo_lcm_unicycle_sample_t m;
        ef_sample(&m, EF_SESSION_ID, sample, (int32_t)k, 0);
        ef_record_clear(&rec);
        (void)send_sample(&m, sample + offset + latency);
        const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
        if (k < 2) {
            EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, cmd.header.status);
        } else {
            EF_ASSERT_STATUS(TVO_OK, cmd.header.status);
            /* Applied at the period's instant on the plant's clock, as if the START had been on time
             * (to the measurement's own transit). */
            TEST_ASSERT_INT64_WITHIN(latency, sample + TAU, cmd.header.utime);
        }
    }
    TEST_ASSERT_INT64_WITHIN(latency, offset, tvo_node_session(&node)->schedule.anchor.offset_us);
}

/* The same slow START with a watchdog of one period, and the third sample of the vote not finite: judged
 * on the moved anchor it reaches the core, which refuses it and, its watchdog expiring with that one
 * period, stops the robots (its clock starts). The move is not committed; the next three samples move
 * the anchor again and the third is served on the plant's schedule, the objective's time counted from
 * the epoch. (Before, the node moved the core's epoch for the trial and could not move it back once
 * the stop had started the clock, and could never re-anchor after: every sample was refused.) */
static void test_node_clock_reanchor_whose_trial_the_core_stops_commits_nothing_and_recovers(void)
{
    const int64_t start_delay = 150000;
    const int64_t offset = NODE_T0 - EF_UTIME;
    const int64_t latency = 100;
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, 1);
    start.watchdog_periods = 1;
    ef_record_clear(&rec);
    (void)send_session(&start, NODE_T0 + start_delay);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    for (int64_t k = 0; k < 6; ++k) {
        const int64_t sample = EF_EPOCH + (k + 1) * H - TAU;
        tvo_lcm_unicycle_sample_t m;
        ef_sample(&m, EF_SESSION_ID, sample, (int32_t)k, 0);
        if (k == 2) {
            m.position_m[0] = (double)NAN;
        }
        ef_record_clear(&rec);
        (void)send_sample(&m, sample + offset + latency);
        const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
        if (k == 2) {
            EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, cmd.header.status); /* the core's stop */
            EXPECT_SAFE_STOP(cmd);
            TEST_ASSERT_EQUAL_INT64(offset + start_delay, tvo_node_session(&node)->schedule.anchor.offset_us);
        } else if (k < 5) {
            EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, cmd.header.status);
        } else {
            EF_ASSERT_STATUS(TVO_OK, cmd.header.status);
            TEST_ASSERT_INT64_WITHIN(latency, sample + TAU, cmd.header.utime);
            TEST_ASSERT_INT64_WITHIN(1, (int64_t)((k + 1) * H), last_telemetry.objective_time_us);
        }
    }
    TEST_ASSERT_INT64_WITHIN(latency, offset, tvo_node_session(&node)->schedule.anchor.offset_us);
}

/* A finite wire double beyond float range is a position beyond the workspace (19), as 1e38 is, not
 * a NaN/Inf (2): the float32 core sees it saturated, never as infinity. The float fields' largest
 * finite value likewise. Each refusal counted under the status its answer carries. */
static void test_plant_finite_values_beyond_float_range_are_implausible_not_non_finite(void)
{
    plant_session_after(2);
    const double far[] = {1e39, 1e300, -1e300, -1e39, DBL_MAX};
    int64_t j = 3;
    int32_t implausible = 0;
    for (size_t i = 0; i < 2u * (sizeof(far) / sizeof(far[0])) + 2u; ++i) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        if (i < 2u * (sizeof(far) / sizeof(far[0]))) {
            m.position_m[i % 2u] = far[i / 2u];
        } else if (i % 2u == 0u) {
            m.heading_rad = FLT_MAX; /* a float field holds no 1e300: its largest finite value */
        } else {
            m.has |= TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
            m.speed_mps = -FLT_MAX;
        }
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT);
        ++implausible;
        TEST_ASSERT_EQUAL_INT32(implausible, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT]);
        TEST_ASSERT_EQUAL_INT32(0, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE]);
        plant_meas(&m, j + 1); /* the genuine stream goes on */
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 1));
        j += 2;
    }
    /* NaN and Inf stay not finite. */
    const double bad[] = {(double)NAN, (double)INFINITY, -(double)INFINITY};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        m.position_m[1] = bad[i];
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE);
        TEST_ASSERT_EQUAL_INT32((int32_t)i + 1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE]);
        plant_meas(&m, j + 1);
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 1));
        j += 2;
    }
    TEST_ASSERT_EQUAL_INT32(implausible, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT]);
}

/* The same for a chain's position and a streamed target's: a finite 1e300 is refused as a value
 * beyond the workspace is (as 1e6 is), not as not finite. */
static void test_chain_and_target_positions_beyond_float_range_are_not_called_non_finite(void)
{
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
    (void)send_session(&start, 0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    const double far[] = {1e39, 1e300, -1e300};
    for (size_t i = 0; i < 2u * (sizeof(far) / sizeof(far[0])); ++i) {
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, 2 * (int64_t)i + 1);
        tvo_lcm_chain_sample_t c;
        memset(&c, 0, sizeof(c));
        c.header = m.header;
        c.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
        c.position_m[i % 2u] = far[i / 2u];
        take_snapshot();
        ef_record_clear(&rec);
        TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_CHAIN_SAMPLE, send_chain_sample(&c, 0));
        const tvo_lcm_chain_command_t cmd = the_chain_command(1, __LINE__);
        EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT, cmd.header.status);
        ASSERT_SESSION_KEPT();
        TEST_ASSERT_EQUAL_INT32((int32_t)i + 1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT]);
        TEST_ASSERT_EQUAL_INT32(0, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE]);
        plant_meas(&m, 2 * (int64_t)i + 2); /* the genuine stream goes on (the watchdog's count restarts) */
        c.header = m.header;
        c.position_m[0] = m.position_m[0];
        c.position_m[1] = m.position_m[1];
        ef_record_clear(&rec);
        TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_CHAIN_SAMPLE, send_chain_sample(&c, 0));
        EF_ASSERT_STATUS(TVO_OK, the_chain_command(1, __LINE__).header.status);
    }

    setUp();
    streamed_session(TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    t.position_m[0] = 1e6; /* finite, beyond the workspace: the status a farther one must share */
    (void)send_target(&t, 0);
    const int32_t beyond = node.last_target_status;
    TEST_ASSERT_TRUE(beyond != TVO_LCM_COMMAND_HEADER_T_STATUS_OK);
    TEST_ASSERT_TRUE(beyond != TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE);
    for (size_t i = 0; i < 2u * (sizeof(far) / sizeof(far[0])); ++i) {
        target_at_epoch(&t);
        t.position_m[0] = 0.0;
        t.position_m[i % 2u] = far[i / 2u];
        (void)send_target(&t, 0);
        EF_ASSERT_STATUS(beyond, node.last_target_status);
    }
    target_at_epoch(&t);
    t.position_m[1] = (double)NAN;
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE, node.last_target_status);
    target_at_epoch(&t);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
}

static void test_plant_target_beyond_the_next_period_is_refused(void)
{
    /* A stray sample 10 s ahead would hold back every genuine sample after it: refused, and the
     * genuine stream goes on. */
    streamed_session(TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 1);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(1));
    tvo_lcm_target_t stray = t;
    stray.header.utime = EF_EPOCH + 10000000;
    (void)send_target(&stray, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, node.last_target_status);
    TEST_ASSERT_EQUAL_INT32(1, node.counters.targets_refused);
    t.header.utime = plant_apply(2) - TAU;
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    plant_meas(&m, 2);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(2));
}

/* The window a first CLOCK_PLANT sample must fall in: max(1 s, W h) after the START or the epoch. */
static int64_t first_window_us(void)
{
    return (W * H > 1000000) ? W * H : 1000000;
}

/* The first period whose sample (stamped apply - tau) lies past the first window of a START at utime. */
static int64_t first_period_past_window(int64_t start_utime)
{
    const int64_t from = start_utime > EF_EPOCH ? start_utime : EF_EPOCH;
    return (from + first_window_us() - EF_EPOCH + TAU) / H + 1;
}

static void test_plant_first_window_starts_at_a_later_epoch(void)
{
    /* An epoch 5 s after the START (allowed: within 2^29 us): the plant's first sample comes after it. */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.epoch_utime = start.utime + 5000000;
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    const int64_t epoch = start.epoch_utime;
    tvo_lcm_unicycle_sample_t m;
    ef_sample(&m, EF_SESSION_ID, epoch + 50 * H - TAU, 50, 0);
    (void)EXPECT_ACCEPTED(m, 0, epoch + 50 * H);
}

static void test_plant_repeated_start_moves_the_first_window(void)
{
    /* The plant re-sends its START (its first ack was lost) 3 s later, stamped with its clock then. */
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    const int64_t j = first_period_past_window(EF_UTIME + 3000000) - 10;
    TEST_ASSERT_TRUE(j > first_period_past_window(EF_UTIME));
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, j);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP); /* past the first START's window */
    tvo_lcm_session_t again = start;
    again.utime = EF_UTIME + 3000000;
    ef_record_clear(&rec);
    (void)send_session(&again, 0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    /* An older repeat (reordered on the link) does not move it back. */
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    /* A repeat moves the window only to a utime a fresh START could have: outside the wire range, or
     * with the epoch more than 2^29 us from it, it moves nothing, and is acked 0 (the session runs). */
    const int64_t bad_utime[] = {INT64_MAX, (int64_t)1 << 60, EF_EPOCH + ((int64_t)1 << 29) + 1};
    for (size_t k = 0; k < sizeof(bad_utime) / sizeof(bad_utime[0]); ++k) {
        tvo_lcm_session_t bad = start;
        bad.utime = bad_utime[k];
        take_snapshot();
        ef_record_clear(&rec);
        (void)send_session(&bad, 0);
        EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
        ASSERT_SESSION_AND_COUNTERS_KEPT();
    }
    plant_meas(&m, j + 1);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 1));
}

static void test_plant_samples_past_the_first_window_that_agree_move_it(void)
{
    /* A plant that could not be served in its first second (say its robot started inside an
     * obstacle) is not refused for ever: three samples in a row past the window that agree on their
     * numbering move the window, and the third is served; a lone stray or a disagreeing one does not. */
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    const int64_t j = first_period_past_window(EF_UTIME) + 200;
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, j);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    plant_meas(&m, j + 1);
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    plant_meas(&m, j + 2);
    m.header.sequence += 7; /* a stray: its numbering disagrees, so the vote starts again */
    (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG);
    const int64_t window_start = tvo_node_session(&node)->schedule.anchor.first_window_utime;
    for (int64_t k = 3; k <= 4; ++k) {
        plant_meas(&m, j + k);
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG);
        TEST_ASSERT_EQUAL_INT64(window_start, tvo_node_session(&node)->schedule.anchor.first_window_utime);
    }
    plant_meas(&m, j + 5);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 5));
    plant_meas(&m, j + 6);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 6));
}

static void test_plant_strays_the_node_refuses_do_not_move_the_first_window(void)
{
    /* Three agreeing samples past the window that are not finite: each is refused, and the window
     * stays where it was (a genuine first sample inside it is served). */
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    const int64_t far = first_period_past_window(EF_UTIME) + 48000; /* 8 min ahead */
    const int64_t window_start = tvo_node_session(&node)->schedule.anchor.first_window_utime;
    tvo_lcm_unicycle_sample_t m;
    for (int64_t k = 0; k < 3; ++k) {
        plant_meas(&m, far + k);
        m.position_m[0] = (double)NAN;
        ef_record_clear(&rec);
        (void)send_sample(&m, 0);
        TEST_ASSERT_TRUE(THE_COMMAND().header.status != TVO_OK);
        TEST_ASSERT_EQUAL_INT64(window_start, tvo_node_session(&node)->schedule.anchor.first_window_utime);
    }
    plant_meas(&m, 2);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(2));
}

static void test_plant_target_stream_may_start_late(void)
{
    /* Before the first accepted measurement a sample may lead the START (or epoch) by one period: a
     * stray half a second ahead is refused, and costs the genuine stream nothing ... */
    streamed_session(TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    t.header.utime = plant_apply(50) - TAU;
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, node.last_target_status);
    t.header.utime = plant_apply(1);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 1);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(1));

    /* ... and a stream that starts after the window is taken once the plant's samples move it (its
     * samples stamped at the apply instant of the period they are sent for, the latest allowed). */
    setUp();
    streamed_session(TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    const int64_t j = first_period_past_window(EF_UTIME) + 50;
    t.header.utime = plant_apply(j);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, node.last_target_status);
    for (int64_t k = 0; k < 2; ++k) {
        plant_meas(&m, j + k);
        (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
    }
    plant_meas(&m, j + 2);
    ef_record_clear(&rec);
    (void)send_sample(&m, 0);
    /* The window moved, but there is no target yet: the third refusal in a row, so the core's watchdog
     * stops (the law's refusal is inside the core's answer, whose reason is the stop's). */
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, THE_COMMAND().header.status);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, node.last_refusal);
    t.header.utime = plant_apply(j + 3);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    plant_meas(&m, j + 3);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(j + 3));
}

static void test_plant_target_two_to_the_32_us_old_is_not_taken_for_a_new_one(void)
{
    /* A session past 2^32 us of the plant's clock (71.6 min): a stray sample stamped 2^32 us - 60 s
     * in the past has the uint32 tick of one 60 s ahead. It is old, and refused as old. */
    streamed_session(TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    const int64_t jump = (int64_t)TVO_MAX_TICK_SPAN / H; /* the longest silence a session spans */
    int64_t j = 1;
    tvo_lcm_unicycle_sample_t m;
    int64_t last = 0;
    while (plant_apply(j) - EF_EPOCH <= ((int64_t)1 << 32) + 120000000) {
        if (j == 1) {
            plant_meas(&m, j);
            (void)EXPECT_ACCEPTED(m, 0, plant_apply(j));
            last = j;
        } else {
            plant_jump_to(j - 2); /* a jump past the watchdog's span: served once three samples agree */
            last = j;
        }
        t.header.utime = plant_apply(j + 1) - TAU;
        (void)send_target(&t, 0);
        EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
        j += jump;
    }
    tvo_lcm_target_t stray = t;
    stray.header.utime = plant_apply(last) + 60000000 - ((int64_t)1 << 32);
    stray.position_m[0] = 99.0;
    (void)send_target(&stray, 0);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER, node.last_target_status);
    t.header.utime = plant_apply(last + 1);
    (void)send_target(&t, 0);
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    plant_meas(&m, last + 1);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(last + 1));
}

static void test_node_clock_sample_two_to_the_32_us_old_is_stale(void)
{
    /* A plant clock past 2^32 us: a stray stamped 2^32 us + 1 ms before a genuine sample has its
     * uint32 tick 1 ms before it, so it would look fresh. It is stale, and the genuine one is served. */
    const int64_t big = ((int64_t)1 << 33);
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, 1);
    start.utime = big;
    start.epoch_utime = big + EF_EPOCH_LEAD;
    ef_record_clear(&rec);
    (void)send_session(&start, NODE_T0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    const int64_t offset = NODE_T0 - big;
    tvo_lcm_unicycle_sample_t m;
    for (int64_t j = 1; j <= 2; ++j) {
        const int64_t apply_node = start.epoch_utime + offset + j * H;
        ef_sample(&m, EF_SESSION_ID, apply_node - 5000 - offset, (int32_t)j, 0);
        if (j == 2) {
            tvo_lcm_unicycle_sample_t stray = m;
            stray.header.utime = m.header.utime - ((int64_t)1 << 32) - 1000;
            stray.position_m[0] = 50.0;
            (void)EXPECT_REFUSED(stray, apply_node - 4000, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE);
        }
        (void)EXPECT_ACCEPTED(m, apply_node - 4000, apply_node - offset);
    }
}

static void test_plant_refusal_by_the_step_keeps_nothing(void)
{
    session_whose_law_fails_next();
    take_snapshot();
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    ef_record_clear(&rec);
    (void)send_sample(&m, 0);
    const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
    TEST_ASSERT_TRUE(cmd.header.status != TVO_OK);
    TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)cmd.header.flags);
    TEST_ASSERT_TRUE(cmd.header.utime >= m.header.utime);
    const tvo_node_session_t *s = tvo_node_session(&node);
    const tvo_sample_clock_t *before = &snapshot.controller.u.unicycle.internal.loop.clock;
    const tvo_sample_clock_t *after = &s->controller.u.unicycle.internal.loop.clock;
    if (before->last_apply_tick != after->last_apply_tick || before->elapsed.ticks != after->elapsed.ticks ||
        before->periods_without_measurement != after->periods_without_measurement) {
        static char text[240];
        (void)snprintf(text, sizeof(text),
                       "refused (status %d) yet the controller's clock moved: last_apply_tick %u -> %u, "
                       "elapsed %llu -> %llu, periods_without_measurement %u -> %u",
                       (int)cmd.header.status, (unsigned)before->last_apply_tick, (unsigned)after->last_apply_tick,
                       (unsigned long long)before->elapsed.ticks, (unsigned long long)after->elapsed.ticks,
                       (unsigned)before->periods_without_measurement, (unsigned)after->periods_without_measurement);
        TEST_FAIL_MESSAGE(text);
    }
    ASSERT_SESSION_KEPT();
}

static void test_node_clock_a_law_failure_after_the_timer_stop_is_answered_with_a_safe_stop(void)
{
    /* After a silence the timer stopped, a measurement the law then fails on (its streamed target
     * sample lies ahead of it) was answered TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG flagged HOLDING with v = omega = 0: the
     * core had stopped, the node said "hold". The answer is the core's: a safe stop. */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, 1);
    start.delay_compensation = 0;
    start.robot[0].target.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    ef_record_clear(&rec);
    (void)send_session(&start, NODE_T0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    (void)send_target(&t, node_apply(0));
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    tvo_lcm_unicycle_sample_t m;
    for (int64_t j = 1; j <= 2; ++j) {
        node_meas(&m, j, (int32_t)j);
        (void)EXPECT_ACCEPTED(m, node_arrival(j), node_apply(j) - OFFSET);
    }
    EXPECT_TIMER_STOP(node_apply(2 + W), node_apply(3 + W));
    const int64_t j = 5 + W;
    t.header.utime = node_arrival(j) - OFFSET + H / 2 - 1; /* plausible, and after the sample below */
    (void)send_target(&t, node_arrival(j));
    EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
    node_meas(&m, j, (int32_t)j);
    const tvo_lcm_unicycle_command_t cmd = EXPECT_REFUSED(m, node_arrival(j), TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG);
    TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP, (uint32_t)cmd.header.flags);
}

static void test_plant_step_refusals_count_toward_the_watchdog(void)
{
    /* A refusal by the controller's step (the law) and refusals of the node's own checks (duplicates)
     * in a row: watchdog_periods of them must end in a safe stop. */
    session_whose_law_fails_next();
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    ef_record_clear(&rec);
    (void)send_sample(&m, 0);
    tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_FUTURE_STAMP, cmd.header.status);
    TEST_ASSERT_EQUAL_UINT32(1u, ef_refusals_in_row(&tvo_node_session(&node)->controller));
    tvo_lcm_unicycle_sample_t dup;
    plant_meas(&dup, 2);
    for (int64_t refusals = 1; refusals < W; ++refusals) {
        ef_record_clear(&rec);
        (void)send_sample(&dup, 0);
        cmd = THE_COMMAND();
    }
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, cmd.header.status);
    TEST_ASSERT_TRUE(((uint32_t)cmd.header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0u);
}

/* ------------------------------------------------------------------------------------------------
 * Integers from the wire at their extremes: START
 * --------------------------------------------------------------------------------------------- */

typedef void (*start_edit_fn)(tvo_lcm_session_t *m, int64_t value);

/*
 * For each value: a START (robot_count 2) edited with it is refused with the given ack, both on an
 * idle node and while a session runs (which runs on, byte for byte). index < -1: the robot or
 * entry index is the edited entry's (given as -index - 2).
 */
static void expect_start_site(start_edit_fn edit, const int64_t *values, size_t count, int32_t status,
                              int32_t param, int32_t part, int32_t index, int line)
{
    for (size_t i = 0; i < count; ++i) {
        for (int running = 0; running < 2; ++running) {
            setUp();
            if (running) {
                plant_session_after(1);
                take_snapshot();
            }
            ef_start(&start, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
            edit(&start, values[i]);
            ef_record_clear(&rec);
            UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, send_session(&start, NODE_T0), line, "handled");
            const tvo_lcm_session_ack_t ack = the_ack(line);
            if (ack.status != (int32_t)status || ack.bad_param != (int32_t)param || ack.bad_part != part ||
                ack.bad_index != index) {
                static char text[240];
                (void)snprintf(text, sizeof(text),
                               "value %lld (%s): expected %s/%s part %d index %d, got %d (%s)/%s part %d index %d",
                               (long long)values[i], running ? "running" : "idle", tvo_protocol_status_str(status),
                               tvo_protocol_param_str(param), (int)part, (int)index, (int)ack.status,
                               tvo_protocol_status_str((int32_t)ack.status), tvo_protocol_param_str((int32_t)ack.bad_param),
                               (int)ack.bad_part, (int)ack.bad_index);
                UNITY_TEST_FAIL(line, text);
            }
            UNITY_TEST_ASSERT_EQUAL_INT64(OTHER_ID, ack.session_id, line, "ack session");
            UNITY_TEST_ASSERT_EQUAL_INT64(running ? EF_SESSION_ID : -1, ack.running_session_id, line, "running id");
            if (running) {
                assert_session_and_counters_kept(line);
            } else {
                UNITY_TEST_ASSERT_NULL(tvo_node_session(&node), line, "still idle");
            }
        }
    }
}
#define EXPECT_START_SITE(edit, values, status, param, part, index)                                              \
    expect_start_site((edit), (values), sizeof(values) / sizeof((values)[0]), (status), (param), (part), (index), \
                      __LINE__)

static const int64_t time_extremes[] = {INT64_MIN, -1, EF_TWO_POW_60 + 1, INT64_MAX};
static const int64_t kind32_extremes[] = {INT32_MIN, -1, 2, INT32_MAX};
static const int64_t robot_index_extremes[] = {INT32_MIN, -1, 2, INT32_MAX}; /* START robot_count is 2 */

static int32_t as_int32(int64_t value)
{
    return (int32_t)value; /* every value given is an int32 */
}

static void edit_utime(tvo_lcm_session_t *m, int64_t v) { m->utime = v; }
static void edit_epoch(tvo_lcm_session_t *m, int64_t v) { m->epoch_utime = v; }
static void edit_period(tvo_lcm_session_t *m, int64_t v) { m->period_us = v; }
static void edit_delay(tvo_lcm_session_t *m, int64_t v) { m->delay_us = v; }
static void edit_watchdog(tvo_lcm_session_t *m, int64_t v) { m->watchdog_periods = as_int32(v); }
static void edit_robot_count(tvo_lcm_session_t *m, int64_t v) { m->robot_count = as_int32(v); }
static void edit_clock_source(tvo_lcm_session_t *m, int64_t v) { m->clock_source = as_int32(v); }
static void edit_plant_kind(tvo_lcm_session_t *m, int64_t v) { m->plant_kind = as_int32(v); }
static void edit_velocity_source(tvo_lcm_session_t *m, int64_t v) { m->velocity_source = as_int32(v); }
static void edit_chain_degree(tvo_lcm_session_t *m, int64_t v)
{
    m->plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
    m->robot_count = 1;
    m->chain_relative_degree = as_int32(v);
}
static void edit_relaxation_degree(tvo_lcm_session_t *m, int64_t v) { m->barrier.relaxation_degree = as_int32(v); }
static void edit_distance_count(tvo_lcm_session_t *m, int64_t v) { m->distance_count = as_int32(v); }
static void edit_halfspace_count(tvo_lcm_session_t *m, int64_t v) { m->halfspace_count = as_int32(v); }
static void edit_obstacle_count(tvo_lcm_session_t *m, int64_t v) { m->obstacle_count = as_int32(v); }
static void edit_offset_count(tvo_lcm_session_t *m, int64_t v) { m->offset_count = as_int32(v); }
static void one_distance(tvo_lcm_session_t *m)
{
    m->distance_count = 1;
    m->distance[0].robot_a = 0;
    m->distance[0].robot_b = 1;
    m->distance[0].min_m = 0.2;
}
static void edit_distance_robot_a(tvo_lcm_session_t *m, int64_t v)
{
    one_distance(m);
    m->distance[0].robot_a = as_int32(v);
}
static void edit_distance_robot_b(tvo_lcm_session_t *m, int64_t v)
{
    one_distance(m);
    m->distance[0].robot_b = as_int32(v);
}
static void edit_halfspace_robot(tvo_lcm_session_t *m, int64_t v)
{
    m->halfspace_count = 1;
    m->halfspace[0].normal[0] = 1.0;
    m->halfspace[0].bound_m = 5.0;
    m->halfspace[0].robot = as_int32(v);
}
static void one_offset(tvo_lcm_session_t *m)
{
    m->offset_count = 1;
    m->offset[0].robot_a = 0;
    m->offset[0].robot_b = 1;
    ef_line_path(&m->offset[0].offset, 0.0, 1.0, 0.0);
}
static void edit_offset_robot_a(tvo_lcm_session_t *m, int64_t v)
{
    one_offset(m);
    m->offset[0].robot_a = as_int32(v);
}
static void edit_offset_robot_b(tvo_lcm_session_t *m, int64_t v)
{
    one_offset(m);
    m->offset[0].robot_b = as_int32(v);
}
static void edit_target_kind(tvo_lcm_session_t *m, int64_t v) { m->robot[1].target.kind = as_int32(v); }
static void edit_offset_kind(tvo_lcm_session_t *m, int64_t v)
{
    one_offset(m);
    m->offset[0].offset.kind = as_int32(v);
}

static void test_start_utime_extremes(void)
{
    EXPECT_START_SITE(edit_utime, time_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_EPOCH, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_epoch_extremes(void)
{
    EXPECT_START_SITE(edit_epoch, time_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_EPOCH, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    const int64_t far[] = {EF_UTIME + (int64_t)TVO_MAX_TICK_SPAN + 1, EF_TWO_POW_60};
    EXPECT_START_SITE(edit_epoch, far, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_EPOCH, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_period_extremes(void)
{
    const int64_t bad[] = {INT64_MIN, -1, 0, (int64_t)TVO_MAX_TICK_SPAN + 1, EF_TWO_POW_60 + 1, INT64_MAX};
    EXPECT_START_SITE(edit_period, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_PERIOD, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_delay_extremes(void)
{
    const int64_t bad[] = {INT64_MIN, -1, H + 1, EF_TWO_POW_60 + 1, INT64_MAX};
    EXPECT_START_SITE(edit_delay, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_DELAY, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_watchdog_extremes(void)
{
    const int64_t bad[] = {INT32_MIN, -1, 0, (int64_t)(TVO_MAX_TICK_SPAN / (uint32_t)EF_PERIOD_US) + 1, INT32_MAX};
    EXPECT_START_SITE(edit_watchdog, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_WATCHDOG, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_robot_count_extremes(void)
{
    /* Robots the wire names but the build does not drive: refused, naming the count. */
    const int64_t beyond_build[] = {TVO_MAX_ROBOTS + 1, TVO_LCM_SESSION_T_MAX_ROBOTS};
    if (TVO_MAX_ROBOTS < TVO_LCM_SESSION_T_MAX_ROBOTS) {
        EXPECT_START_SITE(edit_robot_count, beyond_build, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM,
                          TVO_LCM_SESSION_ACK_T_PARAM_ROBOT_COUNT, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    }
    /* A count that names no robot (so no boot of this node): dropped unanswered, wrong_boot. */
    const int32_t names_none[] = {INT32_MIN, -1, 0, TVO_LCM_SESSION_T_MAX_ROBOTS + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(names_none) / sizeof(names_none[0]); ++i) {
        for (int running = 0; running < 2; ++running) {
            setUp();
            if (running) {
                plant_session_after(1);
                take_snapshot();
            }
            ef_start(&start, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
            start.robot_count = names_none[i];
            ef_record_clear(&rec);
            TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, send_session(&start, 0));
            EXPECT_NOTHING_PUBLISHED();
            TEST_ASSERT_EQUAL_INT32(1, node.counters.wrong_boot);
            if (running) {
                snapshot_counters.wrong_boot++;
                ASSERT_SESSION_AND_COUNTERS_KEPT();
            } else {
                TEST_ASSERT_NULL(tvo_node_session(&node));
            }
        }
    }
}

static void edit_protocol_version(tvo_lcm_session_t *m, int64_t v) { m->protocol_version = as_int32(v); }
static void edit_telemetry_every(tvo_lcm_session_t *m, int64_t v) { m->telemetry_every = as_int32(v); }

static void test_start_protocol_version_extremes(void)
{
    const int64_t bad[] = {INT32_MIN, -1, 0, 2, TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION + 1, INT32_MAX};
    EXPECT_START_SITE(edit_protocol_version, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM,
                      TVO_LCM_SESSION_ACK_T_PARAM_PROTOCOL_VERSION, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_telemetry_every_extremes(void)
{
    const int64_t bad[] = {INT32_MIN, -1, TVO_SESSION_TELEMETRY_EVERY_MAX + 1, INT32_MAX};
    EXPECT_START_SITE(edit_telemetry_every, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM,
                      TVO_LCM_SESSION_ACK_T_PARAM_TELEMETRY_EVERY, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    /* The ends of the range run: 0 is the default (the fewest periods spanning 100 ms), 2^20 at most. */
    const int32_t good[] = {0, 1, TVO_SESSION_TELEMETRY_EVERY_MAX};
    const uint32_t every[] = {(uint32_t)((TVO_SESSION_TELEMETRY_DEFAULT_US + H - 1) / H), 1u,
                              (uint32_t)TVO_SESSION_TELEMETRY_EVERY_MAX};
    for (size_t i = 0; i < sizeof(good) / sizeof(good[0]); ++i) {
        setUp();
        ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        start.telemetry_every = good[i];
        ef_record_clear(&rec);
        (void)send_session(&start, 0);
        EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
        TEST_ASSERT_EQUAL_UINT32(every[i], tvo_node_session(&node)->schedule.timing.telemetry_every);
    }
}

static void test_start_clock_source_extremes(void)
{
    EXPECT_START_SITE(edit_clock_source, kind32_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_CLOCK_SOURCE,
                      TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_plant_kind_extremes(void)
{
    EXPECT_START_SITE(edit_plant_kind, kind32_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_PLANT_KIND,
                      TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_velocity_source_extremes(void)
{
    EXPECT_START_SITE(edit_velocity_source, kind32_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_VELOCITY_SOURCE,
                      TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_chain_relative_degree_extremes(void)
{
    const int64_t bad[] = {INT32_MIN, -1, 0, TVO_MAX_RELATIVE_DEGREE + 1, INT32_MAX};
    EXPECT_START_SITE(edit_chain_degree, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_GAINS, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static void test_start_relaxation_degree_extremes(void)
{
    const int64_t bad[] = {INT32_MIN, -1, (int64_t)UINT8_MAX + 1, INT32_MAX};
    EXPECT_START_SITE(edit_relaxation_degree, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_BARRIER, -1);
}

static void test_start_count_extremes(void)
{
    const int64_t distance[] = {INT32_MIN, -1, TVO_LCM_SESSION_T_MAX_DISTANCE_BOUNDS + 1, INT32_MAX};
    EXPECT_START_SITE(edit_distance_count, distance, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_CAPACITY, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_DISTANCE, -1);
    const int64_t halfspace[] = {INT32_MIN, -1, TVO_LCM_SESSION_T_MAX_HALFSPACES + 1, INT32_MAX};
    EXPECT_START_SITE(edit_halfspace_count, halfspace, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_CAPACITY, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, -1);
    const int64_t obstacles[] = {INT32_MIN, -1, TVO_LCM_SESSION_T_MAX_OBSTACLES + 1, INT32_MAX};
    EXPECT_START_SITE(edit_obstacle_count, obstacles, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_CAPACITY, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, -1);
    const int64_t offsets[] = {INT32_MIN, -1, TVO_LCM_SESSION_T_MAX_OFFSETS + 1, INT32_MAX};
    EXPECT_START_SITE(edit_offset_count, offsets, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_CAPACITY, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_OFFSETS, -1);
}

static void test_start_robot_index_extremes(void)
{
    EXPECT_START_SITE(edit_distance_robot_a, robot_index_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_DISTANCE, 0);
    EXPECT_START_SITE(edit_distance_robot_b, robot_index_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_DISTANCE, 0);
    EXPECT_START_SITE(edit_halfspace_robot, robot_index_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, 0);
    EXPECT_START_SITE(edit_offset_robot_a, robot_index_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_OFFSETS, 0);
    EXPECT_START_SITE(edit_offset_robot_b, robot_index_extremes, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE,
                      TVO_LCM_SESSION_ACK_T_PART_OFFSETS, 0);
}

static void test_start_path_kind_extremes(void)
{
    const int64_t bad[] = {INT32_MIN, -1, TVO_LCM_PATH_T_KIND_STREAMED + 1, INT32_MAX};
    EXPECT_START_SITE(edit_target_kind, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 1);
    EXPECT_START_SITE(edit_offset_kind, bad, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, TVO_LCM_SESSION_ACK_T_PART_OFFSETS, 0);
}

static void test_start_session_id_extremes(void)
{
    /* Any id >= 0 is an id like any other; a negative one is refused (-1 means "none" in acks). */
    const int32_t ids[] = {0, INT32_MAX};
    for (size_t i = 0; i < sizeof(ids) / sizeof(ids[0]); ++i) {
        setUp();
        start_session(ids[i], TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, 1);
        m.header.session_id = ids[i];
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(1));
        tvo_lcm_session_t stop;
        stop_message(&stop, ids[i]);
        ef_record_clear(&rec);
        (void)send_session(&stop, 0);
        EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
        TEST_ASSERT_NULL(tvo_node_session(&node));
    }
    const int32_t negative[] = {INT32_MIN, -1};
    for (size_t i = 0; i < sizeof(negative) / sizeof(negative[0]); ++i) {
        setUp();
        tvo_lcm_session_t bad;
        ef_start(&bad, negative[i], TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        ef_record_clear(&rec);
        (void)send_session(&bad, 0);
        EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, THE_ACK().status);
        TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PARAM_SESSION_ID, THE_ACK().bad_param);
        TEST_ASSERT_NULL(tvo_node_session(&node));
    }
}

/* ------------------------------------------------------------------------------------------------
 * Integers from the wire at their extremes: measurements, targets, the clock
 * --------------------------------------------------------------------------------------------- */

static void test_sample_utime_extremes(void)
{
    for (int anchored = 0; anchored < 2; ++anchored) {
        for (size_t i = 0; i < sizeof(time_extremes) / sizeof(time_extremes[0]); ++i) {
            setUp();
            plant_session_after(anchored);
            tvo_lcm_unicycle_sample_t m;
            plant_meas(&m, anchored + 1);
            m.header.utime = time_extremes[i];
            (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
            setUp();
            node_session_after(anchored);
            node_meas(&m, anchored + 1, anchored + 1);
            m.header.utime = time_extremes[i];
            (void)EXPECT_REFUSED(m, node_arrival(anchored + 1), TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP);
        }
    }
}

/* A negative sequence is refused unanswered (counted as implausibly stamped, nothing kept): an answer
 * would echo it, and sequence -1 is the node's own stop. */
static void expect_negative_sequence_dropped(tvo_lcm_unicycle_sample_t *m, int64_t now_us, int line)
{
    take_snapshot();
    ef_record_clear(&rec);
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(m, now_us), line, "taken as a sample");
    expect_nothing_published(line);
    snapshot_counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP]++;
    assert_session_and_counters_kept(line);
}

static void test_sample_sequence_extremes(void)
{
    const int32_t negative[] = {INT32_MIN, -2, -1};
    for (int anchored = 0; anchored < 2; ++anchored) {
        for (size_t i = 0; i < sizeof(negative) / sizeof(negative[0]); ++i) {
            setUp();
            plant_session_after(anchored);
            tvo_lcm_unicycle_sample_t m;
            plant_meas(&m, anchored + 1);
            m.header.sequence = negative[i];
            expect_negative_sequence_dropped(&m, 0, __LINE__);
            setUp();
            node_session_after(anchored);
            node_meas(&m, anchored + 1, negative[i]);
            expect_negative_sequence_dropped(&m, node_arrival(anchored + 1), __LINE__);
        }
    }
    /* The ends of the range are sequences like any other (no answer's telemetry is lost at them). */
    const int32_t ends[] = {0, INT32_MAX - 1};
    for (size_t i = 0; i < sizeof(ends) / sizeof(ends[0]); ++i) {
        setUp();
        start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, 1);
        m.header.sequence = ends[i];
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(1));
        plant_meas(&m, 2);
        m.header.sequence = ends[i] + 1;
        (void)EXPECT_ACCEPTED(m, 0, plant_apply(2));
    }
}

static void test_sample_robot_extremes(void)
{
    const int8_t bad[] = {INT8_MIN, -1, 1, TVO_LCM_SESSION_T_MAX_ROBOTS, INT8_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        for (int clock = TVO_LCM_SESSION_T_CLOCK_PLANT; clock <= TVO_LCM_SESSION_T_CLOCK_NODE; ++clock) {
            setUp();
            if (clock == TVO_LCM_SESSION_T_CLOCK_PLANT) {
                plant_session_after(1);
            } else {
                node_session_after(1);
            }
            take_snapshot();
            tvo_lcm_unicycle_sample_t m;
            plant_meas(&m, 2);
            m.header.robot = bad[i];
            ef_record_clear(&rec);
            TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SAMPLE, send_sample(&m, node_arrival(2)));
            EXPECT_NOTHING_PUBLISHED();
            snapshot_counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION]++;
            TEST_ASSERT_EQUAL_INT32(1, node.counters.refused[TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION]);
            ASSERT_SESSION_AND_COUNTERS_KEPT();
        }
    }
}

static void test_sample_session_id_extremes(void)
{
    const int32_t ids[] = {INT32_MIN, -1, INT32_MAX};
    for (size_t i = 0; i < sizeof(ids) / sizeof(ids[0]); ++i) {
        setUp();
        plant_session_after(1);
        take_snapshot();
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, 2);
        m.header.session_id = ids[i];
        ef_record_clear(&rec);
        (void)send_sample(&m, 0);
        EXPECT_NOTHING_PUBLISHED();
        TEST_ASSERT_EQUAL_INT32(1, node.counters.other_session);
        snapshot_counters.other_session++;
        ASSERT_SESSION_AND_COUNTERS_KEPT();
        /* Idle: dropped whatever its id, time and sequence. */
        setUp();
        m.header.utime = (i == 0) ? INT64_MIN : INT64_MAX;
        m.header.sequence = ids[i];
        (void)send_sample(&m, 0);
        EXPECT_NOTHING_PUBLISHED();
        TEST_ASSERT_EQUAL_INT32(1, node.counters.idle);
    }
}

static void test_target_utime_robot_count_and_session_extremes(void)
{
    for (int clock = TVO_LCM_SESSION_T_CLOCK_PLANT; clock <= TVO_LCM_SESSION_T_CLOCK_NODE; ++clock) {
        setUp();
        streamed_session(clock, NODE_T0);
        take_snapshot();
        /* The node's clock at the epoch: a sample stamped there is neither early nor late. */
        const int64_t now = NODE_T0 + EF_EPOCH_LEAD;
        tvo_lcm_target_t t;
        target_at_epoch(&t);
        int32_t refused = 0;
        for (size_t i = 0; i < sizeof(time_extremes) / sizeof(time_extremes[0]); ++i) {
            t.header.utime = time_extremes[i];
            ef_record_clear(&rec);
            TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_TARGET, send_target(&t, now));
            EXPECT_NOTHING_PUBLISHED();
            EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP, node.last_target_status);
            TEST_ASSERT_EQUAL_INT32(++refused, node.counters.targets_refused);
        }
        t.header.utime = EF_EPOCH;
        const int8_t robots[] = {INT8_MIN, -1, 1, INT8_MAX};
        for (size_t i = 0; i < sizeof(robots) / sizeof(robots[0]); ++i) {
            t.header.robot = robots[i];
            (void)send_target(&t, now);
            EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION, node.last_target_status);
            TEST_ASSERT_EQUAL_INT32(++refused, node.counters.targets_refused);
        }
        t.header.robot = 0;
        const int32_t ids[] = {INT32_MIN, -1, INT32_MAX};
        for (size_t i = 0; i < sizeof(ids) / sizeof(ids[0]); ++i) {
            t.header.session_id = ids[i];
            (void)send_target(&t, now);
            TEST_ASSERT_EQUAL_INT32((int32_t)i + 1, node.counters.other_session);
        }
        ASSERT_SESSION_KEPT(); /* no target stream was touched */
        /* The sequence is not read: its extremes are harmless. */
        t.header.session_id = EF_SESSION_ID;
        t.header.sequence = INT32_MIN;
        (void)send_target(&t, now);
        EF_ASSERT_STATUS(TVO_OK, node.last_target_status);
        TEST_ASSERT_EQUAL_UINT8(1u, tvo_node_session(&node)->problem.target[0].u.streamed.has_sample);
    }
    /* Without a session: dropped, counted. */
    setUp();
    tvo_lcm_target_t t;
    target_at_epoch(&t);
    t.header.utime = INT64_MIN;
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_TARGET, send_target(&t, INT64_MAX));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(1, node.counters.idle);
}

static void test_node_clock_extremes(void)
{
    const int64_t nows[] = {INT64_MIN, -1, 0, EF_TWO_POW_60, EF_TWO_POW_60 + 1, INT64_MAX};
    for (size_t i = 0; i < sizeof(nows) / sizeof(nows[0]); ++i) {
        /* START at an extreme node time: the offset uses the clamped clock. */
        setUp();
        start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, nows[i]);
        const int64_t clamped = nows[i] < 0 ? 0 : (nows[i] > EF_TWO_POW_60 ? EF_TWO_POW_60 : nows[i]);
        TEST_ASSERT_EQUAL_INT64(clamped - EF_UTIME, tvo_node_session(&node)->schedule.anchor.offset_us);
        /* Measurements, polls and a STOP at every extreme: answers stay within the wire range. */
        for (size_t k = 0; k < sizeof(nows) / sizeof(nows[0]); ++k) {
            tvo_lcm_unicycle_sample_t m;
            ef_sample(&m, EF_SESSION_ID, EF_EPOCH + (int64_t)k * H, (int32_t)k, 0);
            ef_record_clear(&rec);
            (void)send_sample(&m, nows[k]);
            const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
            TEST_ASSERT_TRUE(cmd.header.utime >= 0 && cmd.header.utime <= EF_TWO_POW_60);
            const int64_t deadline = tvo_node_poll(&node, nows[k]);
            TEST_ASSERT_TRUE(deadline >= 0 && deadline <= 3 * EF_TWO_POW_60); /* the announcement's at the latest */
        }
        tvo_lcm_session_t stop;
        stop_message(&stop, EF_SESSION_ID);
        ef_record_clear(&rec);
        (void)send_session(&stop, nows[i]);
        EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    }
    /* The plant's START at the ends of the wire range against the node clock's ends. */
    const int64_t utimes[] = {0, EF_TWO_POW_60};
    for (size_t u = 0; u < 2; ++u) {
        for (size_t i = 0; i < sizeof(nows) / sizeof(nows[0]); ++i) {
            setUp();
            ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, 1);
            start.utime = utimes[u];
            start.epoch_utime = utimes[u];
            (void)send_session(&start, nows[i]);
            EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
            tvo_lcm_unicycle_sample_t m;
            ef_sample(&m, EF_SESSION_ID, utimes[u], 1, 0);
            ef_record_clear(&rec);
            (void)send_sample(&m, nows[i]);
            (void)THE_COMMAND();
            for (size_t k = 0; k < sizeof(nows) / sizeof(nows[0]); ++k) {
                ef_record_clear(&rec);
                (void)tvo_node_poll(&node, nows[k]);
                TEST_ASSERT_TRUE(rec.count == 0u || rec.count == 2u);
            }
        }
    }
    /* NULL node: nothing, no crash. */
    TEST_ASSERT_EQUAL_INT(0, tvo_node_handle(NULL, TVO_NODE_CH_SAMPLE, wire, 10u, 0));
    TEST_ASSERT_EQUAL_INT64(TVO_NODE_NO_DEADLINE, tvo_node_poll(NULL, 0));
    TEST_ASSERT_NULL(tvo_node_session(NULL));
}

/* Every time the node publishes lies in the wire range [0, 2^60] (edge_spec "Wire ranges"), also
 * for a session whose epoch is at the end of that range. */
static void test_commands_stay_within_the_wire_time_range(void)
{
    static char text[240];
    text[0] = '\0';
    for (int clock = TVO_LCM_SESSION_T_CLOCK_PLANT; clock <= TVO_LCM_SESSION_T_CLOCK_NODE; ++clock) {
        setUp();
        ef_start(&start, EF_SESSION_ID, clock, 1);
        start.utime = EF_TWO_POW_60;
        start.epoch_utime = EF_TWO_POW_60;
        (void)send_session(&start, EF_TWO_POW_60);
        EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
        tvo_lcm_unicycle_sample_t m;
        ef_sample(&m, EF_SESSION_ID, EF_TWO_POW_60, 1, 0); /* the latest stamp the wire allows */
        ef_record_clear(&rec);
        (void)send_sample(&m, EF_TWO_POW_60);
        const tvo_lcm_unicycle_command_t cmd = THE_COMMAND();
        if (cmd.header.utime < 0 || cmd.header.utime > EF_TWO_POW_60) {
            const size_t used = strlen(text);
            (void)snprintf(text + used, sizeof(text) - used, "%s: command utime 2^60 + %lld (status %d); ",
                           clock == TVO_LCM_SESSION_T_CLOCK_PLANT ? "CLOCK_PLANT" : "CLOCK_NODE",
                           (long long)(cmd.header.utime - EF_TWO_POW_60), (int)cmd.header.status);
        }
    }
    if (text[0] != '\0') {
        TEST_FAIL_MESSAGE(text); /* outside the wire range */
    }
}

/* ------------------------------------------------------------------------------------------------
 * The node's identity: init, the boot check, announcements
 * --------------------------------------------------------------------------------------------- */

static void test_init_refuses_bad_arguments_and_leaves_an_unusable_node(void)
{
    TEST_ASSERT_EQUAL_INT(-1, tvo_node_init(NULL, -1, EF_BOOT, record, NULL));
    const int8_t robots[] = {INT8_MIN, -2, (int8_t)TVO_NODE_MAX_ROBOTS};
    for (size_t i = 0; i < sizeof(robots) / sizeof(robots[0]); ++i) {
        TEST_ASSERT_EQUAL_INT(-1, tvo_node_init(&node, robots[i], EF_BOOT, record, NULL));
    }
    const int64_t boots[] = {INT64_MIN, -1, 0};
    for (size_t i = 0; i < sizeof(boots) / sizeof(boots[0]); ++i) {
        TEST_ASSERT_EQUAL_INT(-1, tvo_node_init(&node, -1, boots[i], record, NULL));
    }
    TEST_ASSERT_EQUAL_INT(-1, tvo_node_init(&node, -1, EF_BOOT, NULL, NULL));
    /* An unusable node takes nothing, publishes nothing, counts nothing. */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(0, send_session(&start, 0));
    TEST_ASSERT_EQUAL_INT64(TVO_NODE_NO_DEADLINE, tvo_node_poll(&node, 0));
    tvo_node_count_drop(&node, TVO_NODE_DROP_REPLAYED);
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_UINT32(0u, announcements.count);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.replayed);
    TEST_ASSERT_NULL(tvo_node_session(&node));
    /* The ends of the good ranges. */
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(&node, (int8_t)(TVO_NODE_MAX_ROBOTS - 1), INT64_MAX, record, NULL));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(&node, 0, 1, record, NULL));
    TEST_ASSERT_NULL(tvo_node_counters(NULL));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_stop_requested(NULL));
}

static void test_a_session_message_naming_another_boot_is_dropped_unanswered(void)
{
    /* Idle: a START whose robot 1 names an earlier boot of this node (a recording from before its
     * restart) runs nothing and is not answered. */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    start.node_boot_id[1] = EF_OTHER_BOOT;
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, send_session(&start, 0));
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_UINT32(0u, announcements.count);
    TEST_ASSERT_NULL(tvo_node_session(&node));
    TEST_ASSERT_EQUAL_INT32(1, node.counters.wrong_boot);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_EVENT_WRONG_BOOT, node.last_event);
    /* A boot past robot_count is not read: a one-robot START naming this boot for robot 0 runs. */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start.node_boot_id[1] = EF_OTHER_BOOT;
    start.node_boot_id[TVO_LCM_SESSION_T_MAX_ROBOTS - 1] = 0;
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    EF_ASSERT_STATUS(TVO_OK, THE_ACK().status);
    /* Running: a START of a new id, a repeat, a STOP and another action naming another boot change
     * nothing and are not answered; the session answers on. */
    setUp();
    plant_session_after(2);
    take_snapshot();
    tvo_lcm_session_t msg;
    for (int which = 0; which < 4; ++which) {
        if (which < 2) {
            ef_start(&msg, which == 0 ? OTHER_ID : EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        } else {
            stop_message(&msg, EF_SESSION_ID);
            msg.action = (which == 2) ? TVO_LCM_SESSION_T_ACTION_STOP : 7;
        }
        msg.node_boot_id[0] = EF_OTHER_BOOT;
        ef_record_clear(&rec);
        TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_SESSION, send_session(&msg, 0));
        EXPECT_NOTHING_PUBLISHED();
        snapshot_counters.wrong_boot++;
        ASSERT_SESSION_AND_COUNTERS_KEPT();
        TEST_ASSERT_EQUAL_INT(0, tvo_node_stop_requested(&node));
    }
    tvo_lcm_unicycle_sample_t m;
    plant_meas(&m, 3);
    (void)EXPECT_ACCEPTED(m, 0, plant_apply(3));
}

static void test_a_node_of_one_robot_takes_a_start_that_names_its_boot_for_its_robot(void)
{
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(&node, 1, EF_BOOT, record, NULL));
    /* Robot 1 names this node; robot 0 names another node (any boot). */
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    start.node_boot_id[0] = 424242;
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    const ef_message_t *m = ef_record_nth(&rec, TVO_NODE_CH_SESSION_ACK, 0);
    TEST_ASSERT_NOT_NULL(m);
    tvo_lcm_session_ack_t ack;
    TEST_ASSERT_EQUAL_INT((int)m->length, tvo_lcm_session_ack_t_decode(m->data, 0, (int)m->length, &ack));
    EF_ASSERT_STATUS(TVO_OK, ack.status);
    TEST_ASSERT_EQUAL_INT64(EF_BOOT, ack.boot_id);
    TEST_ASSERT_EQUAL_INT(1, ack.own_robot);
    TEST_ASSERT_NOT_NULL(tvo_node_session(&node));
    /* Robot 1 naming another boot, or a session without a robot 1: dropped. */
    ef_start(&start, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    start.node_boot_id[1] = EF_OTHER_BOOT;
    ef_record_clear(&rec);
    (void)send_session(&start, 0);
    EXPECT_NOTHING_PUBLISHED();
    ef_start(&start, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    (void)send_session(&start, 0);
    EXPECT_NOTHING_PUBLISHED();
    TEST_ASSERT_EQUAL_INT32(2, node.counters.wrong_boot);
    TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, tvo_node_session(&node)->session_id);
}

static void expect_announcement(int64_t now, int32_t state, int32_t session_id, int line)
{
    const tvo_lcm_node_status_t status = latest_announcement(line);
    UNITY_TEST_ASSERT_EQUAL_INT64(now, status.utime, line, "the node's clock");
    UNITY_TEST_ASSERT_EQUAL_INT32(TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION, status.protocol_version, line, "protocol");
    UNITY_TEST_ASSERT_EQUAL_INT64(EF_BOOT, status.boot_id, line, "boot");
    UNITY_TEST_ASSERT_EQUAL_INT(-1, status.own_robot, line, "every robot");
    UNITY_TEST_ASSERT_EQUAL_INT(TVO_NODE_MAX_ROBOTS, status.max_robots, line, "the build's robots");
    UNITY_TEST_ASSERT_EQUAL_INT(state, status.state, line, "state");
    UNITY_TEST_ASSERT_EQUAL_INT32(session_id, status.session_id, line, "session");
    UNITY_TEST_ASSERT_EQUAL_MEMORY(&node.counters, &status.counters, sizeof(status.counters), line, "counters");
}
#define EXPECT_ANNOUNCEMENT(now, state, id) expect_announcement((now), (state), (id), __LINE__)

static void expect_announcements(uint32_t count, int line)
{
    UNITY_TEST_ASSERT_EQUAL_UINT32(count, announcements.count, line, "announcements");
    UNITY_TEST_ASSERT_EQUAL_UINT32(0u, announcements.overflow, line, "announcement recorder overflow");
}
#define EXPECT_ANNOUNCEMENTS(count) expect_announcements((count), __LINE__)

static void test_the_node_announces_itself_idle_running_and_at_each_change(void)
{
    const int64_t idle_us = TVO_LCM_NODE_STATUS_T_IDLE_PERIOD_US, running_us = TVO_LCM_NODE_STATUS_T_RUNNING_PERIOD_US;
    const int64_t t0 = 1000;
    /* The first poll announces, idle; then every 250 ms. */
    TEST_ASSERT_EQUAL_INT64(t0 + idle_us, tvo_node_poll(&node, t0));
    EXPECT_ANNOUNCEMENTS(1u);
    EXPECT_ANNOUNCEMENT(t0, TVO_LCM_NODE_STATUS_T_STATE_IDLE, -1);
    TEST_ASSERT_EQUAL_INT64(t0 + idle_us, tvo_node_poll(&node, t0 + idle_us - 1));
    EXPECT_ANNOUNCEMENTS(1u);
    TEST_ASSERT_EQUAL_INT64(t0 + 2 * idle_us, tvo_node_poll(&node, t0 + idle_us));
    EXPECT_ANNOUNCEMENTS(2u);
    /* A START taken: at once, running; then every second. */
    const int64_t t1 = t0 + idle_us + 5000;
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, t1);
    EXPECT_ANNOUNCEMENTS(3u);
    EXPECT_ANNOUNCEMENT(t1, TVO_LCM_NODE_STATUS_T_STATE_RUNNING, EF_SESSION_ID);
    TEST_ASSERT_EQUAL_INT64(t1 + running_us, tvo_node_poll(&node, t1 + running_us - 1));
    EXPECT_ANNOUNCEMENTS(3u);
    /* A repeat, a conflict, a refused START, a STOP of another id: no change, no announcement. */
    tvo_lcm_session_t msg;
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    (void)send_session(&msg, t1 + 1);
    msg.gain_kp = 41.0;
    (void)send_session(&msg, t1 + 2);
    ef_start(&msg, OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.period_us = 0;
    (void)send_session(&msg, t1 + 3);
    stop_message(&msg, OTHER_ID);
    (void)send_session(&msg, t1 + 4);
    EXPECT_ANNOUNCEMENTS(3u);
    TEST_ASSERT_EQUAL_INT64(t1 + 2 * running_us, tvo_node_poll(&node, t1 + running_us));
    EXPECT_ANNOUNCEMENTS(4u);
    EXPECT_ANNOUNCEMENT(t1 + running_us, TVO_LCM_NODE_STATUS_T_STATE_RUNNING, EF_SESSION_ID);
    /* A STOP that ends the session: at once, idle, and 250 ms after. */
    const int64_t t2 = t1 + running_us + 7;
    stop_message(&msg, EF_SESSION_ID);
    (void)send_session(&msg, t2);
    EXPECT_ANNOUNCEMENTS(5u);
    EXPECT_ANNOUNCEMENT(t2, TVO_LCM_NODE_STATUS_T_STATE_IDLE, -1);
    TEST_ASSERT_EQUAL_INT64(t2 + idle_us, tvo_node_poll(&node, t2 + 1));
    EXPECT_ANNOUNCEMENTS(5u);
    /* A START that replaces a running one is a START taken too. */
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, t2 + 10);
    start_session(OTHER_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, t2 + 20);
    EXPECT_ANNOUNCEMENTS(7u);
    EXPECT_ANNOUNCEMENT(t2 + 20, TVO_LCM_NODE_STATUS_T_STATE_RUNNING, OTHER_ID);
    TEST_ASSERT_EQUAL_INT32(3, node.counters.sessions);
}

/* ------------------------------------------------------------------------------------------------
 * Telemetry at its rate; one robot's period is the core's step
 * --------------------------------------------------------------------------------------------- */

/* The answer to a sample whose sequence is `sequence` carries telemetry iff it is a multiple of every. */
static void test_telemetry_follows_the_answers_to_multiples_of_telemetry_every(void)
{
    const int32_t everies[] = {0, 3};
    const int32_t expected_every[] = {(int32_t)((TVO_SESSION_TELEMETRY_DEFAULT_US + H - 1) / H), 3};
    for (size_t e = 0; e < sizeof(everies) / sizeof(everies[0]); ++e) {
        for (int clock = TVO_LCM_SESSION_T_CLOCK_PLANT; clock <= TVO_LCM_SESSION_T_CLOCK_NODE; ++clock) {
            setUp();
            ef_start(&start, EF_SESSION_ID, clock, 1);
            start.telemetry_every = everies[e];
            (void)send_session(&start, NODE_T0);
            const int node_clock = clock == TVO_LCM_SESSION_T_CLOCK_NODE;
            const int32_t every = expected_every[e];
            TEST_ASSERT_EQUAL_UINT32((uint32_t)every, tvo_node_session(&node)->schedule.timing.telemetry_every);
            uint32_t telemetry = 0u;
            for (int64_t j = 1; j <= 25; ++j) {
                tvo_lcm_unicycle_sample_t m;
                if (node_clock) {
                    node_meas(&m, j, (int32_t)(SEQ0 + j));
                } else {
                    plant_meas(&m, j);
                }
                ef_record_clear(&rec);
                (void)send_sample(&m, node_clock ? node_arrival(j) : 0);
                const int carries = (m.header.sequence % every) == 0;
                TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&rec, TVO_NODE_CH_COMMAND));
                TEST_ASSERT_EQUAL_UINT32(carries ? 1u : 0u, ef_record_count(&rec, TVO_NODE_CH_TELEMETRY));
                telemetry += carries ? 1u : 0u;
                if (carries) {
                    (void)THE_COMMAND(); /* the telemetry carries the command's header */
                    /* A refusal of the same sequence (a duplicate) carries it too. */
                    ef_record_clear(&rec);
                    (void)send_sample(&m, node_clock ? node_arrival(j) + 1 : 0);
                    TEST_ASSERT_TRUE(THE_COMMAND().header.status != TVO_LCM_COMMAND_HEADER_T_STATUS_OK);
                }
            }
            TEST_ASSERT_TRUE(telemetry >= 2u);
            if (node_clock) {
                /* The node's own stops carry none. */
                ef_record_clear(&rec);
                (void)tvo_node_poll(&node, node_apply(25 + W));
                TEST_ASSERT_EQUAL_UINT32(1u, ef_record_count(&rec, TVO_NODE_CH_COMMAND));
                TEST_ASSERT_EQUAL_UINT32(0u, ef_record_count(&rec, TVO_NODE_CH_TELEMETRY));
            }
        }
    }
}

/* A one-robot session steps on each sample, exactly as the core's own step would: a reference
 * controller stepped directly with the same measurement gives the same command, bit for bit, over
 * a run with a lost period and a refused duplicate. */
static void test_one_robot_periods_are_the_cores_own_steps(void)
{
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    start_session(EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 0);
    static tvo_problem_t problem;
    static tvo_controller_t reference;
    tvo_problem_desc_t desc;
    tvo_controller_config_t cfg;
    tvo_session_reject_t why;
    TEST_ASSERT_EQUAL_INT(TVO_OK, tvo_session_decode_problem(&start, &desc, &why));
    tvo_problem_culprit_t part;
    TEST_ASSERT_EQUAL_INT(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
    TEST_ASSERT_EQUAL_INT(TVO_OK, tvo_session_decode_unicycle(&start, &cfg, &why));
    tvo_param_t bad = TVO_PARAM_NONE;
    TEST_ASSERT_EQUAL_INT(TVO_OK, tvo_controller_init(&reference, &cfg, &problem.objective, (uint32_t)EF_EPOCH, &bad));
    for (int64_t j = 1; j <= 30; ++j) {
        if (j == 4) {
            continue; /* lost */
        }
        tvo_lcm_unicycle_sample_t m;
        plant_meas(&m, j);
        m.position_m[0] = 0.01 * (double)j;
        m.position_m[1] = 0.3 - 0.002 * (double)(j * j);
        m.heading_rad = 0.05f * (float)j;
        const tvo_lcm_unicycle_command_t got = EXPECT_ACCEPTED(m, 0, plant_apply(j));
        tvo_measurement_t meas;
        memset(&meas, 0, sizeof(meas));
        meas.stamp_tick = (uint32_t)m.header.utime;
        meas.position_m[0][0] = (tvo_real_t)m.position_m[0];
        meas.position_m[0][1] = (tvo_real_t)m.position_m[1];
        meas.heading_rad[0] = (tvo_real_t)m.heading_rad;
        meas.heading_valid = 1u;
        tvo_command_t want;
        TEST_ASSERT_EQUAL_INT(TVO_OK, tvo_controller_step(&reference, &meas, (uint32_t)plant_apply(j), &want));
        TEST_ASSERT_EQUAL_INT(TVO_OUTCOME_APPLIED, want.outcome);
        const float speed = (float)want.speed_mps[0], turn = (float)want.turn_rate_radps[0];
        TEST_ASSERT_EQUAL_MEMORY(&speed, &got.speed_mps, sizeof(speed));
        TEST_ASSERT_EQUAL_MEMORY(&turn, &got.turn_rate_radps, sizeof(turn));
        TEST_ASSERT_EQUAL_INT(tvo_step_wire_flags(want.flags, TVO_OUTCOME_APPLIED), got.header.flags);
        if (j == 10) {
            (void)EXPECT_REFUSED(m, 0, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER); /* the core never sees it */
        }
    }
    TEST_ASSERT_TRUE(tvo_node_session(&node)->controller.u.unicycle.internal.held.speed_mps[0] != TVO_R(0.0));
}

static void test_encode_buffer_holds_every_message(void)
{
    TEST_ASSERT_EQUAL_INT(0, tvo_node_check_buffer());
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_start_when_idle_runs_the_session_and_acks_ok);
    RUN_TEST(test_start_with_a_new_id_replaces_the_running_session);
    RUN_TEST(test_refused_start_while_running_changes_nothing);
    RUN_TEST(test_refused_start_when_idle_leaves_the_node_idle);
    RUN_TEST(test_repeated_start_is_acked_again_without_a_restart);
    RUN_TEST(test_start_of_the_running_id_with_other_content_is_a_conflict);
    RUN_TEST(test_stop_of_the_running_session_ends_it_and_a_start_begins_anew);
    RUN_TEST(test_stop_of_another_id_is_refused_and_the_session_runs_on);
    RUN_TEST(test_unknown_actions_are_refused_and_change_nothing);
    RUN_TEST(test_samples_and_targets_while_idle_are_dropped_and_counted);
    RUN_TEST(test_messages_of_another_session_are_ignored_and_counted);
    RUN_TEST(test_each_readme_session_row_is_what_the_table_does);
    RUN_TEST(test_idle_cells_the_classification_cannot_reach_are_marked_so);
    RUN_TEST(test_plant_period_is_the_apply_instant_nearest_stamp_plus_tau);
    RUN_TEST(test_plant_age_outside_zero_to_h_is_refused_by_the_controller);
    RUN_TEST(test_plant_duplicates_and_reordering_are_out_of_order);
    RUN_TEST(test_plant_stray_stamps_cost_the_genuine_stream_nothing);
    RUN_TEST(test_plant_huge_sequences_are_refused);
    RUN_TEST(test_plant_gap_with_consistent_sequence_is_accepted);
    RUN_TEST(test_plant_one_sample_far_ahead_costs_one_refusal);
    RUN_TEST(test_plant_stale_copies_after_a_jump_do_not_restart_the_vote);
    RUN_TEST(test_target_stamped_at_epoch_minus_tau_is_carried_to_the_epoch);
    RUN_TEST(test_plant_watchdog_refusals_in_a_row_give_a_safe_stop_until_one_is_accepted);
    RUN_TEST(test_plant_fewer_copies_than_the_watchdog_cost_their_refusals_only);
    RUN_TEST(test_plant_wrong_robot_plant_and_non_finite_values_are_refused);
    RUN_TEST(test_node_clock_offset_comes_from_the_start_and_commands_are_in_plant_time);
    RUN_TEST(test_node_clock_sequence_is_only_echoed);
    RUN_TEST(test_node_clock_stamp_more_than_half_a_period_ahead_is_implausible);
    RUN_TEST(test_node_clock_stale_and_repeated_stamps_are_refused);
    RUN_TEST(test_node_timer_has_no_deadline_before_the_first_accepted_measurement);
    RUN_TEST(test_node_timer_stops_at_last_apply_plus_watchdog_periods_then_every_period);
    RUN_TEST(test_node_timer_is_not_moved_by_refused_measurements);
    RUN_TEST(test_plant_clock_sessions_have_no_timer);
    RUN_TEST(test_stop_disarms_the_timer);
    RUN_TEST(test_counters_count_every_kind_of_event_and_the_announcement_carries_them);
    RUN_TEST(test_counters_count_speed_mismatch_steps);
    RUN_TEST(test_plant_implausible_measurements_are_refused_and_keep_nothing);
    RUN_TEST(test_plant_finite_values_beyond_float_range_are_implausible_not_non_finite);
    RUN_TEST(test_plant_each_refusal_is_counted_under_the_status_its_answer_carries);
    RUN_TEST(test_chain_and_target_positions_beyond_float_range_are_not_called_non_finite);
    RUN_TEST(test_slack_rule_is_undone_when_the_first_step_fails);
    RUN_TEST(test_plant_first_measurement_beyond_the_tick_span_is_implausible);
    RUN_TEST(test_chain_session_runs_through_the_node);
    RUN_TEST(test_plant_refusal_by_the_step_keeps_nothing);
    RUN_TEST(test_plant_target_beyond_the_next_period_is_refused);
    RUN_TEST(test_plant_first_window_starts_at_a_later_epoch);
    RUN_TEST(test_plant_repeated_start_moves_the_first_window);
    RUN_TEST(test_plant_samples_past_the_first_window_that_agree_move_it);
    RUN_TEST(test_plant_strays_the_node_refuses_do_not_move_the_first_window);
    RUN_TEST(test_plant_target_stream_may_start_late);
    RUN_TEST(test_plant_target_two_to_the_32_us_old_is_not_taken_for_a_new_one);
    RUN_TEST(test_node_clock_sample_two_to_the_32_us_old_is_stale);
    RUN_TEST(test_node_clock_reanchors_on_agreeing_measurements_before_tracking);
    RUN_TEST(test_node_clock_reanchor_whose_trial_the_core_stops_commits_nothing_and_recovers);
    RUN_TEST(test_plant_step_refusals_count_toward_the_watchdog);
    RUN_TEST(test_node_clock_a_law_failure_after_the_timer_stop_is_answered_with_a_safe_stop);
    RUN_TEST(test_start_utime_extremes);
    RUN_TEST(test_start_epoch_extremes);
    RUN_TEST(test_start_period_extremes);
    RUN_TEST(test_start_delay_extremes);
    RUN_TEST(test_start_watchdog_extremes);
    RUN_TEST(test_start_robot_count_extremes);
    RUN_TEST(test_start_protocol_version_extremes);
    RUN_TEST(test_start_telemetry_every_extremes);
    RUN_TEST(test_start_clock_source_extremes);
    RUN_TEST(test_start_plant_kind_extremes);
    RUN_TEST(test_start_velocity_source_extremes);
    RUN_TEST(test_start_chain_relative_degree_extremes);
    RUN_TEST(test_start_relaxation_degree_extremes);
    RUN_TEST(test_start_count_extremes);
    RUN_TEST(test_start_robot_index_extremes);
    RUN_TEST(test_start_path_kind_extremes);
    RUN_TEST(test_start_session_id_extremes);
    RUN_TEST(test_sample_utime_extremes);
    RUN_TEST(test_sample_sequence_extremes);
    RUN_TEST(test_sample_robot_extremes);
    RUN_TEST(test_sample_session_id_extremes);
    RUN_TEST(test_target_utime_robot_count_and_session_extremes);
    RUN_TEST(test_node_clock_extremes);
    RUN_TEST(test_commands_stay_within_the_wire_time_range);
    RUN_TEST(test_encode_buffer_holds_every_message);
    RUN_TEST(test_init_refuses_bad_arguments_and_leaves_an_unusable_node);
    RUN_TEST(test_a_session_message_naming_another_boot_is_dropped_unanswered);
    RUN_TEST(test_a_node_of_one_robot_takes_a_start_that_names_its_boot_for_its_robot);
    RUN_TEST(test_the_node_announces_itself_idle_running_and_at_each_change);
    RUN_TEST(test_telemetry_follows_the_answers_to_multiples_of_telemetry_every);
    RUN_TEST(test_one_robot_periods_are_the_cores_own_steps);
    return UNITY_END();
}
