/*
 * Cost of message authentication on the board, under qemu -icount shift=0 (tools/bench --auth-only):
 *
 * 1. Signing and verifying (tvo_auth_sign / tvo_auth_open) each message of the wire as the node sends
 *    and receives it (LCM-encoded, on its channel), AUTH_REPEATS times with rising counters, each call
 *    bracketed by the cycle counter: "AUTH <message> bytes <n> sign <median> verify <median>".
 * 2. The same tag through Mbed TLS's mbedtls_chachapoly (starts, two update_aad, finish: what auth.c
 *    called before it computed the tag itself), the median of AUTH_REPEATS, and whether its tag is auth.c's:
 *    "AUTH_MBEDTLS <message> instr <median> same <0|1>" (a 0 fails the bench).
 * 3. Where Mbed TLS's fixed cost of a tag goes: each part called AUTH_PART_CALLS times between two
 *    counter reads, so the resolution is a tick over AUTH_PART_CALLS: "AUTH_PART <name> <instructions>".
 *
 * Instructions are counter ticks times the board's instructions per tick. The key is a fixed test key:
 * the figures do not depend on its value. Ends with "AUTH_DONE".
 */
#include <stdint.h>
#include <string.h>

#include "auth.h"
#include "board.h"
#include "channels.h"
#include "mbedtls/chacha20.h"
#include "mbedtls/chachapoly.h"
#include "mbedtls/platform_util.h"
#include "mbedtls/poly1305.h"
#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

#define AUTH_REPEATS 33u
#define AUTH_PART_CALLS 64u

int main(void);

static uint8_t frame[512];
static uint32_t sign_ticks[AUTH_REPEATS];
static uint32_t verify_ticks[AUTH_REPEATS];
static uint32_t mbedtls_ticks[AUTH_REPEATS];
static tvo_auth_t sender;
static tvo_auth_t receiver;
static mbedtls_chachapoly_context chachapoly;
static mbedtls_chacha20_context chacha20;
static mbedtls_poly1305_context poly1305;
static uint8_t key[TVO_AUTH_KEY_BYTES];

/* Insertion sort of a few values: bounded, no library. */
static uint32_t median_instructions(uint32_t *values, uint32_t count)
{
    for (uint32_t i = 1u; i < count; ++i) {
        const uint32_t v = values[i];
        uint32_t j = i;
        while (j > 0u && values[j - 1u] > v) {
            values[j] = values[j - 1u];
            --j;
        }
        values[j] = v;
    }
    return (uint32_t)(((uint64_t)values[count / 2u] * TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM) /
                      TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN);
}

static void fail(const char *what)
{
    tvo_board_puts("AUTH_ERROR ");
    tvo_board_puts(what);
    tvo_board_puts("\n");
    tvo_board_exit(1);
}

/* Mbed TLS's tag of (channel, message) under the trailer's nonce, as auth.c used to compute it. */
static void mbedtls_tag(const char *channel, const uint8_t *message, uint32_t length, const uint8_t *nonce,
                        uint8_t tag[TVO_AUTH_TAG_BYTES])
{
    if (mbedtls_chachapoly_starts(&chachapoly, nonce, MBEDTLS_CHACHAPOLY_ENCRYPT) != 0 ||
        mbedtls_chachapoly_update_aad(&chachapoly, (const unsigned char *)channel, strlen(channel) + 1u) != 0 ||
        mbedtls_chachapoly_update_aad(&chachapoly, message, length) != 0 ||
        mbedtls_chachapoly_finish(&chachapoly, tag) != 0) {
        fail("mbedtls_chachapoly");
    }
}

/* Signs and verifies the encoded message (length bytes at frame) AUTH_REPEATS times, and computes its
 * tag with Mbed TLS as often; prints both lines. */
static void measure(const char *name, const char *channel, uint32_t length)
{
    uint32_t same = 1u;
    for (uint32_t i = 0u; i < AUTH_REPEATS; ++i) {
        size_t signed_length = 0u;
        size_t message_length = 0u;
        uint32_t start = tvo_board_cycle_counter_read();
        const tvo_auth_status_t signed_status =
            tvo_auth_sign(&sender, channel, frame, length, sizeof(frame), &signed_length);
        uint32_t end = tvo_board_cycle_counter_read();
        sign_ticks[i] = tvo_board_cycle_counter_elapsed(start, end);
        start = tvo_board_cycle_counter_read();
        const tvo_auth_status_t open_status = tvo_auth_open(&receiver, channel, frame, signed_length, &message_length);
        end = tvo_board_cycle_counter_read();
        verify_ticks[i] = tvo_board_cycle_counter_elapsed(start, end);
        if (signed_status != TVO_AUTH_OK || open_status != TVO_AUTH_OK || message_length != length) {
            fail(name);
        }
        uint8_t tag[TVO_AUTH_TAG_BYTES];
        start = tvo_board_cycle_counter_read();
        mbedtls_tag(channel, frame, length, frame + length, tag);
        end = tvo_board_cycle_counter_read();
        mbedtls_ticks[i] = tvo_board_cycle_counter_elapsed(start, end);
        same &= memcmp(tag, frame + length + 12u, TVO_AUTH_TAG_BYTES) == 0 ? 1u : 0u;
    }
    tvo_board_puts("AUTH ");
    tvo_board_puts(name);
    tvo_board_puts(" bytes ");
    tvo_board_put_u32(length);
    tvo_board_puts(" sign ");
    tvo_board_put_u32(median_instructions(sign_ticks, AUTH_REPEATS));
    tvo_board_puts(" verify ");
    tvo_board_put_u32(median_instructions(verify_ticks, AUTH_REPEATS));
    tvo_board_puts("\nAUTH_MBEDTLS ");
    tvo_board_puts(name);
    tvo_board_puts(" instr ");
    tvo_board_put_u32(median_instructions(mbedtls_ticks, AUTH_REPEATS));
    tvo_board_puts(" same ");
    tvo_board_put_u32(same);
    tvo_board_puts("\n");
    if (!same) {
        fail("a tag differs from Mbed TLS's");
    }
}

/* Instructions per call of a part called AUTH_PART_CALLS times in `ticks` counter ticks. */
static void part_ticks(const char *name, uint64_t ticks)
{
    tvo_board_puts("AUTH_PART ");
    tvo_board_puts(name);
    tvo_board_puts(" ");
    tvo_board_put_u32((uint32_t)((ticks * TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM + AUTH_PART_CALLS / 2u) /
                                 (TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN * AUTH_PART_CALLS)));
    tvo_board_puts("\n");
}

/* The same, called between two counter readings. */
static void part(const char *name, uint32_t start, uint32_t end)
{
    part_ticks(name, tvo_board_cycle_counter_elapsed(start, end));
}

/* Mbed TLS's fixed cost of one tag (an empty message on TVO_COMMAND, 12 bytes of AAD: one Poly1305
 * block and the lengths block), part by part. */
static void mbedtls_parts(void)
{
    static const uint8_t nonce[12] = {0u, 0u, 0u, 1u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 1u};
    static uint8_t block[64];
    static uint8_t tag[TVO_AUTH_TAG_BYTES];
    const unsigned char *aad = (const unsigned char *)TVO_CHANNEL_COMMAND;
    const size_t aad_length = strlen(TVO_CHANNEL_COMMAND) + 1u;
    uint32_t start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        mbedtls_tag(TVO_CHANNEL_COMMAND, frame, 0u, nonce, tag);
    }
    part("tag_empty_message", start, tvo_board_cycle_counter_read());
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        (void)mbedtls_chachapoly_starts(&chachapoly, nonce, MBEDTLS_CHACHAPOLY_ENCRYPT);
    }
    part("chachapoly_starts", start, tvo_board_cycle_counter_read());
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        (void)mbedtls_chacha20_starts(&chacha20, nonce, 0u);
        (void)mbedtls_chacha20_update(&chacha20, sizeof(block), block, block);
    }
    part("chacha20_key_stream_block", start, tvo_board_cycle_counter_read());
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        (void)mbedtls_poly1305_starts(&poly1305, block);
    }
    part("poly1305_starts", start, tvo_board_cycle_counter_read());
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        mbedtls_platform_zeroize(block, sizeof(block));
    }
    part("zeroize_64_bytes", start, tvo_board_cycle_counter_read());
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        (void)mbedtls_poly1305_update(&poly1305, block, 16u);
    }
    part("poly1305_block", start, tvo_board_cycle_counter_read());
    /* The AAD, its padding, the lengths block and the tag: starts + update_aad + finish, less starts. */
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        (void)mbedtls_chachapoly_starts(&chachapoly, nonce, MBEDTLS_CHACHAPOLY_ENCRYPT);
        (void)mbedtls_chachapoly_update_aad(&chachapoly, aad, aad_length);
        (void)mbedtls_chachapoly_finish(&chachapoly, tag);
    }
    const uint32_t whole_end = tvo_board_cycle_counter_read();
    const uint32_t whole = tvo_board_cycle_counter_elapsed(start, whole_end);
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        (void)mbedtls_chachapoly_starts(&chachapoly, nonce, MBEDTLS_CHACHAPOLY_ENCRYPT);
    }
    const uint32_t starts_only = tvo_board_cycle_counter_elapsed(start, tvo_board_cycle_counter_read());
    part_ticks("aad_padding_lengths_finish", whole > starts_only ? whole - starts_only : 0u);
    start = tvo_board_cycle_counter_read();
    for (uint32_t i = 0u; i < AUTH_PART_CALLS; ++i) {
        size_t length = 0u;
        (void)tvo_auth_sign(&sender, TVO_CHANNEL_COMMAND, frame, 0u, sizeof(frame), &length);
    }
    part("tvo_auth_sign_empty_message", start, tvo_board_cycle_counter_read());
}

int main(void)
{
    for (uint32_t i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
        key[i] = (uint8_t)(i * 13u + 5u);
    }
    mbedtls_chachapoly_init(&chachapoly);
    mbedtls_chacha20_init(&chacha20);
    mbedtls_poly1305_init(&poly1305);
    if (tvo_auth_init(&sender, key, TVO_AUTH_SENDER_PLANT, 1u) != TVO_AUTH_OK ||
        tvo_auth_init(&receiver, key, TVO_AUTH_SENDER_NODE, 1u) != TVO_AUTH_OK ||
        mbedtls_chachapoly_setkey(&chachapoly, key) != 0 || mbedtls_chacha20_setkey(&chacha20, key) != 0) {
        fail("init");
    }
    tvo_board_cycle_counter_start();
    measure("empty", TVO_CHANNEL_COMMAND, 0u);

    /* The per-period messages, with values of a running session; then the others. */
    tvo_lcm_sample_header_t sample_header = {.utime = 1234567, .session_id = 7, .sequence = 42, .robot = 0};
    tvo_lcm_command_header_t command_header = {
        .utime = 1244567, .session_id = 7, .measurement_sequence = 42, .robot = 0, .status = 0, .flags = 0};

    tvo_lcm_unicycle_sample_t sample;
    memset(&sample, 0, sizeof(sample));
    sample.header = sample_header;
    sample.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    sample.position_m[0] = 0.5;
    sample.position_m[1] = -0.25;
    sample.heading_rad = 0.1f;
    sample.speed_mps = 0.3f;
    int bytes = tvo_lcm_unicycle_sample_t_encode(frame, 0, (int)sizeof(frame), &sample);
    if (bytes <= 0) {
        fail("sample encode");
    }
    measure("unicycle_sample", TVO_CHANNEL_SAMPLE, (uint32_t)bytes);

    tvo_lcm_unicycle_command_t command = {.header = command_header, .speed_mps = 0.31f, .turn_rate_radps = -0.2f};
    bytes = tvo_lcm_unicycle_command_t_encode(frame, 0, (int)sizeof(frame), &command);
    if (bytes <= 0) {
        fail("command encode");
    }
    measure("unicycle_command", TVO_CHANNEL_COMMAND, (uint32_t)bytes);

    tvo_lcm_target_t target;
    memset(&target, 0, sizeof(target));
    target.header = sample_header;
    target.position_m[0] = 1.0;
    target.velocity_mps[0] = 0.5f;
    bytes = tvo_lcm_target_t_encode(frame, 0, (int)sizeof(frame), &target);
    if (bytes <= 0) {
        fail("target encode");
    }
    measure("target", TVO_CHANNEL_TARGET, (uint32_t)bytes);

    tvo_lcm_chain_sample_t chain_sample;
    memset(&chain_sample, 0, sizeof(chain_sample));
    chain_sample.header = sample_header;
    chain_sample.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
    chain_sample.position_m[0] = 0.5;
    bytes = tvo_lcm_chain_sample_t_encode(frame, 0, (int)sizeof(frame), &chain_sample);
    if (bytes <= 0) {
        fail("chain sample encode");
    }
    measure("chain_sample", TVO_CHANNEL_CHAIN_SAMPLE, (uint32_t)bytes);

    tvo_lcm_chain_command_t chain_command = {.header = command_header, .input = {0.1f, -0.2f}};
    bytes = tvo_lcm_chain_command_t_encode(frame, 0, (int)sizeof(frame), &chain_command);
    if (bytes <= 0) {
        fail("chain command encode");
    }
    measure("chain_command", TVO_CHANNEL_CHAIN_COMMAND, (uint32_t)bytes);

    tvo_lcm_telemetry_t telemetry;
    memset(&telemetry, 0, sizeof(telemetry));
    telemetry.header = command_header;
    telemetry.objective_time_us = 420000;
    telemetry.joint_digest = 0x0123456789abcdefll;
    telemetry.output_m[0] = 0.5;
    bytes = tvo_lcm_telemetry_t_encode(frame, 0, (int)sizeof(frame), &telemetry);
    if (bytes <= 0) {
        fail("telemetry encode");
    }
    measure("telemetry", TVO_CHANNEL_TELEMETRY, (uint32_t)bytes);

    tvo_lcm_node_status_t status;
    memset(&status, 0, sizeof(status));
    status.protocol_version = TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION;
    status.boot_id = 17;
    status.own_robot = -1;
    status.session_id = -1;
    bytes = tvo_lcm_node_status_t_encode(frame, 0, (int)sizeof(frame), &status);
    if (bytes <= 0) {
        fail("node status encode");
    }
    measure("node_status", TVO_CHANNEL_NODE, (uint32_t)bytes);

    tvo_lcm_session_ack_t ack;
    memset(&ack, 0, sizeof(ack));
    ack.session_id = 7;
    ack.action = 1;
    ack.boot_id = 17;
    ack.own_robot = -1;
    ack.running_session_id = 7;
    bytes = tvo_lcm_session_ack_t_encode(frame, 0, (int)sizeof(frame), &ack);
    if (bytes <= 0) {
        fail("session ack encode");
    }
    measure("session_ack", TVO_CHANNEL_SESSION_ACK, (uint32_t)bytes);

    mbedtls_parts();
    tvo_board_puts("AUTH_DONE\n");
    tvo_board_exit(0);
}
