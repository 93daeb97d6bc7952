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
    static uint8_t buffer[512];
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
    RUN_TEST(test_tags_equal_mbed_tls_for_every_channel_and_message_length);
    RUN_TEST(test_a_genuine_stream_opens_and_a_replay_is_refused);
    RUN_TEST(test_a_used_counter_is_refused_before_the_tag);
    RUN_TEST(test_forged_altered_and_truncated_frames_are_refused);
    RUN_TEST(test_a_new_sender_is_taken_at_any_counter);
    RUN_TEST(test_a_node_counts_from_its_boot);
    RUN_TEST(test_a_plant_follows_its_clock);
    RUN_TEST(test_senders_are_remembered_up_to_the_limit);
    RUN_TEST(test_bad_arguments_are_refused_and_consume_nothing);
    return UNITY_END();
}
