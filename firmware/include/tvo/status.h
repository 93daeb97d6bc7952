/*
 * What the control core's calls answer, in three vocabularies kept apart (as OSQP keeps its
 * osqp_error_type apart from the solver's status):
 *
 *   tvo_status_t   returned by every public function: TVO_OK, or an error that says the call failed and
 *                  changed nothing (a caller's misuse, or a computation that produced no result).
 *   tvo_outcome_t  what a controller's period did with the robots, carried by the command it delivers
 *   tvo_reason_t   (tvo_command_t.outcome / .reason): applied, or held / stopped and why. A step that
 *                  delivers a command returns TVO_OK whatever its outcome.
 *   tvo_param_t    which field of tvo_controller_config_t an init refused (the chain's configuration
 *                  names its own: tvo_chain_param_t in tvo/chain_controller.h).
 *
 * None of these numbers is the wire's: the edge maps them to command_t.status and session_ack_t's
 * fields in one table (firmware/edge/step_codec.c, session_codec.c).
 */
#ifndef TVO_STATUS_H
#define TVO_STATUS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A call's answer. Every code but TVO_OK means the call changed nothing (outputs aside: a controller's
 *  cmd still receives a command that is safe to apply, see tvo/controller.h). */
typedef enum {
    TVO_OK = 0,
    /* The caller's misuse: */
    TVO_ERR_NULL = 1,                  /* a required pointer was NULL */
    TVO_ERR_NOT_FINITE = 2,            /* an argument was NaN or infinite */
    TVO_ERR_DIMENSION = 3,             /* a size is zero or above its compile-time limit */
    TVO_ERR_PARAM = 4,                 /* a parameter is out of range (an init names it: tvo_param_t) */
    TVO_ERR_CAPACITY = 5,              /* a fixed-size table is full */
    TVO_ERR_NOT_INITIALIZED = 6,       /* the instance was not (successfully) initialised */
    TVO_ERR_TICK_NOT_ADVANCING = 7,    /* a tick or stamp does not advance past the last one taken (apply_tick
                                          past the last period, a streamed target's stamp past its sample's) */
    TVO_ERR_BEFORE_EPOCH = 8,          /* a time before the epoch (objective time 0) */
    /* Computations that produced no result (a controller's step never returns these: it holds or stops,
     * and its command's tvo_reason_t says why): */
    TVO_ERR_NOT_POSITIVE_DEFINITE = 9, /* the Hessian is not positive definite: no Newton step */
    TVO_ERR_NUMERIC = 10               /* a computed value came out NaN or infinite */
} tvo_status_t;

/** Number of tvo_status_t codes (0 .. TVO_STATUS_COUNT - 1). */
#define TVO_STATUS_COUNT 11

/** What a controller's period did: the command it delivers says (tvo_command_t.outcome). */
typedef enum {
    TVO_OUTCOME_APPLIED = 0,           /* a new command, computed from this period's measurement */
    TVO_OUTCOME_HELD = 1,              /* the command in force, repeated; nothing changed (reason: why) */
    TVO_OUTCOME_STOPPED = 2            /* every input zero: the robots stop (reason: why) */
} tvo_outcome_t;

#define TVO_OUTCOME_COUNT 3

/** Why a period's command was held or stopped (TVO_REASON_NONE when applied). */
typedef enum {
    TVO_REASON_NONE = 0,
    /* The measurement refused (held, or stopped when the watchdog expires with it): */
    TVO_REASON_NOT_FINITE = 1,             /* a value the configuration reads is NaN or infinite */
    TVO_REASON_IMPLAUSIBLE_MEASUREMENT = 2, /* finite, but beyond what the session's robot can be */
    TVO_REASON_STALE = 3,                  /* stamped more than one period before the application */
    TVO_REASON_FUTURE_STAMP = 4,           /* stamped after the application time */
    TVO_REASON_STAMP_NOT_NEWER = 5,        /* stamped no later than the last accepted measurement */
    TVO_REASON_MISSING_FIELD = 6,          /* the velocity source needs a field the measurement lacks */
    TVO_REASON_SOURCE_NOT_LINKED = 7,      /* the velocity source set was not linked by the init */
    /* The law could not serve it (its targets, checked before it; then its result): */
    TVO_REASON_TARGET_NOT_READY = 8,       /* a streamed target has no sample yet (one stamped after the
                                              law's time: TVO_REASON_FUTURE_STAMP) */
    TVO_REASON_NUMERIC = 9,                /* a computed value came out NaN or infinite */
    TVO_REASON_NOT_POSITIVE_DEFINITE = 10, /* the Hessian is not positive definite: no Newton step */
    /* No measurement: */
    TVO_REASON_NO_MEASUREMENT = 11,        /* none this period (tvo_controller_miss) */
    /* Stops: */
    TVO_REASON_WATCHDOG = 12,              /* watchdog_periods periods without a good step */
    TVO_REASON_SPEED_MISMATCH = 13,        /* measured speeds contradicted the command (tvo/controller.h) */
    TVO_REASON_STOP_REQUESTED = 14,        /* the caller asked (tvo_controller_safe_stop) */
    /* The caller's own checks: */
    TVO_REASON_REFUSED = 15                /* refused before the core saw it (tvo_controller_refuse) */
} tvo_reason_t;

#define TVO_REASON_COUNT 16

/** Names the field of tvo_controller_config_t an init rejected. */
typedef enum {
    TVO_PARAM_NONE = 0,
    TVO_PARAM_TICK_HZ = 1,
    TVO_PARAM_PERIOD = 2,
    TVO_PARAM_DELAY = 3,               /* delay_ticks, or a switch (delay_compensation, zoh_aware) not 0/1 */
    TVO_PARAM_FILTER_TF = 4,
    TVO_PARAM_GAINS = 5,
    TVO_PARAM_OMEGA_MAX = 6,
    TVO_PARAM_ACCEL_MAX = 7,
    TVO_PARAM_SPEED_MAX = 8,
    TVO_PARAM_MIN_SPEED = 9,
    TVO_PARAM_WATCHDOG = 10,
    TVO_PARAM_ROBOT_COUNT = 11,
    TVO_PARAM_OBJECTIVE = 12,          /* the objective argument: its dimension, or no term */
    TVO_PARAM_VELOCITY_SOURCE = 13,
    TVO_PARAM_INITIAL_SPEED = 14
} tvo_param_t;

#define TVO_PARAM_COUNT 15

/* Bits of a command's flags: what shaped an applied command (its outcome says whether it was applied). */
#define TVO_FLAG_OMEGA_SATURATED (1u << 0)  /* |omega| clipped to omega_max */
#define TVO_FLAG_ACCEL_SATURATED (1u << 1)  /* |dv/dt| clipped to accel_max */
#define TVO_FLAG_SPEED_SATURATED (1u << 2)  /* |v| clipped to speed_max (anti-windup held the state) */
#define TVO_FLAG_LOW_SPEED (1u << 3)        /* |v| below min_speed: 1/v regularised */
/* Bits 4 and 5 are the wire's HOLDING and SAFE_STOP, which the edge derives from the outcome. */
#define TVO_FLAG_PREDICTED (1u << 6)        /* state predicted over the computation delay */
#define TVO_FLAG_REGULARIZED (1u << 7)      /* Hessian not positive definite: the solve shifted it */
#define TVO_FLAG_SPEED_MISMATCH (1u << 8)   /* measured speed contradicts the commanded speed (stall, or a lying plant) */

/** Short English description of a call's status, for logs at the edge (no stdio in the core). */
const char *tvo_status_str(tvo_status_t status);

/** Short English description of a period's outcome. */
const char *tvo_outcome_str(tvo_outcome_t outcome);

/** Short English description of why a period's command was held or stopped. */
const char *tvo_reason_str(tvo_reason_t reason);

/** Name of a parameter as it appears in tvo_controller_config_t. */
const char *tvo_param_str(tvo_param_t param);

#ifdef __cplusplus
}
#endif

#endif /* TVO_STATUS_H */
