"""A problem (and a controller configuration) as C a firmware compiles: initialisers of the public
description structs, exact in both precisions (hexadecimal literals in TVO_R()), and two functions
that fill a tvo_problem_desc_t and a tvo_controller_config_t through the core's own calls."""
import math
import re

from ._lib import core
from ._problem import Problem


def _real(v):
    v = float(v)
    if not math.isfinite(v):
        raise ValueError(f"export_c: {v} is not finite")
    return f"TVO_R({v.hex()})"


def _reals(values):
    return "{" + ", ".join(_real(v) for v in values) + "}"


def _comment(values):
    return ", ".join(repr(float(v)) for v in values)


def export_c(source, name="scenario", controller=None):
    """C header text for `source` (a tvo.Scenario, or a tvo.Problem with `controller`: a dict of
    tvo_controller_config_t fields by C name) defining, all static:
      NAME_problem_desc(tvo_problem_desc_t *desc)           the problem, for tvo_problem_init
      NAME_controller_config(tvo_controller_config_t *cfg)  the controller's settings (if any)
      NAME_start[N][3]                                      the robots' start poses (a Scenario's)
    Polynomial targets (a scenario's `through` waypoints solved) are their coefficients; an
    ellipse's phase rate is exported as its Q0.64 turns, as the node computes them from a double."""
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
        raise ValueError(f"export_c: {name!r} is not a C identifier")
    starts = None
    title = "a tvo.Problem"
    if isinstance(source, Problem):
        problem = source
    else:
        problem, controller, starts = source.problem, source.controller if controller is None else controller, source.starts
        title = f"scenario '{source.name}'"
    lib = core("float32").lib
    guard = f"{name.upper()}_TVO_EXPORT_H"
    data = []   # the static initialisers
    body = []   # NAME_problem_desc's statements
    st = "    if (st != TVO_OK) {\n        return st;\n    }"

    def init_path(path, target_lvalue, label):
        kind = path["kind"]
        if kind == "polynomial":
            coeff = path["coeff"]
            degree = max((j for axis in coeff for j, v in enumerate(axis) if v != 0.0), default=0)
            data.append(f"#if TVO_POLY_MAX_DEGREE < {degree}\n#error \"{label}: a polynomial of degree {degree} needs "
                        f"TVO_POLY_MAX_DEGREE >= {degree}\"\n#endif")
            rows = ",\n    ".join(f"{_reals(axis[:degree + 1])} /* {_comment(axis[:degree + 1])} */" for axis in coeff)
            data.append(f"/* {label}: polynomial, coefficients of t^0 .. t^{degree} per axis (x, y). */\n"
                        f"static const tvo_real_t {name}_{label}_coeff[2][TVO_POLY_MAX_DEGREE + 1] = {{\n    {rows}}};")
            body.append(f"    st = tvo_target_init_polynomial(&{target_lvalue}, {name}_{label}_coeff);\n{st}")
        elif kind in ("circle", "ellipse"):
            circle = kind == "circle"
            axes = [path["radius_m"]] * 2 if circle else path["semi_axis_m"]
            rotation = 0.0 if circle else path.get("rotation_rad", 0.0)
            q64 = lib.tvo_target_turns_q64(path["omega_radps"])
            data.append(f"/* {label}: {kind}, centre ({_comment(path['center_m'])}), semi-axes ({_comment(axes)}), "
                        f"omega {path['omega_radps']!r} rad/s. */\n"
                        f"static const tvo_target_ellipse_t {name}_{label}_ellipse = {{\n"
                        f"    .center_m = {_reals(path['center_m'])},\n    .semi_axis_m = {_reals(axes)},\n"
                        f"    .omega_radps = {_real(path['omega_radps'])},\n    .phase_rad = {_real(path['phase_rad'])},\n"
                        f"    .rotation_rad = {_real(rotation)},\n    .rate_turns_q64 = UINT64_C({q64:#x})}};")
            body.append(f"    st = tvo_target_init_ellipse(&{target_lvalue}, &{name}_{label}_ellipse);\n{st}")
            if circle:
                body.append(f"    {target_lvalue}.kind = TVO_TARGET_CIRCLE;")
        else:
            raise ValueError(f"export_c: {label} is {kind}: only on-board targets (polynomial, circle, ellipse) export")

    body.append(f"    tvo_status_t st = tvo_problem_desc_default(desc);\n{st}")
    body.append(f"    desc->robot_count = (uint8_t){len(problem.robots)};")
    for r, robot in enumerate(problem.robots):
        w = robot["tracking_weight"]
        body.append(f"    desc->tracking_weight[{r}][0] = {_real(w[0])};\n    desc->tracking_weight[{r}][1] = {_real(w[1])};")
        init_path(robot["target"], f"desc->target[{r}]", f"target{r}")
    for field, value in problem.barrier.items():
        rhs = f"(uint8_t){int(value)}" if field == "relaxation_degree" else _real(value)
        body.append(f"    desc->barrier.{field} = {rhs};")

    def table(ctype, cname, count_field, entries, fields):
        if not entries:
            return
        items = []
        for e in entries:
            parts = []
            for f in fields:
                v = e[f]
                parts.append(f".{f} = " + (_reals(v) if isinstance(v, list) else
                                           f"(uint8_t){int(v)}" if f.startswith("robot") else _real(v)))
            items.append("    {" + ", ".join(parts) + "}")
        data.append(f"static const {ctype} {name}_{cname}[{len(entries)}] = {{\n" + ",\n".join(items) + "};")
        body.append(f"    desc->{count_field} = (uint8_t){len(entries)};\n"
                    f"    for (size_t i = 0; i < {len(entries)}u; ++i) {{\n        desc->{cname}[i] = {name}_{cname}[i];\n    }}")

    table("tvo_distance_bound_desc_t", "distance", "distance_count", problem.distance_bounds,
          ("robot_a", "robot_b", "min_m", "min_rate_mps", "max_m", "max_rate_mps"))
    table("tvo_halfspace_desc_t", "halfspace", "halfspace_count", problem.halfspaces,
          ("robot", "normal", "normal_rate", "bound_m", "bound_rate_mps"))
    if problem.obstacles or problem.robot_radius_m:
        body.append(f"    desc->robot_radius_m = {_real(problem.robot_radius_m)};")
    table("tvo_disk_t", "obstacle", "obstacle_count", problem.obstacles, ("center_m", "radius_m"))
    if problem.offsets:
        body.append(f"    desc->offset_count = (uint8_t){len(problem.offsets)};")
    for i, o in enumerate(problem.offsets):
        body.append(f"    desc->offset[{i}].robot_a = (uint8_t){o['robot_a']};\n"
                    f"    desc->offset[{i}].robot_b = (uint8_t){o['robot_b']};")
        init_path(o["offset"], f"desc->offset[{i}].offset", f"offset{i}")
    body.append("    return TVO_OK;")

    out = [f"/*\n * {name}: {title} for the tvo-flat core, generated by tvo.export_c (host/python). Do not edit.\n"
           " * Values are exact hexadecimal literals (decimal in the comments), rounded to tvo_real_t by the\n"
           " * compiler as the core's edge rounds a double. Use:\n"
           f" *     tvo_problem_desc_t desc;  tvo_problem_t problem;  tvo_problem_culprit_t part;\n"
           f" *     {name}_problem_desc(&desc);  tvo_problem_init(&problem, &desc, 2u, &part);\n */",
           f"#ifndef {guard}\n#define {guard}\n", "#include <stddef.h>\n#include <stdint.h>\n",
           '#include "tvo/controller.h"\n#include "tvo/problem.h"\n']
    if starts is not None:
        rows = ",\n    ".join(_reals(s) for s in starts)
        out.append(f"/* The robots' start poses: x (m), y (m), heading (rad). */\n"
                   f"static const tvo_real_t {name}_start[{len(starts)}][3] = {{\n    {rows}}};\n")
    out.append("\n\n".join(data) + "\n")
    out.append(f"/* Fills desc (tvo_problem_desc_default, then the problem); TVO_OK or the first refusal. */\n"
               f"static inline tvo_status_t {name}_problem_desc(tvo_problem_desc_t *desc)\n{{\n"
               + "\n".join(body) + "\n}\n")
    if controller:
        lines = [f"    tvo_status_t st = tvo_controller_config_default(cfg);\n{st}",
                 f"    cfg->robot_count = (uint8_t){len(problem.robots)};"]
        for r, robot in enumerate(problem.robots):
            lines.append(f"    cfg->initial_speed_mps[{r}] = {_real(robot.get('initial_speed_mps', 0.0))};")
        for field, value in controller.items():
            if field in ("tick_hz", "period_ticks", "delay_ticks", "watchdog_periods"):
                lines.append(f"    cfg->{field} = {int(value)}u;")
            elif field in ("delay_compensation", "zoh_aware"):
                lines.append(f"    cfg->{field} = (uint8_t){int(value)};")
            elif field == "velocity_source":
                lines.append(f"    cfg->velocity_source = {'TVO_VELOCITY_FROM_POSITION' if int(value) else 'TVO_VELOCITY_FROM_POSE'};")
            elif field == "initial_speed_mps":
                for r, v in enumerate(value):
                    lines.append(f"    cfg->initial_speed_mps[{r}] = {_real(v)};")
            else:
                lines.append(f"    cfg->{field} = {_real(value)};")
        lines.append("    return TVO_OK;")
        out.append(f"/* Fills cfg (tvo_controller_config_default, then the settings), for tvo_controller_init. */\n"
                   f"static inline tvo_status_t {name}_controller_config(tvo_controller_config_t *cfg)\n{{\n"
                   + "\n".join(lines) + "\n}\n")
    out.append(f"#endif /* {guard} */\n")
    return "\n".join(out)
