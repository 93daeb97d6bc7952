"""tvo: the TV-O motion-control law of the tvo-flat firmware core, from Python.

The same C core (firmware/src) as the firmware, built by the project's CMake as a shared library in
float32 (the firmware's precision) and in float64, called through cffi in API mode: results are bit
for bit those of the firmware build of the same precision. See host/python/README.md.

    import numpy as np, tvo
    problem = tvo.Problem(robots=1).track(0, tvo.ellipse((0, 0), (3, 1.5), 2 * np.pi / 10))
    ctl = tvo.UnicycleController(problem, period_s=0.01, gain_kp=40, gain_kd=13)
    cmd = ctl.step(position=[[-1, -2]], heading=[0.0])     # Command(speed_mps, turn_rate_radps, flags, outcome, reason)
    loop = ctl.run(start=[[-1, -2, 0]], steps=500)          # closed loop with exact unicycle plants
"""
from ._lib import PRECISIONS, ChainParam, Flag, Outcome, Param, Reason, Status, TvoError, core
from ._problem import BuiltProblem, Problem, circle, ellipse, path_position, polynomial, streamed
from ._controller import ChainCommand, ChainController, ClosedLoop, Command, UnicycleController
from ._scenario import Scenario, load_scenario
from ._export import export_c

VELOCITY_FROM_POSE = core().lib.TVO_VELOCITY_FROM_POSE
VELOCITY_FROM_POSITION = core().lib.TVO_VELOCITY_FROM_POSITION

__all__ = ["PRECISIONS", "ChainParam", "Flag", "Outcome", "Param", "Reason", "Status", "TvoError", "core", "BuiltProblem", "Problem", "circle",
           "ellipse", "path_position", "polynomial", "streamed", "ChainCommand", "ChainController", "ClosedLoop", "Command",
           "UnicycleController", "Scenario", "load_scenario", "export_c", "VELOCITY_FROM_POSE",
           "VELOCITY_FROM_POSITION"]
