/*
 * Serial framing (firmware/edge/serial_frame.c): round trips, the COBS edge cases (zeros, 254-byte
 * blocks), resynchronisation, and that corrupted, truncated or oversized frames are dropped and
 * counted, never delivered.
 */
#include <string.h>

#include "serial_frame.h"
#include "unity.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

static uint8_t encoded[TVO_FRAME_MAX_ENCODED];
static uint8_t payload_in[TVO_FRAME_MAX_PAYLOAD];
static uint8_t payload_out[TVO_FRAME_MAX_PAYLOAD];

/* Feeds bytes; returns the number of frames delivered, the last one in payload_out. */
static int feed(tvo_frame_decoder_t *dec, const uint8_t *bytes, size_t n, uint8_t *channel, size_t *length)
{
    int delivered = 0;
    for (size_t i = 0; i < n; ++i) {
        if (tvo_frame_decoder_push(dec, bytes[i], channel, payload_out, length) == TVO_FRAME_OK) {
            ++delivered;
        }
    }
    return delivered;
}

static void round_trip(size_t n, uint8_t fill_mod)
{
    for (size_t i = 0; i < n; ++i) {
        payload_in[i] = (uint8_t)(i % fill_mod); /* fill_mod 1: all zeros; 256: every value */
    }
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(7u, payload_in, n, encoded, sizeof(encoded), &len));
    TEST_ASSERT_EQUAL_UINT8(0u, encoded[len - 1u]);
    for (size_t i = 0; i + 1u < len; ++i) {
        TEST_ASSERT_NOT_EQUAL(0u, encoded[i]); /* the delimiter is the only zero */
    }
    tvo_frame_decoder_t dec;
    tvo_frame_decoder_init(&dec);
    uint8_t channel = 0;
    size_t out_len = 99999u;
    TEST_ASSERT_EQUAL_INT(1, feed(&dec, encoded, len, &channel, &out_len));
    TEST_ASSERT_EQUAL_UINT8(7u, channel);
    TEST_ASSERT_EQUAL_size_t(n, out_len);
    if (n > 0u) {
        TEST_ASSERT_EQUAL_MEMORY(payload_in, payload_out, n);
    }
}

static void test_round_trips_across_cobs_block_boundaries(void)
{
    const size_t sizes[] = {0u, 1u, 2u, 248u, 249u, 250u, 253u, 254u, 255u, 508u, 509u, 1000u, TVO_FRAME_MAX_PAYLOAD};
    for (size_t i = 0; i < sizeof(sizes) / sizeof(sizes[0]); ++i) {
        round_trip(sizes[i], 251u);
        round_trip(sizes[i], 1u);
    }
}

static void test_crc32_matches_the_standard_check_value(void)
{
    /* The CRC-32/ISO-HDLC check value of "123456789". */
    TEST_ASSERT_EQUAL_HEX32(0xCBF43926u, tvo_crc32(0u, (const uint8_t *)"123456789", 9u));
}

static void test_every_single_bit_flip_is_dropped_and_counted(void)
{
    for (size_t i = 0; i < 40u; ++i) {
        payload_in[i] = (uint8_t)(i * 37u + 1u);
    }
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(3u, payload_in, 40u, encoded, sizeof(encoded), &len));
    uint32_t dropped = 0;
    for (size_t byte = 0; byte + 1u < len; ++byte) {
        for (unsigned bit = 0; bit < 8u; ++bit) {
            uint8_t corrupt[TVO_FRAME_MAX_ENCODED];
            memcpy(corrupt, encoded, len);
            corrupt[byte] ^= (uint8_t)(1u << bit);
            tvo_frame_decoder_t dec;
            tvo_frame_decoder_init(&dec);
            uint8_t channel = 0;
            size_t out_len = 0;
            TEST_ASSERT_EQUAL_INT(0, feed(&dec, corrupt, len, &channel, &out_len));
            /* A flip that makes a zero splits the frame in two: both halves are dropped. */
            TEST_ASSERT_TRUE(dec.frames_dropped >= 1u);
            TEST_ASSERT_EQUAL_UINT32(0u, dec.frames_ok);
            dropped += dec.frames_dropped;
        }
    }
    TEST_ASSERT_TRUE(dropped >= 8u * (len - 1u));
}

static void test_truncated_frame_is_dropped_and_the_next_one_delivered(void)
{
    for (size_t i = 0; i < 100u; ++i) {
        payload_in[i] = (uint8_t)(i + 1u);
    }
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(9u, payload_in, 100u, encoded, sizeof(encoded), &len));
    tvo_frame_decoder_t dec;
    tvo_frame_decoder_init(&dec);
    uint8_t channel = 0;
    size_t out_len = 0;
    /* The first half of a frame, then a delimiter (the sender restarted), then a whole frame. */
    TEST_ASSERT_EQUAL_INT(0, feed(&dec, encoded, len / 2u, &channel, &out_len));
    const uint8_t delimiter = 0u;
    TEST_ASSERT_EQUAL_INT(0, feed(&dec, &delimiter, 1u, &channel, &out_len));
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_dropped);
    TEST_ASSERT_EQUAL_INT(1, feed(&dec, encoded, len, &channel, &out_len));
    TEST_ASSERT_EQUAL_size_t(100u, out_len);
    TEST_ASSERT_EQUAL_MEMORY(payload_in, payload_out, 100u);
}

static void test_receiver_joining_mid_stream_resynchronises(void)
{
    size_t len = 0;
    memset(payload_in, 0xAB, 10u);
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(1u, payload_in, 10u, encoded, sizeof(encoded), &len));
    tvo_frame_decoder_t dec;
    tvo_frame_decoder_init(&dec);
    uint8_t channel = 0;
    size_t out_len = 0;
    TEST_ASSERT_EQUAL_INT(0, feed(&dec, encoded + 3, len - 3u, &channel, &out_len)); /* tail only */
    TEST_ASSERT_EQUAL_INT(1, feed(&dec, encoded, len, &channel, &out_len));
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_dropped);
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_ok);
}

static void test_oversized_input_is_dropped_without_overrun(void)
{
    tvo_frame_decoder_t dec;
    tvo_frame_decoder_init(&dec);
    uint8_t channel = 0;
    size_t out_len = 0;
    for (size_t i = 0; i < TVO_FRAME_MAX_ENCODED + 100u; ++i) {
        TEST_ASSERT_EQUAL_INT(TVO_FRAME_INCOMPLETE, tvo_frame_decoder_push(&dec, 0x11u, &channel, payload_out, &out_len));
    }
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_TOO_LONG, tvo_frame_decoder_push(&dec, 0u, &channel, payload_out, &out_len));
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_dropped);
}

static void test_encoder_rejects_oversized_payload_and_small_buffers(void)
{
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_TOO_LONG,
                          tvo_frame_encode(0u, payload_in, TVO_FRAME_MAX_PAYLOAD + 1u, encoded, sizeof(encoded), &len));
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_TOO_LONG, tvo_frame_encode(0u, payload_in, 10u, encoded, 8u, &len));
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_BAD_ARGUMENT, tvo_frame_encode(0u, NULL, 10u, encoded, sizeof(encoded), &len));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_round_trips_across_cobs_block_boundaries);
    RUN_TEST(test_crc32_matches_the_standard_check_value);
    RUN_TEST(test_every_single_bit_flip_is_dropped_and_counted);
    RUN_TEST(test_truncated_frame_is_dropped_and_the_next_one_delivered);
    RUN_TEST(test_receiver_joining_mid_stream_resynchronises);
    RUN_TEST(test_oversized_input_is_dropped_without_overrun);
    RUN_TEST(test_encoder_rejects_oversized_payload_and_small_buffers);
    return UNITY_END();
}
