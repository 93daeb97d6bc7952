"""The core's controllers from Python: one step over numpy arrays, and a batched closed loop."""
import collections

import numpy as np

from ._checks import per_robot, robot_index, robots_text
from ._lib import ChainParam, Flag, Outcome, Reason, TvoError, check, core
from ._problem import BuiltProblem, Problem

UINT32 = 1 << 32

Command = collections.namedtuple("Command", "speed_mps turn_rate_radps flags outcome reason")
Command.__doc__ = """One period's answer: speeds and turn rates (numpy, one per robot, tvo_real_t), the
TVO_FLAG_* bits (tvo.Flag), what the period did (tvo.Outcome: APPLIED, or HELD / STOPPED: the command
in force, or the stop) and why (tvo.Reason, NONE when applied)."""

ChainCommand = collections.namedtuple("ChainCommand", "u flags outcome reason")


def _configure(c, cfg, config, period_s, delay_s):
    """Sets cfg's fields from config (their C names), period_s and delay_s (seconds, in ticks)."""
    ffi = c.ffi
    tick_hz = int(config.pop("tick_hz", cfg.tick_hz))
    cfg.tick_hz = tick_hz
    if period_s is not None:
        cfg.period_ticks = int(round(period_s * tick_hz))
        if delay_s is None and "delay_ticks" not in config:
            cfg.delay_ticks = cfg.period_ticks // 2
    if delay_s is not None:
        cfg.delay_ticks = int(round(delay_s * tick_hz))
    for name, value in config.items():
        try:
            field = getattr(cfg, name)
        except AttributeError:
            fields = sorted(n for n, _ in ffi.typeof(cfg).item.fields)
            raise TypeError(f"no config field {name!r} (fields: {', '.join(fields)})") from None
        if isinstance(field, ffi.CData):
            values = np.asarray(value, dtype=np.float64).reshape(-1)
            if len(values) > len(field):
                raise ValueError(f"{name}: {len(values)} values, at most {len(field)} (one per robot or output)")
            for i, v in enumerate(values):
                field[i] = float(v)
        else:
            setattr(cfg, name, value)


class UnicycleController:
    """tvo_controller_t (tvo/controller.h) for the problem's N unicycles (k = 2).

    problem: a tvo.Problem (built here in `precision`) or a BuiltProblem of that precision.
    period_s / delay_s: h and tau in seconds (ticks of tick_hz; delay h/2 by default).
    config: any field of tvo_controller_config_t by its C name (gain_kp, gain_kd, omega_max_radps,
    zoh_aware, velocity_source = tvo.VELOCITY_FROM_POSITION, ...); the rest are the core's defaults
    (tvo_controller_config_default). A refused parameter raises TvoError naming it.
    """

    def __init__(self, problem, precision="float32", *, period_s=None, delay_s=None, epoch_tick=0, **config):
        c = core(precision)
        if isinstance(problem, Problem):
            problem = problem.build(precision, relative_degree=2)
        if not isinstance(problem, BuiltProblem) or problem.core is not c:
            raise TypeError(f"problem must be a tvo.Problem or a BuiltProblem in {precision}")
        ffi, lib = c.ffi, c.lib
        self.core, self.built = c, problem
        self.robot_count = problem.robot_count
        cfg = ffi.new("tvo_controller_config_t *")
        check(lib.tvo_controller_config_default(cfg), "tvo_controller_config_default")
        cfg.robot_count = self.robot_count
        for r, robot in enumerate(problem.description["robots"]):
            cfg.initial_speed_mps[r] = robot.get("initial_speed_mps", 0.0)
        _configure(c, cfg, dict(config), period_s, delay_s)
        self.config = cfg
        self.ctl = ffi.new("tvo_controller_t *")
        bad = ffi.new("tvo_param_t *")
        check(lib.tvo_controller_init(self.ctl, cfg, problem.objective, epoch_tick % UINT32, bad),
              "tvo_controller_init", param=bad[0])
        self.epoch_tick = epoch_tick % UINT32
        self.tick_hz, self.period_ticks, self.delay_ticks = cfg.tick_hz, cfg.period_ticks, cfg.delay_ticks
        self.periods = 0          # periods stepped or missed: the next default apply tick follows them
        self._meas = ffi.new("tvo_measurement_t *")
        self._cmd = ffi.new("tvo_command_t *")
        self._y = ffi.new("tvo_real_t[]", lib.TVO_MAX_OUTPUT_DIM)
        self._slack_chosen = False

    def _command(self, status, where):
        check(status, where)  # a call error: nothing changed
        n = self.robot_count
        cmd = self._cmd
        return Command(np.array([cmd.speed_mps[r] for r in range(n)], dtype=self.core.dtype),
                       np.array([cmd.turn_rate_radps[r] for r in range(n)], dtype=self.core.dtype),
                       Flag(cmd.flags), Outcome(cmd.outcome), Reason(cmd.reason))

    def next_apply_tick(self):
        return (self.epoch_tick + (self.periods + 1) * self.period_ticks) % UINT32

    def step(self, position, heading=None, speed=None, apply_tick=None, stamp_tick=None):
        """One period: position (N, 2) in m, heading (N,) in rad (None: not measured), speed (N,) in
        m/s (None: not measured). apply_tick defaults to the next period (epoch + (n + 1) h), stamp_tick
        to apply_tick - tau. Returns a Command (numpy arrays); a refused measurement is no exception:
        the command is the one in force, its outcome HELD and its reason why (as on the firmware). A
        misused call (an apply tick that does not advance) raises TvoError and changes nothing."""
        lib = self.core.lib
        n = self.robot_count
        pos = per_robot(position, "step: position", n, ("x", "y"))
        apply_tick = self.next_apply_tick() if apply_tick is None else int(apply_tick) % UINT32
        m = self._meas
        m.stamp_tick = (apply_tick - self.delay_ticks) % UINT32 if stamp_tick is None else int(stamp_tick) % UINT32
        for r in range(n):
            m.position_m[r][0] = pos[r, 0]
            m.position_m[r][1] = pos[r, 1]
        m.heading_valid = heading is not None
        if heading is not None:
            for r, h in enumerate(per_robot(heading, "step: heading", n)):
                m.heading_rad[r] = h
        m.speed_valid = speed is not None
        if speed is not None:
            for r, v in enumerate(per_robot(speed, "step: speed", n)):
                m.speed_mps[r] = v
        if not self._slack_chosen:
            # As the firmware node: the barrier's slack from the first measurement, at t = 0.
            for r in range(n):
                self._y[2 * r] = m.position_m[r][0]
                self._y[2 * r + 1] = m.position_m[r][1]
            check(lib.tvo_problem_choose_slack(self.built.problem, self._y, 0.0), "tvo_problem_choose_slack")
            self._slack_chosen = True
        status = lib.tvo_controller_step(self.ctl, m, apply_tick, self._cmd)
        if status == 0:
            self.periods += 1
        return self._command(status, "tvo_controller_step")

    def miss(self, apply_tick=None):
        """A period without a measurement (tvo_controller_miss): the command in force, or the stop."""
        apply_tick = self.next_apply_tick() if apply_tick is None else int(apply_tick) % UINT32
        status = self.core.lib.tvo_controller_miss(self.ctl, apply_tick, self._cmd)
        if status == 0:
            self.periods += 1
        return self._command(status, "tvo_controller_miss")

    def safe_stop(self):
        return self._command(self.core.lib.tvo_controller_safe_stop(self.ctl, self._cmd), "tvo_controller_safe_stop")

    def stream_target(self, robot, derivs, tick):
        """A new sample of robot's streamed target (tvo.streamed()): derivs (up to 4, 2) = position,
        velocity, acceleration, jerk, valid at plant tick `tick` (converted to objective ticks by
        tvo_controller_objective_ticks). Raises TvoError if refused (not finite, not advancing...)."""
        ffi, lib = self.core.ffi, self.core.lib
        robot = robot_index(robot, self.robot_count, "stream_target")
        d = np.asarray(derivs, dtype=np.float64)
        d = d.reshape(1, -1) if d.ndim == 1 else d
        rows = lib.TVO_STREAM_MAX_DERIV + 1
        if d.ndim != 2 or d.shape[1] != 2 or not 1 <= d.shape[0] <= rows:
            raise ValueError(f"stream_target: derivs of shape {np.shape(derivs)}, expected (1 .. {rows}, 2): position, "
                             f"velocity, ... up to order {rows - 1}, x and y each, of robot {robot}")
        values = np.zeros((rows, 2))
        values[:d.shape[0]] = d
        stamp = ffi.new("uint64_t *")
        check(lib.tvo_controller_objective_ticks(self.ctl, int(tick) % UINT32, stamp), "tvo_controller_objective_ticks")
        target = lib.tvo_problem_target(self.built.problem, robot)
        if target == ffi.NULL:
            raise TvoError(lib.TVO_ERR_PARAM, f"robot {robot}: no such robot")
        check(lib.tvo_target_stream_update(target, stamp[0], self.core.real_array(values, (rows, 2))),
              "tvo_target_stream_update")

    def run(self, start, steps, measure_speed=False):
        """The closed loop with exact unicycle plants (double) for `steps` periods from the poses
        start (N, 3): x, y, heading, at rest. Each period the plant runs the command in force to the
        sampling instant (apply - tau), is measured there (pose; speed too if measure_speed), runs on
        to apply, and the controller's answer is applied. Returns a ClosedLoop."""
        ffi, lib = self.core.ffi, self.core.lib
        n = self.robot_count
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 0:
            raise ValueError(f"run: steps is a whole number of periods >= 0, got {steps!r}")
        poses = [ffi.new("double[3]", [float(v) for v in row])
                 for row in per_robot(start, "run: start", n, ("x", "y", "heading"))]
        out = ClosedLoop(steps, n, self.core.dtype)
        out.poses[0] = [list(p) for p in poses]
        held_v = [0.0] * n
        held_w = [0.0] * n
        before = self.period_ticks - self.delay_ticks
        for k in range(steps):
            apply_tick = self.next_apply_tick()
            for r in range(n):
                lib.tvo_py_unicycle_arc(poses[r], held_v[r], held_w[r], before, self.tick_hz)
            position = [(p[0], p[1]) for p in poses]
            heading = [p[2] for p in poses]
            speed = list(held_v) if measure_speed else None
            for r in range(n):
                lib.tvo_py_unicycle_arc(poses[r], held_v[r], held_w[r], self.delay_ticks, self.tick_hz)
            cmd = self.step(position, heading, speed, apply_tick=apply_tick)
            held_v = [float(v) for v in cmd.speed_mps]
            held_w = [float(w) for w in cmd.turn_rate_radps]
            out.apply_tick[k] = apply_tick
            out.t_s[k] = ((apply_tick - self.epoch_tick) % UINT32) / self.tick_hz
            out.poses[k + 1] = [list(p) for p in poses]
            out.speed_mps[k] = cmd.speed_mps
            out.turn_rate_radps[k] = cmd.turn_rate_radps
            out.flags[k] = int(cmd.flags)
            out.outcome[k] = int(cmd.outcome)
            out.reason[k] = int(cmd.reason)
        return out


class ClosedLoop:
    """A closed loop's record, one row per period k (the command applied at apply_tick[k], t_s[k]
    from the epoch); poses[k + 1] is the plant at that instant (poses[0]: the start)."""

    def __init__(self, steps, robots, dtype):
        self.apply_tick = np.zeros(steps, dtype=np.uint32)
        self.t_s = np.zeros(steps)
        self.poses = np.zeros((steps + 1, robots, 3))
        self.speed_mps = np.zeros((steps, robots), dtype=dtype)
        self.turn_rate_radps = np.zeros((steps, robots), dtype=dtype)
        self.flags = np.zeros(steps, dtype=np.uint32)
        self.outcome = np.zeros(steps, dtype=np.int32)  # tvo.Outcome: 0 APPLIED
        self.reason = np.zeros(steps, dtype=np.int32)   # tvo.Reason: 0 NONE

    def tracking_error(self, problem):
        """|y_r - y_d,r| at each apply instant (steps, N), against the problem's targets (double)."""
        problem = problem if isinstance(problem, Problem) else Problem.from_dict(problem.description)
        return np.stack([np.linalg.norm(self.poses[1:, r, :2] - problem.target_position(r, self.t_s), axis=-1)
                         for r in range(self.poses.shape[1])], axis=-1)


class ChainController:
    """tvo_chain_controller_t (tvo/chain_controller.h): the integrator chain y^(k) = u, y in R^(2N),
    over the problem's objective. relative_degree k (1 .. 3); config: tvo_chain_config_t's fields
    (gain is a_0 .. a_{k-1}, input_max, filtered_derivatives, ...)."""

    def __init__(self, problem, relative_degree=2, precision="float32", *, period_s=None, delay_s=None,
                 epoch_tick=0, **config):
        c = core(precision)
        if isinstance(problem, Problem):
            problem = problem.build(precision, relative_degree=relative_degree)
        ffi, lib = c.ffi, c.lib
        self.core, self.built = c, problem
        self.dim = 2 * problem.robot_count
        cfg = ffi.new("tvo_chain_config_t *")
        check(lib.tvo_chain_config_default(cfg), "tvo_chain_config_default")
        cfg.relative_degree = relative_degree
        _configure(c, cfg, dict(config), period_s, delay_s)
        self.config = cfg
        self.ctl = ffi.new("tvo_chain_controller_t *")
        bad = ffi.new("tvo_chain_param_t *")
        check(lib.tvo_chain_controller_init(self.ctl, cfg, problem.objective, epoch_tick % UINT32, bad),
              "tvo_chain_controller_init", param=bad[0], param_enum=ChainParam)
        self.k = relative_degree
        self.epoch_tick = epoch_tick % UINT32
        self.tick_hz, self.period_ticks, self.delay_ticks = cfg.tick_hz, cfg.period_ticks, cfg.delay_ticks
        self.periods = 0
        self._meas = ffi.new("tvo_chain_measurement_t *")
        self._cmd = ffi.new("tvo_chain_command_t *")
        self._stride = lib.TVO_MAX_Z_DIM
        self._slack_chosen = False

    def step(self, derivs, apply_tick=None, stamp_tick=None):
        """derivs (k, 2N): y, y', ..., y^(k-1) as measured (rows past the first are read only when
        not filtered_derivatives). Returns a ChainCommand (u as numpy)."""
        ffi, lib = self.core.ffi, self.core.lib
        d = np.asarray(derivs, dtype=np.float64)
        d = d.reshape(1, -1) if d.ndim == 1 else d
        if d.ndim != 2 or d.shape[1] != self.dim or not 1 <= d.shape[0] <= self.k:
            robots = self.dim // 2
            given = f" (values for {robots_text(d.shape[1] // 2)})" if d.ndim == 2 and d.shape[1] % 2 == 0 else ""
            raise ValueError(f"step: derivs of shape {np.shape(derivs)}{given}, expected (1 .. {self.k}, {self.dim}): "
                             f"y, y', ... up to y^({self.k - 1}) in rows, each of 2N = {self.dim} values "
                             f"(x, y per robot: this controller drives {robots_text(robots)})")
        apply_tick = ((self.epoch_tick + (self.periods + 1) * self.period_ticks) if apply_tick is None
                      else int(apply_tick)) % UINT32
        m = self._meas
        m.stamp_tick = (apply_tick - self.delay_ticks) % UINT32 if stamp_tick is None else int(stamp_tick) % UINT32
        y = ffi.cast("tvo_real_t *", ffi.addressof(m, "y"))
        for j in range(min(d.shape[0], self.k)):
            for i in range(self.dim):
                y[j * self._stride + i] = d[j, i]
        if not self._slack_chosen:
            check(lib.tvo_problem_choose_slack(self.built.problem, y, 0.0), "tvo_problem_choose_slack")
            self._slack_chosen = True
        status = lib.tvo_chain_controller_step(self.ctl, m, apply_tick, self._cmd)
        check(status, "tvo_chain_controller_step")  # a call error: nothing changed
        self.periods += 1
        return ChainCommand(np.array([self._cmd.u[i] for i in range(self.dim)], dtype=self.core.dtype),
                            Flag(self._cmd.flags), Outcome(self._cmd.outcome), Reason(self._cmd.reason))
