/*
 * Message authentication under fuzzed input, two ways per input:
 *
 * 1. Differential: auth.c computes the RFC 8439 tag itself, and it must equal Mbed TLS's
 *    (mbedtls_chachapoly, Debian's libmbedcrypto) for any key, sender, counter, channel name (1 .. 64
 *    bytes) and message taken from the input; the frame must open, and open no more once any one bit of
 *    it is flipped.
 * 2. The keyed node's entry (auth_link.c in front of node.c): a genuine signed session naming the node's
 *    boot (variant from the first input byte), then a stream of frames that are raw (as a forger sends
 *    them), signed with the key, signed and then altered, signed with the counter already used, or
 *    signed messages of their channel's own length and fingerprint with fuzzed content. Invariants: a
 *    frame the link drops is counted (malformed, unauthenticated or replayed: exactly one of them),
 *    publishes nothing and changes neither the node's sessions nor the link's senders; a genuine frame
 *    of its channel's shape is never dropped by the link; every frame the node publishes opens with the
 *    key, carries a counter (boot << 40) | n above the last, and decodes; a command is finite.
 * Record format of part 2 after the variant byte: mode (1 byte: 0 raw, 1 signed, 2 signed then one bit
 * flipped at the index in the next byte, 3 signed with the last counter again, 4 signed with the
 * channel's own length and fingerprint), channel (1 byte: 0 .. 10, so unknown and output channels
 * too), length (2 bytes LE), clock step (1 byte, x 500 us), [flip index,] then `length` bytes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auth_link.h"
#include "mbedtls/chachapoly.h"

#define BOOT_ID 1234
#define FRAME_CAPACITY (TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES)

static tvo_node_t node;
static tvo_auth_link_t link;
static tvo_auth_t plant;      /* signs the plant's frames */
static tvo_auth_t listener;   /* opens the node's */
static tvo_lcm_session_t session;
static int published;
static uint64_t last_node_counter;
static uint8_t frame[FRAME_CAPACITY];
static const uint8_t key[TVO_AUTH_KEY_BYTES] = {7, 1, 8, 2, 8, 1, 8, 2, 8, 4, 5, 9, 0, 4, 5, 2,
                                                3, 5, 3, 6, 0, 2, 8, 7, 4, 7, 1, 3, 5, 2, 6, 6};

static void fuzz_fail(const char *invariant)
{
    fprintf(stderr, "fuzz_auth: invariant broken: %s\n", invariant);
    abort();
}

/* ---- 1. The tag against Mbed TLS's. ---- */

static void differential(const uint8_t *data, size_t size)
{
    static uint8_t message[1024 + TVO_AUTH_TRAILER_BYTES];
    static uint8_t aad[TVO_AUTH_MAX_CHANNEL_BYTES + 1u + 1024u];
    if (size < TVO_AUTH_KEY_BYTES + 12u + 2u) {
        return;
    }
    const uint8_t *k = data;
    const uint8_t *nonce = data + TVO_AUTH_KEY_BYTES;
    const size_t name_length = 1u + data[TVO_AUTH_KEY_BYTES + 12u] % TVO_AUTH_MAX_CHANNEL_BYTES;
    const uint8_t flip = data[TVO_AUTH_KEY_BYTES + 13u];
    const uint8_t *rest = data + TVO_AUTH_KEY_BYTES + 14u;
    size_t rest_length = size - (TVO_AUTH_KEY_BYTES + 14u);
    char channel[TVO_AUTH_MAX_CHANNEL_BYTES + 1u];
    for (size_t i = 0u; i < name_length; ++i) {
        channel[i] = (char)(1u + (i < rest_length ? rest[i] % 255u : (uint8_t)i)); /* never NUL */
    }
    channel[name_length] = '\0';
    const size_t skip = name_length < rest_length ? name_length : rest_length;
    const uint8_t *bytes = rest + skip;
    size_t length = rest_length - skip;
    if (length > 1024u) {
        length = 1024u;
    }
    uint32_t sender = 0u;
    uint64_t counter = 0u;
    for (unsigned i = 0u; i < 4u; ++i) {
        sender = (sender << 8) | nonce[i];
    }
    for (unsigned i = 4u; i < 12u; ++i) {
        counter = (counter << 8) | nonce[i];
    }
    if (counter == 0u || counter == UINT64_MAX) {
        return; /* a signer's counters lie in 1 .. 2^64 - 2 */
    }
    tvo_auth_t signer;
    size_t signed_length = 0u;
    memcpy(message, bytes, length);
    if (tvo_auth_init(&signer, k, sender, counter) != TVO_AUTH_OK ||
        tvo_auth_sign(&signer, channel, message, length, sizeof(message), &signed_length) != TVO_AUTH_OK ||
        signed_length != length + TVO_AUTH_TRAILER_BYTES) {
        fuzz_fail("a valid frame could not be signed");
    }
    if (memcmp(message + length, nonce, 12u) != 0) {
        fuzz_fail("the trailer's sender and counter are not the nonce");
    }
    /* Mbed TLS's tag of the same: key, nonce, AAD = channel, NUL, message, empty plaintext. */
    memcpy(aad, channel, name_length + 1u);
    memcpy(aad + name_length + 1u, bytes, length);
    uint8_t expected[TVO_AUTH_TAG_BYTES];
    mbedtls_chachapoly_context cipher;
    mbedtls_chachapoly_init(&cipher);
    if (mbedtls_chachapoly_setkey(&cipher, k) != 0 ||
        mbedtls_chachapoly_encrypt_and_tag(&cipher, 0u, nonce, aad, name_length + 1u + length, NULL, NULL, expected) != 0) {
        fuzz_fail("Mbed TLS refused a valid tag");
    }
    mbedtls_chachapoly_free(&cipher);
    if (memcmp(expected, message + length + 12u, TVO_AUTH_TAG_BYTES) != 0) {
        fuzz_fail("auth.c's tag differs from Mbed TLS's");
    }
    tvo_auth_t receiver;
    size_t opened = 0u;
    if (tvo_auth_init(&receiver, k, 0u, 1u) != TVO_AUTH_OK ||
        tvo_auth_open(&receiver, channel, message, signed_length, &opened) != TVO_AUTH_OK || opened != length) {
        fuzz_fail("a signed frame does not open");
    }
    tvo_auth_t fresh;
    (void)tvo_auth_init(&fresh, k, 0u, 1u);
    const size_t bit = (size_t)flip * 131u % (8u * signed_length);
    message[bit / 8u] ^= (uint8_t)(1u << (bit % 8u));
    if (tvo_auth_open(&fresh, channel, message, signed_length, &opened) == TVO_AUTH_OK) {
        fuzz_fail("a frame with a flipped bit opens");
    }
}

/* ---- 2. The keyed node. ---- */

static void transport(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    published++;
    size_t message_length = 0u;
    const char *name = tvo_node_channel_name(channel);
    if (name == NULL || tvo_auth_open(&listener, name, data, length, &message_length) != TVO_AUTH_OK) {
        fuzz_fail("the node published a frame that does not open with the key");
    }
    uint64_t counter = 0u;
    for (unsigned i = 0u; i < 8u; ++i) {
        counter = (counter << 8) | data[message_length + 4u + i];
    }
    if ((counter >> TVO_AUTH_BOOT_COUNTER_BITS) != BOOT_ID || counter <= last_node_counter) {
        fuzz_fail("a node counter outside its boot's range or not above the last");
    }
    last_node_counter = counter;
    if (message_length != tvo_node_channel_message_bytes(channel)) {
        fuzz_fail("the node published a message of another length than its channel's");
    }
    if (channel == TVO_NODE_CH_COMMAND) {
        tvo_lcm_unicycle_command_t command;
        if (tvo_lcm_unicycle_command_t_decode(data, 0, (int)message_length, &command) != (int)message_length) {
            fuzz_fail("the node published a command that does not decode");
        }
        if (!isfinite(command.speed_mps) || !isfinite(command.turn_rate_radps)) {
            fuzz_fail("a command is not finite");
        }
        if ((command.header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0 &&
            (command.speed_mps != 0.0f || command.turn_rate_radps != 0.0f)) {
            fuzz_fail("a safe stop is not all zero");
        }
    }
}

/* A genuine START naming the node's boot: the clock and the robot count from the variant byte. */
static void make_session(uint8_t variant)
{
    const int32_t robots = 1 + (int32_t)((variant >> 1) % (uint8_t)TVO_NODE_MAX_ROBOTS);
    (void)tvo_protocol_default_start(&session, robots); /* 1 .. TVO_NODE_MAX_ROBOTS: in range */
    session.utime = 5000000;
    session.session_id = 77;
    for (int32_t r = 0; r < robots; ++r) {
        session.node_boot_id[r] = BOOT_ID;
        session.robot[r].target.kind = TVO_LCM_PATH_T_KIND_CIRCLE;
        session.robot[r].target.center_m[0] = 3.0 * r;
        session.robot[r].target.semi_axis_m[0] = 1.0;
        session.robot[r].target.omega_radps = 0.5;
    }
    session.clock_source = (variant & 1u) ? TVO_LCM_SESSION_T_CLOCK_NODE : TVO_LCM_SESSION_T_CLOCK_PLANT;
    session.epoch_utime = 5200000;
    session.watchdog_periods = 5;
    session.omega_max_radps = 6.0;
    session.speed_max_mps = 2.0;
}

static int64_t fingerprint_of(int channel)
{
    switch (channel) {
    case TVO_NODE_CH_SESSION: return __tvo_lcm_session_t_get_hash();
    case TVO_NODE_CH_SAMPLE: return __tvo_lcm_unicycle_sample_t_get_hash();
    case TVO_NODE_CH_TARGET: return __tvo_lcm_target_t_get_hash();
    case TVO_NODE_CH_CHAIN_SAMPLE: return __tvo_lcm_chain_sample_t_get_hash();
    default: return 0;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    differential(data, size);
    if (size < 1) {
        return 0;
    }
    published = 0;
    last_node_counter = 0u;
    if (tvo_auth_link_init(&link, key, TVO_AUTH_SENDER_NODE, BOOT_ID, transport, NULL) != TVO_AUTH_OK ||
        tvo_auth_init(&plant, key, TVO_AUTH_SENDER_PLANT, 1000u) != TVO_AUTH_OK ||
        tvo_auth_init(&listener, key, 99u, 1u) != TVO_AUTH_OK ||
        tvo_node_init(&node, -1, BOOT_ID, tvo_auth_link_publish, &link) != 0) {
        fuzz_fail("set-up failed");
    }
    make_session(data[0]);
    int64_t now = 5000000;
    (void)tvo_node_poll(&node, now);
    const int n = tvo_lcm_session_t_encode(frame, 0, (int)TVO_NODE_LARGEST_MESSAGE_BYTES, &session);
    size_t length = 0u;
    if (n <= 0 || tvo_auth_sign(&plant, TVO_CHANNEL_SESSION, frame, (size_t)n, sizeof(frame), &length) != TVO_AUTH_OK) {
        fuzz_fail("the reference session could not be signed");
    }
    tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SESSION, frame, (uint32_t)length, now);
    if (tvo_node_session(&node) == NULL) {
        fuzz_fail("the signed reference session was refused");
    }
    size_t i = 1;
    while (i + 5 <= size) {
        const uint8_t mode = data[i] % 5u;
        const int channel = data[i + 1] % 11;
        size_t message_length = (size_t)data[i + 2] | ((size_t)data[i + 3] << 8);
        now += 500 * (int64_t)data[i + 4];
        i += 5;
        size_t flip = 0u;
        if (mode == 2u && i < size) {
            flip = data[i++];
        }
        if (message_length > size - i) {
            message_length = size - i;
        }
        if (message_length > TVO_NODE_LARGEST_MESSAGE_BYTES) {
            message_length = TVO_NODE_LARGEST_MESSAGE_BYTES;
        }
        memcpy(frame, data + i, message_length);
        i += message_length;
        const char *name = tvo_node_channel_name(channel);
        int shaped = 0; /* signed, of its channel's length and fingerprint: the link must pass it */
        if (mode == 4u && tvo_node_channel_is_input(channel)) {
            const size_t bytes = tvo_node_channel_message_bytes(channel);
            if (bytes > message_length) {
                memset(frame + message_length, 0, bytes - message_length);
            }
            message_length = bytes;
            const uint64_t fingerprint = (uint64_t)fingerprint_of(channel);
            for (unsigned b = 0u; b < 8u; ++b) {
                frame[b] = (uint8_t)(fingerprint >> (56u - 8u * b));
            }
            shaped = 1;
        }
        size_t frame_length = message_length;
        if (mode != 0u && name != NULL) {
            if (mode == 3u && plant.next_counter > 1000u) {
                plant.next_counter -= 1u; /* the counter of the last frame signed: a replay */
            }
            if (tvo_auth_sign(&plant, name, frame, message_length, sizeof(frame), &frame_length) != TVO_AUTH_OK) {
                fuzz_fail("a frame could not be signed");
            }
            if (mode == 2u && frame_length > 0u) {
                frame[flip % frame_length] ^= (uint8_t)(1u << (flip % 8u));
            }
        } else {
            shaped = 0;
        }
        static tvo_node_session_t slots_before[2];
        static tvo_auth_t auth_before;
        static tvo_lcm_node_counters_t counters_before;
        memcpy(slots_before, node.slot, sizeof(slots_before));
        const uint8_t state_before = node.state;
        auth_before = link.auth;
        counters_before = *tvo_node_counters(&node);
        const uint32_t drops_before = link.drops;
        const int published_before = published;
        (void)tvo_auth_link_receive(&link, &node, channel, frame, (uint32_t)frame_length, now);
        const tvo_lcm_node_counters_t *after = tvo_node_counters(&node);
        if (link.drops != drops_before) {
            if (shaped) {
                fuzz_fail("the link dropped a genuine frame of its channel's shape");
            }
            if (published != published_before) {
                fuzz_fail("a dropped frame was answered");
            }
            if (memcmp(&link.auth, &auth_before, sizeof(auth_before)) != 0) {
                fuzz_fail("a dropped frame changed the link's senders");
            }
            if (memcmp(slots_before, node.slot, sizeof(slots_before)) != 0 || state_before != node.state) {
                fuzz_fail("a dropped frame changed the node");
            }
            const int32_t counted = (after->malformed - counters_before.malformed) +
                                    (after->unauthenticated - counters_before.unauthenticated) +
                                    (after->replayed - counters_before.replayed);
            if (counted != 1) {
                fuzz_fail("a dropped frame was not counted exactly once");
            }
        }
        (void)tvo_node_poll(&node, now);
    }
    return 0;
}
