/*
 * Message authentication for the node's links: every message in both directions carries a trailer
 * (sender id, counter, tag) after its bytes, as MAVLink 2 signs packets. Edge code: the control core
 * never sees it, and it is the same on the host (Debian's libmbedcrypto) and the board (the same
 * Mbed TLS release built from Debian's source package with tvo_mbedtls_config.h).
 *
 * The primitive is ChaCha20-Poly1305 (RFC 8439) with an empty plaintext: the message is the
 * associated data, so it travels in clear and only the 16-byte tag is added. The 96-bit nonce is
 * (sender id, counter), which a sender never repeats under one key because counters only increase;
 * the channel's name is authenticated too, so a message cannot be moved to another channel.
 * Chosen over HMAC-SHA256 for the MCU's budget: one ChaCha20 block and a Poly1305 pass over the
 * message, where HMAC needs at least three SHA-256 compressions beyond the message's own.
 *
 * Trailer layout (TVO_AUTH_TRAILER_BYTES, big-endian like LCM's own encoding), after the message:
 *   offset 0   uint32 sender_id
 *   offset 4   uint64 counter      (> the last one the receiver accepted from this sender)
 *   offset 12  uint8  tag[16]      Poly1305 tag over AAD = channel name, 0x00, message bytes
 * nonce = sender_id (4 bytes, big-endian) || counter (8 bytes, big-endian).
 */
#ifndef TVO_AUTH_H
#define TVO_AUTH_H

#include <stddef.h>
#include <stdint.h>

#include "mbedtls/chachapoly.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TVO_AUTH_KEY_BYTES 32u
#define TVO_AUTH_TAG_BYTES 16u
#define TVO_AUTH_TRAILER_BYTES (4u + 8u + TVO_AUTH_TAG_BYTES)
/** Senders whose last counter a receiver remembers; a message from one more is refused. 16: a keyed
 *  fleet node of 8 robots hears 9 (every robot's samples and the plant's sessions). */
#ifndef TVO_AUTH_MAX_SENDERS
#define TVO_AUTH_MAX_SENDERS 16u
#endif
#if TVO_AUTH_MAX_SENDERS < 1u || TVO_AUTH_MAX_SENDERS > 64u
#error "TVO_AUTH_MAX_SENDERS must lie in 1 .. 64"
#endif
/** Default sender ids: each key holder needs its own (a shared id with overlapping counters would
 *  reuse a nonce); a fleet gives each node and plant a distinct one. */
#define TVO_AUTH_SENDER_NODE 1u
#define TVO_AUTH_SENDER_PLANT 2u
/** A keyed fleet's (lcm_types/README.md, "A fleet"): robot k's node signs as FLEET_NODE + k, robot k's
 *  samples are signed as FLEET_ROBOT + k; the plant's sessions stay SENDER_PLANT's. */
#define TVO_AUTH_SENDER_FLEET_NODE 0x100u
#define TVO_AUTH_SENDER_FLEET_ROBOT 0x200u
/** How far a new sender's counter may lag the receiver's clock at start (us): older recordings are
 *  refused after a restart; two machines' clocks must agree within it. */
#define TVO_AUTH_NEW_SENDER_WINDOW_US 60000000u

/** Longest channel name authenticated with a message (the protocol's are far shorter). */
#define TVO_AUTH_MAX_CHANNEL_BYTES 64u

/** The authentication layer's own outcomes (apart from the core's tvo_status_t). */
typedef enum {
    TVO_AUTH_OK = 0,
    TVO_AUTH_ERR_ARGUMENT,      /* NULL pointer, empty or over-long channel name, buffer too small */
    TVO_AUTH_ERR_NOT_KEYED,     /* the context has no key */
    TVO_AUTH_ERR_TRUNCATED,     /* shorter than a trailer: no tag to check */
    TVO_AUTH_ERR_TAG,           /* the tag does not verify: forged, altered, or another key */
    TVO_AUTH_ERR_REPLAY,        /* a valid tag, but the counter is not above the sender's last */
    TVO_AUTH_ERR_SENDERS_FULL,  /* a valid tag from a new sender, and no room to remember it */
    TVO_AUTH_ERR_COUNTER_SPENT, /* signing: this sender's counter reached its end */
    TVO_AUTH_ERR_CRYPTO,        /* the library refused (not expected with valid arguments) */
    TVO_AUTH_STATUS_COUNT
} tvo_auth_status_t;

/** A short constant description of a status ("tag does not verify", ...); never NULL. */
const char *tvo_auth_status_str(tvo_auth_status_t status);

typedef struct {
    uint32_t sender_id;
    uint64_t last_counter;
} tvo_auth_sender_t;

/** One link end: the key, this end's own sender id and counter, and the senders it has heard. */
typedef struct {
    uint8_t key[TVO_AUTH_KEY_BYTES];
    uint8_t keyed;
    uint32_t own_sender_id;
    uint64_t next_counter;                          /* the counter of the next message signed */
    uint64_t new_sender_floor;                      /* a sender not yet heard must start above it */
    uint64_t (*counter_clock)(void);                /* optional: every counter signed is at least its reading */
    tvo_auth_sender_t senders[TVO_AUTH_MAX_SENDERS];
    uint32_t sender_count;
    /* Last: the cipher keyed once at init (keying and wiping it per message cost 440 M4F instructions);
     * every tag restarts it from its nonce, so nothing of one message reaches the next. */
    mbedtls_chachapoly_context cipher;
} tvo_auth_t;

/** Bytes of tvo_auth_t before the cipher's working state: the senders, counters and key. */
#define TVO_AUTH_STATE_BYTES offsetof(tvo_auth_t, cipher)

/**
 * A keyed context that signs as own_sender_id from first_counter on (>= 1; a restarted sender must
 * start above every counter it used before: see tvo_auth_counter_floor in the node's docs) and has
 * heard no sender yet.
 */
tvo_auth_status_t tvo_auth_init(tvo_auth_t *auth, const uint8_t key[TVO_AUTH_KEY_BYTES], uint32_t own_sender_id,
                                uint64_t first_counter);

/**
 * Refuses (TVO_AUTH_ERR_REPLAY) a sender not heard yet whose counter is <= floor: after a restart the
 * receiver has forgotten its senders, and a floor from its clock or from storage keeps an old
 * recording from being accepted as new. Senders already heard keep their own, higher, bound.
 */
tvo_auth_status_t tvo_auth_set_new_sender_floor(tvo_auth_t *auth, uint64_t floor);

/** Raises the next counter signed to at least `counter` (a sender whose counters follow a clock). */
tvo_auth_status_t tvo_auth_counter_at_least(tvo_auth_t *auth, uint64_t counter);

/**
 * A (re)started end whose counters continue from `start` (MAVLink's rule): it signs from at least
 * start, and accepts a sender not heard yet only above start - window, so a recording older than that
 * is refused after the restart. `start` comes from a clock or from storage (a board's key region).
 */
tvo_auth_status_t tvo_auth_start_at(tvo_auth_t *auth, uint64_t start, uint64_t window);

/**
 * tvo_auth_start_at(clock()), and every counter signed from then on at least clock()'s reading (the
 * host's wall clock in us: tvo_auth_wall_clock_counter). Both ends' clocks must agree within window.
 */
tvo_auth_status_t tvo_auth_follow_clock(tvo_auth_t *auth, uint64_t (*clock)(void), uint64_t window);

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
 * Checks a received frame (message, then trailer). On TVO_AUTH_OK, *message_length is the message's
 * length (the trailer is not part of it) and the sender's counter is remembered. On any error the
 * context is unchanged (nothing from a refused frame is kept) and *message_length is 0.
 */
tvo_auth_status_t tvo_auth_open(tvo_auth_t *auth, const char *channel, const uint8_t *frame, size_t frame_length,
                                size_t *message_length);

#ifdef __cplusplus
}
#endif

#endif /* TVO_AUTH_H */
