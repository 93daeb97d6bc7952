"""A planning problem in Python: the same description the firmware node decodes from a session
(firmware/edge/session_codec.c), built into the core's tvo_problem_t by the core's own functions."""
import copy
import math

import numpy as np

from ._lib import PROBLEM_PARTS, TvoError, check, core


# --- time functions (targets and formation offsets): the wire's path_t, in double ----------------

def polynomial(coeff):
    """p(t) = sum_j coeff[axis][j] t^j, axis x then y, degree <= 7 (missing powers are 0)."""
    rows = [list(map(float, axis)) for axis in coeff]
    if len(rows) != 2 or max(len(r) for r in rows) > 8:
        raise ValueError("polynomial: two rows (x, y) of at most 8 coefficients (degree <= 7)")
    return {"kind": "polynomial", "coeff": [r + [0.0] * (8 - len(r)) for r in rows]}


def circle(center_m, radius_m, omega_radps, phase_rad=0.0):
    """center + radius (cos, sin)(omega t + phase)."""
    return {"kind": "circle", "center_m": [float(c) for c in center_m], "radius_m": float(radius_m),
            "omega_radps": float(omega_radps), "phase_rad": float(phase_rad)}


def ellipse(center_m, semi_axis_m, omega_radps, phase_rad=0.0, rotation_rad=0.0):
    """center + R(rotation) (a cos, b sin)(omega t + phase)."""
    return {"kind": "ellipse", "center_m": [float(c) for c in center_m],
            "semi_axis_m": [float(a) for a in semi_axis_m], "omega_radps": float(omega_radps),
            "phase_rad": float(phase_rad), "rotation_rad": float(rotation_rad)}


def streamed():
    """A target streamed at run time (UnicycleController.stream_target): samples of position ..
    jerk, extrapolated causally by the core. Not exportable (it has no on-board function)."""
    return {"kind": "streamed"}


def path_position(path, t_s):
    """The path's position at times t_s (array), in double: for plots and error figures."""
    t = np.asarray(t_s, dtype=np.float64)
    kind = path["kind"]
    if kind == "polynomial":
        return np.stack([np.polynomial.polynomial.polyval(t, path["coeff"][axis]) for axis in (0, 1)], axis=-1)
    if kind in ("circle", "ellipse"):
        a, b = (path["radius_m"],) * 2 if kind == "circle" else path["semi_axis_m"]
        rot = path.get("rotation_rad", 0.0)
        phase = path["omega_radps"] * t + path["phase_rad"]
        u, v = a * np.cos(phase), b * np.sin(phase)
        c, s = math.cos(rot), math.sin(rot)
        return np.stack([path["center_m"][0] + c * u - s * v, path["center_m"][1] + s * u + c * v], axis=-1)
    raise ValueError(f"no position for a {kind} path")


class Problem:
    """What the robots minimise: one tracking term per robot, plus optional distance bounds,
    half-spaces, disk obstacles (all through the relaxed barrier) and formation offsets (equalities).

    Plain data (the JSON of tvo_scenario_export's "problem"), validated by the core when a controller
    is built from it (TvoError names the part).
    """

    def __init__(self, robots=1):
        self.robots = [{"target": None, "tracking_weight": [1.0, 1.0], "initial_speed_mps": 0.0}
                       for _ in range(int(robots))]
        self.barrier = {}                 # overrides of tvo_barrier_config_default's fields
        self.distance_bounds = []
        self.halfspaces = []
        self.robot_radius_m = 0.0
        self.obstacles = []
        self.offsets = []

    # --- building ---
    def track(self, robot, target, weight=(1.0, 1.0)):
        """Robot `robot` tracks `target` (tvo.polynomial / circle / ellipse) with diagonal weight W."""
        self.robots[robot]["target"] = copy.deepcopy(target)
        self.robots[robot]["tracking_weight"] = [float(w) for w in weight]
        return self

    def add_obstacle(self, center_m, radius_m):
        """A disk every robot avoids (with robot_radius_m added)."""
        self.obstacles.append({"center_m": [float(c) for c in center_m], "radius_m": float(radius_m)})
        return self

    def add_halfspace(self, robot, normal, bound_m, normal_rate=(0.0, 0.0), bound_rate_mps=0.0):
        """normal(t) . y_robot <= bound(t), normal and bound moving linearly in t."""
        self.halfspaces.append({"robot": int(robot), "normal": [float(n) for n in normal],
                                "normal_rate": [float(n) for n in normal_rate], "bound_m": float(bound_m),
                                "bound_rate_mps": float(bound_rate_mps)})
        return self

    def add_distance_bound(self, robot_a, robot_b, min_m=0.0, max_m=0.0, min_rate_mps=0.0, max_rate_mps=0.0):
        """min(t) <= |y_a - y_b| <= max(t) (0: that side unbounded)."""
        self.distance_bounds.append({"robot_a": int(robot_a), "robot_b": int(robot_b), "min_m": float(min_m),
                                     "min_rate_mps": float(min_rate_mps), "max_m": float(max_m),
                                     "max_rate_mps": float(max_rate_mps)})
        return self

    def add_offset(self, robot_a, robot_b, offset):
        """Formation: y_a - y_b = d(t), d a time function (tvo.polynomial / circle / ellipse)."""
        self.offsets.append({"robot_a": int(robot_a), "robot_b": int(robot_b), "offset": copy.deepcopy(offset)})
        return self

    # --- as data ---
    def to_dict(self):
        return copy.deepcopy({"robots": self.robots, "barrier": self.barrier,
                              "distance_bounds": self.distance_bounds, "halfspaces": self.halfspaces,
                              "robot_radius_m": self.robot_radius_m, "obstacles": self.obstacles,
                              "offsets": self.offsets})

    @classmethod
    def from_dict(cls, d):
        p = cls(len(d["robots"]))
        p.robots = [{"target": r["target"], "tracking_weight": list(r.get("tracking_weight", [1.0, 1.0])),
                     "initial_speed_mps": float(r.get("initial_speed_mps", 0.0))} for r in d["robots"]]
        p.barrier = dict(d.get("barrier", {}))
        p.distance_bounds = copy.deepcopy(d.get("distance_bounds", []))
        p.halfspaces = copy.deepcopy(d.get("halfspaces", []))
        p.robot_radius_m = float(d.get("robot_radius_m", 0.0))
        p.obstacles = copy.deepcopy(d.get("obstacles", []))
        p.offsets = copy.deepcopy(d.get("offsets", []))
        return p

    def target_position(self, robot, t_s):
        """Robot `robot`'s target at times t_s (double; the core evaluates it in tvo_real_t)."""
        return path_position(self.robots[robot]["target"], t_s)

    @property
    def has_inequalities(self):
        return bool(self.distance_bounds or self.halfspaces or self.obstacles)

    # --- into the core ---
    def build(self, precision="float32", relative_degree=2):
        """The core's tvo_problem_t for this description: a BuiltProblem (TvoError if refused)."""
        return BuiltProblem(self, core(precision), relative_degree)


def _init_path(c, path, target, where):
    """tvo_session_decode_path's mapping: the wire's double values rounded to tvo_real_t."""
    ffi, lib = c.ffi, c.lib
    kind = path["kind"] if path else "none"
    if kind == "polynomial":
        degree = lib.TVO_POLY_MAX_DEGREE
        for axis in (0, 1):
            if any(v != 0.0 for v in path["coeff"][axis][degree + 1:]):
                raise TvoError(lib.TVO_ERR_CAPACITY, f"{where}: degree above TVO_POLY_MAX_DEGREE = {degree}")
        coeff = c.real_array([path["coeff"][axis][:degree + 1] for axis in (0, 1)], (2, degree + 1))
        check(lib.tvo_target_init_polynomial(target, coeff), where)
    elif kind in ("circle", "ellipse"):
        is_circle = kind == "circle"
        e = ffi.new("tvo_target_ellipse_t *")
        for axis in (0, 1):
            e.center_m[axis] = path["center_m"][axis]
            e.semi_axis_m[axis] = path["radius_m"] if is_circle else path["semi_axis_m"][axis]
        e.omega_radps = path["omega_radps"]
        e.phase_rad = path["phase_rad"]
        e.rotation_rad = 0.0 if is_circle else path.get("rotation_rad", 0.0)
        e.rate_turns_q64 = lib.tvo_target_turns_q64(path["omega_radps"])
        check(lib.tvo_target_init_ellipse(target, e), where)
        if is_circle:
            target.kind = lib.TVO_TARGET_CIRCLE
    elif kind == "streamed":
        check(lib.tvo_target_init_streamed(target), where)
    else:
        raise ValueError(f"{where}: a target must be tvo.polynomial, circle, ellipse or streamed, got {kind}")


class BuiltProblem:
    """A tvo_problem_t in one precision (keeps its storage alive for the controllers bound to it)."""

    def __init__(self, problem, c, relative_degree):
        ffi, lib = c.ffi, c.lib
        self.core = c
        self.description = problem.to_dict()
        self.robot_count = len(problem.robots)
        desc = ffi.new("tvo_problem_desc_t *")
        check(lib.tvo_problem_desc_default(desc), "tvo_problem_desc_default")
        if not 1 <= self.robot_count <= lib.TVO_MAX_ROBOTS:
            raise TvoError(lib.TVO_ERR_PARAM, f"{self.robot_count} robots (1 .. {lib.TVO_MAX_ROBOTS})",
                           param=lib.TVO_PARAM_ROBOT_COUNT)
        desc.robot_count = self.robot_count
        for r, robot in enumerate(problem.robots):
            desc.tracking_weight[r][0] = robot["tracking_weight"][0]
            desc.tracking_weight[r][1] = robot["tracking_weight"][1]
            _init_path(c, robot["target"], ffi.addressof(desc.target[r]), f"robot {r}'s target")
        for field, value in problem.barrier.items():
            setattr(desc.barrier, field, value)
        self._fill(desc, "distance", lib.TVO_MAX_DISTANCE_BOUNDS, problem.distance_bounds, "distance bounds")
        self._fill(desc, "halfspace", lib.TVO_MAX_HALFSPACES, problem.halfspaces, "half-spaces")
        desc.robot_radius_m = problem.robot_radius_m
        self._fill(desc, "obstacle", lib.TVO_MAX_OBSTACLES, problem.obstacles, "obstacles")
        if len(problem.offsets) > lib.TVO_MAX_OFFSET_EQUALITIES:
            raise TvoError(lib.TVO_ERR_CAPACITY, f"{len(problem.offsets)} offsets", part="offsets")
        desc.offset_count = len(problem.offsets)
        for i, o in enumerate(problem.offsets):
            desc.offset[i].robot_a = o["robot_a"]
            desc.offset[i].robot_b = o["robot_b"]
            _init_path(c, o["offset"], ffi.addressof(desc.offset[i].offset), f"offset {i}")
        self.desc = desc
        self.problem = ffi.new("tvo_problem_t *")
        bad_part = ffi.new("uint8_t *")
        status = lib.tvo_problem_init(self.problem, desc, relative_degree, bad_part)
        part = PROBLEM_PARTS[bad_part[0]] if bad_part[0] < len(PROBLEM_PARTS) else str(bad_part[0])
        check(status, "tvo_problem_init", part=part)
        self.has_inequalities = problem.has_inequalities

    def _fill(self, desc, name, capacity, entries, part):
        if len(entries) > capacity:
            raise TvoError(self.core.lib.TVO_ERR_CAPACITY, f"{len(entries)} {part} (at most {capacity})", part=part)
        setattr(desc, f"{name}_count", len(entries))
        table = getattr(desc, name)
        for i, entry in enumerate(entries):
            for field, value in entry.items():
                if isinstance(value, list):
                    for j, v in enumerate(value):
                        getattr(table[i], field)[j] = v
                else:
                    setattr(table[i], field, value)

    @property
    def objective(self):
        return self.core.ffi.addressof(self.problem, "objective")
