/*
 * Cost of one controller step, measured on the target: four problems run in closed loop with an
 * exact plant in the same program, and the cycle counter brackets each step (only the step).
 *
 *   unicycle    one unicycle tracking an ellipse (the demo's problem)
 *   obstacles4  one disk unicycle among four disk obstacles (relaxed barrier, local free space)
 *   formation2  two unicycles with 1 <= |y1 - y2| <= 3 (4x4 Hessian, nonconvex bound)
 *   chain_k3    the integrator chain y''' = u in R^2 (k = 3 law, exact derivatives)
 *
 * Prints one line per problem: "BENCH <name> steps <n> min <a> median <b> max <c>" in counter
 * ticks (instructions = ticks * TVO_BOARD_INSTRUCTIONS_PER_TICK under qemu -icount shift=0), then
 * "BENCH_CONFIG" with the build's limits. With an argument (host builds), runs only that problem.
 */
#include <string.h>

#include "board.h"
#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"

#define BENCH_STEPS 400u
#define BENCH_PI 3.14159265358979f

#if defined(TVO_BENCH_HOST)
int main(int argc, char **argv);
#else
int main(void);
#endif

static uint32_t samples[BENCH_STEPS];
static tvo_problem_t problem;
static tvo_controller_t controller;
static tvo_chain_controller_t chain;

/* Insertion sort: bounded (BENCH_STEPS^2), no library, enough for a median of 400 values. */
static void sort_samples(uint32_t count)
{
    for (uint32_t i = 1u; i < count; ++i) {
        const uint32_t v = samples[i];
        uint32_t j = i;
        while (j > 0u && samples[j - 1u] > v) {
            samples[j] = samples[j - 1u];
            --j;
        }
        samples[j] = v;
    }
}

static void report(const char *name, uint32_t count, tvo_status_t last_status)
{
    sort_samples(count);
    tvo_board_puts("BENCH ");
    tvo_board_puts(name);
    tvo_board_puts(" steps ");
    tvo_board_put_u32(count);
    tvo_board_puts(" min ");
    tvo_board_put_u32(samples[0]);
    tvo_board_puts(" median ");
    tvo_board_put_u32(samples[count / 2u]);
    tvo_board_puts(" max ");
    tvo_board_put_u32(samples[count - 1u]);
    tvo_board_puts(" status ");
    tvo_board_put_i32((int32_t)last_status);
    tvo_board_putc('\n');
}

/* The measured span: the counter reads stay on either side of the step (volatile accesses, and
 * the step's result feeds the next read through a compiler barrier). */
#define MEASURE(sample, call)                                \
    do {                                                     \
        const uint32_t before_ = tvo_board_cycle_counter_read(); \
        __asm__ volatile("" ::: "memory");                   \
        const tvo_status_t status_ = (call);                 \
        __asm__ volatile("" ::: "memory");                   \
        const uint32_t after_ = tvo_board_cycle_counter_read(); \
        (sample) = tvo_board_cycle_counter_elapsed(before_, after_); \
        last = status_;                                      \
    } while (0)

static void polynomial_target(tvo_target_t *target, float x0, float vx, float ax, float y0, float vy, float ay)
{
    tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
    memset(coeff, 0, sizeof(coeff));
    coeff[0][0] = x0;
    coeff[0][1] = vx;
    coeff[0][2] = ax;
    coeff[1][0] = y0;
    coeff[1][1] = vy;
    coeff[1][2] = ay;
    (void)tvo_target_init_polynomial(target, (const tvo_real_t(*)[TVO_POLY_MAX_DEGREE + 1])coeff);
}

/* Closed loop of the unicycle controller over `problem` with an exact-arc plant; tau = h/2. */
static tvo_status_t run_unicycle(const char *name, const tvo_pose_t *start, uint8_t robots)
{
    tvo_controller_config_t cfg;
    tvo_param_t bad = TVO_PARAM_NONE;
    tvo_status_t last = tvo_controller_config_default(&cfg);
    cfg.robot_count = robots;
    if (last == TVO_OK) {
        last = tvo_controller_init(&controller, &cfg, &problem.objective, 0u, &bad);
    }
    if (last != TVO_OK) {
        return last;
    }
    tvo_pose_t pose[TVO_MAX_ROBOTS];
    tvo_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    for (uint8_t r = 0; r < robots; ++r) {
        pose[r] = start[r];
    }
    const tvo_real_t half_s = TVO_R(0.5) * tvo_ticks_to_seconds(cfg.period_ticks, cfg.tick_hz);
    for (uint32_t n = 0; n < BENCH_STEPS; ++n) {
        tvo_measurement_t meas;
        memset(&meas, 0, sizeof(meas));
        for (uint8_t r = 0; r < robots; ++r) {
            (void)tvo_unicycle_predict(&pose[r], cmd.speed_mps[r], cmd.turn_rate_radps[r], half_s, &pose[r]);
            meas.position_m[r][0] = pose[r].position_m[0];
            meas.position_m[r][1] = pose[r].position_m[1];
            meas.heading_rad[r] = pose[r].heading_rad;
        }
        meas.heading_valid = 1u;
        meas.stamp_tick = n * cfg.period_ticks + cfg.period_ticks - cfg.delay_ticks;
        if (n == 0u) {
            tvo_real_t y[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};
            for (uint8_t r = 0; r < robots; ++r) {
                y[2u * r] = pose[r].position_m[0];
                y[2u * r + 1u] = pose[r].position_m[1];
            }
            (void)tvo_problem_choose_slack(&problem, y, TVO_R(0.0));
        }
        for (uint8_t r = 0; r < robots; ++r) {
            (void)tvo_unicycle_predict(&pose[r], cmd.speed_mps[r], cmd.turn_rate_radps[r], half_s, &pose[r]);
        }
        MEASURE(samples[n], tvo_controller_step(&controller, &meas, (n + 1u) * cfg.period_ticks, &cmd));
    }
    report(name, BENCH_STEPS, last);
    return last;
}

static tvo_status_t bench_unicycle(void)
{
    tvo_problem_desc_t desc;
    uint8_t part = 0u;
    (void)tvo_problem_desc_default(&desc);
    desc.robot_count = 1u;
    const tvo_target_ellipse_t ellipse = {{TVO_R(0.0), TVO_R(0.0)}, {TVO_R(3.0), TVO_R(1.5)},
                                          2.0f * BENCH_PI / 10.0f, TVO_R(0.0), TVO_R(0.0), 0u};
    (void)tvo_target_init_ellipse(&desc.target[0], &ellipse);
    tvo_status_t st = tvo_problem_init(&problem, &desc, 2u, &part);
    const tvo_pose_t start = {{TVO_R(-1.0), TVO_R(-2.0)}, TVO_R(0.0)};
    return (st == TVO_OK) ? run_unicycle("unicycle", &start, 1u) : st;
}

static tvo_status_t bench_obstacles4(void)
{
    tvo_problem_desc_t desc;
    uint8_t part = 0u;
    (void)tvo_problem_desc_default(&desc);
    desc.robot_count = 1u;
    polynomial_target(&desc.target[0], -5.0f, 0.8f, 0.0f, -5.0f, 0.6f, 0.0f);
    desc.obstacle_count = 4u;
    desc.robot_radius_m = TVO_R(0.2);
    const float centers[4][2] = {{-3.0f, -3.5f}, {-1.0f, -1.0f}, {1.5f, -2.5f}, {2.0f, 1.0f}};
    const float radii[4] = {0.6f, 1.0f, 0.8f, 0.7f};
    for (uint8_t i = 0; i < 4u; ++i) {
        desc.obstacle[i].center_m[0] = centers[i][0];
        desc.obstacle[i].center_m[1] = centers[i][1];
        desc.obstacle[i].radius_m = radii[i];
    }
    tvo_status_t st = tvo_problem_init(&problem, &desc, 2u, &part);
    const tvo_pose_t start = {{TVO_R(-6.0), TVO_R(-4.2)}, TVO_R(-10.0)};
    return (st == TVO_OK) ? run_unicycle("obstacles4", &start, 1u) : st;
}

static tvo_status_t bench_formation2(void)
{
#if TVO_MAX_ROBOTS >= 2
    tvo_problem_desc_t desc;
    uint8_t part = 0u;
    (void)tvo_problem_desc_default(&desc);
    desc.robot_count = 2u;
    polynomial_target(&desc.target[0], -5.0f, 1.0f, 0.0f, -3.0f, 0.0f, 0.0f);
    polynomial_target(&desc.target[1], -2.0f, 0.2f, 0.0f, -3.0f, 0.0f, 0.0f);
    desc.distance_count = 1u;
    desc.distance[0].robot_b = 1u;
    desc.distance[0].min_m = TVO_R(1.0);
    desc.distance[0].max_m = TVO_R(3.0);
    tvo_status_t st = tvo_problem_init(&problem, &desc, 2u, &part);
    const tvo_pose_t start[2] = {{{TVO_R(-4.9), TVO_R(-4.2)}, TVO_R(0.5)}, {{TVO_R(-2.1), TVO_R(-4.3)}, TVO_R(-0.5)}};
    return (st == TVO_OK) ? run_unicycle("formation2", start, 2u) : st;
#else
    return TVO_ERR_DIMENSION; /* built for one robot */
#endif
}

static tvo_status_t bench_chain_k3(void)
{
    tvo_problem_desc_t desc;
    uint8_t part = 0u;
    (void)tvo_problem_desc_default(&desc);
    desc.robot_count = 1u;
    const tvo_real_t center[2] = {TVO_R(0.0), TVO_R(0.0)};
    (void)tvo_target_init_circle(&desc.target[0], center, TVO_R(1.0), 2.0f * BENCH_PI / 10.0f, TVO_R(0.0));
    tvo_status_t last = tvo_problem_init(&problem, &desc, 3u, &part);
    tvo_chain_config_t cfg;
    tvo_param_t bad = TVO_PARAM_NONE;
    (void)tvo_chain_config_default(&cfg);
    cfg.relative_degree = 3u;
    cfg.gain[0] = TVO_R(4.096); /* (s + 1.6)^3 */
    cfg.gain[1] = TVO_R(7.68);
    cfg.gain[2] = TVO_R(4.8);
    if (last == TVO_OK) {
        last = tvo_chain_controller_init(&chain, &cfg, &problem.objective, 0u, &bad);
    }
    if (last != TVO_OK) {
        return last;
    }
    tvo_output_derivs_t state;
    memset(&state, 0, sizeof(state));
    state.d[0][0] = TVO_R(2.0);
    tvo_chain_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    const tvo_real_t half_s = TVO_R(0.5) * tvo_ticks_to_seconds(cfg.period_ticks, cfg.tick_hz);
    for (uint32_t n = 0; n < BENCH_STEPS; ++n) {
        tvo_chain_measurement_t meas;
        (void)tvo_chain_predict(3u, 2u, &state, cmd.u, half_s, &state);
        meas.y = state;
        meas.stamp_tick = n * cfg.period_ticks + cfg.period_ticks - cfg.delay_ticks;
        (void)tvo_chain_predict(3u, 2u, &state, cmd.u, half_s, &state);
        MEASURE(samples[n], tvo_chain_controller_step(&chain, &meas, (n + 1u) * cfg.period_ticks, &cmd));
    }
    report("chain_k3", BENCH_STEPS, last);
    return last;
}

static int bench_run(const char *only)
{
    typedef tvo_status_t (*bench_fn)(void);
    static const struct {
        const char *name;
        bench_fn run;
    } benches[] = {{"unicycle", bench_unicycle},
                   {"obstacles4", bench_obstacles4},
                   {"formation2", bench_formation2},
                   {"chain_k3", bench_chain_k3}};
    tvo_board_cycle_counter_start();
    int failures = 0;
    for (uint32_t i = 0; i < sizeof(benches) / sizeof(benches[0]); ++i) {
        if (only != NULL && strcmp(only, benches[i].name) != 0) {
            continue;
        }
        if (benches[i].run() != TVO_OK) {
            tvo_board_puts("BENCH_ERROR ");
            tvo_board_puts(benches[i].name);
            tvo_board_putc('\n');
            ++failures;
        }
    }
    tvo_board_puts("BENCH_CONFIG max_output_dim ");
    tvo_board_put_u32(TVO_MAX_OUTPUT_DIM);
    tvo_board_puts(" max_equalities ");
    tvo_board_put_u32(TVO_MAX_EQUALITIES);
    tvo_board_puts(" double ");
    tvo_board_put_u32(TVO_USE_DOUBLE);
    tvo_board_putc('\n');
    return failures;
}

#if defined(TVO_BENCH_HOST)
int main(int argc, char **argv)
{
    return bench_run(argc > 1 ? argv[1] : NULL);
}
#else
int main(void)
{
    return bench_run(NULL);
}
#endif
