/*
 * A simulated robot in place of the board, for the main-loop example
 * (firmware/examples/main_loop/): its board_* functions replace the example's weak stubs. The pose
 * follows the exact arc of the held command over each period. After PLANT_PERIODS periods the
 * program exits 0 if every step returned TVO_OK with a finite command and the robot moved, else 1.
 * EXPECT_DOUBLE and EXPECT_MAX_OUTPUT_DIM, when defined, are the layout this build must see.
 */
#include <math.h>

#include "board_io.h"
#include "tvo/unicycle.h"

#if defined(__arm__)
#include "board.h"
#define PLANT_EXIT(code) tvo_board_exit(code)
#else
#include <stdio.h>
#include <stdlib.h>
#define PLANT_EXIT(code) exit(code)
#endif

#if defined(EXPECT_DOUBLE)
_Static_assert((sizeof(tvo_real_t) == sizeof(double)) == EXPECT_DOUBLE, "tvo_real_t is not the library's scalar type");
#endif
#if defined(EXPECT_MAX_OUTPUT_DIM)
_Static_assert(TVO_MAX_OUTPUT_DIM == EXPECT_MAX_OUTPUT_DIM, "TVO_MAX_OUTPUT_DIM is not the library's");
#endif

#define PLANT_PERIODS 500u

static tvo_pose_t pose;   /* starts at the origin, heading along x */
static tvo_command_t held;
static tvo_real_t period_s;
static tvo_real_t path_m;
static uint32_t periods;
static uint32_t failures;

void board_init(const tvo_controller_config_t *cfg)
{
    period_s = tvo_ticks_to_seconds(cfg->period_ticks, cfg->tick_hz);
}

void board_wait_for_tick(void)
{
    path_m += TVO_FABS(held.speed_mps[0]) * period_s;
    if (tvo_unicycle_predict(&pose, held.speed_mps[0], held.turn_rate_radps[0], period_s, &pose) != TVO_OK) {
        ++failures;
    }
}

void board_read_pose(tvo_measurement_t *meas)
{
    meas->position_m[0][0] = pose.position_m[0];
    meas->position_m[0][1] = pose.position_m[1];
    meas->heading_rad[0] = pose.heading_rad;
    meas->heading_valid = 1u;
}

void board_write_command(const tvo_command_t *cmd, tvo_status_t status)
{
    if (status != TVO_OK || !isfinite(cmd->speed_mps[0]) || !isfinite(cmd->turn_rate_radps[0])) {
        ++failures;
    }
    held = *cmd;
    if (++periods < PLANT_PERIODS) {
        return;
    }
#if defined(__arm__)
    tvo_board_puts("plant: ");
    tvo_board_put_u32(periods);
    tvo_board_puts(" periods, ");
    tvo_board_put_u32(failures);
    tvo_board_puts(" failed\n");
#else
    printf("plant: %u periods, %u failed, path %.3f m, final pose (%.3f, %.3f) m, sizeof(tvo_real_t) %u\n",
           (unsigned)periods, (unsigned)failures, (double)path_m, (double)pose.position_m[0],
           (double)pose.position_m[1], (unsigned)sizeof(tvo_real_t));
#endif
    PLANT_EXIT((failures == 0u && path_m > TVO_R(0.0)) ? 0 : 1);
}
