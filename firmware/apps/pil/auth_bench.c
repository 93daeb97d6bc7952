/*
 * Cost of message authentication on the board: signing and verifying (tvo_auth_sign / tvo_auth_open)
 * a one-robot measurement and a command, LCM-encoded as the node sends and receives them, and a
 * fleet's per-robot sample and command (one robot's), each bracketed by the cycle counter,
 * AUTH_REPEATS times with rising counters.
 *
 * Prints "AUTH <message> bytes <n> sign <median> verify <median>" in instructions under
 * qemu -icount shift=0 (counter ticks times the board's instructions per tick), then "AUTH_DONE".
 * The key is a fixed test key: the figures do not depend on its value.
 */
#include <stdint.h>
#include <string.h>

#include "auth.h"
#include "board.h"
#include "channels.h"
#include "tvo_lcm_command_t.h"
#include "tvo_lcm_fleet_command_t.h"
#include "tvo_lcm_fleet_sample_t.h"
#include "tvo_lcm_measurement_t.h"

#define AUTH_REPEATS 33u

int main(void);

static uint8_t frame[512];
static uint32_t sign_ticks[AUTH_REPEATS];
static uint32_t verify_ticks[AUTH_REPEATS];
static tvo_auth_t sender;
static tvo_auth_t receiver;

/* Insertion sort of a few values: bounded, no library. */
static uint32_t median(uint32_t *values, uint32_t count)
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

/* Signs and verifies the encoded message (length bytes at frame) AUTH_REPEATS times; prints its line. */
static void measure(const char *name, const char *channel, uint32_t length)
{
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
    }
    tvo_board_puts("AUTH ");
    tvo_board_puts(name);
    tvo_board_puts(" bytes ");
    tvo_board_put_u32(length);
    tvo_board_puts(" sign ");
    tvo_board_put_u32(median(sign_ticks, AUTH_REPEATS));
    tvo_board_puts(" verify ");
    tvo_board_put_u32(median(verify_ticks, AUTH_REPEATS));
    tvo_board_puts("\n");
}

int main(void)
{
    uint8_t key[TVO_AUTH_KEY_BYTES];
    for (uint32_t i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
        key[i] = (uint8_t)(i * 13u + 5u);
    }
    if (tvo_auth_init(&sender, key, 1u, 1u) != TVO_AUTH_OK || tvo_auth_init(&receiver, key, 2u, 1u) != TVO_AUTH_OK) {
        fail("init");
    }
    tvo_board_cycle_counter_start();
    measure("empty", TVO_CHANNEL_COMMAND, 0u);

    tvo_lcm_measurement_t measurement;
    memset(&measurement, 0, sizeof(measurement));
    measurement.utime = 1234567;
    measurement.session_id = 7;
    measurement.sequence = 42;
    measurement.robot_count = 1;
    measurement.position_m[0][0] = 0.5;
    measurement.position_m[0][1] = -0.25;
    measurement.heading_rad[0] = 0.1;
    measurement.speed_mps[0] = 0.3;
    measurement.heading_valid = 1;
    measurement.speed_valid = 1;
    const int measurement_bytes = tvo_lcm_measurement_t_encode(frame, 0, (int)sizeof(frame), &measurement);
    if (measurement_bytes <= 0) {
        fail("measurement encode");
    }
    measure("measurement", TVO_CHANNEL_MEASUREMENT, (uint32_t)measurement_bytes);

    tvo_lcm_command_t command;
    memset(&command, 0, sizeof(command));
    command.utime = 1244567;
    command.session_id = 7;
    command.measurement_sequence = 42;
    command.robot_count = 1;
    command.speed_mps[0] = 0.31;
    command.turn_rate_radps[0] = -0.2;
    const int command_bytes = tvo_lcm_command_t_encode(frame, 0, (int)sizeof(frame), &command);
    if (command_bytes <= 0) {
        fail("command encode");
    }
    measure("command", TVO_CHANNEL_COMMAND, (uint32_t)command_bytes);

    /* A fleet's per-robot messages, as a node of a one-robot fleet (robot 0) hears and answers them. */
    tvo_lcm_fleet_sample_t sample;
    memset(&sample, 0, sizeof(sample));
    sample.utime = measurement.utime;
    sample.session_id = measurement.session_id;
    sample.sequence = measurement.sequence;
    sample.robot_count = 1;
    sample.position_m[0] = 0.5;
    sample.position_m[1] = -0.25;
    sample.heading_rad = 0.1;
    sample.speed_mps = 0.3;
    sample.heading_valid = 1;
    sample.speed_valid = 1;
    const int sample_bytes = tvo_lcm_fleet_sample_t_encode(frame, 0, (int)sizeof(frame), &sample);
    if (sample_bytes <= 0) {
        fail("fleet sample encode");
    }
    measure("fleet_sample", TVO_CHANNEL_FLEET_SAMPLE "_R0", (uint32_t)sample_bytes);

    tvo_lcm_fleet_command_t row;
    memset(&row, 0, sizeof(row));
    row.utime = command.utime;
    row.session_id = command.session_id;
    row.measurement_sequence = command.measurement_sequence;
    row.robot_count = 1;
    row.speed_mps = command.speed_mps[0];
    row.turn_rate_radps = command.turn_rate_radps[0];
    row.joint_speed_mps[0] = row.speed_mps;
    row.joint_turn_rate_radps[0] = row.turn_rate_radps;
    const int row_bytes = tvo_lcm_fleet_command_t_encode(frame, 0, (int)sizeof(frame), &row);
    if (row_bytes <= 0) {
        fail("fleet command encode");
    }
    measure("fleet_command", TVO_CHANNEL_FLEET_COMMAND "_R0", (uint32_t)row_bytes);
    tvo_board_puts("AUTH_DONE\n");
    tvo_board_exit(0);
}
