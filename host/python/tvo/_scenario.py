"""Scenario files (host/scenarios/*.yaml) in Python, solved by the host's own code: tvo_scenario_export
prints the session tvo_sim would START (a `through` target already solved into its polynomial)."""
import json
import os
import subprocess

import numpy as np

from ._problem import Problem


class Scenario:
    """A solved scenario: .problem (tvo.Problem), .controller (UnicycleController keyword arguments,
    tvo_sim's timing and gains: ticks of 1 MHz as the node's), .starts (N, 3), .duration_s, .name."""

    def __init__(self, data):
        self.data = data
        self.name = data["name"]
        self.duration_s = float(data["duration_s"])
        self.problem = Problem.from_dict(data["problem"])
        self.starts = np.array([r["start"] for r in data["problem"]["robots"]], dtype=np.float64)
        c = data["controller"]
        self.controller = {
            "tick_hz": 1000000, "period_ticks": int(c["period_us"]), "delay_ticks": int(c["delay_us"]),
            "delay_compensation": int(bool(c["delay_compensation"])), "zoh_aware": int(bool(c["zoh_aware"])),
            "watchdog_periods": int(c["watchdog_periods"]),
            "velocity_source": 1 if c["velocity_source"] == "position" else 0,
            **{k: float(c[k]) for k in ("filter_tf_s", "gain_kp", "gain_kd", "omega_max_radps",
                                        "accel_max_mps2", "speed_max_mps", "min_speed_mps")}}

    @property
    def steps(self):
        return int(round(self.duration_s * 1e6 / self.controller["period_ticks"]))

    def make_controller(self, precision="float32", **overrides):
        from ._controller import UnicycleController
        return UnicycleController(self.problem, precision, **{**self.controller, **overrides})


def load_scenario(name_or_path, *sim_options, exporter=None):
    """The scenario as tvo_sim would run it: a built-in name (demo, obstacles, ...) or a .yaml file;
    sim_options are tvo_sim's (e.g. "--robots", "2", "--gains", "30,11"). A bad file raises
    ValueError with tvo_sim's file:line:col message."""
    env = None
    if exporter is None:
        from . import _build_paths
        exporter = _build_paths.SCENARIO_EXPORT
        if _build_paths.SCENARIO_DIR and "TVO_SCENARIO_DIR" not in os.environ:
            # an installed package: the built-in names are its own copies (a set $TVO_SCENARIO_DIR wins)
            env = {**os.environ, "TVO_SCENARIO_DIR": _build_paths.SCENARIO_DIR}
    run = subprocess.run([exporter, "--scenario", str(name_or_path), *map(str, sim_options)],
                         capture_output=True, text=True, check=False, env=env)
    if run.returncode != 0:
        raise ValueError((run.stderr or run.stdout).strip())
    return Scenario(json.loads(run.stdout))
