/* Message authentication: ChaCha20-Poly1305 tags over (channel, message), counters per sender. */
#include "auth.h"

#include <string.h>

#include "mbedtls/chachapoly.h"
#include "mbedtls/platform_util.h"

#define NONCE_BYTES 12u

static const char *const status_text[TVO_AUTH_STATUS_COUNT] = {
    [TVO_AUTH_OK] = "ok",
    [TVO_AUTH_ERR_ARGUMENT] = "bad argument (NULL, channel name, or buffer size)",
    [TVO_AUTH_ERR_NOT_KEYED] = "no key",
    [TVO_AUTH_ERR_TRUNCATED] = "shorter than an authentication trailer",
    [TVO_AUTH_ERR_TAG] = "tag does not verify",
    [TVO_AUTH_ERR_REPLAY] = "counter not above the sender's last (a replay)",
    [TVO_AUTH_ERR_SENDERS_FULL] = "too many senders to remember",
    [TVO_AUTH_ERR_COUNTER_SPENT] = "counter exhausted",
    [TVO_AUTH_ERR_CRYPTO] = "cryptographic library error",
};

const char *tvo_auth_status_str(tvo_auth_status_t status)
{
    if ((unsigned)status >= (unsigned)TVO_AUTH_STATUS_COUNT) {
        return "unknown authentication status";
    }
    return status_text[status];
}

static void put_be32(uint8_t *p, uint32_t v)
{
    for (unsigned i = 0u; i < 4u; ++i) {
        p[i] = (uint8_t)(v >> (24u - 8u * i));
    }
}

static void put_be64(uint8_t *p, uint64_t v)
{
    for (unsigned i = 0u; i < 8u; ++i) {
        p[i] = (uint8_t)(v >> (56u - 8u * i));
    }
}

static uint32_t get_be32(const uint8_t *p)
{
    uint32_t v = 0u;
    for (unsigned i = 0u; i < 4u; ++i) {
        v = (v << 8) | p[i];
    }
    return v;
}

static uint64_t get_be64(const uint8_t *p)
{
    uint64_t v = 0u;
    for (unsigned i = 0u; i < 8u; ++i) {
        v = (v << 8) | p[i];
    }
    return v;
}

/* Length of a channel name including its NUL, or 0 if it is empty or longer than the limit. */
static size_t channel_bytes(const char *channel)
{
    for (size_t n = 0u; n <= TVO_AUTH_MAX_CHANNEL_BYTES; ++n) {
        if (channel[n] == '\0') {
            return (n == 0u) ? 0u : n + 1u;
        }
    }
    return 0u;
}

/* The tag of (channel, message) under the nonce (sender_id, counter): the keyed cipher restarted. */
static tvo_auth_status_t compute_tag(tvo_auth_t *auth, const char *channel, size_t channel_length,
                                     const uint8_t *message, size_t length, const uint8_t trailer_head[12],
                                     uint8_t tag[TVO_AUTH_TAG_BYTES])
{
    int rc = mbedtls_chachapoly_starts(&auth->cipher, trailer_head, MBEDTLS_CHACHAPOLY_ENCRYPT);
    if (rc == 0) {
        rc = mbedtls_chachapoly_update_aad(&auth->cipher, (const unsigned char *)channel, channel_length);
    }
    if (rc == 0 && length > 0u) {
        rc = mbedtls_chachapoly_update_aad(&auth->cipher, message, length);
    }
    if (rc == 0) {
        rc = mbedtls_chachapoly_finish(&auth->cipher, tag);
    }
    return (rc == 0) ? TVO_AUTH_OK : TVO_AUTH_ERR_CRYPTO;
}

tvo_auth_status_t tvo_auth_init(tvo_auth_t *auth, const uint8_t key[TVO_AUTH_KEY_BYTES], uint32_t own_sender_id,
                                uint64_t first_counter)
{
    if (auth == NULL || key == NULL || first_counter == 0u) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    memset(auth, 0, sizeof(*auth));
    memcpy(auth->key, key, TVO_AUTH_KEY_BYTES);
    mbedtls_chachapoly_init(&auth->cipher);
    if (mbedtls_chachapoly_setkey(&auth->cipher, key) != 0) {
        mbedtls_platform_zeroize(auth, sizeof(*auth));
        return TVO_AUTH_ERR_CRYPTO;
    }
    auth->keyed = 1u;
    auth->own_sender_id = own_sender_id;
    auth->next_counter = first_counter;
    return TVO_AUTH_OK;
}

tvo_auth_status_t tvo_auth_set_new_sender_floor(tvo_auth_t *auth, uint64_t floor)
{
    if (auth == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    auth->new_sender_floor = floor;
    return TVO_AUTH_OK;
}

tvo_auth_status_t tvo_auth_counter_at_least(tvo_auth_t *auth, uint64_t counter)
{
    if (auth == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (counter > auth->next_counter) {
        auth->next_counter = counter;
    }
    return TVO_AUTH_OK;
}

tvo_auth_status_t tvo_auth_start_at(tvo_auth_t *auth, uint64_t start, uint64_t window)
{
    if (auth == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    (void)tvo_auth_counter_at_least(auth, start);
    return tvo_auth_set_new_sender_floor(auth, start > window ? start - window : 0u);
}

tvo_auth_status_t tvo_auth_follow_clock(tvo_auth_t *auth, uint64_t (*clock)(void), uint64_t window)
{
    if (auth == NULL || clock == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    auth->counter_clock = clock;
    return tvo_auth_start_at(auth, clock(), window);
}

void tvo_auth_clear(tvo_auth_t *auth)
{
    if (auth != NULL) {
        mbedtls_platform_zeroize(auth, sizeof(*auth));
    }
}

tvo_auth_status_t tvo_auth_sign(tvo_auth_t *auth, const char *channel, uint8_t *message, size_t length,
                                size_t capacity, size_t *signed_length)
{
    if (signed_length != NULL) {
        *signed_length = 0u;
    }
    if (auth == NULL || channel == NULL || message == NULL || signed_length == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (!auth->keyed) {
        return TVO_AUTH_ERR_NOT_KEYED;
    }
    const size_t name_length = channel_bytes(channel);
    if (name_length == 0u || capacity < TVO_AUTH_TRAILER_BYTES || length > capacity - TVO_AUTH_TRAILER_BYTES) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (auth->counter_clock != NULL) {
        (void)tvo_auth_counter_at_least(auth, auth->counter_clock());
    }
    if (auth->next_counter == UINT64_MAX) {
        return TVO_AUTH_ERR_COUNTER_SPENT;
    }
    uint8_t *trailer = message + length;
    put_be32(trailer, auth->own_sender_id);
    put_be64(trailer + 4u, auth->next_counter);
    const tvo_auth_status_t status =
        compute_tag(auth, channel, name_length, message, length, trailer, trailer + NONCE_BYTES);
    if (status != TVO_AUTH_OK) {
        return status;
    }
    auth->next_counter += 1u;
    *signed_length = length + TVO_AUTH_TRAILER_BYTES;
    return TVO_AUTH_OK;
}

/* The slot remembering sender_id, or -1. */
static int32_t find_sender(const tvo_auth_t *auth, uint32_t sender_id)
{
    for (uint32_t i = 0u; i < auth->sender_count && i < TVO_AUTH_MAX_SENDERS; ++i) {
        if (auth->senders[i].sender_id == sender_id) {
            return (int32_t)i;
        }
    }
    return -1;
}

tvo_auth_status_t tvo_auth_open(tvo_auth_t *auth, const char *channel, const uint8_t *frame, size_t frame_length,
                                size_t *message_length)
{
    if (message_length != NULL) {
        *message_length = 0u;
    }
    if (auth == NULL || channel == NULL || frame == NULL || message_length == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (!auth->keyed) {
        return TVO_AUTH_ERR_NOT_KEYED;
    }
    const size_t name_length = channel_bytes(channel);
    if (name_length == 0u) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (frame_length < TVO_AUTH_TRAILER_BYTES) {
        return TVO_AUTH_ERR_TRUNCATED;
    }
    const size_t length = frame_length - TVO_AUTH_TRAILER_BYTES;
    const uint8_t *trailer = frame + length;
    uint8_t expected[TVO_AUTH_TAG_BYTES];
    const tvo_auth_status_t status = compute_tag(auth, channel, name_length, frame, length, trailer, expected);
    if (status != TVO_AUTH_OK) {
        return status;
    }
    /* Constant time: a forger learns nothing from how long the comparison took. */
    uint8_t difference = 0u;
    for (unsigned i = 0u; i < TVO_AUTH_TAG_BYTES; ++i) {
        difference |= (uint8_t)(expected[i] ^ trailer[NONCE_BYTES + i]);
    }
    mbedtls_platform_zeroize(expected, sizeof(expected));
    if (difference != 0u) {
        return TVO_AUTH_ERR_TAG;
    }
    const uint32_t sender_id = get_be32(trailer);
    const uint64_t counter = get_be64(trailer + 4u);
    const int32_t slot = find_sender(auth, sender_id);
    if (slot >= 0) {
        if (counter <= auth->senders[slot].last_counter) {
            return TVO_AUTH_ERR_REPLAY;
        }
        auth->senders[slot].last_counter = counter;
    } else {
        if (counter <= auth->new_sender_floor) {
            return TVO_AUTH_ERR_REPLAY;
        }
        if (auth->sender_count >= TVO_AUTH_MAX_SENDERS) {
            return TVO_AUTH_ERR_SENDERS_FULL;
        }
        auth->senders[auth->sender_count].sender_id = sender_id;
        auth->senders[auth->sender_count].last_counter = counter;
        auth->sender_count += 1u;
    }
    *message_length = length;
    return TVO_AUTH_OK;
}
