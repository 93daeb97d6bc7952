/* Message authentication: ChaCha20-Poly1305 tags over (channel, message), counters per sender. */
#include "auth.h"

#include <string.h>

#include "mbedtls/platform_util.h"

#define NONCE_BYTES 12u
#define BLOCK_BYTES 16u

static const char *const status_text[TVO_AUTH_STATUS_COUNT] = {
    [TVO_AUTH_OK] = "ok",
    [TVO_AUTH_ERR_ARGUMENT] = "bad argument (NULL, channel name, buffer size or boot id)",
    [TVO_AUTH_ERR_NOT_KEYED] = "no key",
    [TVO_AUTH_ERR_TRUNCATED] = "shorter than an authentication trailer",
    [TVO_AUTH_ERR_TAG] = "tag does not verify",
    [TVO_AUTH_ERR_REPLAY] = "counter not above the sender's last (a replay)",
    [TVO_AUTH_ERR_SENDERS_FULL] = "too many senders to remember",
    [TVO_AUTH_ERR_COUNTER_SPENT] = "counter exhausted",
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
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static uint32_t get_be32(const uint8_t *p)
{
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | (uint32_t)p[3];
}

static uint64_t get_be64(const uint8_t *p)
{
    return ((uint64_t)get_be32(p) << 32) | get_be32(p + 4u);
}

/* RFC 8439 reads bytes as little-endian words; on a little-endian machine one (unaligned) load. */
static inline uint32_t get_le32(const uint8_t *p)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint32_t v;
    memcpy(&v, p, sizeof(v));
    return v;
#else
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
#endif
}

static inline void put_le32(uint8_t *p, uint32_t v)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    memcpy(p, &v, sizeof(v));
#else
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
#endif
}

/* ---- The tag: RFC 8439 section 2.8 with an empty plaintext, computed for exactly that case. ---- */

#define ROTL32(v, n) (((v) << (n)) | ((v) >> (32u - (n))))
#define QUARTER_ROUND(a, b, c, d)                                                                                      \
    do {                                                                                                               \
        a += b;                                                                                                        \
        d ^= a;                                                                                                        \
        d = ROTL32(d, 16u);                                                                                            \
        c += d;                                                                                                        \
        b ^= c;                                                                                                        \
        b = ROTL32(b, 12u);                                                                                            \
        a += b;                                                                                                        \
        d ^= a;                                                                                                        \
        d = ROTL32(d, 8u);                                                                                             \
        c += d;                                                                                                        \
        b ^= c;                                                                                                        \
        b = ROTL32(b, 7u);                                                                                             \
    } while (0)

/* The one-time Poly1305 key: the first 32 bytes of ChaCha20's block 0 under (key, nonce), as words. */
typedef struct {
    uint32_t r[4]; /* clamped (RFC 8439 2.5) */
    uint32_t s[4];
} one_time_key_t;

/* RFC 8439 2.3 for block counter 0, keeping only the output words 0..7 (the rest would be key stream
 * for a plaintext, which this protocol does not have). */
static void one_time_key(const uint32_t key[8], const uint8_t nonce[NONCE_BYTES], one_time_key_t *otk)
{
    uint32_t x0 = 0x61707865u, x1 = 0x3320646eu, x2 = 0x79622d32u, x3 = 0x6b206574u; /* "expand 32-byte k" */
    uint32_t x4 = key[0], x5 = key[1], x6 = key[2], x7 = key[3];
    uint32_t x8 = key[4], x9 = key[5], x10 = key[6], x11 = key[7];
    uint32_t x12 = 0u, x13 = get_le32(nonce), x14 = get_le32(nonce + 4u), x15 = get_le32(nonce + 8u);
    for (unsigned double_round = 0u; double_round < 10u; ++double_round) {
        QUARTER_ROUND(x0, x4, x8, x12);
        QUARTER_ROUND(x1, x5, x9, x13);
        QUARTER_ROUND(x2, x6, x10, x14);
        QUARTER_ROUND(x3, x7, x11, x15);
        QUARTER_ROUND(x0, x5, x10, x15);
        QUARTER_ROUND(x1, x6, x11, x12);
        QUARTER_ROUND(x2, x7, x8, x13);
        QUARTER_ROUND(x3, x4, x9, x14);
    }
    otk->r[0] = (x0 + 0x61707865u) & 0x0fffffffu;
    otk->r[1] = (x1 + 0x3320646eu) & 0x0ffffffcu;
    otk->r[2] = (x2 + 0x79622d32u) & 0x0ffffffcu;
    otk->r[3] = (x3 + 0x6b206574u) & 0x0ffffffcu;
    otk->s[0] = x4 + key[0];
    otk->s[1] = x5 + key[1];
    otk->s[2] = x6 + key[2];
    otk->s[3] = x7 + key[3];
}

/* Poly1305's accumulator, 130 bits in radix 2^32 (acc[4] holds the top bits). */
typedef struct {
    uint32_t acc[5];
} poly_acc_t;

/* Whole 16-byte blocks of the padded AAD, in order: some in place, some assembled (the channel's end
 * joined to the message's start, the message's zero-padded end, the lengths block). */
typedef struct {
    const uint8_t *data;
    size_t blocks;
} poly_segment_t;

#define POLY_SEGMENTS 5u

/* acc = (acc + block + 2^128) * r mod 2^130 - 5 (partly reduced), for every block of the segments: the
 * AEAD pads its associated data with zeros to whole blocks, so every block carries the 2^128 bit. The
 * arithmetic of Mbed TLS's poly1305_process (32x32 -> 64-bit products, r's top bits pre-scaled by 5/4),
 * in one pass so r stays in registers. */
static void poly_blocks(poly_acc_t *poly, const one_time_key_t *otk, const poly_segment_t *segments, size_t count)
{
    const uint32_t r0 = otk->r[0], r1 = otk->r[1], r2 = otk->r[2], r3 = otk->r[3];
    const uint32_t rs1 = r1 + (r1 >> 2), rs2 = r2 + (r2 >> 2), rs3 = r3 + (r3 >> 2);
    uint32_t a0 = 0u, a1 = 0u, a2 = 0u, a3 = 0u, a4 = 0u;
    for (size_t s = 0u; s < count && s < POLY_SEGMENTS; ++s) {
        const uint8_t *in = segments[s].data;
        for (size_t b = 0u; b < segments[s].blocks; ++b, in += BLOCK_BYTES) {
            uint64_t d0 = (uint64_t)a0 + get_le32(in);
            uint64_t d1 = (uint64_t)a1 + get_le32(in + 4u) + (d0 >> 32);
            uint64_t d2 = (uint64_t)a2 + get_le32(in + 8u) + (d1 >> 32);
            uint64_t d3 = (uint64_t)a3 + get_le32(in + 12u) + (d2 >> 32);
            a0 = (uint32_t)d0;
            a1 = (uint32_t)d1;
            a2 = (uint32_t)d2;
            a3 = (uint32_t)d3;
            a4 += (uint32_t)(d3 >> 32) + 1u;
            d0 = (uint64_t)a0 * r0 + (uint64_t)a1 * rs3 + (uint64_t)a2 * rs2 + (uint64_t)a3 * rs1;
            d1 = (uint64_t)a0 * r1 + (uint64_t)a1 * r0 + (uint64_t)a2 * rs3 + (uint64_t)a3 * rs2 + (uint64_t)a4 * rs1;
            d2 = (uint64_t)a0 * r2 + (uint64_t)a1 * r1 + (uint64_t)a2 * r0 + (uint64_t)a3 * rs3 + (uint64_t)a4 * rs2;
            d3 = (uint64_t)a0 * r3 + (uint64_t)a1 * r2 + (uint64_t)a2 * r1 + (uint64_t)a3 * r0 + (uint64_t)a4 * rs3;
            a4 *= r0;
            d1 += d0 >> 32;
            d2 += d1 >> 32;
            d3 += d2 >> 32;
            a0 = (uint32_t)d0;
            a1 = (uint32_t)d1;
            a2 = (uint32_t)d2;
            a3 = (uint32_t)d3;
            a4 += (uint32_t)(d3 >> 32);
            /* The bits above 2^130 fold back times 5 (2^130 = 5 mod p). */
            d0 = (uint64_t)a0 + (a4 >> 2) + (a4 & 0xfffffffcu);
            a4 &= 3u;
            a0 = (uint32_t)d0;
            d0 = (uint64_t)a1 + (d0 >> 32);
            a1 = (uint32_t)d0;
            d0 = (uint64_t)a2 + (d0 >> 32);
            a2 = (uint32_t)d0;
            d0 = (uint64_t)a3 + (d0 >> 32);
            a3 = (uint32_t)d0;
            a4 += (uint32_t)(d0 >> 32);
        }
    }
    poly->acc[0] = a0;
    poly->acc[1] = a1;
    poly->acc[2] = a2;
    poly->acc[3] = a3;
    poly->acc[4] = a4;
}

/* The tag: acc fully reduced mod 2^130 - 5 (in constant time), plus s, its low 128 bits. */
static void poly_finish(const poly_acc_t *poly, const one_time_key_t *otk, uint8_t tag[TVO_AUTH_TAG_BYTES])
{
    uint32_t a0 = poly->acc[0], a1 = poly->acc[1], a2 = poly->acc[2], a3 = poly->acc[3];
    uint64_t d = (uint64_t)a0 + 5u;
    const uint32_t g0 = (uint32_t)d;
    d = (uint64_t)a1 + (d >> 32);
    const uint32_t g1 = (uint32_t)d;
    d = (uint64_t)a2 + (d >> 32);
    const uint32_t g2 = (uint32_t)d;
    d = (uint64_t)a3 + (d >> 32);
    const uint32_t g3 = (uint32_t)d;
    const uint32_t g4 = poly->acc[4] + (uint32_t)(d >> 32);
    const uint32_t take_g = 0u - (g4 >> 2); /* all ones when acc >= 2^130 - 5 */
    a0 = (a0 & ~take_g) | (g0 & take_g);
    a1 = (a1 & ~take_g) | (g1 & take_g);
    a2 = (a2 & ~take_g) | (g2 & take_g);
    a3 = (a3 & ~take_g) | (g3 & take_g);
    d = (uint64_t)a0 + otk->s[0];
    put_le32(tag, (uint32_t)d);
    d = (uint64_t)a1 + otk->s[1] + (d >> 32);
    put_le32(tag + 4u, (uint32_t)d);
    d = (uint64_t)a2 + otk->s[2] + (d >> 32);
    put_le32(tag + 8u, (uint32_t)d);
    put_le32(tag + 12u, a3 + otk->s[3] + (uint32_t)(d >> 32));
}

/* Wipes the one-time key: word stores the compiler must keep (cheaper than a call per tag). */
static void wipe_one_time_key(one_time_key_t *otk)
{
    volatile uint32_t *words = (volatile uint32_t *)otk;
    for (unsigned i = 0u; i < sizeof(*otk) / sizeof(uint32_t); ++i) {
        words[i] = 0u;
    }
}

/* Copies n < BLOCK_BYTES bytes into block at `at` (a short loop: cheaper than a library call here). */
static void put_bytes(uint8_t block[BLOCK_BYTES], size_t at, const uint8_t *bytes, size_t n)
{
    for (size_t i = 0u; i < n && at + i < BLOCK_BYTES; ++i) {
        block[at + i] = bytes[i];
    }
}

/* The tag of AAD = channel (channel_length bytes, its NUL included) || message under the nonce. */
static void compute_tag(const tvo_auth_t *auth, const char *channel, size_t channel_length, const uint8_t *message,
                        size_t length, const uint8_t nonce[NONCE_BYTES], uint8_t tag[TVO_AUTH_TAG_BYTES])
{
    one_time_key_t otk;
    poly_acc_t poly;
    /* Public bytes only (channel, message, lengths): not wiped. */
    uint8_t joined[BLOCK_BYTES] = {0u};
    uint8_t tail[BLOCK_BYTES] = {0u};
    uint8_t lengths[BLOCK_BYTES] = {0u};
    poly_segment_t segments[POLY_SEGMENTS];
    size_t count = 0u;
    one_time_key(auth->key_words, nonce, &otk);
    /* The channel's whole blocks (none for the protocol's names), then its rest joined to the message's
     * first bytes in one block, the message's whole blocks in place, its rest padded with zeros. */
    const size_t channel_whole = channel_length / BLOCK_BYTES;
    const size_t channel_rest = channel_length % BLOCK_BYTES;
    segments[count++] = (poly_segment_t){(const uint8_t *)channel, channel_whole};
    size_t taken = 0u;
    if (channel_rest > 0u) {
        taken = BLOCK_BYTES - channel_rest < length ? BLOCK_BYTES - channel_rest : length;
        put_bytes(joined, 0u, (const uint8_t *)channel + channel_length - channel_rest, channel_rest);
        put_bytes(joined, channel_rest, message, taken);
        segments[count++] = (poly_segment_t){joined, 1u};
    }
    segments[count++] = (poly_segment_t){message + taken, (length - taken) / BLOCK_BYTES};
    const size_t rest = (length - taken) % BLOCK_BYTES;
    if (rest > 0u) {
        put_bytes(tail, 0u, message + length - rest, rest);
        segments[count++] = (poly_segment_t){tail, 1u};
    }
    /* The lengths block: the AAD's length and the ciphertext's (0), little-endian 64-bit each. */
    const uint64_t aad_length = (uint64_t)channel_length + length;
    put_le32(lengths, (uint32_t)aad_length);
    put_le32(lengths + 4u, (uint32_t)(aad_length >> 32));
    segments[count++] = (poly_segment_t){lengths, 1u};
    poly_blocks(&poly, &otk, segments, count);
    poly_finish(&poly, &otk, tag);
    wipe_one_time_key(&otk);
}

/* ---- Counters and senders. ---- */

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

tvo_auth_status_t tvo_auth_init(tvo_auth_t *auth, const uint8_t key[TVO_AUTH_KEY_BYTES], uint32_t own_sender_id,
                                uint64_t first_counter)
{
    if (auth == NULL || key == NULL || first_counter == 0u) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    memset(auth, 0, sizeof(*auth));
    for (unsigned i = 0u; i < 8u; ++i) {
        auth->key_words[i] = get_le32(key + 4u * i);
    }
    auth->keyed = 1u;
    auth->own_sender_id = own_sender_id;
    auth->next_counter = first_counter;
    auth->counter_end = UINT64_MAX;
    return TVO_AUTH_OK;
}

tvo_auth_status_t tvo_auth_count_from_boot(tvo_auth_t *auth, int64_t boot_id)
{
    if (auth == NULL || boot_id < 1 || boot_id > TVO_AUTH_MAX_BOOT_ID) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    auth->next_counter = ((uint64_t)boot_id << TVO_AUTH_BOOT_COUNTER_BITS) | 1u;
    auth->counter_end = ((uint64_t)boot_id + 1u) << TVO_AUTH_BOOT_COUNTER_BITS;
    auth->counter_clock = NULL;
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

tvo_auth_status_t tvo_auth_follow_clock(tvo_auth_t *auth, uint64_t (*clock)(void))
{
    if (auth == NULL || clock == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    auth->counter_clock = clock;
    return tvo_auth_counter_at_least(auth, clock());
}

void tvo_auth_clear(tvo_auth_t *auth)
{
    if (auth != NULL) {
        mbedtls_platform_zeroize(auth, sizeof(*auth));
    }
}

/* The name's bytes with its NUL if channel[channel_length] is its NUL and the length is in range, else 0. */
static size_t known_channel_bytes(const char *channel, size_t channel_length)
{
    return (channel != NULL && channel_length >= 1u && channel_length <= TVO_AUTH_MAX_CHANNEL_BYTES &&
            channel[channel_length] == '\0')
               ? channel_length + 1u
               : 0u;
}

tvo_auth_status_t tvo_auth_sign(tvo_auth_t *auth, const char *channel, uint8_t *message, size_t length,
                                size_t capacity, size_t *signed_length)
{
    const size_t name_length = channel != NULL ? channel_bytes(channel) : 0u;
    return tvo_auth_sign_channel(auth, channel, name_length > 0u ? name_length - 1u : 0u, message, length, capacity,
                                 signed_length);
}

tvo_auth_status_t tvo_auth_sign_channel(tvo_auth_t *auth, const char *channel, size_t channel_length, uint8_t *message,
                                        size_t length, size_t capacity, size_t *signed_length)
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
    const size_t name_length = known_channel_bytes(channel, channel_length);
    if (name_length == 0u || capacity < TVO_AUTH_TRAILER_BYTES || length > capacity - TVO_AUTH_TRAILER_BYTES) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (auth->counter_clock != NULL) {
        (void)tvo_auth_counter_at_least(auth, auth->counter_clock());
    }
    if (auth->next_counter >= auth->counter_end) {
        return TVO_AUTH_ERR_COUNTER_SPENT;
    }
    uint8_t *trailer = message + length;
    put_be32(trailer, auth->own_sender_id);
    put_be32(trailer + 4u, (uint32_t)(auth->next_counter >> 32));
    put_be32(trailer + 8u, (uint32_t)auth->next_counter);
    compute_tag(auth, channel, name_length, message, length, trailer, trailer + NONCE_BYTES);
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
    const size_t name_length = channel != NULL ? channel_bytes(channel) : 0u;
    return tvo_auth_open_channel(auth, channel, name_length > 0u ? name_length - 1u : 0u, frame, frame_length,
                                 message_length);
}

tvo_auth_status_t tvo_auth_open_channel(tvo_auth_t *auth, const char *channel, size_t channel_length,
                                        const uint8_t *frame, size_t frame_length, size_t *message_length)
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
    const size_t name_length = known_channel_bytes(channel, channel_length);
    if (name_length == 0u) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    if (frame_length < TVO_AUTH_TRAILER_BYTES) {
        return TVO_AUTH_ERR_TRUNCATED;
    }
    const size_t length = frame_length - TVO_AUTH_TRAILER_BYTES;
    const uint8_t *trailer = frame + length;
    const uint32_t sender_id = get_be32(trailer);
    const uint64_t counter = get_be64(trailer + 4u);
    const int32_t slot = find_sender(auth, sender_id);
    /* A counter a known sender has used: a replay, refused before any cryptography is spent on it. */
    if (slot >= 0 && counter <= auth->senders[slot].last_counter) {
        return TVO_AUTH_ERR_REPLAY;
    }
    uint8_t expected[TVO_AUTH_TAG_BYTES];
    compute_tag(auth, channel, name_length, frame, length, trailer, expected);
    /* Constant time: a forger learns nothing from how long the comparison took. */
    uint32_t difference = 0u;
    for (unsigned i = 0u; i < TVO_AUTH_TAG_BYTES; i += 4u) {
        difference |= get_le32(expected + i) ^ get_le32(trailer + NONCE_BYTES + i);
    }
    if (difference != 0u) {
        return TVO_AUTH_ERR_TAG;
    }
    if (slot >= 0) {
        auth->senders[slot].last_counter = counter;
    } else {
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
