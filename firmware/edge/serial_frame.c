/* COBS + CRC-32 framing; see serial_frame.h. */
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

tvo_frame_status_t tvo_frame_encode(uint8_t channel, const uint8_t *payload, size_t payload_length, uint8_t *out,
                                    size_t out_capacity, size_t *out_length)
{
    if ((payload == NULL && payload_length > 0u) || out == NULL || out_length == NULL) {
        return TVO_FRAME_BAD_ARGUMENT;
    }
    if (payload_length > TVO_FRAME_MAX_PAYLOAD) {
        return TVO_FRAME_TOO_LONG;
    }
    uint32_t crc = tvo_crc32(0u, &channel, 1u);
    crc = tvo_crc32(crc, payload, payload_length);
    const uint8_t crc_bytes[4] = {(uint8_t)crc, (uint8_t)(crc >> 8), (uint8_t)(crc >> 16), (uint8_t)(crc >> 24)};
    const size_t packet_length = 1u + payload_length + 4u;
    /* COBS: each block starts with a code byte = distance to the next zero (or 0xFF for 254 data bytes). */
    size_t code_index = 0u;
    size_t o = 1u;
    uint8_t code = 1u;
    for (size_t i = 0; i < packet_length; ++i) {
        const uint8_t byte = (i == 0u) ? channel : (i <= payload_length) ? payload[i - 1u] : crc_bytes[i - 1u - payload_length];
        if (o + 2u > out_capacity) {
            return TVO_FRAME_TOO_LONG;
        }
        if (byte == 0u) {
            out[code_index] = code;
            code_index = o++;
            code = 1u;
            continue;
        }
        out[o++] = byte;
        if (++code == 0xFFu) {
            out[code_index] = code;
            code_index = o++;
            code = 1u;
        }
    }
    if (o + 1u > out_capacity) {
        return TVO_FRAME_TOO_LONG;
    }
    out[code_index] = code;
    out[o++] = 0u; /* delimiter */
    *out_length = o;
    return TVO_FRAME_OK;
}

void tvo_frame_decoder_init(tvo_frame_decoder_t *decoder)
{
    if (decoder != NULL) {
        memset(decoder, 0, sizeof(*decoder));
    }
}

/* Decodes COBS in place from buffer[0..length) into packet; returns the packet length or 0 if malformed. */
static size_t cobs_decode(const uint8_t *in, size_t length, uint8_t *packet, size_t capacity)
{
    size_t i = 0u;
    size_t o = 0u;
    while (i < length) {
        const uint8_t code = in[i++];
        if (code == 0u || i + (size_t)code - 1u > length) {
            return 0u;
        }
        for (uint8_t k = 1u; k < code; ++k) {
            if (o >= capacity) {
                return 0u;
            }
            packet[o++] = in[i++];
        }
        if (code != 0xFFu && i < length) {
            if (o >= capacity) {
                return 0u;
            }
            packet[o++] = 0u;
        }
    }
    return o;
}

tvo_frame_status_t tvo_frame_decoder_push(tvo_frame_decoder_t *decoder, uint8_t byte, uint8_t *channel,
                                          uint8_t *payload, size_t *payload_length)
{
    if (decoder == NULL || channel == NULL || payload == NULL || payload_length == NULL) {
        return TVO_FRAME_BAD_ARGUMENT;
    }
    if (byte != 0u) {
        if (decoder->length >= sizeof(decoder->buffer)) {
            decoder->overflowed = 1u;
        } else {
            decoder->buffer[decoder->length++] = byte;
        }
        return TVO_FRAME_INCOMPLETE;
    }
    /* A delimiter: whatever was collected is one frame. */
    const size_t collected = decoder->length;
    const uint8_t overflowed = decoder->overflowed;
    decoder->length = 0u;
    decoder->overflowed = 0u;
    if (collected == 0u) {
        return TVO_FRAME_INCOMPLETE; /* back-to-back delimiters: nothing to report */
    }
    tvo_frame_status_t st = TVO_FRAME_OK;
    /* The packet reuses the front of the receive buffer: COBS never expands when decoding. */
    uint8_t *packet = decoder->buffer;
    size_t packet_length = 0u;
    if (overflowed) {
        st = TVO_FRAME_TOO_LONG;
    } else {
        packet_length = cobs_decode(decoder->buffer, collected, packet, sizeof(decoder->buffer));
        if (packet_length == 0u) {
            st = TVO_FRAME_BAD_COBS;
        } else if (packet_length < 5u) {
            st = TVO_FRAME_TOO_SHORT;
        } else if (packet_length - 5u > TVO_FRAME_MAX_PAYLOAD) {
            st = TVO_FRAME_TOO_LONG;
        }
    }
    if (st == TVO_FRAME_OK) {
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
    if (st == TVO_FRAME_OK) {
        decoder->frames_ok++;
    } else {
        decoder->frames_dropped++;
    }
    return st;
}
