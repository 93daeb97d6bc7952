/*
 * The serial-frame decoder (the board's first contact with the link): arbitrary bytes in, and
 * every frame it accepts must be one the encoder could have made (re-encoding it and decoding again
 * gives the same channel and payload). A second half of the input is framed by the encoder and must
 * come back intact through a fresh decoder.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "serial_frame.h"

static void fail(const char *what)
{
    fprintf(stderr, "fuzz invariant broken: %s\n", what);
    abort();
}

static uint8_t payload[TVO_FRAME_MAX_PAYLOAD];
static uint8_t again[TVO_FRAME_MAX_PAYLOAD];
static uint8_t encoded[TVO_FRAME_MAX_ENCODED];

/* Feeds `frame` to a fresh decoder; the one frame it yields must be (channel, body). */
static void roundtrip(uint8_t channel, const uint8_t *body, size_t length)
{
    size_t encoded_length = 0;
    if (tvo_frame_encode(channel, body, length, encoded, sizeof(encoded), &encoded_length) != TVO_FRAME_OK) {
        fail("encode refused a payload within the maximum");
    }
    tvo_frame_decoder_t decoder;
    tvo_frame_decoder_init(&decoder);
    int frames = 0;
    for (size_t k = 0; k < encoded_length; ++k) {
        uint8_t got_channel = 0;
        size_t got_length = 0;
        if (tvo_frame_decoder_push(&decoder, encoded[k], &got_channel, again, &got_length) == TVO_FRAME_OK) {
            frames++;
            if (got_channel != channel || got_length != length || memcmp(again, body, length) != 0) {
                fail("a frame did not come back as it was sent");
            }
        }
    }
    if (frames != 1) {
        fail("an encoded frame did not decode exactly once");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    tvo_frame_decoder_t decoder;
    tvo_frame_decoder_init(&decoder);
    for (size_t i = 0; i < size; ++i) {
        uint8_t channel = 0;
        size_t length = 0;
        if (tvo_frame_decoder_push(&decoder, data[i], &channel, payload, &length) == TVO_FRAME_OK) {
            if (length > TVO_FRAME_MAX_PAYLOAD) {
                fail("decoded payload longer than the maximum");
            }
            roundtrip(channel, payload, length);
        }
    }
    if (size >= 1) {
        const size_t length = (size - 1) < TVO_FRAME_MAX_PAYLOAD ? size - 1 : TVO_FRAME_MAX_PAYLOAD;
        roundtrip((uint8_t)(data[0] & TVO_FRAME_MAX_CHANNEL), data + 1, length); /* channels are 7-bit */
    }
    return 0;
}
