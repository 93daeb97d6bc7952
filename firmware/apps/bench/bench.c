/*
 * Cost of one controller step, measured on the target: four problems run in closed loop with an
 * exact plant in the same program, and the cycle counter brackets each step (only the step).
 * The unicycle problems are in bench_problems.c; here also
 *   chain_k3    the integrator chain y''' = u in R^2 (k = 3 law, exact derivatives)
 *
 * Prints one line per problem: "BENCH <name> steps <n> min <a> median <b> max <c> status <s>" in
 * instructions under qemu -icount shift=0 (counter ticks times the board's instructions per tick;
 * status 0: the last step applied its command, else its call error or 100 + why it held or stopped),
 * then "BENCH_DIGEST <name> <n>", a 32-bit FNV-1a hash of every command's bytes (two builds of the
 * core that compute the same commands bit for bit print the same digest),
 * "BENCH_SKIP <name>" for a problem the build's limits cannot hold, then "BENCH_CONFIG" with the
 * build's limits and the resolution. With an argument (host builds), runs only that problem.
 * On Cortex-M, each step also runs with the stack below it painted and interrupts off, and
 * "BENCH_STACK <name> <bytes>" gives the deepest any step wrote below its caller's stack pointer;
 * "BENCH_STACK hostile <bytes>" the same for steps fed hostile measurements (huge finite headings,
 * positions and speeds, which the step accepts and must still handle in bounded stack).
 */
#include <string.h>

#include "bench_problems.h"
#include "board.h"
#include "tvo/chain_controller.h"
#include "internal/chain_controller.h"
#include "internal/objective.h"

#define BENCH_PI 3.14159265358979f

#if defined(TVO_BENCH_HOST)
int main(int argc, char **argv);
#else
int main(void);
#endif

static uint32_t samples[BENCH_STEPS];
static bench_loop_t loop; /* its problem and controller's place also serve chain_k3, which runs last */

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

static uint32_t instructions(uint32_t ticks)
{
    return (uint32_t)(((uint64_t)ticks * TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM) / TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN);
}

static uint32_t digest; /* the current problem's, bench_problems.h's FNV-1a */

/* The last step's answer as one number: 0 when it applied a new command, else its call error, or
 * 100 + the reason it held or stopped. */
static int32_t period_verdict(tvo_status_t status, uint8_t outcome, uint8_t reason)
{
    if (status != TVO_OK) {
        return (int32_t)status;
    }
    return (outcome == TVO_OUTCOME_APPLIED) ? 0 : 100 + (int32_t)reason;
}

static void report(const char *name, uint32_t count, int32_t last_status)
{
    sort_samples(count);
    tvo_board_puts("BENCH ");
    tvo_board_puts(name);
    tvo_board_puts(" steps ");
    tvo_board_put_u32(count);
    tvo_board_puts(" min ");
    tvo_board_put_u32(instructions(samples[0]));
    tvo_board_puts(" median ");
    tvo_board_put_u32(instructions(samples[count / 2u]));
    tvo_board_puts(" max ");
    tvo_board_put_u32(instructions(samples[count - 1u]));
    tvo_board_puts(" status ");
    tvo_board_put_i32(last_status);
    tvo_board_puts("\nBENCH_DIGEST ");
    tvo_board_puts(name);
    tvo_board_putc(' ');
    tvo_board_put_u32(digest);
    tvo_board_putc('\n');
}

#if defined(__arm__)
/* The window painted below the caller's stack pointer: 4 KiB, several times any step's static bound
 * (tools/footprint.py); a step that wrote to its bottom word would be reported as using it all. */
#define STACK_WINDOW_WORDS 1024u
#define STACK_PAINT 0xA5A5A5A5u
static volatile uint32_t *stack_window;
static uint32_t stack_deepest; /* bytes, the deepest step of the current problem */

/* Paints the window just below the stack pointer of the caller (the frame the step is called from)
 * and masks interrupts, whose exception frames would land there too. Inline, so the pointer read is
 * the calling function's. */
#define STACK_PAINT_BELOW_HERE()                                               \
    do {                                                                       \
        uint32_t sp_;                                                          \
        __asm__ volatile("mov %0, sp" : "=r"(sp_));                            \
        stack_window = (volatile uint32_t *)(sp_ - 4u * STACK_WINDOW_WORDS);   \
        for (uint32_t i_ = 0; i_ < STACK_WINDOW_WORDS; ++i_) {                 \
            stack_window[i_] = STACK_PAINT;                                    \
        }                                                                      \
        __asm__ volatile("cpsid i" ::: "memory");                              \
    } while (0)

/* After the step: the lowest word no longer painted is how deep it went; then interrupts back on
 * (after the scan, so a pending one cannot leave its frame in the window first). */
static void stack_measure_after_step(void)
{
    uint32_t untouched = 0u;
    while (untouched < STACK_WINDOW_WORDS && stack_window[untouched] == STACK_PAINT) {
        ++untouched;
    }
    __asm__ volatile("cpsie i" ::: "memory");
    const uint32_t used = 4u * (STACK_WINDOW_WORDS - untouched);
    if (used > stack_deepest) {
        stack_deepest = used;
    }
}

static void stack_report(const char *name)
{
    tvo_board_puts("BENCH_STACK ");
    tvo_board_puts(name);
    tvo_board_putc(' ');
    tvo_board_put_u32(stack_deepest);
    tvo_board_putc('\n');
    stack_deepest = 0u;
}
#else
#define STACK_PAINT_BELOW_HERE() ((void)0)
static void stack_measure_after_step(void) {}
static void stack_report(const char *name)
{
    (void)name;
}
#endif

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

/* The closed loop of a unicycle problem, each step bracketed by the counter. */
static tvo_status_t bench_unicycle_problem(bench_unicycle_problem_t which)
{
    tvo_status_t last = bench_loop_init(&loop, which);
    if (last != TVO_OK) {
        return last;
    }
    digest = BENCH_DIGEST_BASIS;
    for (uint32_t n = 0; n < BENCH_STEPS; ++n) {
        const tvo_status_t advanced = bench_loop_advance(&loop);
        if (advanced != TVO_OK) {
            return advanced;
        }
        STACK_PAINT_BELOW_HERE();
        MEASURE(samples[n], tvo_controller_step(&loop.controller, &loop.meas, loop.apply_tick, &loop.cmd));
        stack_measure_after_step();
        digest = bench_digest_command(digest, &loop.cmd); /* outside the measured span */
    }
    report(bench_problem_name(which), BENCH_STEPS, period_verdict(last, loop.cmd.outcome, loop.cmd.reason));
    stack_report(bench_problem_name(which));
    return last;
}

/* Hostile measurements the step accepts (finite, so not refused at the door) on the unicycle
 * problem, whose ordinary steps are shallow: how deep the step goes for them (the trigonometry of a huge heading, limits
 * hit by huge positions and speeds). The statuses are whatever the step decides; only the stack is
 * measured here (the edge's and the fuzzers' tests judge the answers). */
static tvo_status_t bench_hostile(void)
{
    static const tvo_real_t headings_rad[] = {TVO_R(1e30), TVO_R(-3.4e38), TVO_R(8192.5), TVO_R(-1e9)};
    static const tvo_real_t positions_m[] = {TVO_R(1e30), TVO_R(-1e20), TVO_R(3.0e38), TVO_R(0.5)};
    tvo_status_t last = bench_loop_init(&loop, BENCH_UNICYCLE);
    if (last != TVO_OK) {
        return last;
    }
    for (uint32_t n = 0; n < 40u; ++n) {
        if (bench_loop_advance(&loop) != TVO_OK) {
            return TVO_ERR_NUMERIC;
        }
        if (n >= 8u) {
            const uint32_t k = n % 4u;
            loop.meas.heading_rad[0] = headings_rad[k];
            loop.meas.position_m[0][k % 2u] = positions_m[(n / 4u) % 4u];
            loop.meas.speed_valid = 1u;
            loop.meas.speed_mps[0] = (k == 3u) ? TVO_R(1e35) : TVO_R(0.3);
        }
        STACK_PAINT_BELOW_HERE();
        (void)tvo_controller_step(&loop.controller, &loop.meas, loop.apply_tick, &loop.cmd);
        stack_measure_after_step();
    }
    stack_report("hostile");
    return TVO_OK;
}

static tvo_status_t bench_unicycle(void)
{
    return bench_unicycle_problem(BENCH_UNICYCLE);
}

static tvo_status_t bench_obstacles4(void)
{
    return bench_unicycle_problem(BENCH_OBSTACLES4);
}

static tvo_status_t bench_formation2(void)
{
    return bench_unicycle_problem(BENCH_FORMATION2);
}

/* The scaling families (bench_problems.h): each a closed loop like the three above. */
static tvo_status_t bench_formation4(void)
{
    return bench_unicycle_problem(BENCH_FORMATION4);
}

static tvo_status_t bench_formation8(void)
{
    return bench_unicycle_problem(BENCH_FORMATION8);
}

static tvo_status_t bench_formation16(void)
{
    return bench_unicycle_problem(BENCH_FORMATION16);
}

static tvo_status_t bench_formation32(void)
{
    return bench_unicycle_problem(BENCH_FORMATION32);
}

static tvo_status_t bench_obstacles0(void)
{
    return bench_unicycle_problem(BENCH_OBSTACLES0);
}

static tvo_status_t bench_obstacles8(void)
{
    return bench_unicycle_problem(BENCH_OBSTACLES8);
}

static tvo_status_t bench_obstacles16(void)
{
    return bench_unicycle_problem(BENCH_OBSTACLES16);
}

static tvo_status_t bench_chain_k3(void)
{
    tvo_problem_desc_t desc;
    tvo_problem_culprit_t part;
    (void)tvo_problem_desc_default(&desc);
    desc.robot_count = 1u;
    const tvo_real_t center[2] = {TVO_R(0.0), TVO_R(0.0)};
    (void)tvo_target_init_circle(&desc.target[0], center, TVO_R(1.0), 2.0f * BENCH_PI / 10.0f, TVO_R(0.0));
    tvo_status_t last = tvo_problem_init(&loop.problem, &desc, 3u, &part);
    tvo_chain_config_t cfg;
    tvo_chain_param_t bad = TVO_CHAIN_PARAM_NONE;
    (void)tvo_chain_config_default(&cfg);
    cfg.relative_degree = 3u;
    cfg.gain[0] = TVO_R(4.096); /* (s + 1.6)^3 */
    cfg.gain[1] = TVO_R(7.68);
    cfg.gain[2] = TVO_R(4.8);
    if (last == TVO_OK) {
        last = tvo_chain_controller_init(&loop.chain, &cfg, &loop.problem.objective, 0u, &bad);
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
    digest = BENCH_DIGEST_BASIS;
    for (uint32_t n = 0; n < BENCH_STEPS; ++n) {
        tvo_chain_measurement_t meas;
        (void)tvo_chain_predict(3u, 2u, &state, cmd.u, half_s, &state);
        meas.y = state;
        meas.stamp_tick = n * cfg.period_ticks + cfg.period_ticks - cfg.delay_ticks;
        (void)tvo_chain_predict(3u, 2u, &state, cmd.u, half_s, &state);
        STACK_PAINT_BELOW_HERE();
        MEASURE(samples[n], tvo_chain_controller_step(&loop.chain, &meas, (n + 1u) * cfg.period_ticks, &cmd));
        stack_measure_after_step();
        digest = bench_digest_bytes(digest, &cmd.u, sizeof(cmd.u));
    }
    report("chain_k3", BENCH_STEPS, period_verdict(last, cmd.outcome, cmd.reason));
    stack_report("chain_k3");
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
                   {"chain_k3", bench_chain_k3},
                   {"hostile", bench_hostile},
                   {"formation4", bench_formation4},
                   {"formation8", bench_formation8},
                   {"obstacles0", bench_obstacles0},
                   {"obstacles8", bench_obstacles8},
                   {"obstacles16", bench_obstacles16},
                   {"formation16", bench_formation16},
                   {"formation32", bench_formation32}};
    tvo_board_cycle_counter_start();
    int failures = 0;
    for (uint32_t i = 0; i < sizeof(benches) / sizeof(benches[0]); ++i) {
        if (only != NULL && strcmp(only, benches[i].name) != 0) {
            continue;
        }
        const tvo_status_t st = benches[i].run();
        if (st == TVO_ERR_DIMENSION) {
            tvo_board_puts("BENCH_SKIP "); /* the build's limits cannot hold it */
            tvo_board_puts(benches[i].name);
            tvo_board_putc('\n');
        } else if (st != TVO_OK) {
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
    tvo_board_puts(" instructions_per_tick ");
    tvo_board_put_u32(TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM);
    tvo_board_putc('/');
    tvo_board_put_u32(TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN);
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
