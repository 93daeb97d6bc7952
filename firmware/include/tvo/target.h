/*
 * Moving targets y_d(t) in the plane and their time derivatives.
 *
 * Analytic targets live on board (polynomial sum A_j t^j, circle, ellipse); a streamed target holds
 * the latest sample (position .. jerk at a tick stamp) sent by the host and extrapolates it
 * causally by its Taylor polynomial to the time asked for.
 */
#ifndef TVO_TARGET_H
#define TVO_TARGET_H

#include "tvo/config.h"
#include "tvo/jet.h"
#include "tvo/objective.h"
#include "tvo/status.h"
#include "tvo/trig.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    TVO_TARGET_POLYNOMIAL = 0,
    TVO_TARGET_CIRCLE = 1,
    TVO_TARGET_ELLIPSE = 2,
    TVO_TARGET_STREAMED = 3
} tvo_target_kind_t;

typedef struct {
    tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1]; /* per axis: A_0 .. A_D (m, m/s, m/s^2, ...) */
} tvo_target_polynomial_t;

typedef struct {
    tvo_real_t center_m[2];
    tvo_real_t semi_axis_m[2];  /* a along the rotated x axis, b along the rotated y axis; a = b: circle */
    tvo_real_t omega_radps;     /* angular rate of the parameter, may be negative */
    tvo_real_t phase_rad;
    tvo_real_t rotation_rad;    /* rotation of the ellipse's axes */
    /* omega as fractional turns per second in Q0.64 (tvo_target_turns_q64 of the double value), so
     * the phase stays exact over hours in float32; 0: derived from omega_radps at its precision. */
    uint64_t rate_turns_q64;
} tvo_target_ellipse_t;

typedef struct {
    uint64_t stamp_ticks;       /* ticks since the objective's epoch at which deriv[] holds */
    tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2]; /* position, velocity, acceleration, jerk */
    uint8_t has_sample;
} tvo_target_streamed_t;

typedef struct tvo_target {
    tvo_target_kind_t kind;
    union {
        tvo_target_polynomial_t polynomial;
        tvo_target_ellipse_t ellipse;   /* circles are ellipses with equal semi-axes */
        tvo_target_streamed_t streamed;
    } u;
    tvo_real_t axis_m[2][2];    /* ellipse: the rotated semi-axes R (a, 0) and R (0, b), by init */
    uint64_t phase0_q64;        /* ellipse: phase at t = 0 in turns, Q0.64 */
    uint64_t rate_q64;          /* ellipse: fractional turns per second, Q0.64 */
    uint8_t poly_degree;        /* polynomial: the highest power with a non-zero coefficient */
} tvo_target_t;

/** Polynomial target; coeff[axis][j] multiplies t^j, degree <= TVO_POLY_MAX_DEGREE. */
tvo_status_t tvo_target_init_polynomial(tvo_target_t *target,
                                        const tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1]);
/** |omega| above this is refused (TVO_ERR_PARAM): the angle a second adds stays in tvo_sincos_turns' range. */
#define TVO_TARGET_MAX_OMEGA_RADPS TVO_SINCOS_FAST_LIMIT_RAD

/** Circle centre + radius (cos, sin) of (omega t + phase). radius > 0, |omega| <= TVO_TARGET_MAX_OMEGA_RADPS. */
tvo_status_t tvo_target_init_circle(tvo_target_t *target, const tvo_real_t center_m[2],
                                    tvo_real_t radius_m, tvo_real_t omega_radps, tvo_real_t phase_rad);
/** Ellipse: centre + R(rotation) (a cos, b sin) of (omega t + phase). a, b > 0, |omega| <= TVO_TARGET_MAX_OMEGA_RADPS. */
tvo_status_t tvo_target_init_ellipse(tvo_target_t *target, const tvo_target_ellipse_t *ellipse);
/**
 * The fractional part of omega / (2 pi) in Q0.64 turns per second, from a double (an edge that
 * receives omega in double keeps its precision this way; see tvo_target_ellipse_t). 0 if not finite.
 */
uint64_t tvo_target_turns_q64(double omega_radps);

/** Streamed target with no sample yet: a controller's step holds its command in force (reason
 *  TVO_REASON_TARGET_NOT_READY) until one arrives, and while the law's time precedes the sample's stamp
 *  (TVO_REASON_FUTURE_STAMP); the step checks both before its law. An objective notes that a target is
 *  streamed when the term reading it is added: re-initialising a target as streamed afterwards needs the
 *  objective built again (its init and adds; tvo_problem_init does both), else the law refuses the target
 *  (TVO_REASON_NUMERIC). */
tvo_status_t tvo_target_init_streamed(tvo_target_t *target);

/**
 * New streamed sample valid at stamp_ticks (since the objective's epoch); deriv[j] is the j-th time
 * derivative, j = 0..TVO_STREAM_MAX_DERIV. Rejects a value not finite (TVO_ERR_NOT_FINITE) or beyond the
 * workspace (TVO_ERR_PARAM), a target not streamed (TVO_ERR_PARAM), and a stamp that does not advance past
 * the last sample's (TVO_ERR_TICK_NOT_ADVANCING); a refused sample changes nothing.
 */
tvo_status_t tvo_target_stream_update(tvo_target_t *target, uint64_t stamp_ticks,
                                      const tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2]);

#ifdef __cplusplus
}
#endif

#endif /* TVO_TARGET_H */
