/*
 * Framing of messages on a byte stream (a UART, QEMU's -serial): COBS-encoded packets ended by a
 * 0x00 byte, each packet = [channel (1 byte)] [payload] [CRC-32 of channel and payload, little-endian].
 *
 * COBS (Cheshire & Baker, "Consistent Overhead Byte Stuffing") removes every 0x00 from the packet,
 * so 0x00 only ever ends a frame: a receiver that starts mid-stream or loses bytes resynchronises at
 * the next 0x00. The CRC-32 (IEEE 802.3, reflected 0xEDB88320) rejects corrupted frames; truncated
 * ones fail it or the COBS structure. Fixed buffers, no allocation: usable on the MCU and the host.
 */
#ifndef TVO_SERIAL_FRAME_H
#define TVO_SERIAL_FRAME_H

#include <stddef.h>
#include <stdint.h>

/** Largest payload a frame carries: the largest message of the wire (session_t) with an authentication
 *  trailer, rounded up to 64 bytes (pil.c and pil_bridge.c check at build time that it holds them). */
#define TVO_FRAME_MAX_PAYLOAD 11456u
/** Packet = channel + payload + CRC; COBS adds one byte per 254 plus one; then the 0x00 delimiter. */
#define TVO_FRAME_PACKET_BYTES(payload_bytes) (1u + (payload_bytes) + 4u)
#define TVO_FRAME_ENCODED_BYTES(payload_bytes)                                                                       \
    (TVO_FRAME_PACKET_BYTES(payload_bytes) + TVO_FRAME_PACKET_BYTES(payload_bytes) / 254u + 2u)
#define TVO_FRAME_MAX_PACKET TVO_FRAME_PACKET_BYTES(TVO_FRAME_MAX_PAYLOAD)
#define TVO_FRAME_MAX_ENCODED TVO_FRAME_ENCODED_BYTES(TVO_FRAME_MAX_PAYLOAD)

typedef enum {
    TVO_FRAME_OK = 0,
    TVO_FRAME_INCOMPLETE = 1,   /* byte consumed, no frame finished yet */
    TVO_FRAME_BAD_COBS = 2,     /* malformed stuffing (a truncated or corrupted frame) */
    TVO_FRAME_BAD_CRC = 3,      /* checksum mismatch */
    TVO_FRAME_TOO_LONG = 4,     /* more bytes than any valid frame before a delimiter */
    TVO_FRAME_TOO_SHORT = 5,    /* fewer bytes than channel + CRC */
    TVO_FRAME_BAD_ARGUMENT = 6
} tvo_frame_status_t;

/** CRC-32 (IEEE) of data, continuing from crc (start with 0). */
uint32_t tvo_crc32(uint32_t crc, const uint8_t *data, size_t length);

/**
 * Encodes one frame into out (capacity TVO_FRAME_ENCODED_BYTES(payload_length) is always enough;
 * TVO_FRAME_MAX_ENCODED for any payload), delimiter included; *out_length receives its length.
 */
tvo_frame_status_t tvo_frame_encode(uint8_t channel, const uint8_t *payload, size_t payload_length, uint8_t *out,
                                    size_t out_capacity, size_t *out_length);

/** Receiver state: feed it bytes one at a time. */
typedef struct {
    uint8_t buffer[TVO_FRAME_MAX_ENCODED];
    size_t length;
    uint8_t overflowed;           /* discard until the next delimiter */
    uint32_t frames_ok;
    uint32_t frames_dropped;      /* bad COBS, bad CRC, too long or too short: counted, never returned */
} tvo_frame_decoder_t;

void tvo_frame_decoder_init(tvo_frame_decoder_t *decoder);

/**
 * Consumes one byte. On TVO_FRAME_OK a frame ended with this byte and passed its checks: *channel,
 * payload[0 .. *payload_length) hold it (payload capacity >= TVO_FRAME_MAX_PAYLOAD). payload may be
 * the decoder's own buffer (a board saves a second frame's worth of RAM): the payload is then valid
 * until the next byte is pushed. Errors mean a frame ended with this byte and was dropped (and counted).
 */
tvo_frame_status_t tvo_frame_decoder_push(tvo_frame_decoder_t *decoder, uint8_t byte, uint8_t *channel,
                                          uint8_t *payload, size_t *payload_length);

#endif /* TVO_SERIAL_FRAME_H */
