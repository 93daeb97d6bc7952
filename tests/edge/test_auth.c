/*
 * Message authentication (firmware/edge/auth.c): tags against two other implementations, boot-based
 * counters, the cheapest refusal first, and every refusal leaving the receiver unchanged.
 *
 * The fixed vectors come from Python's `cryptography` package (Debian python3-cryptography), not from
 * this code: ChaCha20Poly1305(key).encrypt(nonce, b"", channel + b"\0" + message) with
 * key = bytes(range(32)) and nonce = sender_id (4 bytes, big-endian) + counter (8 bytes, big-endian).
 * The sweep compares with Mbed TLS's mbedtls_chachapoly (the library auth.c's tag must equal bit for bit).
 */
#include <string.h>

#include "auth.h"
#include "mbedtls/chachapoly.h"
#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static uint8_t test_key[TVO_AUTH_KEY_BYTES];

static void make_key(void)
{
    for (unsigned i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
        test_key[i] = (uint8_t)i;
    }
}

static void hex_to_bytes(const char *hex, uint8_t *out, size_t n)
{
    for (size_t i = 0u; i < n; ++i) {
        unsigned v = 0u;
        for (unsigned j = 0u; j < 2u; ++j) {
            const char c = hex[2u * i + j];
            v = (v << 4) | (unsigned)((c >= 'a') ? (c - 'a' + 10) : (c - '0'));
        }
        out[i] = (uint8_t)v;
    }
}

static uint64_t trailer_counter(const uint8_t *trailer)
{
    uint64_t counter = 0u;
    for (unsigned i = 4u; i < 12u; ++i) {
        counter = (counter << 8) | trailer[i];
    }
    return counter;
}

/* Signs message (copied into a buffer) as sender/counter and checks the trailer against the vector. */
static void check_vector(const char *channel, const uint8_t *message, size_t length, uint32_t sender,
                         uint64_t counter, const char *tag_hex)
{
    static uint8_t buffer[12u * 1024u]; /* up to a START (session_t: 11,427 bytes) and its trailer */
    tvo_auth_t auth;
    make_key();
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&auth, test_key, sender, counter));
    memcpy(buffer, message, length);
    size_t signed_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&auth, channel, buffer, length, sizeof(buffer), &signed_length));
    TEST_ASSERT_EQUAL_UINT32(length + TVO_AUTH_TRAILER_BYTES, signed_length);
    if (length > 0u) {
        TEST_ASSERT_EQUAL_MEMORY(message, buffer, length);
    }
    const uint8_t *trailer = buffer + length;
    TEST_ASSERT_EQUAL_HEX8((uint8_t)(sender >> 24), trailer[0]);
    TEST_ASSERT_EQUAL_HEX8((uint8_t)sender, trailer[3]);
    TEST_ASSERT_EQUAL_UINT64(counter, trailer_counter(trailer));
    uint8_t expected[TVO_AUTH_TAG_BYTES];
    hex_to_bytes(tag_hex, expected, sizeof(expected));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expected, trailer + 12, TVO_AUTH_TAG_BYTES);
    TEST_ASSERT_EQUAL_UINT64(counter + 1u, auth.next_counter);
    /* And it opens. */
    tvo_auth_t receiver;
    size_t message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&receiver, test_key, 99u, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&receiver, channel, buffer, signed_length, &message_length));
    TEST_ASSERT_EQUAL_UINT32(length, message_length);
}

static void test_tags_match_an_independent_implementation(void)
{
    const char *text = "tvo-flat worked example";
    check_vector("TVO_MEASUREMENT", (const uint8_t *)text, strlen(text), 7u, 1u, "f587554e608400e45f818031d640c10f");
    check_vector("TVO_COMMAND", (const uint8_t *)"", 0u, 0x01020304u, 0x0102030405060708u,
                 "5637ac1861b8a7ad2b93ee4747f8c4c4");
    static uint8_t long_message[300];
    for (unsigned i = 0u; i < sizeof(long_message); ++i) {
        long_message[i] = (uint8_t)((i * 7u + 3u) & 255u);
    }
    check_vector("TVO_MEASUREMENT", long_message, sizeof(long_message), 0xfffffffeu, 123456789012345u,
                 "df84f13d080971720a813ef64c3c8376");
}

/* One vector per message of the wire (lcm_types/README.md gives them to plant writers): the message's
 * LCM encoding of documented field values (checked below against the generated code), its sender and
 * counter (the plant's follow its clock; a node's are boot 17 << 40 | 5), and the tag python3-cryptography
 * computed for key = bytes(range(32)). */
typedef struct {
    const char *type;
    const char *channel;
    uint32_t sender;
    uint64_t counter;
    const char *tag_hex;
    const char *message_hex;
} message_vector_t;

static const message_vector_t message_vectors[] = {
    {"unicycle_sample_t", "TVO_SAMPLE", 2u, UINT64_C(1700000000123456), "12fd9a9d7378e7a33eff43e2f9bf81d6",
     "1029dfde5d7afbb400060a24182022400000002a0000000700033ff8000000000000bfd00000000000003f0000003f400000"
    },
    {"unicycle_command_t", "TVO_COMMAND", 1u, UINT64_C(18691697672197), "539d7a2ecf8602e3edf2bb6db49f81a9",
     "6b041d8a70c23e9400060a24182049500000002a00000007000000003f000000be000000"
    },
    {"target_t", "TVO_TARGET", 2u, UINT64_C(1700000000123456), "037944e30780859a007a3d51d8f113a3",
     "f93a33a5bb0da41b00060a24182022400000002a000000070040000000000000003ff00000000000003f0000000000000000"
     "000000be8000003e00000000000000"
    },
    {"chain_sample_t", "TVO_CHAIN_SAMPLE", 2u, UINT64_C(1700000000123456), "1bcc6aa7da04430a0a35f36330264dc5",
     "6a31d2ad2af09bff00060a24182022400000002a0000000700043fe00000000000003ff80000000000003e80000000000000"
     "00000000bf800000"
    },
    {"chain_command_t", "TVO_CHAIN_COMMAND", 1u, UINT64_C(18691697672197), "1e437727c8f3d3e5a9524e03d7189cd0",
     "b5a35cfd53b2198f00060a24182049500000002a00000007000000003e800000bf000000"
    },
    {"telemetry_t", "TVO_TELEMETRY", 1u, UINT64_C(18691697672197), "2065b5e6a2bc197424adc3e2bff9c173",
     "07f466b34826d73a00060a24182049500000002a00000007000000000000000000011170000123456789abcdef3ff8000000"
     "000000bfd000000000000000000000000000000000000000000000000000000000000000000000000000003f400000000000"
     "000000000000000000"},
    {"node_status_t", "TVO_NODE", 1u, UINT64_C(18691697672197), "b816372a61705e484c4d853ed9a3a50d",
     "accb19b75e21feed00000000004c4b40000000030000000000000011ff04010000002a000000070000000000000000000000"
     "0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
     "0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
     "0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
     "0000000000000000000000"
    },
    {"session_ack_t", "TVO_SESSION_ACK", 1u, UINT64_C(18691697672197), "72ae96d317b82d1143b2b20c73383758",
     "46e60650a9a02d9f00060a24181e40000000002a010000000000000011ff000000000000000000ffffffff0000002a"
    },
};

static void test_every_message_has_a_vector_from_an_independent_implementation(void)
{
    static uint8_t message[256];
    for (size_t v = 0u; v < sizeof(message_vectors) / sizeof(message_vectors[0]); ++v) {
        const message_vector_t *m = &message_vectors[v];
        const size_t length = strlen(m->message_hex) / 2u;
        TEST_ASSERT_TRUE(length <= sizeof(message));
        hex_to_bytes(m->message_hex, message, length);
        check_vector(m->channel, message, length, m->sender, m->counter, m->tag_hex);
    }
}

static void expect_encoding(const char *type, const uint8_t *bytes, int length)
{
    for (size_t v = 0u; v < sizeof(message_vectors) / sizeof(message_vectors[0]); ++v) {
        if (strcmp(message_vectors[v].type, type) == 0) {
            static uint8_t expected[256];
            TEST_ASSERT_EQUAL_size_t(strlen(message_vectors[v].message_hex) / 2u, (size_t)length);
            hex_to_bytes(message_vectors[v].message_hex, expected, (size_t)length);
            TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(expected, bytes, (uint32_t)length, type);
            return;
        }
    }
    TEST_FAIL_MESSAGE(type);
}

/* The vectors' bytes are the generated code's encoding of the field values lcm_types/README.md states. */
static void test_the_vectors_are_the_lcm_encoding_of_their_fields(void)
{
    static uint8_t b[256];
    const tvo_lcm_sample_header_t sh = {.utime = 1700000000123456LL, .session_id = 42, .sequence = 7, .robot = 0};
    const tvo_lcm_command_header_t ch = {
        .utime = 1700000000133456LL, .session_id = 42, .measurement_sequence = 7, .robot = 0, .status = 0, .flags = 0};
    tvo_lcm_unicycle_sample_t s;
    memset(&s, 0, sizeof(s));
    s.header = sh;
    s.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    s.position_m[0] = 1.5;
    s.position_m[1] = -0.25;
    s.heading_rad = 0.5f;
    s.speed_mps = 0.75f;
    expect_encoding("unicycle_sample_t", b, tvo_lcm_unicycle_sample_t_encode(b, 0, (int)sizeof(b), &s));
    const tvo_lcm_unicycle_command_t c = {.header = ch, .speed_mps = 0.5f, .turn_rate_radps = -0.125f};
    expect_encoding("unicycle_command_t", b, tvo_lcm_unicycle_command_t_encode(b, 0, (int)sizeof(b), &c));
    tvo_lcm_target_t t;
    memset(&t, 0, sizeof(t));
    t.header = sh;
    t.position_m[0] = 2.0;
    t.position_m[1] = 1.0;
    t.velocity_mps[0] = 0.5f;
    t.acceleration_mps2[1] = -0.25f;
    t.jerk_mps3[0] = 0.125f;
    expect_encoding("target_t", b, tvo_lcm_target_t_encode(b, 0, (int)sizeof(b), &t));
    tvo_lcm_chain_sample_t cs;
    memset(&cs, 0, sizeof(cs));
    cs.header = sh;
    cs.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
    cs.position_m[0] = 0.5;
    cs.position_m[1] = 1.5;
    cs.output_rate_mps[0] = 0.25f;
    cs.output_accel_mps2[1] = -1.0f;
    expect_encoding("chain_sample_t", b, tvo_lcm_chain_sample_t_encode(b, 0, (int)sizeof(b), &cs));
    const tvo_lcm_chain_command_t cc = {.header = ch, .input = {0.25f, -0.5f}};
    expect_encoding("chain_command_t", b, tvo_lcm_chain_command_t_encode(b, 0, (int)sizeof(b), &cc));
    tvo_lcm_telemetry_t te;
    memset(&te, 0, sizeof(te));
    te.header = ch;
    te.objective_time_us = 70000;
    te.joint_digest = 0x0123456789abcdefLL;
    te.output_m[0] = 1.5;
    te.output_m[1] = -0.25;
    te.speed_state_mps = 0.75f;
    expect_encoding("telemetry_t", b, tvo_lcm_telemetry_t_encode(b, 0, (int)sizeof(b), &te));
    tvo_lcm_node_status_t ns;
    memset(&ns, 0, sizeof(ns));
    ns.utime = 5000000;
    ns.protocol_version = TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION;
    ns.boot_id = 17;
    ns.own_robot = -1;
    ns.max_robots = 4;
    ns.state = TVO_LCM_NODE_STATUS_T_STATE_RUNNING;
    ns.session_id = 42;
    ns.counters.accepted = 7;
    expect_encoding("node_status_t", b, tvo_lcm_node_status_t_encode(b, 0, (int)sizeof(b), &ns));
    tvo_lcm_session_ack_t ack;
    memset(&ack, 0, sizeof(ack));
    ack.utime = 1700000000000000LL;
    ack.session_id = 42;
    ack.action = TVO_LCM_SESSION_T_ACTION_START;
    ack.boot_id = 17;
    ack.own_robot = -1;
    ack.bad_index = -1;
    ack.running_session_id = 42;
    expect_encoding("session_ack_t", b, tvo_lcm_session_ack_t_encode(b, 0, (int)sizeof(b), &ack));
}

/* The START of lcm_types/README.md's message vectors (the demo's setting, session 42 on the node of boot
 * 17, signed by the plant): too long to spell in hex, so built from the fields the README's Python sets
 * (the rest zero, as the generated Python's defaults) and checked against the tag python3-cryptography
 * computed there (CTest docs_message_vectors asserts the same tag). */
static void test_the_start_vector_is_the_encoding_of_its_fields(void)
{
    static tvo_lcm_session_t start;
    static uint8_t b[12u * 1024u];
    memset(&start, 0, sizeof(start));
    start.utime = 1700000000000000LL;
    start.protocol_version = TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION;
    start.session_id = 42;
    start.action = TVO_LCM_SESSION_T_ACTION_START;
    start.node_boot_id[0] = 17;
    start.clock_source = TVO_LCM_SESSION_T_CLOCK_PLANT;
    start.epoch_utime = 1700000001000000LL;
    start.period_us = 10000;
    start.delay_us = 5000;
    start.delay_compensation = 1;
    start.watchdog_periods = 10;
    start.plant_kind = TVO_LCM_SESSION_T_PLANT_UNICYCLE;
    start.velocity_source = TVO_LCM_SESSION_T_VELOCITY_FROM_POSE;
    start.filter_tf_s = 0.05;
    start.gain_kp = 40.0;
    start.gain_kd = 13.0;
    start.omega_max_radps = 6.283185307179586;
    start.accel_max_mps2 = 15.0;
    start.speed_max_mps = 5.0;
    start.min_speed_mps = 0.05;
    start.robot_count = 1;
    start.robot[0].tracking_weight[0] = 1.0;
    start.robot[0].tracking_weight[1] = 1.0;
    start.robot[0].target.kind = TVO_LCM_PATH_T_KIND_ELLIPSE;
    start.robot[0].target.semi_axis_m[0] = 3.0;
    start.robot[0].target.semi_axis_m[1] = 1.5;
    start.robot[0].target.omega_radps = 0.6283185307179586;
    const int length = tvo_lcm_session_t_encode(b, 0, (int)sizeof(b), &start);
    TEST_ASSERT_EQUAL_INT(11427, length);
    check_vector("TVO_SESSION", b, (size_t)length, TVO_AUTH_SENDER_PLANT, UINT64_C(1700000000123456),
                 "fad660a8d30fea66f7ea672b46ad0224");
}

/* A small deterministic generator for the sweep (xorshift32). */
static uint32_t sweep_state = 0x9e3779b9u;
static uint8_t next_byte(void)
{
    sweep_state ^= sweep_state << 13;
    sweep_state ^= sweep_state >> 17;
    sweep_state ^= sweep_state << 5;
    return (uint8_t)(sweep_state >> 24);
}

/* Mbed TLS's tag of (channel, message) under (sender, counter): the reference auth.c must equal. */
static void mbedtls_tag(const uint8_t key[TVO_AUTH_KEY_BYTES], const char *channel, const uint8_t *message,
                        size_t length, const uint8_t nonce[12], uint8_t tag[TVO_AUTH_TAG_BYTES])
{
    static uint8_t aad[TVO_AUTH_MAX_CHANNEL_BYTES + 1u + 512u];
    const size_t name_length = strlen(channel) + 1u;
    memcpy(aad, channel, name_length);
    memcpy(aad + name_length, message, length);
    mbedtls_chachapoly_context cipher;
    mbedtls_chachapoly_init(&cipher);
    TEST_ASSERT_EQUAL(0, mbedtls_chachapoly_setkey(&cipher, key));
    TEST_ASSERT_EQUAL(0, mbedtls_chachapoly_encrypt_and_tag(&cipher, 0u, nonce, aad, name_length + length, NULL, NULL, tag));
    mbedtls_chachapoly_free(&cipher);
}

/* Every channel length the link takes (1 .. 64) against message lengths 0 .. 200 (every alignment of
 * both against Poly1305's 16-byte blocks), random keys, senders, counters and bytes. */
static void test_tags_equal_mbed_tls_for_every_channel_and_message_length(void)
{
    static uint8_t frame[200u + TVO_AUTH_TRAILER_BYTES];
    static char channel[TVO_AUTH_MAX_CHANNEL_BYTES + 1u];
    uint8_t key[TVO_AUTH_KEY_BYTES];
    unsigned compared = 0u;
    for (size_t name_length = 1u; name_length <= TVO_AUTH_MAX_CHANNEL_BYTES; ++name_length) {
        for (size_t length = 0u; length <= 200u; ++length) {
            for (unsigned i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
                key[i] = next_byte();
            }
            for (size_t i = 0u; i < name_length; ++i) {
                channel[i] = (char)('!' + next_byte() % 94u); /* printable, never NUL */
            }
            channel[name_length] = '\0';
            for (size_t i = 0u; i < length; ++i) {
                frame[i] = next_byte();
            }
            const uint32_t sender = ((uint32_t)next_byte() << 24) | next_byte();
            const uint64_t counter = ((uint64_t)next_byte() << 56) | ((uint64_t)next_byte() << 20) | 1u;
            tvo_auth_t auth;
            size_t signed_length = 0u;
            TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&auth, key, sender, counter));
            TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&auth, channel, frame, length, sizeof(frame), &signed_length));
            uint8_t expected[TVO_AUTH_TAG_BYTES];
            mbedtls_tag(key, channel, frame, length, frame + length, expected);
            TEST_ASSERT_EQUAL_HEX8_ARRAY(expected, frame + length + 12u, TVO_AUTH_TAG_BYTES);
            compared++;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(64u * 201u, compared);
}

typedef struct {
    tvo_auth_t sender;
    tvo_auth_t receiver;
    uint8_t frame[128];
    size_t frame_length;
} link_t;

static void link_init(link_t *link)
{
    make_key();
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&link->sender, test_key, 42u, 1000u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&link->receiver, test_key, 1u, 1u));
}

static void link_send(link_t *link, const char *channel, const char *text)
{
    const size_t length = strlen(text);
    memcpy(link->frame, text, length);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&link->sender, channel, link->frame, length, sizeof(link->frame),
                                                 &link->frame_length));
}

/* Opens a frame expected to be refused with status; the receiver must not change at all. */
static void expect_refused(link_t *link, const char *channel, const uint8_t *frame, size_t length,
                           tvo_auth_status_t status)
{
    tvo_auth_t before;
    memcpy(&before, &link->receiver, sizeof(before));
    size_t message_length = 99u;
    TEST_ASSERT_EQUAL_STRING(tvo_auth_status_str(status),
                             tvo_auth_status_str(tvo_auth_open(&link->receiver, channel, frame, length, &message_length)));
    TEST_ASSERT_EQUAL_UINT32(0u, message_length);
    TEST_ASSERT_EQUAL_MEMORY(&before, &link->receiver, sizeof(before));
}

static void test_a_genuine_stream_opens_and_a_replay_is_refused(void)
{
    link_t link;
    link_init(&link);
    size_t message_length = 0u;
    link_send(&link, "TVO_SAMPLE", "sample one");
    uint8_t first[128];
    const size_t first_length = link.frame_length;
    memcpy(first, link.frame, first_length);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&link.receiver, "TVO_SAMPLE", first, first_length, &message_length));
    TEST_ASSERT_EQUAL_UINT32(strlen("sample one"), message_length);
    link_send(&link, "TVO_SAMPLE", "sample two");
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&link.receiver, "TVO_SAMPLE", link.frame, link.frame_length, &message_length));
    TEST_ASSERT_EQUAL_UINT64(1001u, link.receiver.senders[0].last_counter);
    /* The same frame again, and the older one: both replays. */
    expect_refused(&link, "TVO_SAMPLE", link.frame, link.frame_length, TVO_AUTH_ERR_REPLAY);
    expect_refused(&link, "TVO_SAMPLE", first, first_length, TVO_AUTH_ERR_REPLAY);
}

/* A known sender's used counter is refused before the tag is computed: even a frame whose tag is
 * garbage is a replay, which is what lets a flood of copies cost no cryptography. An unknown sender's
 * frame with a garbage tag is unauthenticated. */
static void test_a_used_counter_is_refused_before_the_tag(void)
{
    link_t link;
    link_init(&link);
    size_t message_length = 0u;
    link_send(&link, "TVO_SAMPLE", "genuine");
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&link.receiver, "TVO_SAMPLE", link.frame, link.frame_length, &message_length));
    uint8_t forged[128];
    memcpy(forged, link.frame, link.frame_length);
    memset(forged + link.frame_length - TVO_AUTH_TAG_BYTES, 0xA5, TVO_AUTH_TAG_BYTES); /* a garbage tag */
    expect_refused(&link, "TVO_SAMPLE", forged, link.frame_length, TVO_AUTH_ERR_REPLAY);
    forged[link.frame_length - TVO_AUTH_TRAILER_BYTES] ^= 0x01u; /* another sender id: not heard yet */
    expect_refused(&link, "TVO_SAMPLE", forged, link.frame_length, TVO_AUTH_ERR_TAG);
    /* A higher counter of the known sender with a garbage tag: the tag is checked, and refuses it. */
    forged[link.frame_length - TVO_AUTH_TRAILER_BYTES] ^= 0x01u;
    forged[link.frame_length - TVO_AUTH_TRAILER_BYTES + 4u] = 0x01u; /* counter + 2^56 */
    expect_refused(&link, "TVO_SAMPLE", forged, link.frame_length, TVO_AUTH_ERR_TAG);
}

static void test_forged_altered_and_truncated_frames_are_refused(void)
{
    link_t link;
    link_init(&link);
    link_send(&link, "TVO_SESSION", "start session 5");
    uint8_t frame[128];
    const size_t length = link.frame_length;
    /* Every single bit flipped anywhere (message, sender, counter, tag) breaks the tag. */
    for (size_t bit = 0u; bit < 8u * length; ++bit) {
        memcpy(frame, link.frame, length);
        frame[bit / 8u] ^= (uint8_t)(1u << (bit % 8u));
        expect_refused(&link, "TVO_SESSION", frame, length, TVO_AUTH_ERR_TAG);
    }
    /* Cut short: a tag that is too short or gone. */
    for (size_t cut = 1u; cut <= length; ++cut) {
        const tvo_auth_status_t status = (length - cut < TVO_AUTH_TRAILER_BYTES) ? TVO_AUTH_ERR_TRUNCATED : TVO_AUTH_ERR_TAG;
        expect_refused(&link, "TVO_SESSION", link.frame, length - cut, status);
    }
    /* Moved to another channel. */
    expect_refused(&link, "TVO_COMMAND", link.frame, length, TVO_AUTH_ERR_TAG);
    /* Signed with another key. */
    uint8_t other_key[TVO_AUTH_KEY_BYTES];
    memcpy(other_key, test_key, sizeof(other_key));
    other_key[31] ^= 0x80u;
    tvo_auth_t forger;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&forger, other_key, 42u, 5000u));
    memcpy(frame, "start session 5", 15u);
    size_t forged_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&forger, "TVO_SESSION", frame, 15u, sizeof(frame), &forged_length));
    expect_refused(&link, "TVO_SESSION", frame, forged_length, TVO_AUTH_ERR_TAG);
    /* The genuine frame still opens after all of that. */
    size_t message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&link.receiver, "TVO_SESSION", link.frame, length, &message_length));
}

/* No window: a receiver takes a sender it has not heard at any counter (a node restarted, or a plant
 * that restarted with a clock behind), then only higher counters from it. */
static void test_a_new_sender_is_taken_at_any_counter(void)
{
    make_key();
    tvo_auth_t sender, receiver;
    uint8_t frame[64];
    size_t length = 0u, message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&sender, test_key, 7u, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&receiver, test_key, 1u, 1u));
    memcpy(frame, "first", 5u);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&sender, "TVO_NODE", frame, 5u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&receiver, "TVO_NODE", frame, length, &message_length));
    TEST_ASSERT_EQUAL_UINT32(1u, receiver.sender_count);
    TEST_ASSERT_EQUAL_UINT64(1u, receiver.senders[0].last_counter);
}

/* A node's counters: (boot << 40) | n from n = 1, never past its boot's range; boot ids checked. */
static void test_a_node_counts_from_its_boot(void)
{
    make_key();
    tvo_auth_t node, plant;
    uint8_t frame[64];
    size_t length = 0u, message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&node, test_key, TVO_AUTH_SENDER_NODE, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&plant, test_key, TVO_AUTH_SENDER_PLANT, 1u));
    const int64_t bad_boots[] = {0, -1, INT64_MIN, TVO_AUTH_MAX_BOOT_ID + 1, INT64_MAX};
    for (unsigned i = 0u; i < sizeof(bad_boots) / sizeof(bad_boots[0]); ++i) {
        TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_count_from_boot(&node, bad_boots[i]));
        TEST_ASSERT_EQUAL_UINT64(1u, node.next_counter);
    }
    TEST_ASSERT_EQUAL_INT64(8388607, TVO_AUTH_MAX_BOOT_ID);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_count_from_boot(&node, 5));
    for (uint64_t n = 1u; n <= 3u; ++n) {
        memcpy(frame, "status", 6u);
        TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&node, "TVO_NODE", frame, 6u, sizeof(frame), &length));
        TEST_ASSERT_EQUAL_UINT64((UINT64_C(5) << 40) | n, trailer_counter(frame + 6u));
        TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&plant, "TVO_NODE", frame, length, &message_length));
    }
    /* The node restarts with the next boot: its first counter is above every one of the last boot. */
    tvo_auth_t restarted;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&restarted, test_key, TVO_AUTH_SENDER_NODE, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_count_from_boot(&restarted, 6));
    memcpy(frame, "status", 6u);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&restarted, "TVO_NODE", frame, 6u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&plant, "TVO_NODE", frame, length, &message_length));
    /* The last counter of boot 5 signs; the next would be boot 6's first: refused, nothing consumed. */
    node.next_counter = (UINT64_C(6) << 40) - 1u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&node, "TVO_NODE", frame, 6u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_COUNTER_SPENT, tvo_auth_sign(&node, "TVO_NODE", frame, 6u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT32(0u, length);
    TEST_ASSERT_EQUAL_UINT64(UINT64_C(6) << 40, node.next_counter);
    /* The largest boot id: its last counter stays below 2^63. */
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_count_from_boot(&node, TVO_AUTH_MAX_BOOT_ID));
    TEST_ASSERT_EQUAL_UINT64(UINT64_C(1) << 63, node.counter_end);
}

static uint64_t fake_wall_us = 1700000000000000u;
static uint64_t fake_wall(void)
{
    return fake_wall_us;
}

/* A plant's counters follow its wall clock (us), and never go back when the clock does. */
static void test_a_plant_follows_its_clock(void)
{
    make_key();
    tvo_auth_t plant;
    uint8_t frame[64];
    size_t length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&plant, test_key, TVO_AUTH_SENDER_PLANT, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_follow_clock(&plant, NULL));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_follow_clock(&plant, fake_wall));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&plant, "TVO_SAMPLE", frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT64(fake_wall_us, trailer_counter(frame + 1u));
    fake_wall_us -= 5000000u; /* the clock steps back 5 s */
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&plant, "TVO_SAMPLE", frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT64(fake_wall_us + 5000001u, trailer_counter(frame + 1u));
    fake_wall_us += 10000000u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&plant, "TVO_SAMPLE", frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT64(fake_wall_us, trailer_counter(frame + 1u));
}

static void test_senders_are_remembered_up_to_the_limit(void)
{
    make_key();
    static tvo_auth_t receiver;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&receiver, test_key, 1u, 1u));
    TEST_ASSERT_TRUE(TVO_AUTH_MAX_SENDERS >= 33u); /* a plant of 32 nodes, and itself */
    uint8_t frame[64];
    size_t length = 0u, message_length = 0u;
    for (uint32_t id = 0u; id <= TVO_AUTH_MAX_SENDERS; ++id) {
        tvo_auth_t sender;
        TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&sender, test_key, 100u + id, 1u));
        memcpy(frame, "x", 1u);
        TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&sender, "TVO_TARGET", frame, 1u, sizeof(frame), &length));
        const tvo_auth_status_t expected = (id < TVO_AUTH_MAX_SENDERS) ? TVO_AUTH_OK : TVO_AUTH_ERR_SENDERS_FULL;
        TEST_ASSERT_EQUAL(expected, tvo_auth_open(&receiver, "TVO_TARGET", frame, length, &message_length));
    }
    TEST_ASSERT_EQUAL_UINT32(TVO_AUTH_MAX_SENDERS, receiver.sender_count);
}

/* The variants for a known name length give the same frames, and refuse a length that is not the name's. */
static void test_a_known_channel_length_signs_and_opens_the_same(void)
{
    make_key();
    tvo_auth_t a, b, receiver;
    uint8_t frame_a[64], frame_b[64];
    size_t length_a = 0u, length_b = 0u, opened = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&a, test_key, 9u, 77u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&b, test_key, 9u, 77u));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&receiver, test_key, 1u, 1u));
    memcpy(frame_a, "same message", 12u);
    memcpy(frame_b, "same message", 12u);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign(&a, "TVO_SAMPLE", frame_a, 12u, sizeof(frame_a), &length_a));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_sign_channel(&b, "TVO_SAMPLE", 10u, frame_b, 12u, sizeof(frame_b), &length_b));
    TEST_ASSERT_EQUAL_UINT32(length_a, length_b);
    TEST_ASSERT_EQUAL_MEMORY(frame_a, frame_b, length_a);
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_open_channel(&receiver, "TVO_SAMPLE", 9u, frame_a, length_a, &opened));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_open_channel(&receiver, "", 0u, frame_a, length_a, &opened));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT,
                      tvo_auth_sign_channel(&b, "TVO_SAMPLE", 4u, frame_b, 12u, sizeof(frame_b), &length_b));
    TEST_ASSERT_EQUAL_UINT32(0u, length_b);
    TEST_ASSERT_EQUAL_UINT64(78u, b.next_counter); /* nothing consumed by the refusal */
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open_channel(&receiver, "TVO_SAMPLE", 10u, frame_a, length_a, &opened));
    TEST_ASSERT_EQUAL_UINT32(12u, opened);
}

static void test_bad_arguments_are_refused_and_consume_nothing(void)
{
    make_key();
    tvo_auth_t auth;
    uint8_t frame[64] = {0};
    size_t length = 7u;
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_init(&auth, test_key, 1u, 0u)); /* counters start at 1 */
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_init(NULL, test_key, 1u, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_count_from_boot(NULL, 1));
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&auth, test_key, 1u, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_sign(&auth, "", frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT32(0u, length);
    /* No room for the trailer. */
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT,
                      tvo_auth_sign(&auth, "C", frame, sizeof(frame) - TVO_AUTH_TRAILER_BYTES + 1u, sizeof(frame), &length));
    static char long_channel[TVO_AUTH_MAX_CHANNEL_BYTES + 2u];
    memset(long_channel, 'A', TVO_AUTH_MAX_CHANNEL_BYTES + 1u);
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_sign(&auth, long_channel, frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_open(&auth, long_channel, frame, 40u, &length));
    TEST_ASSERT_EQUAL_UINT64(1u, auth.next_counter);
    auth.next_counter = UINT64_MAX;
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_COUNTER_SPENT, tvo_auth_sign(&auth, "C", frame, 1u, sizeof(frame), &length));
    tvo_auth_clear(&auth);
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_NOT_KEYED, tvo_auth_sign(&auth, "C", frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_NOT_KEYED, tvo_auth_open(&auth, "C", frame, 40u, &length));
    for (unsigned i = 0u; i < 8u; ++i) {
        TEST_ASSERT_EQUAL_HEX32(0u, auth.key_words[i]);
    }
    TEST_ASSERT_EQUAL_STRING("unknown authentication status", tvo_auth_status_str(TVO_AUTH_STATUS_COUNT));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_tags_match_an_independent_implementation);
    RUN_TEST(test_every_message_has_a_vector_from_an_independent_implementation);
    RUN_TEST(test_the_vectors_are_the_lcm_encoding_of_their_fields);
    RUN_TEST(test_the_start_vector_is_the_encoding_of_its_fields);
    RUN_TEST(test_tags_equal_mbed_tls_for_every_channel_and_message_length);
    RUN_TEST(test_a_genuine_stream_opens_and_a_replay_is_refused);
    RUN_TEST(test_a_used_counter_is_refused_before_the_tag);
    RUN_TEST(test_forged_altered_and_truncated_frames_are_refused);
    RUN_TEST(test_a_new_sender_is_taken_at_any_counter);
    RUN_TEST(test_a_node_counts_from_its_boot);
    RUN_TEST(test_a_plant_follows_its_clock);
    RUN_TEST(test_senders_are_remembered_up_to_the_limit);
    RUN_TEST(test_a_known_channel_length_signs_and_opens_the_same);
    RUN_TEST(test_bad_arguments_are_refused_and_consume_nothing);
    return UNITY_END();
}
