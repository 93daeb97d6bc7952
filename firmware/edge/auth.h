/*
 * Message authentication for the node's links: every message in both directions carries a trailer
 * (sender id, counter, tag) after its bytes, as MAVLink 2 signs packets. Edge code: the control core
 * never sees it, and it is the same code on the host and the board.
 *
 * The primitive is ChaCha20-Poly1305 (RFC 8439) with an empty plaintext: the message is the
 * associated data, so it travels in clear and only the 16-byte tag is added. The 96-bit nonce is
 * (sender id, counter), which a sender never repeats under one key because counters only increase;
 * the channel's name is authenticated too, so a message cannot be moved to another channel.
 * Chosen over HMAC-SHA256 for the MCU's budget: one ChaCha20 block and a Poly1305 pass over the
 * message, where HMAC needs at least three SHA-256 compressions beyond the message's own.
 *
 * The tag is computed by auth.c itself (RFC 8439's ChaCha20 block and Poly1305, for the one case this
 * protocol uses: the key stream's first 32 bytes and a Poly1305 pass over the padded associated data),
 * because Mbed TLS's general AEAD path spent about 1,000 Cortex-M4F instructions per tag on work this
 * case does not need (the 64-byte key stream XORed into zeros, its buffers zeroed, the padding fed
 * through its queue); tools/bench's auth part measures both. The tags are Mbed TLS's bit for bit:
 * tests/edge/test_auth.c checks vectors of an independent implementation and Mbed TLS's own, and
 * tests/fuzz/fuzz_auth.c compares with Mbed TLS's mbedtls_chachapoly on fuzzed keys, nonces, channels
 * and messages.
 *
 * Trailer layout (TVO_AUTH_TRAILER_BYTES, big-endian like LCM's own encoding), after the message:
 *   offset 0   uint32 sender_id
 *   offset 4   uint64 counter      (> the last one the receiver accepted from this sender)
 *   offset 12  uint8  tag[16]      Poly1305 tag over AAD = channel name, 0x00, message bytes
 * nonce = sender_id (4 bytes, big-endian) || counter (8 bytes, big-endian).
 *
 * Counters: a node signs with (boot_id << TVO_AUTH_BOOT_COUNTER_BITS) | n, n = 1, 2, ... (its boot
 * id never repeats, so neither do its counters, with no clock); a plant's counters follow its wall
 * clock in microseconds (tvo_auth_follow_clock). A receiver accepts a sender it has not heard at any
 * counter and then only higher ones, for as long as it runs: what keeps a recording from before a
 * node's restart out is the boot id a START must name (lcm_types/README.md, "An authenticated bus").
 */
#ifndef TVO_AUTH_H
#define TVO_AUTH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TVO_AUTH_KEY_BYTES 32u
#define TVO_AUTH_TAG_BYTES 16u
#define TVO_AUTH_TRAILER_BYTES (4u + 8u + TVO_AUTH_TAG_BYTES)
/** Senders whose last counter a receiver remembers; a frame from one more is refused. 40: a plant of a
 *  32-robot fleet hears 32 nodes, and a node hears the plant, the hub and tools besides. */
#ifndef TVO_AUTH_MAX_SENDERS
#define TVO_AUTH_MAX_SENDERS 40u
#endif
#if TVO_AUTH_MAX_SENDERS < 1u || TVO_AUTH_MAX_SENDERS > 255u
#error "TVO_AUTH_MAX_SENDERS must lie in 1 .. 255"
#endif
/** Default sender ids: each key holder needs its own (a shared id with overlapping counters would
 *  reuse a nonce). A node that drives every robot signs as SENDER_NODE, robot k's node as
 *  SENDER_FLEET_NODE + k (--sender-id overrides), the plant as SENDER_PLANT; SENDER_FLEET_ROBOT + k
 *  is left for a radio that relays robot k's frames under its own counters (a test hub). */
#define TVO_AUTH_SENDER_NODE 1u
#define TVO_AUTH_SENDER_PLANT 2u
#define TVO_AUTH_SENDER_FLEET_NODE 0x100u
#define TVO_AUTH_SENDER_FLEET_ROBOT 0x200u

/** A node's counters: its boot id in the bits above these, its message number n >= 1 in them
 *  (2^40 messages per boot: 348 years at 100 messages per second). */
#define TVO_AUTH_BOOT_COUNTER_BITS 40u
/** The largest boot id whose counters fit (2^23 - 1: the counter stays below 2^63). */
#define TVO_AUTH_MAX_BOOT_ID ((int64_t)((UINT64_C(1) << (63u - TVO_AUTH_BOOT_COUNTER_BITS)) - 1u))

/** Longest channel name authenticated with a message (the protocol's are far shorter). */
#define TVO_AUTH_MAX_CHANNEL_BYTES 64u

/** The authentication layer's own outcomes (apart from the core's tvo_status_t). */
typedef enum {
    TVO_AUTH_OK = 0,
    TVO_AUTH_ERR_ARGUMENT,      /* NULL pointer, empty or over-long channel name, buffer too small, bad boot id */
    TVO_AUTH_ERR_NOT_KEYED,     /* the context has no key */
    TVO_AUTH_ERR_TRUNCATED,     /* shorter than a trailer: no tag to check */
    TVO_AUTH_ERR_TAG,           /* the tag does not verify: forged, altered, or another key */
    TVO_AUTH_ERR_REPLAY,        /* the counter is not above its sender's last (checked before the tag) */
    TVO_AUTH_ERR_SENDERS_FULL,  /* a valid tag from a new sender, and no room to remember it */
    TVO_AUTH_ERR_COUNTER_SPENT, /* signing: this sender's counter reached its end (its boot's range) */
    TVO_AUTH_STATUS_COUNT
} tvo_auth_status_t;

/** A short constant description of a status ("tag does not verify", ...); never NULL. */
const char *tvo_auth_status_str(tvo_auth_status_t status);

typedef struct {
    uint64_t last_counter;
    uint32_t sender_id;
} tvo_auth_sender_t;

/** One link end: the key, this end's own sender id and counter, and the senders it has heard. */
typedef struct {
    uint32_t key_words[8];                          /* the key as ChaCha20 reads it: 8 little-endian words */
    uint8_t keyed;
    uint32_t own_sender_id;
    uint64_t next_counter;                          /* the counter of the next message signed */
    uint64_t counter_end;                           /* the first counter this end may not sign */
    uint64_t (*counter_clock)(void);                /* optional: every counter signed is at least its reading */
    uint32_t sender_count;
    tvo_auth_sender_t senders[TVO_AUTH_MAX_SENDERS];
} tvo_auth_t;

/**
 * A keyed context that signs as own_sender_id from first_counter on (>= 1) and has heard no sender
 * yet. A node then calls tvo_auth_count_from_boot, a plant tvo_auth_follow_clock.
 */
tvo_auth_status_t tvo_auth_init(tvo_auth_t *auth, const uint8_t key[TVO_AUTH_KEY_BYTES], uint32_t own_sender_id,
                                uint64_t first_counter);

/**
 * Signs from (boot_id << TVO_AUTH_BOOT_COUNTER_BITS) | 1 on, and never past that boot's range
 * (TVO_AUTH_ERR_COUNTER_SPENT after 2^40 - 1 messages). boot_id in 1 .. TVO_AUTH_MAX_BOOT_ID, else
 * TVO_AUTH_ERR_ARGUMENT and nothing changes.
 */
tvo_auth_status_t tvo_auth_count_from_boot(tvo_auth_t *auth, int64_t boot_id);

/** Raises the next counter signed to at least `counter` (a sender whose counters follow a clock). */
tvo_auth_status_t tvo_auth_counter_at_least(tvo_auth_t *auth, uint64_t counter);

/**
 * Every counter signed from now on at least clock()'s reading (the host's wall clock in us:
 * tvo_auth_wall_clock_counter), so a restarted plant starts above every counter it used before.
 */
tvo_auth_status_t tvo_auth_follow_clock(tvo_auth_t *auth, uint64_t (*clock)(void));

/** Wipes the key and the senders (a key leaves memory when the context is done with). */
void tvo_auth_clear(tvo_auth_t *auth);

/**
 * Appends the trailer to message[0 .. length): writes TVO_AUTH_TRAILER_BYTES at message + length
 * (capacity >= length + TVO_AUTH_TRAILER_BYTES) and consumes one counter. *signed_length is the
 * bytes to send. On an error nothing is consumed and *signed_length is 0.
 */
tvo_auth_status_t tvo_auth_sign(tvo_auth_t *auth, const char *channel, uint8_t *message, size_t length,
                                size_t capacity, size_t *signed_length);

/**
 * Checks a received frame (message, then trailer), cheapest refusal first: too short for a trailer;
 * a sender already heard whose counter is not above its last (a replay: no tag computed); the tag;
 * a new sender with no room left. On TVO_AUTH_OK, *message_length is the message's length (the
 * trailer is not part of it) and the sender's counter is remembered. On any error the context is
 * unchanged (nothing from a refused frame is kept) and *message_length is 0.
 */
tvo_auth_status_t tvo_auth_open(tvo_auth_t *auth, const char *channel, const uint8_t *frame, size_t frame_length,
                                size_t *message_length);

/**
 * tvo_auth_sign and tvo_auth_open for a channel name whose length the caller knows: channel_length
 * bytes (1 .. TVO_AUTH_MAX_CHANNEL_BYTES, its NUL not counted; channel holds at least channel_length + 1
 * bytes, and channel[channel_length] must be the NUL, else TVO_AUTH_ERR_ARGUMENT). For a link that signs
 * and opens the same few names every period and looks their lengths up once (counting a name's bytes
 * costs about 80 Cortex-M4F instructions a tag).
 */
tvo_auth_status_t tvo_auth_sign_channel(tvo_auth_t *auth, const char *channel, size_t channel_length, uint8_t *message,
                                        size_t length, size_t capacity, size_t *signed_length);
tvo_auth_status_t tvo_auth_open_channel(tvo_auth_t *auth, const char *channel, size_t channel_length,
                                        const uint8_t *frame, size_t frame_length, size_t *message_length);

#ifdef __cplusplus
}
#endif

#endif /* TVO_AUTH_H */
