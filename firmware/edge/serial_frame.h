/*
 * Framing of messages on a byte stream (a UART, QEMU's -serial): COBS-encoded packets ended by a
 * 0x00 byte, each packet = [channel (1 byte)] [payload] [CRC-32 of channel and payload, little-endian].
 *
 * Between the packet and COBS, an optional zero-run stage: when it makes the frame shorter (a
 * session_t of 11,427 bytes is 11,327 zeros: fixed arrays for 32 robots), the channel byte goes with
 * bit 7 set (TVO_FRAME_ZERO_RUNS) and every run of zeros after it (payload and CRC) is written as
 * pairs 0x00 n, n = 1..255 zeros (a longer run: several pairs). Otherwise the packet goes as it is,
 * so no frame is longer than COBS alone makes it. The CRC is over the original packet (channel
 * without the flag), so a corrupted run length fails it; n = 0 or a 0x00 with no n is malformed.
 *
 * COBS (Cheshire & Baker, "Consistent Overhead Byte Stuffing") removes every 0x00 from the packet,
 * so 0x00 only ever ends a frame: a receiver that starts mid-stream or loses bytes resynchronises at
 * the next 0x00. The CRC-32 (IEEE 802.3, reflected 0xEDB88320) rejects corrupted frames; truncated
 * ones fail it or the COBS structure. The decoder undoes COBS and the zero runs byte by byte, into a
 * packet-sized buffer. Fixed buffers, no allocation: usable on the MCU and the host.
 */
#ifndef TVO_SERIAL_FRAME_H
#define TVO_SERIAL_FRAME_H

#include <stddef.h>
#include <stdint.h>

/** Largest payload a frame carries: the largest message of the wire (session_t) with an authentication
 *  trailer, rounded up to 64 bytes (pil.c and pil_bridge.c check at build time that it holds them). */
#define TVO_FRAME_MAX_PAYLOAD 11456u
/** Channels are 7-bit: bit 7 of the channel byte on the link marks the zero-run stage. */
#define TVO_FRAME_MAX_CHANNEL 0x7Fu
#define TVO_FRAME_ZERO_RUNS 0x80u
/** Packet = channel + payload + CRC; COBS adds one byte per 254 plus one; then the 0x00 delimiter.
 *  The zero-run stage is used only when it is shorter than the packet, so it adds nothing here. */
#define TVO_FRAME_PACKET_BYTES(payload_bytes) (1u + (payload_bytes) + 4u)
#define TVO_FRAME_ENCODED_BYTES(payload_bytes)                                                                       \
    (TVO_FRAME_PACKET_BYTES(payload_bytes) + TVO_FRAME_PACKET_BYTES(payload_bytes) / 254u + 2u)
#define TVO_FRAME_MAX_PACKET TVO_FRAME_PACKET_BYTES(TVO_FRAME_MAX_PAYLOAD)
#define TVO_FRAME_MAX_ENCODED TVO_FRAME_ENCODED_BYTES(TVO_FRAME_MAX_PAYLOAD)

typedef enum {
    TVO_FRAME_OK = 0,
    TVO_FRAME_INCOMPLETE = 1,   /* byte consumed, no frame finished yet */
    TVO_FRAME_BAD_COBS = 2,     /* malformed stuffing or zero run (a truncated or corrupted frame) */
    TVO_FRAME_BAD_CRC = 3,      /* checksum mismatch */
    TVO_FRAME_TOO_LONG = 4,     /* decodes to more than TVO_FRAME_MAX_PACKET bytes before a delimiter */
    TVO_FRAME_TOO_SHORT = 5,    /* fewer bytes than channel + CRC */
    TVO_FRAME_BAD_ARGUMENT = 6
} tvo_frame_status_t;

/** CRC-32 (IEEE) of data, continuing from crc (start with 0). */
uint32_t tvo_crc32(uint32_t crc, const uint8_t *data, size_t length);

/**
 * Encodes one frame into out (capacity TVO_FRAME_ENCODED_BYTES(payload_length) is always enough;
 * TVO_FRAME_MAX_ENCODED for any payload), delimiter included; *out_length receives its length.
 * channel must be <= TVO_FRAME_MAX_CHANNEL (else TVO_FRAME_BAD_ARGUMENT).
 */
tvo_frame_status_t tvo_frame_encode(uint8_t channel, const uint8_t *payload, size_t payload_length, uint8_t *out,
                                    size_t out_capacity, size_t *out_length);

/** Receiver state: feed it bytes one at a time; COBS and the zero runs are undone as they arrive. */
typedef struct {
    uint8_t buffer[TVO_FRAME_MAX_PACKET]; /* the packet decoded so far (channel byte without its flag) */
    size_t length;
    uint8_t receiving;            /* a byte other than the delimiter came since the last one */
    uint8_t block_left;           /* COBS: data bytes left in the current block (0: a code byte is next) */
    uint8_t block_code;           /* COBS: the current block's code (0xFF: no zero after it) */
    uint8_t zero_pending;         /* COBS: a block ended in a zero, written if the frame goes on */
    uint8_t zero_runs;            /* the frame uses the zero-run stage (its channel byte had the flag) */
    uint8_t run_next;             /* zero-run stage: the next byte is a run length */
    uint8_t failure;              /* a tvo_frame_status_t this frame already failed with: discard until the delimiter */
    uint32_t frames_ok;
    uint32_t frames_dropped;      /* bad COBS, bad CRC, too long or too short: counted, never returned */
} tvo_frame_decoder_t;

void tvo_frame_decoder_init(tvo_frame_decoder_t *decoder);

/**
 * Consumes one byte. On TVO_FRAME_OK a frame ended with this byte and passed its checks: *channel,
 * payload[0 .. *payload_length) hold it (payload capacity >= TVO_FRAME_MAX_PAYLOAD). payload may be
 * the decoder's own buffer (a board saves a second frame's worth of RAM): the payload is then valid
 * until the next byte is pushed. A frame that decodes past TVO_FRAME_MAX_PACKET is dropped as
 * TVO_FRAME_TOO_LONG, a zero run of length 0 or cut by the frame's end as TVO_FRAME_BAD_COBS. Errors mean a frame ended with this byte and was dropped (and counted).
 */
tvo_frame_status_t tvo_frame_decoder_push(tvo_frame_decoder_t *decoder, uint8_t byte, uint8_t *channel,
                                          uint8_t *payload, size_t *payload_length);

#endif /* TVO_SERIAL_FRAME_H */
