/* Human-readable names of statuses, outcomes, reasons and parameters, for the edge's logs. */
#include "tvo/status.h"

const char *tvo_status_str(tvo_status_t status)
{
    switch (status) {
    case TVO_OK: return "ok";
    case TVO_ERR_NULL: return "null pointer";
    case TVO_ERR_NOT_FINITE: return "argument not finite (NaN or Inf)";
    case TVO_ERR_DIMENSION: return "dimension out of range";
    case TVO_ERR_PARAM: return "parameter out of range";
    case TVO_ERR_CAPACITY: return "fixed-size table full";
    case TVO_ERR_NOT_INITIALIZED: return "not initialised";
    case TVO_ERR_TICK_NOT_ADVANCING: return "tick or stamp does not advance past the last one taken";
    case TVO_ERR_BEFORE_EPOCH: return "time before the epoch";
    case TVO_ERR_NOT_POSITIVE_DEFINITE: return "Hessian not positive definite";
    case TVO_ERR_NUMERIC: return "result not finite";
    default: return "unknown status";
    }
}

const char *tvo_outcome_str(tvo_outcome_t outcome)
{
    switch (outcome) {
    case TVO_OUTCOME_APPLIED: return "applied";
    case TVO_OUTCOME_HELD: return "held";
    case TVO_OUTCOME_STOPPED: return "stopped";
    default: return "unknown outcome";
    }
}

const char *tvo_reason_str(tvo_reason_t reason)
{
    switch (reason) {
    case TVO_REASON_NONE: return "none";
    case TVO_REASON_NOT_FINITE: return "measurement not finite (NaN or Inf)";
    case TVO_REASON_IMPLAUSIBLE_MEASUREMENT: return "measurement beyond the robot's workspace, heading range or speed";
    case TVO_REASON_STALE: return "measurement stale (older than one period)";
    case TVO_REASON_FUTURE_STAMP: return "measurement stamped after the application time";
    case TVO_REASON_STAMP_NOT_NEWER: return "measurement not newer than the last accepted one";
    case TVO_REASON_MISSING_FIELD: return "measurement lacks a field the configuration needs";
    case TVO_REASON_SOURCE_NOT_LINKED: return "velocity source not linked by the init";
    case TVO_REASON_TARGET_NOT_READY: return "streamed target has no sample yet";
    case TVO_REASON_NUMERIC: return "law result not finite";
    case TVO_REASON_NOT_POSITIVE_DEFINITE: return "Hessian not positive definite";
    case TVO_REASON_NO_MEASUREMENT: return "no measurement this period";
    case TVO_REASON_WATCHDOG: return "watchdog expired: safe stop";
    case TVO_REASON_SPEED_MISMATCH: return "measured speed contradicted the command: stop";
    case TVO_REASON_STOP_REQUESTED: return "safe stop requested";
    case TVO_REASON_REFUSED: return "measurement refused by the caller's checks";
    default: return "unknown reason";
    }
}

const char *tvo_param_str(tvo_param_t param)
{
    switch (param) {
    case TVO_PARAM_NONE: return "none";
    case TVO_PARAM_TICK_HZ: return "tick_hz";
    case TVO_PARAM_PERIOD: return "period_ticks";
    case TVO_PARAM_DELAY: return "delay_ticks";
    case TVO_PARAM_FILTER_TF: return "filter_tf_s";
    case TVO_PARAM_GAINS: return "gain_kp/gain_kd";
    case TVO_PARAM_OMEGA_MAX: return "omega_max_radps";
    case TVO_PARAM_ACCEL_MAX: return "accel_max_mps2";
    case TVO_PARAM_SPEED_MAX: return "speed_max_mps";
    case TVO_PARAM_MIN_SPEED: return "min_speed_mps";
    case TVO_PARAM_WATCHDOG: return "watchdog_periods";
    case TVO_PARAM_ROBOT_COUNT: return "robot_count";
    case TVO_PARAM_OBJECTIVE: return "objective";
    case TVO_PARAM_VELOCITY_SOURCE: return "velocity_source";
    case TVO_PARAM_INITIAL_SPEED: return "initial_speed_mps";
    default: return "unknown parameter";
    }
}
