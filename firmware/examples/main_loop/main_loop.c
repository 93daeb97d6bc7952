/*
 * Your own main loop: the control core on your board, one robot tracking a circle. Every period:
 * sample the pose, compute the command, and apply it at the next timer tick (tau = h, compensated).
 * The board_* functions (board_io.h) are weak stubs here: define them in your board code.
 */
#include <string.h>

#include "board_io.h"
#include "tvo/problem.h"

int main(void);

__attribute__((weak)) void board_init(const tvo_controller_config_t *cfg) { (void)cfg; }
__attribute__((weak)) void board_wait_for_tick(void) {}
__attribute__((weak)) void board_read_pose(tvo_measurement_t *meas) { meas->heading_valid = 1u; }
__attribute__((weak)) void board_write_command(const tvo_command_t *cmd, tvo_status_t status)
{
    (void)cmd;
    (void)status;
}

/* Static: the caller owns every instance; the core allocates nothing. */
static tvo_problem_t problem;
static tvo_controller_t controller;

int main(void)
{
    static const tvo_real_t center_m[2] = {TVO_R(0.0), TVO_R(0.0)};
    tvo_problem_desc_t desc;
    tvo_controller_config_t cfg;
    tvo_status_t status = tvo_controller_config_default(&cfg);   /* 100 Hz on a 1 MHz tick */
    cfg.delay_ticks = cfg.period_ticks;   /* applied one period after its sample */
    if (status == TVO_OK) status = tvo_problem_desc_default(&desc);
    desc.robot_count = cfg.robot_count;
    if (status == TVO_OK) status = tvo_target_init_circle(&desc.target[0], center_m, TVO_R(1.0), TVO_R(0.5), TVO_R(0.0));
    if (status == TVO_OK) status = tvo_problem_init(&problem, &desc, 2u, NULL);
    if (status == TVO_OK) status = tvo_controller_init(&controller, &cfg, &problem.objective, 0u, NULL);
    if (status != TVO_OK) {
        return (int)status;
    }
    board_init(&cfg);
    for (uint32_t tick = 0u;;) {
        tvo_measurement_t meas;
        tvo_command_t cmd;
        memset(&meas, 0, sizeof(meas));
        meas.stamp_tick = tick;
        board_read_pose(&meas);
        tick += cfg.period_ticks;
        status = tvo_controller_step(&controller, &meas, tick, &cmd);
        board_wait_for_tick();
        board_write_command(&cmd, status);
    }
}
