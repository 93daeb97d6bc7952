/*
 * The paper's loop, written once: the values tvo_controller_config_default, tvo_chain_config_default and
 * tvo_barrier_config_default give, which the host's plant (tvo_sim's options), the example plants and the Python module
 * (tvo.defaults) send in a START. Plain double literals, so a host, a plant in another language and the
 * core in either precision read the same numbers.
 */
#ifndef TVO_DEFAULTS_H
#define TVO_DEFAULTS_H

/* Timing: h = 10 ms, the sample taken tau = 5 ms before its period's command applies, ticks in us. */
#define TVO_DEFAULT_TICK_HZ 1000000
#define TVO_DEFAULT_PERIOD_US 10000
#define TVO_DEFAULT_DELAY_US 5000
/* No good step for this many periods: the watchdog's stop. */
#define TVO_DEFAULT_WATCHDOG_PERIODS 10

/* The dirty derivative's time constant (s), both plants. */
#define TVO_DEFAULT_FILTER_TF_S 0.05

/* The unicycle: k = 2 gains (poles -5, -8) and the limits a ground robot is held to. */
#define TVO_DEFAULT_GAIN_KP 40.0
#define TVO_DEFAULT_GAIN_KD 13.0
#define TVO_DEFAULT_OMEGA_MAX_RADPS 6.283185307179586
#define TVO_DEFAULT_ACCEL_MAX_MPS2 15.0
#define TVO_DEFAULT_SPEED_MAX_MPS 5.0
#define TVO_DEFAULT_MIN_SPEED_MPS 0.05

/* The chain (k = 2 default): gains of (s + 1.6)^2 and the bound on its input. */
#define TVO_DEFAULT_CHAIN_GAIN_0 2.56
#define TVO_DEFAULT_CHAIN_GAIN_1 3.2
#define TVO_DEFAULT_CHAIN_INPUT_MAX 1e3

/* The barrier (tvo_barrier_config_default): c0, alpha_c (1/s), c_max, delta0, alpha_s (1/s), eps_s, m_r. */
#define TVO_DEFAULT_BARRIER_C0 1.0
#define TVO_DEFAULT_BARRIER_ALPHA_C_PER_S 1.0
#define TVO_DEFAULT_BARRIER_C_MAX 1e4
#define TVO_DEFAULT_BARRIER_DELTA0 0.05
#define TVO_DEFAULT_BARRIER_ALPHA_S_PER_S 1.0
#define TVO_DEFAULT_BARRIER_SLACK_MARGIN 0.1
#define TVO_DEFAULT_BARRIER_RELAXATION_DEGREE 4

#endif /* TVO_DEFAULTS_H */
