"""A planning problem in Python: the same description the firmware node decodes from a session
(firmware/edge/session_codec.c), built into the core's tvo_problem_t by the core's own functions."""
import copy
import math

import numpy as np

from ._checks import pair, real, robot_index, robot_pair, robots_text
from ._lib import PROBLEM_PARTS, TvoError, check, core


# --- time functions (targets and formation offsets): the wire's path_t, in double ----------------

def polynomial(coeff):
    """p(t) = sum_j coeff[axis][j] t^j, axis x then y, degree <= 7 (missing powers are 0)."""
    rows = [[real(v, f"polynomial: coefficient [{axis}][{j}]") for j, v in enumerate(row)]
            for axis, row in enumerate(coeff)]
    if len(rows) != 2 or max(len(r) for r in rows) > 8:
        raise ValueError("polynomial: two rows (x, y) of at most 8 coefficients (degree <= 7), got "
                         f"{len(rows)} rows of {[len(r) for r in rows]}")
    return {"kind": "polynomial", "coeff": [r + [0.0] * (8 - len(r)) for r in rows]}


def circle(center_m, radius_m, omega_radps, phase_rad=0.0):
    """center + radius (cos, sin)(omega t + phase)."""
    return {"kind": "circle", "center_m": pair(center_m, "circle: center_m"), "radius_m": real(radius_m, "circle: radius_m"),
            "omega_radps": real(omega_radps, "circle: omega_radps"), "phase_rad": real(phase_rad, "circle: phase_rad")}


def ellipse(center_m, semi_axis_m, omega_radps, phase_rad=0.0, rotation_rad=0.0):
    """center + R(rotation) (a cos, b sin)(omega t + phase)."""
    return {"kind": "ellipse", "center_m": pair(center_m, "ellipse: center_m"),
            "semi_axis_m": pair(semi_axis_m, "ellipse: semi_axis_m"), "omega_radps": real(omega_radps, "ellipse: omega_radps"),
            "phase_rad": real(phase_rad, "ellipse: phase_rad"), "rotation_rad": real(rotation_rad, "ellipse: rotation_rad")}


def streamed():
    """A target streamed at run time (UnicycleController.stream_target): samples of position ..
    jerk, extrapolated causally by the core. Not exportable (it has no on-board function)."""
    return {"kind": "streamed"}


def _time_function(path, what):
    """A copy of a time function made by tvo.polynomial / circle / ellipse / streamed, else TypeError."""
    kinds = ("polynomial", "circle", "ellipse", "streamed")
    if not isinstance(path, dict) or path.get("kind") not in kinds:
        raise TypeError(f"{what}: a time function from tvo.polynomial, tvo.circle, tvo.ellipse or tvo.streamed, "
                        f"got {path!r}")
    return copy.deepcopy(path)


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
        if isinstance(robots, bool) or not isinstance(robots, int) or robots < 1:
            raise ValueError(f"Problem(robots): a whole number of robots >= 1, got {robots!r}")
        self.robots = [{"target": None, "tracking_weight": [1.0, 1.0], "initial_speed_mps": 0.0}
                       for _ in range(robots)]
        self.barrier = {}                 # overrides of tvo_barrier_config_default's fields
        self.distance_bounds = []
        self.halfspaces = []
        self.robot_radius_m = 0.0
        self.obstacles = []
        self.offsets = []

    # --- building ---
    def track(self, robot, target, weight=(1.0, 1.0)):
        """Robot `robot` tracks `target` (tvo.polynomial / circle / ellipse) with diagonal weight W."""
        r = robot_index(robot, len(self.robots), "track")
        self.robots[r]["target"] = _time_function(target, f"track: robot {r}'s target")
        self.robots[r]["tracking_weight"] = pair(weight, f"track: robot {r}'s weight")
        return self

    def add_obstacle(self, center_m, radius_m):
        """A disk every robot avoids (with robot_radius_m added)."""
        self.obstacles.append({"center_m": pair(center_m, "add_obstacle: center_m"),
                               "radius_m": real(radius_m, "add_obstacle: radius_m")})
        return self

    def add_halfspace(self, robot, normal, bound_m, normal_rate=(0.0, 0.0), bound_rate_mps=0.0):
        """normal(t) . y_robot <= bound(t), normal and bound moving linearly in t."""
        self.halfspaces.append({"robot": robot_index(robot, len(self.robots), "add_halfspace"),
                                "normal": pair(normal, "add_halfspace: normal"),
                                "normal_rate": pair(normal_rate, "add_halfspace: normal_rate"),
                                "bound_m": real(bound_m, "add_halfspace: bound_m"),
                                "bound_rate_mps": real(bound_rate_mps, "add_halfspace: bound_rate_mps")})
        return self

    def add_distance_bound(self, robot_a, robot_b, min_m=0.0, max_m=0.0, min_rate_mps=0.0, max_rate_mps=0.0):
        """min(t) <= |y_a - y_b| <= max(t) (0: that side unbounded)."""
        a, b = robot_pair(robot_a, robot_b, len(self.robots), "add_distance_bound")
        self.distance_bounds.append({"robot_a": a, "robot_b": b, "min_m": real(min_m, "add_distance_bound: min_m"),
                                     "min_rate_mps": real(min_rate_mps, "add_distance_bound: min_rate_mps"),
                                     "max_m": real(max_m, "add_distance_bound: max_m"),
                                     "max_rate_mps": real(max_rate_mps, "add_distance_bound: max_rate_mps")})
        return self

    def add_offset(self, robot_a, robot_b, offset):
        """Formation: y_a - y_b = d(t), d a time function (tvo.polynomial / circle / ellipse)."""
        a, b = robot_pair(robot_a, robot_b, len(self.robots), "add_offset")
        self.offsets.append({"robot_a": a, "robot_b": b, "offset": _time_function(offset, "add_offset: offset")})
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
            if robot["target"] is None:
                raise ValueError(f"robot {r} has no target (of {robots_text(self.robot_count)}): "
                                 f"problem.track({r}, tvo.circle(...)) or another time function")
            desc.tracking_weight[r][0] = robot["tracking_weight"][0]
            desc.tracking_weight[r][1] = robot["tracking_weight"][1]
            _init_path(c, robot["target"], ffi.addressof(desc.target[r]), f"robot {r}'s target")
        for field, value in problem.barrier.items():
            try:
                setattr(desc.barrier, field, value)
            except AttributeError:
                fields = sorted(n for n, _ in ffi.typeof("tvo_barrier_config_t").fields)
                raise TypeError(f"barrier: no field {field!r} (fields: {', '.join(fields)})") from None
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
        bad = ffi.new("tvo_problem_culprit_t *")
        status = lib.tvo_problem_init(self.problem, desc, relative_degree, bad)
        if status != 0:
            part = PROBLEM_PARTS[bad.part] if bad.part < len(PROBLEM_PARTS) else str(bad.part)
            culprit, detail = _Diagnosis(c, desc, problem, relative_degree, bad.index).explain(part)
            raise TvoError(status, "tvo_problem_init", part=part, culprit=culprit, detail=detail)
        self.has_inequalities = problem.has_inequalities

    def _fill(self, desc, name, capacity, entries, part):
        if len(entries) > capacity:
            raise TvoError(self.core.lib.TVO_ERR_CAPACITY, f"{len(entries)} {part} (at most {capacity} in this "
                           "build: tvo/config.h)", part=part)
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


class _Diagnosis:
    """What is wrong, in words, with the entry of a refused part the core named (its culprit index),
    or, for a robot's weights and the barrier's fields, with the field whose default the core accepts
    when tvo_problem_init is asked again. The core stays the judge: this only names."""

    def __init__(self, c, desc, problem, relative_degree, index):
        self.c, self.desc, self.problem, self.k = c, desc, problem, relative_degree
        self.index = index
        self.limit_m = c.lib.TVO_POSITION_LIMIT_M_VALUE

    def copy(self):
        ffi = self.c.ffi
        d = ffi.new("tvo_problem_desc_t *")
        ffi.memmove(d, self.desc, ffi.sizeof("tvo_problem_desc_t"))
        return d

    def accepts(self, d):
        ffi = self.c.ffi
        return self.c.lib.tvo_problem_init(ffi.new("tvo_problem_t *"), d, self.k, ffi.NULL) == 0

    def first_refused(self, count):
        """The entry the core refused (tvo_problem_culprit_t.index), or None for the part as a whole."""
        return self.index if 0 <= self.index < count else None

    def explain(self, part):
        method = {"robots/targets": self.robots, "barrier": self.barrier, "distance bounds": self.distance_bounds,
                  "half-spaces": self.halfspaces, "obstacles": self.obstacles}.get(part)
        return method() if method else (None, None)

    def robots(self):
        for r, robot in enumerate(self.problem.robots):
            d = self.copy()
            d.tracking_weight[r][0] = d.tracking_weight[r][1] = 1.0
            if not self.accepts(self.desc) and self.accepts(d):
                return f"robot {r}'s weight", f"{robot['tracking_weight']}: both must be finite and > 0"
        return None, None

    _BARRIER_RULES = {"c0": "finite and > 0", "alpha_c_per_s": "finite and >= 0", "c_max": "finite and >= c0",
                      "delta0": "finite and > 0", "alpha_s_per_s": "finite and > 0", "slack_margin": "finite and > 0"}

    def barrier(self):
        default = self.c.ffi.new("tvo_barrier_config_t *")
        self.c.lib.tvo_barrier_config_default(default)
        for field, value in self.problem.barrier.items():
            d = self.copy()
            setattr(d.barrier, field, getattr(default, field))
            if self.accepts(d):
                rule = self._BARRIER_RULES.get(field)
                if field == "relaxation_degree":
                    rule = f"at least k + 1 = {self.k + 1} (the law differentiates the barrier k = {self.k} times)"
                return f"barrier['{field}']", f"{value!r} refused: must be {rule} (default {getattr(default, field)!r})"
        return None, None

    def distance_bounds(self):
        i = self.first_refused(len(self.problem.distance_bounds))
        if i is None:
            return None, None
        b = self.problem.distance_bounds[i]
        lo, hi = b["min_m"], b["max_m"]
        if not (math.isfinite(lo) and math.isfinite(hi)):
            why = "min_m and max_m must be finite"
        elif lo < 0 or hi < 0:
            why = "min_m and max_m must be >= 0 (0: that side unbounded)"
        elif lo == 0 and hi == 0:
            why = "min_m and max_m are both 0: give at least one bound"
        elif hi > 0 and lo >= hi:
            why = f"min_m ({lo}) must be below max_m ({hi})"
        else:
            why = "refused with these values"
        return f"distance_bounds[{i}] (robots {b['robot_a']} and {b['robot_b']})", why

    def halfspaces(self):
        i = self.first_refused(len(self.problem.halfspaces))
        if i is None:
            return None, None
        h = self.problem.halfspaces[i]
        values = h["normal"] + h["normal_rate"] + [h["bound_m"], h["bound_rate_mps"]]
        if not all(math.isfinite(v) for v in values):
            why = "normal, normal_rate, bound_m and bound_rate_mps must be finite"
        elif h["normal"] == [0.0, 0.0]:
            why = "normal (0, 0) has no direction"
        elif any(abs(v) > self.limit_m for v in values):
            why = f"normal, normal_rate, bound_m and bound_rate_mps must lie within +-{self.limit_m} (tvo/config.h)"
        else:
            why = "refused with these values"
        return f"halfspaces[{i}] (robot {h['robot']})", why

    def obstacles(self):
        obstacles, radius = self.problem.obstacles, self.problem.robot_radius_m
        d = self.copy()
        d.robot_radius_m = 0.0
        if self.accepts(d):
            return "robot_radius_m", f"{radius} m refused: must be finite and in 0 .. {self.limit_m} m"
        i = self.first_refused(len(obstacles))
        if i is None:
            return None, None
        d = self.copy()
        d.obstacle_count = 1
        d.obstacle[0] = self.desc.obstacle[i]
        o = obstacles[i]
        if not self.accepts(d):
            return f"obstacles[{i}]", (f"centre {tuple(o['center_m'])}, radius {o['radius_m']} m: the radius must be "
                                       f"> 0 and at most {self.limit_m} m, the centre within +-{self.limit_m} m, "
                                       "all finite")
        for j in range(i):
            d = self.copy()
            d.obstacle_count = 2
            d.obstacle[0] = self.desc.obstacle[j]
            d.obstacle[1] = self.desc.obstacle[i]
            if not self.accepts(d):
                p = obstacles[j]
                apart = math.dist(p["center_m"], o["center_m"])
                return (f"obstacles[{j}] and obstacles[{i}]",
                        f"they overlap: centres {apart:.4g} m apart, not more than the radii's sum "
                        f"{p['radius_m'] + o['radius_m']:.4g} m (give one disk that covers both, or move them apart)")
        return f"obstacles[{i}]", "refused with the obstacles before it"
