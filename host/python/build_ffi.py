#!/usr/bin/python3
"""Writes the C source of the `tvo` module's extension (cffi, API mode) for one precision.

API mode: cffi emits C that includes the core's real public headers and is compiled by the
project's CMake against them, so every struct size and field offset comes from the compiler, never
from a copy here. The declarations below name only the public fields Python reads or writes; each
struct ends in "...;" (the rest, whatever it becomes, is the compiler's business), arrays are sized
"[...]" and tvo_real_t is "float..." (float or double, as TVO_USE_DOUBLE says). The names of the
status codes, outcomes, reasons, parameter names and flags are read from tvo/status.h (and the chain's
parameter names from tvo/chain_controller.h): enumerators and macros become integer constants whose
values the compiler supplies, so a code added there is picked up.

Usage: build_ffi.py INCLUDE_DIR MODULE_NAME OUT_C
"""
import os
import re
import sys

import cffi


def enum_names(header, type_name):
    """The enumerators of `typedef enum { ... } type_name;` in header, in order."""
    m = re.search(r"typedef\s+enum\s*\{(.*?)\}\s*" + type_name + r"\s*;", header, re.S)
    if not m:
        raise SystemExit(f"build_ffi.py: no enum {type_name} in its header")
    body = re.sub(r"/\*.*?\*/", "", m.group(1), flags=re.S)
    return re.findall(r"\b(TVO_[A-Z0-9_]+)\s*=", body)


def flag_names(header):
    return re.findall(r"^#define\s+(TVO_FLAG_[A-Z0-9_]+)\s", header, re.M)


def cdef_text(include_dir):
    with open(f"{include_dir}/tvo/status.h", encoding="utf-8") as f:
        status_h = f.read()
    with open(f"{include_dir}/tvo/chain_controller.h", encoding="utf-8") as f:
        chain_h = f.read()
    names = (enum_names(status_h, "tvo_status_t") + enum_names(status_h, "tvo_outcome_t") +
             enum_names(status_h, "tvo_reason_t") + enum_names(status_h, "tvo_param_t") +
             enum_names(chain_h, "tvo_chain_param_t") + flag_names(status_h))
    constants = "\n".join(f"#define {name} ..." for name in names)
    return f"""
typedef float... tvo_real_t;
typedef int... tvo_status_t;
typedef int... tvo_outcome_t;
typedef int... tvo_reason_t;
typedef int... tvo_param_t;
typedef int... tvo_chain_param_t;
typedef int... tvo_velocity_source_t;
typedef int... tvo_target_kind_t;
{constants}
#define TVO_STATUS_COUNT ...
#define TVO_OUTCOME_COUNT ...
#define TVO_REASON_COUNT ...
#define TVO_PARAM_COUNT ...
#define TVO_CHAIN_PARAM_COUNT ...
#define TVO_VELOCITY_FROM_POSE ...
#define TVO_VELOCITY_FROM_POSITION ...
#define TVO_TARGET_CIRCLE ...
#define TVO_USE_DOUBLE ...
#define TVO_MAX_ROBOTS ...
#define TVO_MAX_OUTPUT_DIM ...
#define TVO_MAX_Z_DIM ...
#define TVO_MAX_RELATIVE_DEGREE ...
#define TVO_MAX_OBSTACLES ...
#define TVO_POSITION_LIMIT_M_VALUE ...
#define TVO_MAX_DISTANCE_BOUNDS ...
#define TVO_MAX_HALFSPACES ...
#define TVO_MAX_OFFSET_EQUALITIES ...
#define TVO_POLY_MAX_DEGREE ...
#define TVO_STREAM_MAX_DERIV ...

const char *tvo_status_str(tvo_status_t status);
const char *tvo_outcome_str(tvo_outcome_t outcome);
const char *tvo_reason_str(tvo_reason_t reason);
const char *tvo_param_str(tvo_param_t param);
const char *tvo_chain_param_str(tvo_chain_param_t param);

/* --- the problem (tvo/problem.h, tvo/target.h, tvo/barrier.h, tvo/constraints.h) --- */
typedef struct {{ tvo_target_kind_t kind; ...; }} tvo_target_t;
typedef struct {{ ...; }} tvo_objective_t;
typedef struct {{
    tvo_real_t center_m[2];
    tvo_real_t semi_axis_m[2];
    tvo_real_t omega_radps;
    tvo_real_t phase_rad;
    tvo_real_t rotation_rad;
    uint64_t rate_turns_q64;
    ...;
}} tvo_target_ellipse_t;
typedef struct {{
    tvo_real_t c0; tvo_real_t alpha_c_per_s; tvo_real_t c_max; tvo_real_t delta0;
    tvo_real_t alpha_s_per_s; tvo_real_t slack_margin; uint8_t relaxation_degree;
    ...;
}} tvo_barrier_config_t;
typedef struct {{ tvo_real_t center_m[2]; tvo_real_t radius_m; ...; }} tvo_disk_t;
typedef struct {{
    uint8_t robot_a; uint8_t robot_b;
    tvo_real_t min_m; tvo_real_t min_rate_mps; tvo_real_t max_m; tvo_real_t max_rate_mps;
    ...;
}} tvo_distance_bound_desc_t;
typedef struct {{
    uint8_t robot; tvo_real_t normal[2]; tvo_real_t normal_rate[2]; tvo_real_t bound_m; tvo_real_t bound_rate_mps;
    ...;
}} tvo_halfspace_desc_t;
typedef struct {{ uint8_t robot_a; uint8_t robot_b; tvo_target_t offset; ...; }} tvo_offset_desc_t;
typedef struct {{
    uint8_t robot_count;
    tvo_target_t target[...];
    tvo_real_t tracking_weight[...][2];
    tvo_barrier_config_t barrier;
    uint8_t distance_count;
    tvo_distance_bound_desc_t distance[...];
    uint8_t halfspace_count;
    tvo_halfspace_desc_t halfspace[...];
    uint8_t obstacle_count;
    tvo_real_t robot_radius_m;
    tvo_disk_t obstacle[...];
    uint8_t offset_count;
    tvo_offset_desc_t offset[...];
    ...;
}} tvo_problem_desc_t;
typedef struct {{ tvo_objective_t objective; ...; }} tvo_problem_t;

tvo_status_t tvo_barrier_config_default(tvo_barrier_config_t *cfg);
tvo_status_t tvo_target_init_polynomial(tvo_target_t *target, const void *coeff); /* tvo_real_t[2][D+1] */
tvo_status_t tvo_target_init_circle(tvo_target_t *target, const tvo_real_t center_m[2], tvo_real_t radius_m,
                                    tvo_real_t omega_radps, tvo_real_t phase_rad);
tvo_status_t tvo_target_init_ellipse(tvo_target_t *target, const tvo_target_ellipse_t *ellipse);
uint64_t tvo_target_turns_q64(double omega_radps);
tvo_status_t tvo_target_init_streamed(tvo_target_t *target);
tvo_status_t tvo_target_stream_update(tvo_target_t *target, uint64_t stamp_ticks, const void *deriv); /* [D+1][2] */
tvo_target_t *tvo_problem_target(tvo_problem_t *problem, uint8_t robot);
tvo_status_t tvo_problem_desc_default(tvo_problem_desc_t *desc);
typedef struct {{ uint8_t part; int16_t index; }} tvo_problem_culprit_t;
tvo_status_t tvo_problem_init(tvo_problem_t *problem, const tvo_problem_desc_t *desc, uint8_t relative_degree,
                              tvo_problem_culprit_t *bad);
tvo_status_t tvo_problem_choose_slack(tvo_problem_t *problem, const tvo_real_t *y, tvo_real_t t_s);

/* --- the unicycle controller (tvo/controller.h) --- */
typedef struct {{
    uint32_t tick_hz; uint32_t period_ticks; uint32_t delay_ticks;
    uint8_t robot_count; uint8_t delay_compensation; uint8_t zoh_aware;
    tvo_velocity_source_t velocity_source;
    tvo_real_t filter_tf_s; tvo_real_t gain_kp; tvo_real_t gain_kd; tvo_real_t omega_max_radps;
    tvo_real_t accel_max_mps2; tvo_real_t speed_max_mps; tvo_real_t min_speed_mps;
    uint32_t watchdog_periods;
    tvo_real_t initial_speed_mps[...];
    ...;
}} tvo_controller_config_t;
typedef struct {{
    uint32_t stamp_tick;
    tvo_real_t position_m[...][2];
    tvo_real_t heading_rad[...];
    tvo_real_t speed_mps[...];
    uint8_t heading_valid;
    uint8_t speed_valid;
    ...;
}} tvo_measurement_t;
typedef struct {{
    tvo_real_t speed_mps[...];
    tvo_real_t turn_rate_radps[...];
    uint32_t flags;
    uint8_t outcome;
    uint8_t reason;
    ...;
}} tvo_command_t;
typedef struct {{ ...; }} tvo_controller_t;

tvo_status_t tvo_controller_config_default(tvo_controller_config_t *cfg);
tvo_status_t tvo_controller_init(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                 const tvo_objective_t *objective, uint32_t epoch_tick, tvo_param_t *bad_param);
tvo_status_t tvo_controller_step(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                 uint32_t apply_tick, tvo_command_t *cmd);
tvo_status_t tvo_controller_miss(tvo_controller_t *ctl, uint32_t apply_tick, tvo_command_t *cmd);
tvo_status_t tvo_controller_safe_stop(tvo_controller_t *ctl, tvo_command_t *cmd);
tvo_status_t tvo_controller_objective_ticks(const tvo_controller_t *ctl, uint32_t tick, uint64_t *objective_ticks);

/* --- the integrator chain (tvo/chain_controller.h): y^(k) = u --- */
typedef struct {{ ...; }} tvo_output_derivs_t;
typedef struct {{
    uint32_t tick_hz; uint32_t period_ticks; uint32_t delay_ticks;
    uint8_t relative_degree; uint8_t delay_compensation; uint8_t zoh_aware; uint8_t filtered_derivatives;
    tvo_real_t filter_tf_s;
    tvo_real_t gain[...];
    tvo_real_t input_max;
    uint32_t watchdog_periods;
    ...;
}} tvo_chain_config_t;
typedef struct {{ uint32_t stamp_tick; tvo_output_derivs_t y; ...; }} tvo_chain_measurement_t;
typedef struct {{ tvo_real_t u[...]; uint32_t flags; uint8_t outcome; uint8_t reason; ...; }} tvo_chain_command_t;
typedef struct {{ ...; }} tvo_chain_controller_t;
tvo_status_t tvo_chain_config_default(tvo_chain_config_t *cfg);
tvo_status_t tvo_chain_controller_init(tvo_chain_controller_t *ctl, const tvo_chain_config_t *cfg,
                                       const tvo_objective_t *objective, uint32_t epoch_tick,
                                       tvo_chain_param_t *bad_param);
tvo_status_t tvo_chain_controller_step(tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                       uint32_t apply_tick, tvo_chain_command_t *cmd);
tvo_status_t tvo_chain_controller_miss(tvo_chain_controller_t *ctl, uint32_t apply_tick, tvo_chain_command_t *cmd);

/* --- the closed loop's plant (host/python/src/plant.h): exact unicycle arcs in double --- */
void tvo_py_unicycle_arc(double *pose, double speed_mps, double turn_rate_radps, uint32_t ticks, uint32_t tick_hz);
"""


SOURCE = """
#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"
#include "tvo/status.h"
#include "plant.h"
"""


def main(argv):
    if len(argv) != 4:
        raise SystemExit(__doc__)
    include_dir, module, out_c = argv[1:]
    ffi = cffi.FFI()
    ffi.cdef(cdef_text(include_dir))
    ffi.set_source(module, SOURCE)
    os.makedirs(os.path.dirname(os.path.abspath(out_c)), exist_ok=True)
    ffi.emit_c_code(out_c)


if __name__ == "__main__":
    main(sys.argv)
