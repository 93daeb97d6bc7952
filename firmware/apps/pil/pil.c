/*
 * Processor-in-the-loop program: the firmware node (edge/node.c: the control core behind the same
 * LCM-encoded messages as tvo_firmware_node) on the microcontroller, talking over UART0, on the
 * board's monotonic clock (SysTick), so a CLOCK_NODE session keeps its schedule and its watchdog here
 * as it does on the host.
 *
 * Frames on the serial link (edge/serial_frame.h): COBS + CRC-32, tagged with channels.h's numbers.
 * Corrupted or truncated frames fail the checks and are counted and dropped, never acted on; a lost
 * measurement is then a message that never arrived. The host side is tvo_pil_bridge, which
 * republishes the frames on LCM. A session STOP ends the program; its exit code (via semihosting)
 * is 0, and one line of counts (key=value) is printed on the semihosting console.
 */
#include <stdint.h>
#include <string.h>

#include "board.h"
#include "node.h"
#include "serial_frame.h"
#if defined(TVO_PIL_AUTH)
#include "auth_link.h"
#endif

int main(void);

static tvo_node_t node;
static tvo_frame_decoder_t decoder;
static uint8_t payload[TVO_FRAME_MAX_PAYLOAD];
static uint8_t frame[TVO_FRAME_MAX_ENCODED];
static uint32_t frames_sent;
#if defined(TVO_PIL_AUTH)
static tvo_auth_link_t link;  /* keyed (a provisioned key region): frames opened before the node, its own signed */
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

static void report(int64_t now_us)
{
    tvo_board_puts("PIL");
    put_count(" frames_received=", decoder.frames_ok);
    put_count(" frames_dropped=", decoder.frames_dropped);
    put_count(" frames_sent=", frames_sent);
    put_node_count(" malformed=", node.counters.malformed);
    put_node_count(" accepted=", node.counters.accepted);
    put_node_count(" safe_stops=", node.counters.safe_stops);
    for (uint32_t status = 0u; status < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++status) {
        if (node.counters.refused[status] != 0) { /* refused_<tvo_status_t>=count, for the reasons seen */
            tvo_board_puts(" refused_");
            tvo_board_put_u32(status);
            put_node_count("=", node.counters.refused[status]);
        }
    }
#if defined(TVO_PIL_AUTH)
    put_count(" keyed=", (uint64_t)keyed);
    put_node_count(" unauthenticated=", node.counters.unauthenticated);
    put_node_count(" replayed=", node.counters.replayed);
#endif
    put_count(" clock_us=", (uint64_t)now_us);
    put_count(" clock_faults=", clock_faults);
    tvo_board_putc('\n');
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
#if defined(TVO_PIL_AUTH)
    /* A provisioned key region: every frame both ways authenticated, never a fallback to plain. */
    const uint8_t *region = tvo_board_key_region();
    if (memcmp(region, TVO_BOARD_KEY_MAGIC, 4u) == 0) {
        uint64_t counter_base = 0u;
        for (uint32_t i = 0u; i < 8u; ++i) {
            counter_base |= (uint64_t)region[36u + i] << (8u * i);
        }
        if (counter_base == 0u ||
            tvo_auth_link_init(&link, region + 4u, TVO_AUTH_SENDER_NODE, counter_base, publish, NULL) != TVO_AUTH_OK ||
            tvo_auth_start_at(&link.auth, counter_base, TVO_AUTH_NEW_SENDER_WINDOW_US) != TVO_AUTH_OK) {
            tvo_board_puts("PIL: the key region is provisioned but unusable (counter base 0?)\n");
            return 1;
        }
        keyed = 1;
        /* Interim boot id until the provisioned boot counter: the counter base, new at every provisioning. */
        (void)tvo_node_init(&node, -1, counter_base <= (uint64_t)INT64_MAX ? (int64_t)counter_base : INT64_MAX,
                            tvo_auth_link_publish, &link);
        tvo_board_puts("PIL: keyed: every message is authenticated\n");
    } else {
        tvo_board_puts("PIL: the bus is unauthenticated (no key provisioned)\n");
        (void)tvo_node_init(&node, -1, 1, publish, NULL); /* interim boot id until the provisioned boot counter */
    }
#else
    (void)tvo_node_init(&node, -1, 1, publish, NULL); /* interim boot id until the provisioned boot counter */
#endif
    tvo_frame_decoder_init(&decoder);
    tvo_board_puts("PIL ready\n");
    int64_t last_us = 0;
    int64_t given_us = 0;        /* the latest time given to the node: it must never go back */
    int64_t deadline_us = 0;     /* poll the node when its deadline has come, and after every message */
    int64_t frame_start_us = -1; /* arrival of the first byte of the frame being received; -1 between frames */
    int64_t last_byte_us = 0;
    while (!node.stop_requested) {
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
        const tvo_frame_status_t st = tvo_frame_decoder_push(&decoder, byte, &channel, payload, &length);
        if (byte == 0u) {
            const int64_t arrival_us = frame_start_us > given_us ? frame_start_us : given_us;
            frame_start_us = -1;
            if (st == TVO_FRAME_OK) {
#if defined(TVO_PIL_AUTH)
                if (keyed) {
                    (void)tvo_auth_link_receive(&link, &node, channel, payload, (uint32_t)length, arrival_us);
                } else {
                    (void)tvo_node_handle(&node, channel, payload, (uint32_t)length, arrival_us);
                }
#else
                (void)tvo_node_handle(&node, channel, payload, (uint32_t)length, arrival_us);
#endif
                given_us = arrival_us;
                deadline_us = now_us; /* the message may have moved the deadline */
            }
        }
    }
    report(last_us);
    return 0;
}
