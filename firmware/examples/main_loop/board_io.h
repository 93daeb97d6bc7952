/*
 * What the main-loop example (main_loop.c) needs from your board. main_loop.c defines each as a
 * weak stub; define them in your board code and the stubs drop out of the link.
 */
#ifndef TVO_EXAMPLE_BOARD_IO_H
#define TVO_EXAMPLE_BOARD_IO_H

#include "tvo/controller.h"

/** Clocks, sensors, motors, and a timer that fires every cfg->period_ticks / cfg->tick_hz s. */
void board_init(const tvo_controller_config_t *cfg);
/** Blocks until the period timer fires. */
void board_wait_for_tick(void);
/** Position and heading of every robot now; set heading_valid (speed_valid if you measure it). */
void board_read_pose(tvo_measurement_t *meas);
/** Speed and turn rate to the motor drivers: a safe command (held, or stop) whatever the status. */
void board_write_command(const tvo_command_t *cmd, tvo_status_t status);

#endif /* TVO_EXAMPLE_BOARD_IO_H */
