/*
 * The keyed node against an attacker on the bus (auth_link.c in front of node.c): a genuine
 * CLOCK_PLANT session runs twice, once clean and once with an attack between every two genuine
 * messages. Each attack must be dropped unanswered and counted, and the node must publish the very
 * same frames (commands bit for bit, signed with the same counters) as in the clean run.
 */
#include "auth_link.h"
#include "edge_fixture.h"

#define H EF_PERIOD_US
#define TAU EF_DELAY_US
#define STEPS 40
#define WIRE_CAPACITY 16384 /* a session_t is 11,427 bytes encoded */
#define FRAME_CAPACITY (WIRE_CAPACITY + TVO_AUTH_TRAILER_BYTES)

/* Every clock here is a fake in microseconds of "wall" time; counters follow it. */
static uint64_t fake_wall_us;
static uint64_t fake_wall(void)
{
    return fake_wall_us;
}

static const uint8_t genuine_key[TVO_AUTH_KEY_BYTES] = {
    0x1f, 0x2e, 0x3d, 0x4c, 0x5b, 0x6a, 0x79, 0x88, 0x97, 0xa6, 0xb5, 0xc4, 0xd3, 0xe2, 0xf1, 0x00,
    0x0f, 0x1e, 0x2d, 0x3c, 0x4b, 0x5a, 0x69, 0x78, 0x87, 0x96, 0xa5, 0xb4, 0xc3, 0xd2, 0xe1, 0xf0};

static tvo_node_t node;
static tvo_auth_link_t link;
static ef_record_t rec;
static tvo_auth_t plant;    /* the genuine plant's end */
static tvo_auth_t forger;   /* a sender with another key */

typedef struct {
    uint32_t count;
    uint32_t length[STEPS + 4];
    uint8_t bytes[STEPS + 4][FRAME_CAPACITY];
} frames_t;

static frames_t clean_commands;
static frames_t attacked_commands;
static uint32_t acks_seen;

/* A frame of the last genuine kind sent, kept for the replays. */
static uint8_t kept_start[FRAME_CAPACITY];
static uint32_t kept_start_length;
static uint8_t kept_measurement[FRAME_CAPACITY];
static uint32_t kept_measurement_length;

void setUp(void) {}
void tearDown(void) {}

static uint32_t encode_sign(tvo_auth_t *signer, int channel, const void *msg, uint8_t *frame)
{
    int n = -1;
    switch (channel) {
    case TVO_NODE_CH_SESSION:
        n = tvo_lcm_session_t_encode(frame, 0, WIRE_CAPACITY, (const tvo_lcm_session_t *)msg);
        break;
    case TVO_NODE_CH_SAMPLE:
        n = tvo_lcm_unicycle_sample_t_encode(frame, 0, WIRE_CAPACITY, (const tvo_lcm_unicycle_sample_t *)msg);
        break;
    default:
        n = tvo_lcm_target_t_encode(frame, 0, WIRE_CAPACITY, (const tvo_lcm_target_t *)msg);
        break;
    }
    TEST_ASSERT_TRUE(n > 0);
    if (signer == NULL) {
        return (uint32_t)n; /* an unsigned message, as an unkeyed plant sends */
    }
    (void)tvo_auth_counter_at_least(signer, fake_wall_us);
    size_t signed_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(signer, tvo_node_channel_name(channel), frame, (size_t)n,
                                                 FRAME_CAPACITY, &signed_length));
    return (uint32_t)signed_length;
}

/* Hands a frame to the keyed node and moves the commands it published into out (if any). */
static void deliver(int channel, const uint8_t *frame, uint32_t length, int64_t now_us, frames_t *out)
{
    ef_record_clear(&rec);
    (void)tvo_auth_link_receive(&link, &node, channel, frame, length, now_us);
    TEST_ASSERT_EQUAL_UINT32(0u, rec.overflow);
    for (uint32_t i = 0u; i < rec.count; ++i) {
        const ef_message_t *m = &rec.message[i];
        if (m->channel == TVO_NODE_CH_SESSION_ACK) {
            acks_seen++;
        }
        if (m->channel == TVO_NODE_CH_COMMAND && out != NULL) {
            TEST_ASSERT_TRUE(out->count < STEPS + 4);
            out->length[out->count] = m->length;
            memcpy(out->bytes[out->count], m->data, m->length);
            out->count++;
        }
    }
}

/* A frame an attacker sends: nothing may be published in answer, and it must be counted as `kind`. */
static void attack(int channel, const uint8_t *frame, uint32_t length, int64_t now_us, int32_t *kind)
{
    const int32_t before = *kind;
    const tvo_lcm_node_counters_t counters_before = node.counters;
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL_INT(0, tvo_auth_link_receive(&link, &node, channel, frame, length, now_us));
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, rec.count, "an attack was answered");
    TEST_ASSERT_EQUAL_INT32(before + 1, *kind);
    /* Nothing else moved: only the drop's own counter. */
    tvo_lcm_node_counters_t expected = counters_before;
    if (kind == &node.counters.unauthenticated) {
        expected.unauthenticated++;
    } else {
        expected.replayed++;
    }
    TEST_ASSERT_EQUAL_MEMORY(&expected, &node.counters, sizeof(expected));
}

static void start_node(void)
{
    ef_record_clear(&rec);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK,
                      tvo_auth_link_init(&link, genuine_key, TVO_AUTH_SENDER_NODE, 1u, ef_record_publish, &rec));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_follow_clock(&link.auth, fake_wall, TVO_AUTH_NEW_SENDER_WINDOW_US));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(&node, -1, EF_BOOT, tvo_auth_link_publish, &link));
}

static void reset_world(void)
{
    fake_wall_us = 1800000000000000u; /* 2027-01-15 in us since the Unix epoch */
    acks_seen = 0u;
    uint8_t other_key[TVO_AUTH_KEY_BYTES];
    memcpy(other_key, genuine_key, sizeof(other_key));
    other_key[0] ^= 0x01u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&plant, genuine_key, TVO_AUTH_SENDER_PLANT, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&forger, other_key, TVO_AUTH_SENDER_PLANT, 1u));
    start_node();
}

static int64_t sample_utime(int64_t j)
{
    return EF_EPOCH + j * H - TAU;
}

/* The genuine session; with attacks, each genuine message is followed by one of them in turn. */
static void run_session(int with_attacks, frames_t *out)
{
    static uint8_t frame[FRAME_CAPACITY];
    static uint8_t forged[FRAME_CAPACITY];
    tvo_lcm_session_t start;
    tvo_lcm_unicycle_sample_t meas;
    reset_world();
    memset(out, 0, sizeof(*out));

    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    kept_start_length = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, kept_start);
    deliver(TVO_NODE_CH_SESSION, kept_start, kept_start_length, EF_UTIME, out);
    TEST_ASSERT_EQUAL_UINT32(1u, acks_seen);

    for (int64_t j = 1; j <= STEPS; ++j) {
        fake_wall_us += H;
        const int64_t now = sample_utime(j);
        ef_sample(&meas, EF_SESSION_ID, now, (int32_t)j, 0);
        meas.position_m[0] = 0.01 * (double)j;
        const uint32_t length = encode_sign(&plant, TVO_NODE_CH_SAMPLE, &meas, frame);
        deliver(TVO_NODE_CH_SAMPLE, frame, length, now, out);
        if (!with_attacks) {
            memcpy(kept_measurement, frame, length);
            kept_measurement_length = length;
            continue;
        }
        uint32_t n = 0u;
        tvo_lcm_session_t evil_session;
        tvo_lcm_unicycle_sample_t evil;
        switch (j % 10) {
        case 1: /* a forged START of another session, signed with another key */
            ef_start(&evil_session, 666, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
            n = encode_sign(&forger, TVO_NODE_CH_SESSION, &evil_session, forged);
            attack(TVO_NODE_CH_SESSION, forged, n, now, &node.counters.unauthenticated);
            break;
        case 2: /* a forged STOP of the running session, unsigned */
            ef_start(&evil_session, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
            evil_session.action = TVO_LCM_SESSION_T_ACTION_STOP;
            n = encode_sign(NULL, TVO_NODE_CH_SESSION, &evil_session, forged);
            attack(TVO_NODE_CH_SESSION, forged, n, now, &node.counters.unauthenticated);
            break;
        case 3: /* a forged measurement 20 s ahead whose sequence agrees, signed with another key */
            ef_sample(&evil, EF_SESSION_ID, now + 20000000, (int32_t)(j + 2000), 0);
            evil.position_m[0] = 5.0;
            n = encode_sign(&forger, TVO_NODE_CH_SAMPLE, &evil, forged);
            attack(TVO_NODE_CH_SAMPLE, forged, n, now, &node.counters.unauthenticated);
            break;
        case 4: { /* a forged target sample */
            tvo_lcm_target_t target;
            memset(&target, 0, sizeof(target));
            target.header.utime = now;
            target.header.session_id = EF_SESSION_ID;
            target.position_m[0] = 9.0;
            n = encode_sign(&forger, TVO_NODE_CH_TARGET, &target, forged);
            attack(TVO_NODE_CH_TARGET, forged, n, now, &node.counters.unauthenticated);
            break;
        }
        case 5: /* the genuine measurement just accepted, replayed */
            attack(TVO_NODE_CH_SAMPLE, frame, length, now, &node.counters.replayed);
            break;
        case 6: /* the genuine START, replayed */
            attack(TVO_NODE_CH_SESSION, kept_start, kept_start_length, now, &node.counters.replayed);
            break;
        case 7: /* the genuine measurement with one bit of its tag flipped */
            memcpy(forged, frame, length);
            forged[length - 1u] ^= 0x40u;
            attack(TVO_NODE_CH_SAMPLE, forged, length, now, &node.counters.unauthenticated);
            break;
        case 8: /* truncated tags: the genuine frame cut by 1 .. 16 bytes */
            for (uint32_t cut = 1u; cut <= TVO_AUTH_TAG_BYTES; ++cut) {
                attack(TVO_NODE_CH_SAMPLE, frame, length - cut, now, &node.counters.unauthenticated);
            }
            break;
        case 9: /* a forged vote of three samples that agree with each other */
            for (int64_t k = 0; k < 3; ++k) {
                ef_sample(&evil, EF_SESSION_ID, now + 1000000 + k * H, (int32_t)(j + 500 + k), 0);
                n = encode_sign(&forger, TVO_NODE_CH_SAMPLE, &evil, forged);
                attack(TVO_NODE_CH_SAMPLE, forged, n, now, &node.counters.unauthenticated);
            }
            break;
        default: /* the genuine frame moved to another channel */
            attack(TVO_NODE_CH_TARGET, frame, length, now, &node.counters.unauthenticated);
            break;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(1u, acks_seen); /* no attack got an ack */
}

static void test_every_attack_is_dropped_unanswered_and_changes_no_command(void)
{
    run_session(0, &clean_commands);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.unauthenticated);
    TEST_ASSERT_EQUAL_INT32(0, node.counters.replayed);
    TEST_ASSERT_EQUAL_UINT32(STEPS, clean_commands.count);

    run_session(1, &attacked_commands);
    /* Per 10 steps: forged START, STOP, measurement, target (4), a flipped tag (1), 16 truncations, 3 votes, 1 moved. */
    TEST_ASSERT_EQUAL_INT32((STEPS / 10) * 25, node.counters.unauthenticated);
    TEST_ASSERT_EQUAL_INT32((STEPS / 10) * 2, node.counters.replayed);
    TEST_ASSERT_EQUAL_INT32(STEPS, node.counters.accepted);

    TEST_ASSERT_EQUAL_UINT32(clean_commands.count, attacked_commands.count);
    for (uint32_t i = 0u; i < clean_commands.count; ++i) {
        TEST_ASSERT_EQUAL_UINT32(clean_commands.length[i], attacked_commands.length[i]);
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(clean_commands.bytes[i], attacked_commands.bytes[i], clean_commands.length[i],
                                         "a command differs from the run without attacks");
    }
}

static void test_the_node_signs_what_it_publishes_and_the_plant_can_open_it(void)
{
    run_session(0, &clean_commands);
    tvo_auth_t plant_receiver;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&plant_receiver, genuine_key, 99u, 1u));
    for (uint32_t i = 0u; i < clean_commands.count; ++i) {
        size_t message_length = 0u;
        TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&plant_receiver, TVO_CHANNEL_COMMAND, clean_commands.bytes[i],
                                                     clean_commands.length[i], &message_length));
        tvo_lcm_unicycle_command_t cmd;
        TEST_ASSERT_EQUAL_INT((int)message_length,
                              tvo_lcm_unicycle_command_t_decode(clean_commands.bytes[i], 0, (int)message_length, &cmd));
        TEST_ASSERT_EQUAL_INT64(EF_SESSION_ID, cmd.header.session_id);
        TEST_ASSERT_EQUAL_INT32(0, cmd.header.status);
    }
    /* The same command frame twice: the plant refuses the second (a replayed command). */
    size_t message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_REPLAY, tvo_auth_open(&plant_receiver, TVO_CHANNEL_COMMAND, clean_commands.bytes[0],
                                                          clean_commands.length[0], &message_length));
}

static void test_a_restarted_node_refuses_recordings_from_before_its_window(void)
{
    static uint8_t frame[FRAME_CAPACITY];
    tvo_lcm_session_t start;
    reset_world();
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    const uint32_t recorded = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, frame);
    /* The node restarts two minutes later: it has forgotten every sender. */
    fake_wall_us += 120000000u;
    start_node();
    attack(TVO_NODE_CH_SESSION, frame, recorded, EF_UTIME, &node.counters.replayed);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_IDLE, node.state);
    /* The genuine plant, still running, is heard at once: its counters follow the clock. */
    const uint32_t fresh = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, frame);
    acks_seen = 0u;
    deliver(TVO_NODE_CH_SESSION, frame, fresh, EF_UTIME, NULL);
    TEST_ASSERT_EQUAL_UINT32(1u, acks_seen);
    TEST_ASSERT_EQUAL_INT(TVO_NODE_RUNNING, node.state);
}

static void test_a_node_counter_never_repeats_across_a_restart(void)
{
    reset_world();
    static uint8_t frame[FRAME_CAPACITY];
    tvo_lcm_session_t start;
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    const uint32_t n = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, frame);
    deliver(TVO_NODE_CH_SESSION, frame, n, EF_UTIME, NULL);
    const uint64_t before_restart = link.auth.next_counter; /* above every counter signed so far */
    fake_wall_us += 1000u; /* a restart takes over a millisecond; no node sends 1,000 messages in one */
    start_node();
    TEST_ASSERT_TRUE(link.auth.next_counter >= before_restart);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_attack_is_dropped_unanswered_and_changes_no_command);
    RUN_TEST(test_the_node_signs_what_it_publishes_and_the_plant_can_open_it);
    RUN_TEST(test_a_restarted_node_refuses_recordings_from_before_its_window);
    RUN_TEST(test_a_node_counter_never_repeats_across_a_restart);
    return UNITY_END();
}
