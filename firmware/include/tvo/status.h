/*
 * Status codes, parameter names and command flags shared by every block of the control core.
 *
 * Every public function returns a tvo_status_t; 0 means success. The numeric values are part of
 * the wire protocol (command_t.status) and must not be renumbered.
 */
#ifndef TVO_STATUS_H
#define TVO_STATUS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    TVO_OK = 0,
    TVO_ERR_NULL = 1,                /* a required pointer was NULL */
    TVO_ERR_NOT_FINITE = 2,          /* an input was NaN or infinite */
    TVO_ERR_DIMENSION = 3,           /* a size is zero or above its compile-time limit */
    TVO_ERR_PARAM = 4,               /* a parameter is out of range (see tvo_param_t) */
    TVO_ERR_CAPACITY = 5,            /* a fixed-size table is full */
    TVO_ERR_NOT_INITIALIZED = 6,     /* the instance was not (successfully) initialised */
    TVO_ERR_NOT_POSITIVE_DEFINITE = 7, /* the Hessian is not positive definite: no Newton step */
    TVO_ERR_NUMERIC = 8,             /* a computed value came out NaN or infinite */
    TVO_ERR_STALE = 9,               /* the measurement is older than one period */
    TVO_ERR_OUT_OF_ORDER = 10,       /* a timestamp did not advance */
    TVO_ERR_FUTURE_STAMP = 11,       /* the measurement is stamped after the application time */
    TVO_ERR_NO_MEASUREMENT = 12,     /* no measurement arrived for this period */
    TVO_ERR_MISSING_FIELD = 13,      /* the velocity source needs a field the measurement lacks */
    TVO_ERR_TARGET_NOT_READY = 14,   /* a streamed target has no sample yet */
    TVO_ERR_WATCHDOG = 15,           /* no valid measurement within the watchdog: safe stop */
    TVO_ERR_IMPLAUSIBLE_STAMP = 16,  /* the stamp (or stamp and sequence) does not fit the schedule */
    TVO_ERR_SESSION_CONFLICT = 17,   /* a START reuses the running session's id with other content */
    TVO_ERR_NO_SESSION = 18,         /* no such session is running (send START) */
    TVO_ERR_IMPLAUSIBLE_MEASUREMENT = 19 /* finite, but beyond what the session's robot can be (tvo/controller.h) */
} tvo_status_t;

/** Number of status codes: arrays indexed by status (the node's refusal counters) hold this many. */
#define TVO_STATUS_COUNT 20

/** Names the parameter an init rejected. */
typedef enum {
    TVO_PARAM_NONE = 0,
    TVO_PARAM_TICK_HZ = 1,
    TVO_PARAM_PERIOD = 2,
    TVO_PARAM_DELAY = 3,
    TVO_PARAM_FILTER_TF = 4,
    TVO_PARAM_GAINS = 5,
    TVO_PARAM_OMEGA_MAX = 6,
    TVO_PARAM_ACCEL_MAX = 7,
    TVO_PARAM_SPEED_MAX = 8,
    TVO_PARAM_MIN_SPEED = 9,
    TVO_PARAM_WATCHDOG = 10,
    TVO_PARAM_ROBOT_COUNT = 11,
    TVO_PARAM_OBJECTIVE = 12,
    TVO_PARAM_VELOCITY_SOURCE = 13,
    TVO_PARAM_INITIAL_SPEED = 14,
    TVO_PARAM_EPOCH = 15,
    TVO_PARAM_CLOCK_SOURCE = 16,
    TVO_PARAM_PLANT_KIND = 17,
    TVO_PARAM_SESSION_ID = 18
} tvo_param_t;

/* Bits of tvo_command_t.flags: what shaped the command, for telemetry and fault counting. */
#define TVO_FLAG_OMEGA_SATURATED (1u << 0)  /* |omega| clipped to omega_max */
#define TVO_FLAG_ACCEL_SATURATED (1u << 1)  /* |dv/dt| clipped to accel_max */
#define TVO_FLAG_SPEED_SATURATED (1u << 2)  /* |v| clipped to speed_max (anti-windup held the state) */
#define TVO_FLAG_LOW_SPEED (1u << 3)        /* |v| below min_speed: 1/v regularised */
#define TVO_FLAG_HOLDING (1u << 4)          /* no usable measurement: previous command held */
#define TVO_FLAG_SAFE_STOP (1u << 5)        /* watchdog expired or law failed: v = 0, omega = 0 */
#define TVO_FLAG_PREDICTED (1u << 6)        /* state predicted over the computation delay */
#define TVO_FLAG_REGULARIZED (1u << 7)      /* Hessian not positive definite: the solve shifted it */
#define TVO_FLAG_SPEED_MISMATCH (1u << 8)   /* measured speed contradicts the commanded speed (stall, or a lying plant) */

/** Short English description of a status, for logs at the edge (no stdio in the core). */
const char *tvo_status_str(tvo_status_t status);

/** Name of a parameter as it appears in tvo_controller_config_t. */
const char *tvo_param_str(tvo_param_t param);

#ifdef __cplusplus
}
#endif

#endif /* TVO_STATUS_H */
