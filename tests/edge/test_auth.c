/*
 * Message authentication (firmware/edge/auth.c): tags against an independent implementation, and
 * every refusal leaving the receiver unchanged.
 *
 * The expected tags come from Python's `cryptography` package (Debian python3-cryptography), not from
 * this code: ChaCha20Poly1305(key).encrypt(nonce, b"", channel + b"\0" + message) with
 * key = bytes(range(32)) and nonce = sender_id (4 bytes, big-endian) + counter (8 bytes, big-endian).
 */
#include <string.h>

#include "auth.h"
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
    TEST_ASSERT_EQUAL_HEX8((uint8_t)(counter >> 56), trailer[4]);
    TEST_ASSERT_EQUAL_HEX8((uint8_t)counter, trailer[11]);
    uint8_t expected[TVO_AUTH_TAG_BYTES];
    hex_to_bytes(tag_hex, expected, sizeof(expected));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expected, trailer + 12, TVO_AUTH_TAG_BYTES);
    TEST_ASSERT_EQUAL_UINT64(counter + 1u, auth.next_counter);
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

/* Opens a frame expected to be refused with status; the receiver's state (senders, counters, key:
 * everything before its cipher's working state) must not change. */
static void expect_refused(link_t *link, const char *channel, const uint8_t *frame, size_t length,
                           tvo_auth_status_t status)
{
    tvo_auth_t before;
    memcpy(&before, &link->receiver, sizeof(before));
    size_t message_length = 99u;
    TEST_ASSERT_EQUAL_STRING(tvo_auth_status_str(status),
                             tvo_auth_status_str(tvo_auth_open(&link->receiver, channel, frame, length, &message_length)));
    TEST_ASSERT_EQUAL_UINT32(0u, message_length);
    TEST_ASSERT_EQUAL_MEMORY(&before, &link->receiver, TVO_AUTH_STATE_BYTES);
}

static void test_a_genuine_stream_opens_and_a_replay_is_refused(void)
{
    link_t link;
    link_init(&link);
    size_t message_length = 0u;
    link_send(&link, "TVO_MEASUREMENT", "sample one");
    uint8_t first[128];
    const size_t first_length = link.frame_length;
    memcpy(first, link.frame, first_length);
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_open(&link.receiver, "TVO_MEASUREMENT", first, first_length, &message_length));
    TEST_ASSERT_EQUAL_UINT32(strlen("sample one"), message_length);
    link_send(&link, "TVO_MEASUREMENT", "sample two");
    TEST_ASSERT_EQUAL(TVO_AUTH_OK,
                      tvo_auth_open(&link.receiver, "TVO_MEASUREMENT", link.frame, link.frame_length, &message_length));
    TEST_ASSERT_EQUAL_UINT64(1001u, link.receiver.senders[0].last_counter);
    /* The same frame again, and the older one: both replays. */
    expect_refused(&link, "TVO_MEASUREMENT", link.frame, link.frame_length, TVO_AUTH_ERR_REPLAY);
    expect_refused(&link, "TVO_MEASUREMENT", first, first_length, TVO_AUTH_ERR_REPLAY);
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

static void test_the_floor_refuses_old_recordings_from_unheard_senders(void)
{
    link_t link;
    link_init(&link);
    link_send(&link, "TVO_MEASUREMENT", "recorded before the restart"); /* counter 1000 */
    /* A restarted receiver has forgotten the sender; its floor (from storage or its clock) is 1000. */
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_set_new_sender_floor(&link.receiver, 1000u));
    expect_refused(&link, "TVO_MEASUREMENT", link.frame, link.frame_length, TVO_AUTH_ERR_REPLAY);
    link_send(&link, "TVO_MEASUREMENT", "after the restart"); /* counter 1001 */
    size_t message_length = 0u;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK,
                      tvo_auth_open(&link.receiver, "TVO_MEASUREMENT", link.frame, link.frame_length, &message_length));
}

static void test_senders_are_remembered_up_to_the_limit(void)
{
    make_key();
    tvo_auth_t receiver;
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&receiver, test_key, 1u, 1u));
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
    TEST_ASSERT_EQUAL(TVO_AUTH_OK, tvo_auth_init(&auth, test_key, 1u, 1u));
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_sign(&auth, "", frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT32(0u, length);
    /* No room for the trailer. */
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT,
                      tvo_auth_sign(&auth, "C", frame, sizeof(frame) - TVO_AUTH_TRAILER_BYTES + 1u, sizeof(frame), &length));
    static char long_channel[TVO_AUTH_MAX_CHANNEL_BYTES + 2u];
    memset(long_channel, 'A', TVO_AUTH_MAX_CHANNEL_BYTES + 1u);
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_ARGUMENT, tvo_auth_sign(&auth, long_channel, frame, 1u, sizeof(frame), &length));
    TEST_ASSERT_EQUAL_UINT64(1u, auth.next_counter);
    auth.next_counter = UINT64_MAX;
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_COUNTER_SPENT, tvo_auth_sign(&auth, "C", frame, 1u, sizeof(frame), &length));
    tvo_auth_clear(&auth);
    TEST_ASSERT_EQUAL(TVO_AUTH_ERR_NOT_KEYED, tvo_auth_sign(&auth, "C", frame, 1u, sizeof(frame), &length));
    for (unsigned i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
        TEST_ASSERT_EQUAL_HEX8(0u, auth.key[i]);
    }
    TEST_ASSERT_EQUAL_STRING("unknown authentication status", tvo_auth_status_str(TVO_AUTH_STATUS_COUNT));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_tags_match_an_independent_implementation);
    RUN_TEST(test_a_genuine_stream_opens_and_a_replay_is_refused);
    RUN_TEST(test_forged_altered_and_truncated_frames_are_refused);
    RUN_TEST(test_the_floor_refuses_old_recordings_from_unheard_senders);
    RUN_TEST(test_senders_are_remembered_up_to_the_limit);
    RUN_TEST(test_bad_arguments_are_refused_and_consume_nothing);
    return UNITY_END();
}
