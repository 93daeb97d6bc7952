/*
 * The keyed node against an attacker on the bus (auth_link.c in front of node.c): a genuine
 * CLOCK_PLANT session runs twice, once clean and once with an attack between every two genuine
 * frames. Each attack must be dropped unanswered and counted in the node's counters as what it is
 * (malformed, unauthenticated, replayed; nothing else moves), in the cheapest order (no tag computed
 * for a frame that is no message of its channel or reuses a known sender's counter), and the node must
 * publish the very same frames (commands bit for bit, signed with the same counters) as in the clean run.
 * Then what a restart does: recordings of the last boot never run, and counters never repeat.
 */
#include <string.h>

#include "auth_link.h"
#include "unity.h"

#define H 10000
#define TAU 5000
#define START_UTIME 5000000
#define EPOCH (START_UTIME + 300000)
#define SESSION_ID 4242
#define STEPS 40
#define BOOT 5
#define FRAME_CAPACITY (TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES)
#define RECORD_CAPACITY 16

static const uint8_t genuine_key[TVO_AUTH_KEY_BYTES] = {
    0x1f, 0x2e, 0x3d, 0x4c, 0x5b, 0x6a, 0x79, 0x88, 0x97, 0xa6, 0xb5, 0xc4, 0xd3, 0xe2, 0xf1, 0x00,
    0x0f, 0x1e, 0x2d, 0x3c, 0x4b, 0x5a, 0x69, 0x78, 0x87, 0x96, 0xa5, 0xb4, 0xc3, 0xd2, 0xe1, 0xf0};

/* What the node published during one call: channel and signed frame. */
typedef struct {
    uint32_t count;
    int channel[RECORD_CAPACITY];
    uint32_t length[RECORD_CAPACITY];
    uint8_t bytes[RECORD_CAPACITY][TVO_NODE_BUFFER_BYTES + TVO_AUTH_TRAILER_BYTES];
} published_t;

typedef struct {
    uint32_t count;
    uint32_t length[STEPS + 4];
    uint8_t bytes[STEPS + 4][TVO_NODE_BUFFER_BYTES + TVO_AUTH_TRAILER_BYTES];
} frames_t;

static tvo_node_t node;
static tvo_auth_link_t link;
static published_t published;
static tvo_auth_t plant;    /* the genuine plant's end */
static tvo_auth_t forger;   /* a sender with another key */
static frames_t clean_commands;
static frames_t attacked_commands;
static uint32_t acks_seen;
static uint64_t plant_clock_us;

void setUp(void) {}
void tearDown(void) {}

static void record(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    TEST_ASSERT_TRUE(published.count < RECORD_CAPACITY && length <= sizeof(published.bytes[0]));
    published.channel[published.count] = channel;
    published.length[published.count] = length;
    memcpy(published.bytes[published.count], data, length);
    published.count++;
}

/* A START of one unicycle tracking a line, on the plant clock, naming boot `boot`. */
static void make_start(tvo_lcm_session_t *m, int32_t session_id, int64_t boot)
{
    (void)tvo_protocol_default_start(m, 1);
    m->utime = START_UTIME;
    m->session_id = session_id;
    m->node_boot_id[0] = boot;
    m->epoch_utime = EPOCH;
    m->period_us = H;
    m->delay_us = TAU;
    m->watchdog_periods = 3;
    m->speed_max_mps = 2.0;
    m->robot[0].target.kind = TVO_LCM_PATH_T_KIND_POLYNOMIAL;
    m->robot[0].target.coeff[0][0] = 0.5;
    m->robot[0].target.coeff[0][1] = 0.2;
}

/* Robot 0's sample of period j (sequence j, stamped tau before period j's apply instant). */
static void make_sample(tvo_lcm_unicycle_sample_t *m, int32_t session_id, int64_t j)
{
    memset(m, 0, sizeof(*m));
    m->header.utime = EPOCH + j * H - TAU;
    m->header.session_id = session_id;
    m->header.sequence = (int32_t)j;
    m->header.robot = 0;
    m->has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING;
    m->position_m[0] = 0.01 * (double)j;
}

/* The message encoded into frame, then signed by signer (NULL: left unsigned); the frame's length. */
static uint32_t encode_sign(tvo_auth_t *signer, int channel, const void *msg, uint8_t *frame)
{
    int n = -1;
    switch (channel) {
    case TVO_NODE_CH_SESSION:
        n = tvo_lcm_session_t_encode(frame, 0, FRAME_CAPACITY, (const tvo_lcm_session_t *)msg);
        break;
    case TVO_NODE_CH_SAMPLE:
        n = tvo_lcm_unicycle_sample_t_encode(frame, 0, FRAME_CAPACITY, (const tvo_lcm_unicycle_sample_t *)msg);
        break;
    default:
        n = tvo_lcm_target_t_encode(frame, 0, FRAME_CAPACITY, (const tvo_lcm_target_t *)msg);
        break;
    }
    TEST_ASSERT_TRUE(n > 0);
    if (signer == NULL) {
        return (uint32_t)n;
    }
    (void)tvo_auth_counter_at_least(signer, plant_clock_us);
    size_t signed_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(signer, tvo_node_channel_name(channel), frame, (size_t)n,
                                                 FRAME_CAPACITY, &signed_length));
    return (uint32_t)signed_length;
}

/* Hands a frame to the keyed node and keeps the commands it published in out (if any). */
static void deliver(int channel, const uint8_t *frame, uint32_t length, int64_t now_us, frames_t *out)
{
    published.count = 0u;
    (void)tvo_auth_link_receive(&link, &node, channel, frame, length, now_us);
    for (uint32_t i = 0u; i < published.count; ++i) {
        if (published.channel[i] == TVO_NODE_CH_SESSION_ACK) {
            acks_seen++;
        }
        if (published.channel[i] == TVO_NODE_CH_COMMAND && out != NULL) {
            TEST_ASSERT_TRUE(out->count < STEPS + 4);
            out->length[out->count] = published.length[i];
            memcpy(out->bytes[out->count], published.bytes[i], published.length[i]);
            out->count++;
        }
    }
}

/* Which counter a dropped frame must move. */
typedef enum { DROP_MALFORMED, DROP_UNAUTHENTICATED, DROP_REPLAYED } drop_kind_t;

/* A frame an attacker sends: nothing may be published in answer, it must be counted as `kind`, and
 * nothing else may change: no other counter, nor the link's memory of its senders. */
static void attack(int channel, const uint8_t *frame, uint32_t length, int64_t now_us, drop_kind_t kind)
{
    static tvo_auth_t auth_before;
    const tvo_lcm_node_counters_t before = *tvo_node_counters(&node);
    auth_before = link.auth;
    published.count = 0u;
    TEST_ASSERT_EQUAL_INT(0, tvo_auth_link_receive(&link, &node, channel, frame, length, now_us));
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, published.count, "an attack was answered");
    tvo_lcm_node_counters_t expected = before;
    switch (kind) {
    case DROP_MALFORMED: expected.malformed++; break;
    case DROP_UNAUTHENTICATED: expected.unauthenticated++; break;
    case DROP_REPLAYED: expected.replayed++; break;
    default: TEST_FAIL(); break;
    }
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&expected, tvo_node_counters(&node), sizeof(expected),
                                     "a drop moved another counter than its own");
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&auth_before, &link.auth, sizeof(auth_before), "a drop changed the link's senders");
}

static void start_node(int64_t boot)
{
    published.count = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_link_init(&link, genuine_key, TVO_AUTH_SENDER_NODE, boot, record, NULL));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_init(&node, -1, boot, tvo_auth_link_publish, &link));
    (void)tvo_node_poll(&node, 1000); /* the first announcement */
}

static void reset_world(void)
{
    plant_clock_us = 1800000000000000u; /* the plant's counters follow its wall clock (us since 1970) */
    acks_seen = 0u;
    uint8_t other_key[TVO_AUTH_KEY_BYTES];
    memcpy(other_key, genuine_key, sizeof(other_key));
    other_key[0] ^= 0x01u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&plant, genuine_key, TVO_AUTH_SENDER_PLANT, 1u));
    /* The forger takes the plant's sender id and counters above the plant's: its frames cost a tag each
     * (with a counter the plant has used they would be refused as replays before that). */
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&forger, other_key, TVO_AUTH_SENDER_PLANT, UINT64_C(1) << 62));
    start_node(BOOT);
}

/* The genuine session; with attacks, each genuine sample is followed by one of them in turn. */
static void run_session(int with_attacks, frames_t *out)
{
    static uint8_t frame[FRAME_CAPACITY];
    static uint8_t forged[FRAME_CAPACITY];
    static uint8_t kept_start[FRAME_CAPACITY];
    static tvo_lcm_session_t start;
    tvo_lcm_unicycle_sample_t sample;
    reset_world();
    memset(out, 0, sizeof(*out));

    make_start(&start, SESSION_ID, BOOT);
    const uint32_t kept_start_length = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, kept_start);
    deliver(TVO_NODE_CH_SESSION, kept_start, kept_start_length, START_UTIME, out);
    TEST_ASSERT_EQUAL_UINT32(1u, acks_seen);

    for (int64_t j = 1; j <= STEPS; ++j) {
        plant_clock_us += H;
        const int64_t now = EPOCH + j * H - TAU;
        make_sample(&sample, SESSION_ID, j);
        const uint32_t length = encode_sign(&plant, TVO_NODE_CH_SAMPLE, &sample, frame);
        deliver(TVO_NODE_CH_SAMPLE, frame, length, now, out);
        if (!with_attacks) {
            continue;
        }
        uint32_t n = 0u;
        static tvo_lcm_session_t evil_session;
        tvo_lcm_unicycle_sample_t evil;
        switch (j % 12) {
        case 1: /* a forged START of another session, signed with another key */
            make_start(&evil_session, 666, BOOT);
            n = encode_sign(&forger, TVO_NODE_CH_SESSION, &evil_session, forged);
            attack(TVO_NODE_CH_SESSION, forged, n, now, DROP_UNAUTHENTICATED);
            break;
        case 2: /* a forged STOP of the running session, unsigned: no trailer, so no frame of its channel */
            make_start(&evil_session, SESSION_ID, BOOT);
            evil_session.action = TVO_LCM_SESSION_T_ACTION_STOP;
            n = encode_sign(NULL, TVO_NODE_CH_SESSION, &evil_session, forged);
            attack(TVO_NODE_CH_SESSION, forged, n, now, DROP_MALFORMED);
            break;
        case 3: /* a forged sample 20 s ahead whose sequence agrees, signed with another key */
            make_sample(&evil, SESSION_ID, j + 2000);
            evil.position_m[0] = 5.0;
            n = encode_sign(&forger, TVO_NODE_CH_SAMPLE, &evil, forged);
            attack(TVO_NODE_CH_SAMPLE, forged, n, now, DROP_UNAUTHENTICATED);
            break;
        case 4: { /* a forged target sample */
            tvo_lcm_target_t target;
            memset(&target, 0, sizeof(target));
            target.header.utime = now;
            target.header.session_id = SESSION_ID;
            target.position_m[0] = 9.0;
            n = encode_sign(&forger, TVO_NODE_CH_TARGET, &target, forged);
            attack(TVO_NODE_CH_TARGET, forged, n, now, DROP_UNAUTHENTICATED);
            break;
        }
        case 5: /* the genuine sample just accepted, replayed */
            attack(TVO_NODE_CH_SAMPLE, frame, length, now, DROP_REPLAYED);
            break;
        case 6: /* the genuine START, replayed */
            attack(TVO_NODE_CH_SESSION, kept_start, kept_start_length, now, DROP_REPLAYED);
            break;
        case 7: /* the genuine sample with one bit of its tag flipped and a counter above the last: the tag */
            memcpy(forged, frame, length);
            forged[length - TVO_AUTH_TRAILER_BYTES + 4u] ^= 0x01u;
            forged[length - 1u] ^= 0x40u;
            attack(TVO_NODE_CH_SAMPLE, forged, length, now, DROP_UNAUTHENTICATED);
            break;
        case 8: /* cut short by 1 .. 16 bytes: no frame of its channel */
            for (uint32_t cut = 1u; cut <= TVO_AUTH_TAG_BYTES; ++cut) {
                attack(TVO_NODE_CH_SAMPLE, frame, length - cut, now, DROP_MALFORMED);
            }
            break;
        case 9: /* a forged vote of three samples that agree with each other */
            for (int64_t k = 0; k < 3; ++k) {
                make_sample(&evil, SESSION_ID, j + 500 + k);
                n = encode_sign(&forger, TVO_NODE_CH_SAMPLE, &evil, forged);
                attack(TVO_NODE_CH_SAMPLE, forged, n, now, DROP_UNAUTHENTICATED);
            }
            break;
        case 10: /* the genuine frame with its tag garbled: a used counter, refused before the tag */
            memcpy(forged, frame, length);
            memset(forged + length - TVO_AUTH_TAG_BYTES, 0x5a, TVO_AUTH_TAG_BYTES);
            attack(TVO_NODE_CH_SAMPLE, forged, length, now, DROP_REPLAYED);
            break;
        case 11: /* the genuine frame on another channel (another length), and with another fingerprint */
            attack(TVO_NODE_CH_TARGET, frame, length, now, DROP_MALFORMED);
            attack(TVO_NODE_CH_COMMAND, frame, length, now, DROP_MALFORMED);
            memcpy(forged, frame, length);
            forged[3] ^= 0x01u;
            attack(TVO_NODE_CH_SAMPLE, forged, length, now, DROP_MALFORMED);
            break;
        default: { /* a frame the plant's own key signed that is no sample (the fingerprint of another type) */
            uint8_t *fake = forged;
            memset(fake, 0x11, tvo_node_channel_message_bytes(TVO_NODE_CH_SAMPLE));
            size_t signed_length = 0u;
            TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&plant, TVO_CHANNEL_SAMPLE, fake,
                                                         tvo_node_channel_message_bytes(TVO_NODE_CH_SAMPLE),
                                                         FRAME_CAPACITY, &signed_length));
            attack(TVO_NODE_CH_SAMPLE, fake, (uint32_t)signed_length, now, DROP_MALFORMED);
            break;
        }
        }
    }
    TEST_ASSERT_EQUAL_UINT32(1u, acks_seen); /* no attack got an ack */
}

static void test_every_attack_is_dropped_unanswered_counted_and_changes_no_command(void)
{
    run_session(0, &clean_commands);
    const tvo_lcm_node_counters_t *c = tvo_node_counters(&node);
    TEST_ASSERT_EQUAL_INT32(0, c->malformed + c->unauthenticated + c->replayed);
    TEST_ASSERT_EQUAL_UINT32(STEPS, clean_commands.count);

    run_session(1, &attacked_commands);
    /* STEPS / 12 = 3 full rounds of the 12 cases, and cases 1 .. 4 of a fourth. */
    TEST_ASSERT_EQUAL_INT32(4 * 1 + 3 * 16 + 3 * 3 + 3 * 1, c->malformed);                       /* 2, 8, 11, 0 */
    TEST_ASSERT_EQUAL_INT32(4 + 4 + 4 + 3 + 3 * 3, c->unauthenticated);                          /* 1, 3, 4, 7, 9 */
    TEST_ASSERT_EQUAL_INT32(3 + 3 + 3, c->replayed);                                             /* 5, 6, 10 */
    TEST_ASSERT_EQUAL_INT32(STEPS, c->accepted);
    TEST_ASSERT_EQUAL_UINT32(clean_commands.count, attacked_commands.count);
    for (uint32_t i = 0u; i < clean_commands.count; ++i) {
        TEST_ASSERT_EQUAL_UINT32(clean_commands.length[i], attacked_commands.length[i]);
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(clean_commands.bytes[i], attacked_commands.bytes[i], clean_commands.length[i],
                                         "a command differs from the run without attacks");
    }
}

static uint64_t trailer_counter(const uint8_t *frame, uint32_t length)
{
    uint64_t counter = 0u;
    for (uint32_t i = 0u; i < 8u; ++i) {
        counter = (counter << 8) | frame[length - TVO_AUTH_TRAILER_BYTES + 4u + i];
    }
    return counter;
}

static void test_the_node_signs_from_its_boot_and_the_plant_opens_it(void)
{
    run_session(0, &clean_commands);
    tvo_auth_t plant_receiver;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&plant_receiver, genuine_key, 99u, 1u));
    uint64_t last = 0u;
    for (uint32_t i = 0u; i < clean_commands.count; ++i) {
        size_t message_length = 0u;
        const uint64_t counter = trailer_counter(clean_commands.bytes[i], clean_commands.length[i]);
        TEST_ASSERT_EQUAL_UINT64(BOOT, counter >> TVO_AUTH_BOOT_COUNTER_BITS);
        TEST_ASSERT_TRUE(counter > last);
        last = counter;
        TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&plant_receiver, TVO_CHANNEL_COMMAND, clean_commands.bytes[i],
                                                     clean_commands.length[i], &message_length));
        tvo_lcm_unicycle_command_t cmd;
        TEST_ASSERT_EQUAL_INT((int)message_length,
                              tvo_lcm_unicycle_command_t_decode(clean_commands.bytes[i], 0, (int)message_length, &cmd));
        TEST_ASSERT_EQUAL_INT32(SESSION_ID, cmd.header.session_id);
        TEST_ASSERT_EQUAL_INT8(0, cmd.header.status);
    }
    /* The same command frame twice: the plant refuses the second (a replayed command). */
    size_t message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_REPLAY, tvo_auth_open(&plant_receiver, TVO_CHANNEL_COMMAND, clean_commands.bytes[0],
                                                          clean_commands.length[0], &message_length));
}

/* A recording of boot 5's session (START, samples, STOP) replayed to the node restarted as boot 6:
 * the recording's tags verify (the key is the same) but nothing of it runs: its START and STOP name
 * another boot (wrong_boot), its samples find no session (idle). Then the genuine plant, whose counters
 * are above the recording's, starts a session naming boot 6 and is served; the recording played again
 * after that is refused as a replay before any tag is computed. */
static void test_a_recording_from_before_a_restart_never_runs(void)
{
    enum { RECORDED = 8 };
    static uint8_t recording[RECORDED + 2][FRAME_CAPACITY];
    static uint32_t recorded_length[RECORDED + 2];
    static int recorded_channel[RECORDED + 2];
    static tvo_lcm_session_t start;
    tvo_lcm_unicycle_sample_t sample;
    reset_world();
    make_start(&start, SESSION_ID, BOOT);
    recorded_channel[0] = TVO_NODE_CH_SESSION;
    recorded_length[0] = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, recording[0]);
    deliver(TVO_NODE_CH_SESSION, recording[0], recorded_length[0], START_UTIME, NULL);
    for (int64_t j = 1; j <= RECORDED; ++j) {
        plant_clock_us += H;
        make_sample(&sample, SESSION_ID, j);
        recorded_channel[j] = TVO_NODE_CH_SAMPLE;
        recorded_length[j] = encode_sign(&plant, TVO_NODE_CH_SAMPLE, &sample, recording[j]);
        deliver(TVO_NODE_CH_SAMPLE, recording[j], recorded_length[j], EPOCH + j * H - TAU, NULL);
    }
    TEST_ASSERT_EQUAL_INT32(RECORDED, tvo_node_counters(&node)->accepted);
    start.action = TVO_LCM_SESSION_T_ACTION_STOP;
    recorded_channel[RECORDED + 1] = TVO_NODE_CH_SESSION;
    recorded_length[RECORDED + 1] = encode_sign(&plant, TVO_NODE_CH_SESSION, &start, recording[RECORDED + 1]);
    deliver(TVO_NODE_CH_SESSION, recording[RECORDED + 1], recorded_length[RECORDED + 1], EPOCH + RECORDED * H, NULL);
    TEST_ASSERT_EQUAL_INT(1, tvo_node_stop_requested(&node));

    /* The node restarts (a new boot id; it has forgotten its senders); the recording arrives at once. */
    start_node(BOOT + 1);
    acks_seen = 0u;
    for (int i = 0; i < RECORDED + 2; ++i) {
        deliver(recorded_channel[i], recording[i], recorded_length[i], START_UTIME + i, NULL);
    }
    const tvo_lcm_node_counters_t *c = tvo_node_counters(&node);
    TEST_ASSERT_EQUAL_UINT32(0u, acks_seen);
    TEST_ASSERT_EQUAL_INT32(2, c->wrong_boot);
    TEST_ASSERT_EQUAL_INT32(RECORDED, c->idle);
    TEST_ASSERT_EQUAL_INT32(0, c->accepted);
    TEST_ASSERT_NULL(tvo_node_session(&node));
    /* The genuine plant heard boot 6 announce itself and starts again, naming it. */
    static uint8_t frame[FRAME_CAPACITY];
    plant_clock_us += 1000000u;
    make_start(&start, SESSION_ID + 1, BOOT + 1);
    deliver(TVO_NODE_CH_SESSION, frame, encode_sign(&plant, TVO_NODE_CH_SESSION, &start, frame), START_UTIME, NULL);
    TEST_ASSERT_EQUAL_UINT32(1u, acks_seen);
    TEST_ASSERT_NOT_NULL(tvo_node_session(&node));
    plant_clock_us += H;
    make_sample(&sample, SESSION_ID + 1, 1);
    deliver(TVO_NODE_CH_SAMPLE, frame, encode_sign(&plant, TVO_NODE_CH_SAMPLE, &sample, frame), EPOCH + H - TAU, NULL);
    TEST_ASSERT_EQUAL_INT32(1, c->accepted);
    /* The recording again, racing the genuine plant: every frame a replay now, counted. */
    for (int i = 0; i < RECORDED + 2; ++i) {
        attack(recorded_channel[i], recording[i], recorded_length[i], EPOCH + H, DROP_REPLAYED);
    }
    TEST_ASSERT_EQUAL_INT32(RECORDED + 2, c->replayed);
}

/* A restarted node's counters are all above its last boot's (boot << 40), with no clock. */
static void test_a_node_counter_never_repeats_across_a_restart(void)
{
    reset_world();
    (void)tvo_node_poll(&node, 2000000); /* an announcement of boot 5 */
    const uint64_t before_restart = link.auth.next_counter;
    TEST_ASSERT_TRUE(before_restart > ((uint64_t)BOOT << TVO_AUTH_BOOT_COUNTER_BITS));
    start_node(BOOT + 1);
    TEST_ASSERT_TRUE(published.count >= 1u); /* the new boot's first announcement, signed */
    TEST_ASSERT_TRUE(trailer_counter(published.bytes[0], published.length[0]) > before_restart);
    TEST_ASSERT_EQUAL_UINT64(((uint64_t)(BOOT + 1) << TVO_AUTH_BOOT_COUNTER_BITS) | 1u,
                             trailer_counter(published.bytes[0], published.length[0]));
    /* A link refuses a boot id outside 1 .. 2^23 - 1. */
    tvo_auth_link_t other;
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_link_init(&other, genuine_key, 1u, 0, record, NULL));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT,
                      tvo_auth_link_init(&other, genuine_key, 1u, TVO_AUTH_MAX_BOOT_ID + 1, record, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_attack_is_dropped_unanswered_counted_and_changes_no_command);
    RUN_TEST(test_the_node_signs_from_its_boot_and_the_plant_opens_it);
    RUN_TEST(test_a_recording_from_before_a_restart_never_runs);
    RUN_TEST(test_a_node_counter_never_repeats_across_a_restart);
    return UNITY_END();
}
