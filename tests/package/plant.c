/*
 * A simulated robot in place of the board, for the main-loop example
 * (firmware/examples/main_loop/): its board_* functions replace the example's weak stubs. The pose
 * follows the exact arc of the held command over each period (in double, the plant's own: the
 * package installs only the public API, no plant model). After PLANT_PERIODS periods the
 * program exits 0 if every step returned TVO_OK with a finite command and the robot moved, else 1.
 * EXPECT_DOUBLE and EXPECT_MAX_OUTPUT_DIM, when defined, are the layout this build must see.
 */
#include <math.h>

#include "board_io.h"
#include "tvo/tvo.h"

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

static struct {
    double position_m[2];
    double heading_rad;
} pose; /* starts at the origin, heading along x */
static tvo_command_t held;
static double period_s;
static double path_m;
static uint32_t periods;
static uint32_t failures;

void board_init(const tvo_controller_config_t *cfg)
{
    period_s = (double)cfg->period_ticks / (double)cfg->tick_hz;
}

void board_wait_for_tick(void)
{
    const double v = (double)held.speed_mps[0];
    const double w = (double)held.turn_rate_radps[0];
    const double turn = w * period_s;
    /* The arc's chord: length v h sinc(turn / 2), along the heading at mid-turn. */
    const double half = 0.5 * turn;
    const double chord = v * period_s * (fabs(half) < 1e-9 ? 1.0 : sin(half) / half);
    path_m += fabs(v) * period_s;
    pose.position_m[0] += chord * cos(pose.heading_rad + half);
    pose.position_m[1] += chord * sin(pose.heading_rad + half);
    pose.heading_rad += turn;
    if (!isfinite(pose.position_m[0]) || !isfinite(pose.position_m[1]) || !isfinite(pose.heading_rad)) {
        ++failures;
    }
}

void board_read_pose(tvo_measurement_t *meas)
{
    meas->position_m[0][0] = (tvo_real_t)pose.position_m[0];
    meas->position_m[0][1] = (tvo_real_t)pose.position_m[1];
    meas->heading_rad[0] = (tvo_real_t)pose.heading_rad;
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
           (unsigned)periods, (unsigned)failures, path_m, pose.position_m[0],
           pose.position_m[1], (unsigned)sizeof(tvo_real_t));
#endif
    PLANT_EXIT((failures == 0u && path_m > 0.0) ? 0 : 1);
}
