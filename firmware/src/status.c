/* Human-readable names of status codes and parameters, for the edge's logs. */
#include "tvo/status.h"

const char *tvo_status_str(tvo_status_t status)
{
    switch (status) {
    case TVO_OK: return "ok";
    case TVO_ERR_NULL: return "null pointer";
    case TVO_ERR_NOT_FINITE: return "input not finite (NaN or Inf)";
    case TVO_ERR_DIMENSION: return "dimension out of range";
    case TVO_ERR_PARAM: return "parameter out of range";
    case TVO_ERR_CAPACITY: return "fixed-size table full";
    case TVO_ERR_NOT_INITIALIZED: return "not initialised";
    case TVO_ERR_NOT_POSITIVE_DEFINITE: return "Hessian not positive definite";
    case TVO_ERR_NUMERIC: return "result not finite";
    case TVO_ERR_STALE: return "measurement stale (older than one period)";
    case TVO_ERR_OUT_OF_ORDER: return "timestamp did not advance";
    case TVO_ERR_FUTURE_STAMP: return "timestamp in the future";
    case TVO_ERR_NO_MEASUREMENT: return "no measurement this period";
    case TVO_ERR_MISSING_FIELD: return "measurement lacks a field the configuration needs";
    case TVO_ERR_TARGET_NOT_READY: return "streamed target has no sample yet";
    case TVO_ERR_WATCHDOG: return "watchdog expired: safe stop";
    case TVO_ERR_IMPLAUSIBLE_STAMP: return "stamp does not fit the session's schedule";
    case TVO_ERR_SESSION_CONFLICT: return "session id already running with other parameters";
    case TVO_ERR_NO_SESSION: return "no such session running (send START)";
    case TVO_ERR_IMPLAUSIBLE_MEASUREMENT: return "measurement beyond the robot's workspace, heading range or speed";
    default: return "unknown status";
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
    case TVO_PARAM_EPOCH: return "epoch_tick";
    case TVO_PARAM_CLOCK_SOURCE: return "clock_source";
    case TVO_PARAM_PLANT_KIND: return "plant_kind";
    case TVO_PARAM_SESSION_ID: return "session_id";
    default: return "unknown parameter";
    }
}
