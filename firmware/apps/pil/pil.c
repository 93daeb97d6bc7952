/*
 * Processor-in-the-loop program: the firmware node (edge/node.c: the control core behind the same
 * LCM-encoded messages as tvo_firmware_node) on the microcontroller, talking over UART0, on the
 * board's monotonic clock (SysTick), so a CLOCK_NODE session keeps its schedule and its watchdog here
 * as it does on the host. Its identity comes from the provisioned region (board.h): the boot id the
 * provisioner wrote for this boot, and the key if one is provisioned (then every frame both ways is
 * authenticated). It drives every robot of its sessions (own robot -1) and announces itself
 * (node_status_t on TVO_NODE) over the same link, idle or running.
 *
 * Frames on the serial link (edge/serial_frame.h): COBS, zero runs, CRC-32, tagged with channels.h's numbers.
 * Corrupted or truncated frames fail the checks and are counted and dropped, never acted on; a lost
 * sample is then a message that never arrived. The host side is tvo_pil_bridge, which republishes
 * the frames on LCM. A session STOP ends the program; its exit code (via semihosting) is 0, and one
 * line of counts (key=value) is printed on the semihosting console.
 */
#include <stdint.h>
#include <string.h>

#include "auth.h"
#include "board.h"
#include "channels.h"
#include "node.h"
#include "serial_frame.h"
#if defined(TVO_PIL_AUTH)
#include "auth_link.h"
#endif

int main(void);

/* Every frame the target takes fits the link's payload: the largest message, signed. */
_Static_assert(TVO_FRAME_MAX_PAYLOAD >= TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES,
               "a serial frame holds a signed session_t");

static tvo_node_t node;
/* Frames in: decoded byte by byte into the decoder's own packet buffer (serial_frame.h), no second one. */
static tvo_frame_decoder_t decoder;
/* Frames out: the node's messages, signed, encoded. */
static uint8_t frame[TVO_FRAME_ENCODED_BYTES(TVO_NODE_BUFFER_BYTES + TVO_AUTH_TRAILER_BYTES)];
static uint32_t frames_sent;
static uint32_t frames_unsent; /* a message that did not fit a frame (must stay 0) */
#if defined(TVO_PIL_AUTH)
static tvo_auth_link_t link;  /* keyed (a provisioned key): frames opened before the node, its own signed */
static int keyed;
#endif
static uint32_t clock_faults; /* readings that failed or went back: must stay 0 (the node needs monotonic time) */

/*
 * A message is stamped with the arrival of its first byte: clocking in the rest takes time in
 * proportion to its length (on QEMU's UART a 2 KB START takes ~40 ms, a measurement ~5 ms; at 115200
 * baud 184 ms and 26 ms), and the node takes a START's transit as age for its whole session (the
 * plant-to-node clock offset), so a START stamped at its last byte makes every later measurement
 * look that much early. The node's timer is not polled while a frame arrives (a stamp must not
 * precede a time the node was already given), but only while its bytes keep coming and for at most
 * FRAME_HOLD_MAX_US, so a broken or endless frame cannot hold the watchdog off.
 */
#define FRAME_HOLD_MAX_US 200000
#define FRAME_BYTE_GAP_US 10000

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    size_t frame_length = 0u;
    if (tvo_frame_encode((uint8_t)channel, data, length, frame, sizeof(frame), &frame_length) == TVO_FRAME_OK) {
        tvo_board_uart_write(frame, (uint32_t)frame_length);
        ++frames_sent;
    } else {
        ++frames_unsent;
    }
}

static void put_count(const char *key, uint64_t value)
{
    tvo_board_puts(key);
    tvo_board_put_u64(value);
}

static void put_node_count(const char *key, int32_t value)
{
    tvo_board_puts(key);
    tvo_board_put_i32(value);
}

/* One line of key=value counts at the end: the link's frames, the node's counters (node_counters_t). */
static void report(int64_t boot_id, int64_t now_us)
{
    const tvo_lcm_node_counters_t *c = tvo_node_counters(&node);
    tvo_board_puts("PIL");
    put_count(" boot_id=", (uint64_t)boot_id);
    put_count(" frames_received=", decoder.frames_ok);
    put_count(" frames_dropped=", decoder.frames_dropped);
    put_count(" frames_sent=", frames_sent);
    put_count(" frames_unsent=", frames_unsent);
    put_node_count(" accepted=", c->accepted);
    put_node_count(" malformed=", c->malformed);
    put_node_count(" unauthenticated=", c->unauthenticated);
    put_node_count(" replayed=", c->replayed);
    put_node_count(" wrong_boot=", c->wrong_boot);
    put_node_count(" idle=", c->idle);
    put_node_count(" other_session=", c->other_session);
    put_node_count(" predicted=", c->predicted);
    put_node_count(" safe_stops=", c->safe_stops);
    put_node_count(" targets_refused=", c->targets_refused);
    put_node_count(" sessions=", c->sessions);
    for (uint32_t status = 0u; status < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++status) {
        if (c->refused[status] != 0) { /* refused_<command_header_t.STATUS_*>=count, for the reasons seen */
            tvo_board_puts(" refused_");
            tvo_board_put_u32(status);
            put_node_count("=", c->refused[status]);
        }
    }
#if defined(TVO_PIL_AUTH)
    put_count(" keyed=", (uint64_t)keyed);
    put_count(" unsigned_drops=", link.unsigned_drops);
#else
    put_count(" keyed=", 0u);
#endif
    put_count(" clock_us=", (uint64_t)now_us);
    put_count(" clock_faults=", clock_faults);
    tvo_board_putc('\n');
}

/* A frame that passed the link's checks: to the node through the keyed link, or straight. A frame on a
 * channel the node does not take is counted malformed either way (every drop is counted). */
static void receive(uint8_t channel, const uint8_t *payload, size_t length, int64_t arrival_us)
{
#if defined(TVO_PIL_AUTH)
    if (keyed) {
        (void)tvo_auth_link_receive(&link, &node, channel, payload, (uint32_t)length, arrival_us);
        return;
    }
#endif
    if (!tvo_node_channel_is_input(channel)) {
        tvo_node_count_drop(&node, TVO_NODE_DROP_MALFORMED);
        return;
    }
    (void)tvo_node_handle(&node, channel, payload, (uint32_t)length, arrival_us);
}

/* The boot id the provisioner wrote (board.h), or 0 if there is none or it is out of range. */
static int64_t provisioned_boot_id(const uint8_t *region)
{
    if (memcmp(region, TVO_BOARD_BOOT_MAGIC, 4u) != 0) {
        return 0;
    }
    uint64_t boot_id = 0u;
    for (uint32_t i = 0u; i < 8u; ++i) {
        boot_id |= (uint64_t)region[TVO_BOARD_BOOT_ID_OFFSET + i] << (8u * i);
    }
    return (boot_id >= 1u && boot_id <= (uint64_t)TVO_AUTH_MAX_BOOT_ID) ? (int64_t)boot_id : 0;
}

int main(void)
{
    if (tvo_node_check_buffer() != 0) {
        tvo_board_puts("PIL: TVO_NODE_BUFFER_BYTES too small\n");
        return 1;
    }
    if (tvo_board_clock_start() != 0) {
        tvo_board_puts("PIL: the SysTick clock does not run\n");
        return 1;
    }
    tvo_board_uart_init();
    const uint8_t *region = tvo_board_provisioned_region();
    const int64_t boot_id = provisioned_boot_id(region);
    if (boot_id == 0) {
        tvo_board_puts("PIL: no boot id provisioned (board.h: the provisioner writes one at every boot; "
                       "tools/pil_run.py does)\n");
        return 1;
    }
    const int key_provisioned = memcmp(region + TVO_BOARD_KEY_MAGIC_OFFSET, TVO_BOARD_KEY_MAGIC, 4u) == 0;
    int init_status = -1;
#if defined(TVO_PIL_AUTH)
    /* A provisioned key: every frame both ways authenticated, never a fallback to plain. */
    if (key_provisioned) {
        if (tvo_auth_link_init(&link, region + TVO_BOARD_KEY_OFFSET, TVO_AUTH_SENDER_NODE, boot_id, publish, NULL) !=
            TVO_AUTH_OK) {
            tvo_board_puts("PIL: the key is provisioned but the link does not start\n");
            return 1;
        }
        keyed = 1;
        init_status = tvo_node_init(&node, -1, boot_id, tvo_auth_link_publish, &link);
        tvo_board_puts("PIL: keyed: every message is authenticated\n");
    } else {
        tvo_board_puts("PIL: the bus is unauthenticated (no key provisioned)\n");
        init_status = tvo_node_init(&node, -1, boot_id, publish, NULL);
    }
#else
    if (key_provisioned) {
        tvo_board_puts("PIL: a key is provisioned, but this image has no authentication (built without Mbed TLS)\n");
        return 1;
    }
    init_status = tvo_node_init(&node, -1, boot_id, publish, NULL);
#endif
    if (init_status != 0) {
        tvo_board_puts("PIL: the node does not start\n");
        return 1;
    }
    tvo_frame_decoder_init(&decoder);
    tvo_board_puts("PIL ready\n");
    int64_t last_us = 0;
    int64_t given_us = 0;        /* the latest time given to the node: it must never go back */
    int64_t deadline_us = 0;     /* poll the node when its deadline has come, and after every message */
    int64_t frame_start_us = -1; /* arrival of the first byte of the frame being received; -1 between frames */
    int64_t last_byte_us = 0;
    while (!tvo_node_stop_requested(&node)) {
        const int64_t now_us = tvo_board_now_us();
        if (now_us < last_us) {
            ++clock_faults;
            continue; /* -1 (a read that kept racing the wrap interrupt) or a step back: not a time */
        }
        last_us = now_us;
        const int receiving = frame_start_us >= 0 && now_us - frame_start_us < FRAME_HOLD_MAX_US &&
                              now_us - last_byte_us < FRAME_BYTE_GAP_US;
        if (!receiving && now_us >= deadline_us) {
            deadline_us = tvo_node_poll(&node, now_us);
            given_us = now_us;
        }
        uint8_t byte = 0u;
        if (!tvo_board_uart_read(&byte)) {
            continue;
        }
        last_byte_us = now_us;
        if (byte != 0u && frame_start_us < 0) {
            frame_start_us = now_us;
        }
        uint8_t channel = 0u;
        size_t length = 0u;
        const tvo_frame_status_t st = tvo_frame_decoder_push(&decoder, byte, &channel, decoder.buffer, &length);
        if (byte == 0u) {
            const int64_t arrival_us = frame_start_us > given_us ? frame_start_us : given_us;
            frame_start_us = -1;
            if (st == TVO_FRAME_OK) {
                receive(channel, decoder.buffer, length, arrival_us);
                given_us = arrival_us;
                deadline_us = now_us; /* the message may have moved the deadline */
            }
        }
    }
    report(boot_id, last_us);
    return 0;
}
