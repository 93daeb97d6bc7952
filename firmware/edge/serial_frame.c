/* COBS + zero runs + CRC-32 framing; see serial_frame.h. */
#include "serial_frame.h"

#include <string.h>

uint32_t tvo_crc32(uint32_t crc, const uint8_t *data, size_t length)
{
    crc = ~crc;
    for (size_t i = 0; i < length; ++i) {
        crc ^= data[i];
        for (unsigned bit = 0; bit < 8u; ++bit) {
            /* Bitwise, table-free: a frame per 10 ms does not need the speed of a 1 KiB table. */
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
    }
    return ~crc;
}

/* COBS writer: each block starts with a code byte = distance to the next zero (0xFF: 254 data bytes, no zero). */
typedef struct {
    uint8_t *out;
    size_t capacity;
    size_t code_index;
    size_t length;
    uint8_t code;
    uint8_t full; /* out could not take a byte: the frame does not fit */
} cobs_writer_t;

static void cobs_put(cobs_writer_t *w, uint8_t byte)
{
    if (w->full || w->length + 2u > w->capacity) {
        w->full = 1u; /* + 2: this byte and the delimiter */
        return;
    }
    if (byte == 0u) {
        w->out[w->code_index] = w->code;
        w->code_index = w->length++;
        w->code = 1u;
        return;
    }
    w->out[w->length++] = byte;
    if (++w->code == 0xFFu) {
        w->out[w->code_index] = w->code;
        w->code_index = w->length++;
        w->code = 1u;
    }
}

/* The packet after its channel byte: payload then CRC. */
typedef struct {
    const uint8_t *payload;
    size_t payload_length;
    uint8_t crc_bytes[4];
} frame_body_t;

static uint8_t body_byte(const frame_body_t *body, size_t i)
{
    return i < body->payload_length ? body->payload[i] : body->crc_bytes[i - body->payload_length];
}

/* Zeros from body byte i on, at most 255 (one run length byte). */
static size_t zero_run_at(const frame_body_t *body, size_t i, size_t body_length)
{
    size_t run = 0u;
    while (run < 255u && i + run < body_length && body_byte(body, i + run) == 0u) {
        ++run;
    }
    return run;
}

/* Writes the body through the zero-run stage to w if w is not NULL; returns the stage's length. */
static size_t zero_runs_write(const frame_body_t *body, size_t body_length, cobs_writer_t *w)
{
    size_t written = 0u;
    size_t i = 0u;
    while (i < body_length) { /* bounded: i grows by at least one per turn */
        const uint8_t byte = body_byte(body, i);
        if (byte != 0u) {
            if (w != NULL) {
                cobs_put(w, byte);
            }
            ++written;
            ++i;
            continue;
        }
        const size_t run = zero_run_at(body, i, body_length);
        if (w != NULL) {
            cobs_put(w, 0u);
            cobs_put(w, (uint8_t)run);
        }
        written += 2u;
        i += run;
    }
    return written;
}

tvo_frame_status_t tvo_frame_encode(uint8_t channel, const uint8_t *payload, size_t payload_length, uint8_t *out,
                                    size_t out_capacity, size_t *out_length)
{
    if ((payload == NULL && payload_length > 0u) || out == NULL || out_length == NULL ||
        channel > TVO_FRAME_MAX_CHANNEL) {
        return TVO_FRAME_BAD_ARGUMENT;
    }
    if (payload_length > TVO_FRAME_MAX_PAYLOAD) {
        return TVO_FRAME_TOO_LONG;
    }
    uint32_t crc = tvo_crc32(0u, &channel, 1u);
    crc = tvo_crc32(crc, payload, payload_length);
    const frame_body_t body = {payload,
                               payload_length,
                               {(uint8_t)crc, (uint8_t)(crc >> 8), (uint8_t)(crc >> 16), (uint8_t)(crc >> 24)}};
    const size_t body_length = payload_length + 4u;
    /* The zero-run stage only when it is shorter: a frame is never longer than COBS alone makes it. */
    const int zero_runs = zero_runs_write(&body, body_length, NULL) < body_length;
    cobs_writer_t w = {out, out_capacity, 0u, 1u, 1u, 0u};
    cobs_put(&w, zero_runs ? (uint8_t)(channel | TVO_FRAME_ZERO_RUNS) : channel);
    if (zero_runs) {
        (void)zero_runs_write(&body, body_length, &w);
    } else {
        for (size_t i = 0; i < body_length; ++i) {
            cobs_put(&w, body_byte(&body, i));
        }
    }
    if (w.full || w.length + 1u > out_capacity) {
        return TVO_FRAME_TOO_LONG;
    }
    out[w.code_index] = w.code;
    out[w.length++] = 0u; /* delimiter */
    *out_length = w.length;
    return TVO_FRAME_OK;
}

/* Forgets the frame being received (the counters stay). */
static void decoder_restart(tvo_frame_decoder_t *decoder)
{
    decoder->length = 0u;
    decoder->receiving = 0u;
    decoder->block_left = 0u;
    decoder->block_code = 0u;
    decoder->zero_pending = 0u;
    decoder->zero_runs = 0u;
    decoder->run_next = 0u;
    decoder->failure = (uint8_t)TVO_FRAME_OK;
}

void tvo_frame_decoder_init(tvo_frame_decoder_t *decoder)
{
    if (decoder != NULL) {
        memset(decoder, 0, sizeof(*decoder));
        decoder_restart(decoder);
    }
}

/* Appends count copies of byte to the packet; past the buffer the frame is TOO_LONG. */
static void packet_put(tvo_frame_decoder_t *decoder, uint8_t byte, size_t count)
{
    if (count > sizeof(decoder->buffer) - decoder->length) {
        decoder->failure = (uint8_t)TVO_FRAME_TOO_LONG;
        return;
    }
    memset(decoder->buffer + decoder->length, byte, count);
    decoder->length += count;
}

/* One byte out of COBS: the channel byte, or a byte of the (maybe zero-run coded) body. */
static void unstuffed_put(tvo_frame_decoder_t *decoder, uint8_t byte)
{
    if (decoder->failure != (uint8_t)TVO_FRAME_OK) {
        return;
    }
    if (decoder->length == 0u) {
        decoder->zero_runs = (byte & TVO_FRAME_ZERO_RUNS) != 0u;
        packet_put(decoder, (uint8_t)(byte & TVO_FRAME_MAX_CHANNEL), 1u);
    } else if (decoder->run_next) {
        decoder->run_next = 0u;
        if (byte == 0u) {
            decoder->failure = (uint8_t)TVO_FRAME_BAD_COBS; /* a run of no zeros: never written */
        } else {
            packet_put(decoder, 0u, byte);
        }
    } else if (decoder->zero_runs && byte == 0u) {
        decoder->run_next = 1u;
    } else {
        packet_put(decoder, byte, 1u);
    }
}

tvo_frame_status_t tvo_frame_decoder_push(tvo_frame_decoder_t *decoder, uint8_t byte, uint8_t *channel,
                                          uint8_t *payload, size_t *payload_length)
{
    if (decoder == NULL || channel == NULL || payload == NULL || payload_length == NULL) {
        return TVO_FRAME_BAD_ARGUMENT;
    }
    if (byte != 0u) {
        decoder->receiving = 1u;
        if (decoder->block_left == 0u) { /* a code byte: the previous block's zero, if any, was data */
            if (decoder->zero_pending) {
                decoder->zero_pending = 0u;
                unstuffed_put(decoder, 0u);
            }
            decoder->block_code = byte;
            decoder->block_left = (uint8_t)(byte - 1u);
        } else {
            unstuffed_put(decoder, byte);
            --decoder->block_left;
        }
        if (decoder->block_left == 0u && decoder->block_code != 0xFFu) {
            decoder->zero_pending = 1u; /* dropped if the frame ends here */
        }
        return TVO_FRAME_INCOMPLETE;
    }
    /* A delimiter: whatever was received is one frame. */
    if (!decoder->receiving) {
        return TVO_FRAME_INCOMPLETE; /* back-to-back delimiters: nothing to report */
    }
    tvo_frame_status_t st = (tvo_frame_status_t)decoder->failure;
    const size_t packet_length = decoder->length;
    const uint8_t *packet = decoder->buffer;
    if (st != TVO_FRAME_OK) {
        /* already failed */
    } else if (decoder->block_left != 0u || decoder->run_next) {
        st = TVO_FRAME_BAD_COBS; /* a block or a zero run cut short */
    } else if (packet_length < 5u) {
        st = TVO_FRAME_TOO_SHORT;
    } else {
        const size_t body = packet_length - 4u;
        const uint32_t expected = (uint32_t)packet[body] | ((uint32_t)packet[body + 1u] << 8) |
                                  ((uint32_t)packet[body + 2u] << 16) | ((uint32_t)packet[body + 3u] << 24);
        if (tvo_crc32(0u, packet, body) != expected) {
            st = TVO_FRAME_BAD_CRC;
        } else {
            *channel = packet[0];
            *payload_length = body - 1u;
            memmove(payload, packet + 1u, body - 1u);
        }
    }
    decoder_restart(decoder);
    if (st == TVO_FRAME_OK) {
        decoder->frames_ok++;
    } else {
        decoder->frames_dropped++;
    }
    return st;
}
