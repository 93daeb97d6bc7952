/*
 * Serial framing (firmware/edge/serial_frame.c): round trips, the COBS edge cases (zeros, 254-byte
 * blocks), the zero-run stage (runs of 255/256 zeros, isolated zeros, malformed runs), resynchronisation,
 * and that corrupted, truncated or oversized frames are dropped and counted, never delivered.
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

/* Encodes payload_in[0..n) on channel 7, checks it comes back, returns the frame's length. */
static size_t round_trip_length(size_t n)
{
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(7u, payload_in, n, encoded, sizeof(encoded), &len));
    TEST_ASSERT_TRUE(len <= TVO_FRAME_ENCODED_BYTES(n));
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
    return len;
}

static void round_trip(size_t n, uint8_t fill_mod)
{
    for (size_t i = 0; i < n; ++i) {
        payload_in[i] = (uint8_t)(i % fill_mod); /* fill_mod 1: all zeros; 256: every value */
    }
    (void)round_trip_length(n);
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

/* COBS of stage (the bytes between the packet and COBS, as a sender would write them) + delimiter:
 * written here independently of the encoder, to build frames the encoder never makes. */
static size_t cobs_frame(const uint8_t *stage, size_t n, uint8_t *out)
{
    size_t code_index = 0u;
    size_t o = 1u;
    uint8_t code = 1u;
    for (size_t i = 0; i < n; ++i) {
        if (stage[i] == 0u) {
            out[code_index] = code;
            code_index = o++;
            code = 1u;
            continue;
        }
        out[o++] = stage[i];
        if (++code == 0xFFu) {
            out[code_index] = code;
            code_index = o++;
            code = 1u;
        }
    }
    out[code_index] = code;
    out[o++] = 0u;
    return o;
}

static void put_crc(uint8_t *at, uint32_t crc)
{
    for (unsigned k = 0; k < 4u; ++k) {
        at[k] = (uint8_t)(crc >> (8u * k));
    }
}


static void test_zero_runs_cost_two_bytes_per_255_zeros(void)
{
    /* A marker byte, a run of `run` zeros, a marker: the run costs 2 bytes per 255 zeros (or part). */
    const size_t runs[] = {1u, 2u, 254u, 255u, 256u, 510u, 511u, 5000u, TVO_FRAME_MAX_PAYLOAD - 2u};
    for (size_t r = 0; r < sizeof(runs) / sizeof(runs[0]); ++r) {
        const size_t run = runs[r];
        memset(payload_in, 0, run + 2u);
        payload_in[0] = 0xA5u;
        payload_in[run + 1u] = 0x5Au;
        const size_t len = round_trip_length(run + 2u);
        const size_t pairs = (run + 254u) / 255u;
        /* channel + 2 markers + pairs + CRC (4, maybe holding zeros: at most 4 more) + COBS + delimiter */
        if (run >= 3u) {
            TEST_ASSERT_TRUE(len <= 1u + 2u + 2u * pairs + 8u + (3u + 2u * pairs + 8u) / 254u + 2u);
        }
    }
}

static void test_all_zero_largest_payload_is_short_on_the_link(void)
{
    memset(payload_in, 0, TVO_FRAME_MAX_PAYLOAD);
    const size_t len = round_trip_length(TVO_FRAME_MAX_PAYLOAD);
    /* 11,456 zeros = 45 runs of 255 zeros and one of 181: 92 bytes, plus channel, CRC, COBS, delimiter. */
    TEST_ASSERT_TRUE(len <= 92u + 1u + 8u + 2u);
    TEST_ASSERT_TRUE(len >= 92u);
}

static void test_isolated_zeros_never_cost_more_than_cobs_alone(void)
{
    /* 0, x, 0, x, ...: the zero-run stage would grow it by half; the frame goes without it. */
    for (size_t i = 0; i < 1000u; ++i) {
        payload_in[i] = (i % 2u == 0u) ? 0u : (uint8_t)(i | 1u);
    }
    const size_t len = round_trip_length(1000u);
    TEST_ASSERT_TRUE(len <= 1u + 1000u + 4u + (1005u / 254u) + 2u);
    TEST_ASSERT_EQUAL_UINT8(0u, encoded[1] & TVO_FRAME_ZERO_RUNS);
}

static void test_malformed_zero_runs_are_dropped_and_counted(void)
{
    uint8_t stage[16];
    uint8_t frame[32];
    uint8_t channel = 0;
    size_t out_len = 0;
    /* A run of length 0 (never written), with a CRC the packet would otherwise pass. */
    const uint8_t packet[] = {7u, 0xAAu, 0u, 0xBBu};
    const uint32_t crc = tvo_crc32(0u, packet, sizeof(packet));
    const uint8_t with_run_0[] = {7u | TVO_FRAME_ZERO_RUNS, 0xAAu, 0u, 0u, 0xBBu};
    memcpy(stage, with_run_0, sizeof(with_run_0));
    put_crc(stage + sizeof(with_run_0), crc);
    tvo_frame_decoder_t dec;
    tvo_frame_decoder_init(&dec);
    size_t len = cobs_frame(stage, sizeof(with_run_0) + 4u, frame);
    TEST_ASSERT_EQUAL_INT(0, feed(&dec, frame, len, &channel, &out_len));
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_dropped);
    /* The same with run length 1 is the genuine frame: delivered (so the drop above was the run). */
    stage[3] = 1u;
    len = cobs_frame(stage, sizeof(with_run_0) + 4u, frame);
    TEST_ASSERT_EQUAL_INT(1, feed(&dec, frame, len, &channel, &out_len));
    TEST_ASSERT_EQUAL_size_t(3u, out_len);
    TEST_ASSERT_EQUAL_MEMORY(packet + 1, payload_out, 3u);
    /* A corrupted run length (2 instead of 1): the CRC over the original packet catches it. */
    stage[3] = 2u;
    len = cobs_frame(stage, sizeof(with_run_0) + 4u, frame);
    TEST_ASSERT_EQUAL_INT(0, feed(&dec, frame, len, &channel, &out_len));
    TEST_ASSERT_EQUAL_UINT32(2u, dec.frames_dropped);
    /* A zero whose run length the frame's end cuts off. */
    const uint8_t cut[] = {7u | TVO_FRAME_ZERO_RUNS, 1u, 2u, 3u, 4u, 5u, 0u};
    len = cobs_frame(cut, sizeof(cut), frame);
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_INCOMPLETE, tvo_frame_decoder_push(&dec, frame[0], &channel, payload_out, &out_len));
    size_t i = 1u;
    for (; i + 1u < len; ++i) {
        TEST_ASSERT_EQUAL_INT(TVO_FRAME_INCOMPLETE, tvo_frame_decoder_push(&dec, frame[i], &channel, payload_out, &out_len));
    }
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_BAD_COBS, tvo_frame_decoder_push(&dec, frame[i], &channel, payload_out, &out_len));
    TEST_ASSERT_EQUAL_UINT32(3u, dec.frames_dropped);
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_ok);
}

static void test_frame_decoding_past_the_limit_is_too_long(void)
{
    /* 60 pairs 0x00 0xFF = 15,300 zeros from 121 bytes: past TVO_FRAME_MAX_PACKET, never written past it. */
    static uint8_t stage[1u + 120u];
    static uint8_t frame[sizeof(stage) + 8u];
    stage[0] = 7u | TVO_FRAME_ZERO_RUNS;
    for (size_t k = 0; k < 60u; ++k) {
        stage[1u + 2u * k] = 0u;
        stage[2u + 2u * k] = 0xFFu;
    }
    TEST_ASSERT_TRUE(60u * 255u > TVO_FRAME_MAX_PACKET);
    const size_t len = cobs_frame(stage, sizeof(stage), frame);
    tvo_frame_decoder_t dec;
    tvo_frame_decoder_init(&dec);
    uint8_t channel = 0;
    size_t out_len = 0;
    for (size_t i = 0; i + 1u < len; ++i) {
        TEST_ASSERT_EQUAL_INT(TVO_FRAME_INCOMPLETE, tvo_frame_decoder_push(&dec, frame[i], &channel, payload_out, &out_len));
        TEST_ASSERT_TRUE(dec.length <= TVO_FRAME_MAX_PACKET);
    }
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_TOO_LONG, tvo_frame_decoder_push(&dec, 0u, &channel, payload_out, &out_len));
    TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_dropped);
    /* The decoder is ready for the next frame. */
    memset(payload_in, 0, 300u);
    size_t good = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(2u, payload_in, 300u, encoded, sizeof(encoded), &good));
    TEST_ASSERT_EQUAL_INT(1, feed(&dec, encoded, good, &channel, &out_len));
    TEST_ASSERT_EQUAL_size_t(300u, out_len);
}

static void test_zero_run_frame_truncated_or_bit_flipped_is_dropped(void)
{
    memset(payload_in, 0, 2000u);
    for (size_t i = 0; i < 2000u; i += 97u) {
        payload_in[i] = (uint8_t)(i | 1u);
    }
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(1u, payload_in, 2000u, encoded, sizeof(encoded), &len));
    TEST_ASSERT_TRUE(len < 200u); /* the zero-run stage was used */
    for (size_t cut = 1u; cut + 1u < len; ++cut) {
        tvo_frame_decoder_t dec;
        tvo_frame_decoder_init(&dec);
        uint8_t channel = 0;
        size_t out_len = 0;
        const uint8_t delimiter = 0u;
        TEST_ASSERT_EQUAL_INT(0, feed(&dec, encoded, cut, &channel, &out_len));
        TEST_ASSERT_EQUAL_INT(0, feed(&dec, &delimiter, 1u, &channel, &out_len));
        TEST_ASSERT_EQUAL_UINT32(1u, dec.frames_dropped);
    }
    for (size_t byte = 0; byte + 1u < len; ++byte) {
        for (unsigned bit = 0; bit < 8u; ++bit) {
            uint8_t corrupt[256];
            memcpy(corrupt, encoded, len);
            corrupt[byte] ^= (uint8_t)(1u << bit);
            tvo_frame_decoder_t dec;
            tvo_frame_decoder_init(&dec);
            uint8_t channel = 0;
            size_t out_len = 0;
            TEST_ASSERT_EQUAL_INT(0, feed(&dec, corrupt, len, &channel, &out_len));
            TEST_ASSERT_TRUE(dec.frames_dropped >= 1u);
        }
    }
}

static void test_encoder_rejects_channels_above_7_bits(void)
{
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_BAD_ARGUMENT,
                          tvo_frame_encode(TVO_FRAME_MAX_CHANNEL + 1u, payload_in, 1u, encoded, sizeof(encoded), &len));
    TEST_ASSERT_EQUAL_INT(TVO_FRAME_OK, tvo_frame_encode(TVO_FRAME_MAX_CHANNEL, payload_in, 1u, encoded, sizeof(encoded), &len));
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
    RUN_TEST(test_zero_runs_cost_two_bytes_per_255_zeros);
    RUN_TEST(test_all_zero_largest_payload_is_short_on_the_link);
    RUN_TEST(test_isolated_zeros_never_cost_more_than_cobs_alone);
    RUN_TEST(test_malformed_zero_runs_are_dropped_and_counted);
    RUN_TEST(test_frame_decoding_past_the_limit_is_too_long);
    RUN_TEST(test_zero_run_frame_truncated_or_bit_flipped_is_dropped);
    RUN_TEST(test_encoder_rejects_channels_above_7_bits);
    return UNITY_END();
}
