/*
 * Processor-in-the-loop program: the firmware node (edge/node.c: the control core behind the same
 * LCM-encoded messages as tvo_firmware_node) on the microcontroller, talking over UART0.
 *
 * Frames on the serial link (edge/serial_frame.h): COBS + CRC-32, tagged with the node's channel
 * numbers. Corrupted or truncated frames fail the checks and are counted and dropped, never acted
 * on; a lost measurement then looks like a missed period to the node (a holding command). The host
 * side is tvo_pil_bridge, which republishes the frames on LCM. A session STOP ends the program;
 * its exit code (via semihosting) is 0, and the frame counts are printed on the semihosting console.
 */
#include <stdint.h>

#include "board.h"
#include "node.h"
#include "serial_frame.h"

int main(void);

static tvo_node_t node;
static tvo_frame_decoder_t decoder;
static uint8_t payload[TVO_FRAME_MAX_PAYLOAD];
static uint8_t frame[TVO_FRAME_MAX_ENCODED];
static uint32_t frames_sent;

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    size_t frame_length = 0u;
    if (tvo_frame_encode((uint8_t)channel, data, length, frame, sizeof(frame), &frame_length) == TVO_FRAME_OK) {
        tvo_board_uart_write(frame, (uint32_t)frame_length);
        ++frames_sent;
    }
}

static void report(void)
{
    tvo_board_puts("PIL frames received ");
    tvo_board_put_u32(decoder.frames_ok);
    tvo_board_puts(" dropped ");
    tvo_board_put_u32(decoder.frames_dropped);
    tvo_board_puts(" undecodable ");
    tvo_board_put_u32(node.decode_errors);
    tvo_board_puts(" sent ");
    tvo_board_put_u32(frames_sent);
    tvo_board_putc('\n');
}

int main(void)
{
    if (tvo_node_check_buffer() != 0) {
        tvo_board_puts("PIL: TVO_NODE_BUFFER_BYTES too small\n");
        return 1;
    }
    tvo_board_uart_init();
    tvo_node_init(&node, publish, NULL);
    tvo_frame_decoder_init(&decoder);
    tvo_board_puts("PIL ready\n");
    while (!node.stop_requested) {
        uint8_t byte = 0u;
        if (!tvo_board_uart_read(&byte)) {
            continue;
        }
        uint8_t channel = 0u;
        size_t length = 0u;
        if (tvo_frame_decoder_push(&decoder, byte, &channel, payload, &length) == TVO_FRAME_OK) {
            (void)tvo_node_handle(&node, channel, payload, (uint32_t)length);
        }
    }
    report();
    return 0;
}
