#!/usr/bin/python3
"""The `tvo` module's API: problems, status codes as exceptions and enums with the core's text, one
step over numpy arrays, misses and the watchdog, the chain controller, both precisions, scenarios.
Usage: test_module.py   (PYTHONPATH: <build>/host/python)"""
import math
import subprocess
import sys
import unittest

import numpy as np

import tvo


def demo_problem():
    return tvo.Problem(1).track(0, tvo.ellipse((0.0, 0.0), (3.0, 1.5), 2 * math.pi / 10))


class StatusTest(unittest.TestCase):
    def test_codes_and_text_come_from_the_core(self):
        lib, ffi = tvo.core().lib, tvo.core().ffi
        self.assertEqual(int(tvo.Status.TVO_OK), 0)
        self.assertEqual(len(tvo.Status), lib.TVO_STATUS_COUNT)
        self.assertEqual(len(tvo.Outcome), lib.TVO_OUTCOME_COUNT)
        self.assertEqual(len(tvo.Reason), lib.TVO_REASON_COUNT)
        self.assertEqual(len(tvo.Param), lib.TVO_PARAM_COUNT)
        self.assertEqual(len(tvo.ChainParam), lib.TVO_CHAIN_PARAM_COUNT)
        self.assertEqual(tvo.Status.TVO_ERR_TICK_NOT_ADVANCING.message,
                         ffi.string(lib.tvo_status_str(lib.TVO_ERR_TICK_NOT_ADVANCING)).decode())
        self.assertIn("stale", tvo.Reason.STALE.message)
        self.assertEqual(tvo.Reason.WATCHDOG.message, ffi.string(lib.tvo_reason_str(lib.TVO_REASON_WATCHDOG)).decode())
        self.assertEqual(tvo.Outcome.HELD.message, "held")
        self.assertEqual(str(tvo.Param.TVO_PARAM_GAINS), "gain_kp/gain_kd")
        self.assertEqual(str(tvo.ChainParam.TVO_CHAIN_PARAM_INPUT_MAX), "input_max")
        self.assertEqual(tvo.Flag.PREDICTED, lib.TVO_FLAG_PREDICTED)
        self.assertFalse(hasattr(tvo.Flag, "SAFE_STOP"))  # the outcome says it: tvo.Outcome.STOPPED

    def test_refused_parameter_raises_naming_it(self):
        with self.assertRaises(tvo.TvoError) as caught:
            tvo.UnicycleController(demo_problem(), gain_kp=-1.0)
        self.assertEqual(caught.exception.status, tvo.Status.TVO_ERR_PARAM)
        self.assertEqual(caught.exception.param, tvo.Param.TVO_PARAM_GAINS)
        self.assertIn("gain_kp/gain_kd", str(caught.exception))
        self.assertIn(tvo.Status.TVO_ERR_PARAM.message, str(caught.exception))

    def test_refused_problem_names_the_part(self):
        p = demo_problem().add_obstacle((1.0, 1.0), -0.5)
        with self.assertRaises(tvo.TvoError) as caught:
            tvo.UnicycleController(p)
        self.assertEqual(caught.exception.part, "obstacles")

    def test_unknown_config_field(self):
        with self.assertRaises(TypeError):
            tvo.UnicycleController(demo_problem(), gain_kq=1.0)


class StepTest(unittest.TestCase):
    def test_one_step_over_numpy_arrays(self):
        for precision in tvo.PRECISIONS:
            ctl = tvo.UnicycleController(demo_problem(), precision, period_s=0.01)
            cmd = ctl.step(np.array([[-1.0, -2.0]]), heading=np.array([0.0]))
            self.assertEqual((cmd.outcome, cmd.reason), (tvo.Outcome.APPLIED, tvo.Reason.NONE))
            self.assertEqual(cmd.speed_mps.dtype, np.dtype(precision))
            self.assertEqual(cmd.speed_mps.shape, (1,))
            self.assertTrue(np.all(np.isfinite(cmd.turn_rate_radps)))
            self.assertIn(tvo.Flag.PREDICTED, cmd.flags)

    def test_refusal_is_an_outcome_not_an_exception(self):
        ctl = tvo.UnicycleController(demo_problem(), period_s=0.01)
        cmd = ctl.step([[-1.0, -2.0]], heading=None)   # pose mode needs the heading
        self.assertEqual((cmd.outcome, cmd.reason), (tvo.Outcome.HELD, tvo.Reason.MISSING_FIELD))
        cmd = ctl.step([[math.nan, -2.0]], heading=[0.0])
        self.assertEqual((cmd.outcome, cmd.reason), (tvo.Outcome.HELD, tvo.Reason.NOT_FINITE))

    def test_misuse_raises_and_changes_nothing(self):
        ctl = tvo.UnicycleController(demo_problem(), period_s=0.01)
        cmd = ctl.step([[-1.0, -2.0]], heading=[0.0])
        self.assertEqual(cmd.outcome, tvo.Outcome.APPLIED)
        with self.assertRaises(tvo.TvoError) as caught:
            ctl.step([[-1.0, -2.0]], heading=[0.0], apply_tick=ctl.next_apply_tick() - ctl.period_ticks)
        self.assertEqual(caught.exception.status, tvo.Status.TVO_ERR_TICK_NOT_ADVANCING)
        self.assertEqual(ctl.step([[-1.0, -2.0]], heading=[0.0]).outcome, tvo.Outcome.APPLIED)

    def test_misses_reach_the_watchdog(self):
        ctl = tvo.UnicycleController(demo_problem(), period_s=0.01, watchdog_periods=3)
        self.assertEqual(ctl.step([[-1.0, -2.0]], [0.0]).outcome, tvo.Outcome.APPLIED)
        answers = [(cmd.outcome, cmd.reason) for cmd in (ctl.miss() for _ in range(3))]
        self.assertEqual(answers[:2], [(tvo.Outcome.HELD, tvo.Reason.NO_MEASUREMENT)] * 2)
        self.assertEqual(answers[2], (tvo.Outcome.STOPPED, tvo.Reason.WATCHDOG))

    def test_closed_loop_tracks_in_both_precisions(self):
        errors = {}
        for precision in tvo.PRECISIONS:
            ctl = tvo.UnicycleController(demo_problem(), precision, period_s=0.01)
            loop = ctl.run([[-1.0, -2.0, 0.0]], 1000)
            self.assertTrue(np.all(loop.outcome == tvo.Outcome.APPLIED))
            errors[precision] = loop.tracking_error(demo_problem())[-1, 0]
            self.assertLess(errors[precision], 0.01)
        self.assertNotEqual(errors["float32"], errors["float64"])  # two builds, not one

    def test_two_robots_with_a_distance_bound(self):
        p = tvo.Problem(2).track(0, tvo.circle((0, 0), 2.0, 0.5)).track(1, tvo.circle((0, 0), 2.0, 0.5, math.pi / 2))
        p.add_distance_bound(0, 1, min_m=1.0)
        loop = tvo.UnicycleController(p, period_s=0.01).run([[2.0, 0.0, 1.6], [0.0, 2.0, 3.1]], 300)
        self.assertTrue(np.all(loop.outcome == tvo.Outcome.APPLIED))
        d = np.linalg.norm(loop.poses[:, 0, :2] - loop.poses[:, 1, :2], axis=-1)
        self.assertGreater(d.min(), 0.9)

    def test_streamed_target(self):
        p = tvo.Problem(1).track(0, tvo.streamed())
        ctl = tvo.UnicycleController(p, period_s=0.01)
        cmd = ctl.step([[0.0, 0.0]], [0.0])
        self.assertEqual((cmd.outcome, cmd.reason), (tvo.Outcome.HELD, tvo.Reason.TARGET_NOT_READY))
        # A target moving along x at 0.5 m/s from (1, 0), streamed every period, stamped at the sample.
        for _ in range(100):
            apply = ctl.next_apply_tick()
            sample = apply - ctl.delay_ticks
            ctl.stream_target(0, [[1.0 + 0.5 * sample * 1e-6, 0.0], [0.5, 0.0]], sample)
            cmd = ctl.step([[0.0, 0.0]], [0.0], apply_tick=apply)
            self.assertEqual(cmd.outcome, tvo.Outcome.APPLIED)
        self.assertGreater(cmd.speed_mps[0], 0.0)   # towards the target ahead
        with self.assertRaises(tvo.TvoError) as caught:
            ctl.stream_target(0, [[math.inf, 0.0]], ctl.next_apply_tick() - ctl.delay_ticks)
        self.assertEqual(caught.exception.status, tvo.Status.TVO_ERR_NOT_FINITE)
        with self.assertRaises(ValueError):
            tvo.export_c(p)

    def test_chain_controller(self):
        p = tvo.Problem(1).track(0, tvo.polynomial([[1.0, 0.2], [-0.5]]))
        ctl = tvo.ChainController(p, relative_degree=2, period_s=0.01)
        y = np.zeros((2, 2))   # y, y' of the double integrator
        for _ in range(800):
            cmd = ctl.step(y)
            self.assertEqual((cmd.outcome, cmd.reason), (tvo.Outcome.APPLIED, tvo.Reason.NONE))
            h = 0.01
            y = np.array([y[0] + y[1] * h + 0.5 * cmd.u * h * h, y[1] + cmd.u * h])
        t = 800 * 0.01
        self.assertLess(np.linalg.norm(y[0] - [1.0 + 0.2 * t, -0.5]), 0.05)


class MistakesTest(unittest.TestCase):
    """Each shape or range mistake a user can make through the API is refused with a message that
    names the culprit (the robot count, the entry, the expected shape), as tvo_sim's scenario files."""

    def refused(self, error, call, *fragments):
        with self.assertRaises(error) as caught:
            call()
        for fragment in fragments:
            self.assertIn(fragment, str(caught.exception))
        return caught.exception

    def test_robot_count_of_measurements_and_starts(self):
        ctl = tvo.UnicycleController(demo_problem(), period_s=0.01)
        self.refused(ValueError, lambda: ctl.step([[0.0, 0.0], [1.0, 1.0]], [0.0]),
                     "step: position", "values for 2 robots", "drives 1 robot", "expected shape (1, 2)")
        self.refused(ValueError, lambda: ctl.step([0.0, 0.0, 1.0, 1.0], [0.0]), "2 robots as one flat row")
        self.refused(ValueError, lambda: ctl.step([[0.0, 0.0, 0.0]], [0.0]), "shape (1, 3)", "x, y per robot")
        self.refused(ValueError, lambda: ctl.step([[0.0, 0.0]], [0.0, 1.0]), "step: heading", "values for 2 robots")
        self.refused(ValueError, lambda: ctl.step([[0.0, 0.0]], [0.0], speed=[1.0, 2.0]), "step: speed")
        self.refused(ValueError, lambda: ctl.run([[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]], 10),
                     "run: start", "values for 2 robots", "x, y, heading per robot")
        self.refused(ValueError, lambda: ctl.run([[0.0, 0.0, 0.0]], 2.5), "run: steps", "got 2.5")
        self.assertEqual(ctl.periods, 0)   # nothing of a refused call is kept
        self.assertEqual(ctl.step([-1.0, -2.0], 0.0).outcome, tvo.Outcome.APPLIED)   # one robot: no robot axis
        two = tvo.Problem(2).track(0, tvo.circle((0, 0), 2.0, 0.5)).track(1, tvo.circle((0, 0), 2.0, 0.5, 1.0))
        self.refused(ValueError, lambda: tvo.UnicycleController(two).step([[0.0, 0.0]], [0.0]),
                     "values for 1 robot", "drives 2 robots")
        self.refused(ValueError, lambda: tvo.UnicycleController(demo_problem(), initial_speed_mps=[0.0] * 9),
                     "initial_speed_mps: 9 values")

    def test_chain_and_streamed_shapes(self):
        chain = tvo.ChainController(tvo.Problem(1).track(0, tvo.polynomial([[1.0], [0.0]])), relative_degree=2)
        self.refused(ValueError, lambda: chain.step(np.zeros((2, 4))), "values for 2 robots", "2N = 2",
                     "drives 1 robot")
        self.refused(ValueError, lambda: chain.step(np.zeros((3, 2))), "expected (1 .. 2, 2)")
        ctl = tvo.UnicycleController(tvo.Problem(1).track(0, tvo.streamed()), period_s=0.01)
        self.refused(IndexError, lambda: ctl.stream_target(1, [[0.0, 0.0]], 0), "robot 1", "has 1 robot (0 .. 0)")
        rows = tvo.core().lib.TVO_STREAM_MAX_DERIV + 1
        self.refused(ValueError, lambda: ctl.stream_target(0, np.zeros((rows + 1, 2)), 0), f"expected (1 .. {rows}, 2)")

    def test_problem_entries_name_the_robot(self):
        p = tvo.Problem(2)
        self.refused(IndexError, lambda: p.track(2, tvo.circle((0, 0), 1.0, 1.0)), "track: robot 2",
                     "has 2 robots (0 .. 1)")
        self.refused(TypeError, lambda: p.track(0, (0.0, 0.0)), "robot 0's target", "tvo.polynomial")
        self.refused(ValueError, lambda: p.track(0, tvo.circle((0, 0), 1.0, 1.0), weight=(1.0,)), "robot 0's weight")
        self.refused(IndexError, lambda: p.add_distance_bound(0, 5, min_m=1.0), "add_distance_bound: robot 5")
        self.refused(ValueError, lambda: p.add_distance_bound(1, 1, min_m=1.0), "two different robots", "1 twice")
        self.refused(IndexError, lambda: p.add_halfspace(3, (1.0, 0.0), 1.0), "add_halfspace: robot 3")
        self.refused(ValueError, lambda: p.add_offset(0, 0, tvo.polynomial([[1.0], [0.0]])), "add_offset")
        self.refused(ValueError, lambda: p.add_obstacle((0.0, 0.0, 1.0), 0.5), "add_obstacle: center_m", "two numbers")
        self.refused(TypeError, lambda: p.add_obstacle((0.0, 0.0), "big"), "add_obstacle: radius_m")
        self.refused(ValueError, lambda: tvo.circle((0.0, 0.0, 0.0), 1.0, 1.0), "circle: center_m")
        self.refused(ValueError, lambda: tvo.ellipse((0.0, 0.0), (1.0,), 1.0), "ellipse: semi_axis_m")
        self.refused(ValueError, lambda: tvo.polynomial([[1.0], [0.0], [2.0]]), "two rows (x, y)", "got 3 rows")
        self.refused(ValueError, lambda: tvo.Problem(0), "robots >= 1, got 0")
        self.assertEqual((p.distance_bounds, p.halfspaces, p.offsets, p.obstacles), ([], [], [], []))
        p.track(0, tvo.circle((0, 0), 1.0, 1.0))
        self.refused(ValueError, lambda: tvo.UnicycleController(p), "robot 1 has no target (of 2 robots)")

    def test_core_refusals_name_the_entry(self):
        def core_refused(problem, culprit, *fragments):
            error = self.refused(tvo.TvoError, lambda: tvo.UnicycleController(problem), culprit, *fragments)
            self.assertEqual(error.culprit, culprit)
            return error

        three = demo_problem().add_obstacle((5.0, 5.0), 1.0).add_obstacle((-5.0, 5.0), 1.0).add_obstacle((5.5, 5.0), 1.0)
        error = core_refused(three, "obstacles[0] and obstacles[2]", "they overlap", "centres 0.5 m apart",
                             "radii's sum 2 m")
        self.assertEqual(error.part, "obstacles")
        core_refused(demo_problem().add_obstacle((5.0, 5.0), 1.0).add_obstacle((9.0, 9.0), -0.5),
                     "obstacles[1]", "the radius must be > 0")
        radius = demo_problem().add_obstacle((5.0, 5.0), 1.0)
        radius.robot_radius_m = -0.1
        core_refused(radius, "robot_radius_m", "-0.1 m refused")
        core_refused(tvo.Problem(2).track(0, tvo.circle((0, 0), 2.0, 0.5)).track(1, tvo.circle((0, 0), 1.0, 0.5))
                     .add_distance_bound(0, 1, min_m=0.5).add_distance_bound(0, 1, min_m=2.0, max_m=1.0),
                     "distance_bounds[1] (robots 0 and 1)", "min_m (2.0) must be below max_m (1.0)")
        core_refused(demo_problem().add_halfspace(0, (0.0, 0.0), 1.0), "halfspaces[0] (robot 0)", "no direction")
        barrier = demo_problem().add_obstacle((5.0, 5.0), 1.0)
        barrier.barrier = {"relaxation_degree": 2, "c0": 1.0}
        core_refused(barrier, "barrier['relaxation_degree']", "at least k + 1 = 3")
        weight = demo_problem()
        weight.robots[0]["tracking_weight"] = [1.0, -2.0]
        core_refused(weight, "robot 0's weight", "both must be finite and > 0")
        barrier.barrier = {"c_zero": 1.0}
        self.refused(TypeError, lambda: tvo.UnicycleController(barrier), "barrier: no field 'c_zero'", "c0")
        crowded = demo_problem()
        for i in range(tvo.core().lib.TVO_MAX_OBSTACLES + 1):
            crowded.add_obstacle((10.0 * i, 50.0), 1.0)
        self.refused(tvo.TvoError, lambda: tvo.UnicycleController(crowded), "9 obstacles (at most 8")


class ReadmeTest(unittest.TestCase):
    def test_readme_python_runs(self):
        """host/python/README.md's Python blocks run as written (the tuning one with its problem)."""
        import os
        import re
        readme = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "README.md")
        with open(readme, encoding="utf-8") as f:
            blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
        self.assertGreaterEqual(len(blocks), 2)
        scope = {}
        exec(blocks[0], scope)   # pylint: disable=exec-used
        self.assertEqual(scope["cmd"].outcome, tvo.Outcome.APPLIED)
        scope["start"] = [[-1.0, -2.0, 0.0]]
        exec(blocks[1], scope)   # pylint: disable=exec-used
        self.assertLess(scope["score"](40, 13, seconds=2.0), 1.0)


class ScenarioTest(unittest.TestCase):
    def test_builtin_scenario_runs(self):
        s = tvo.load_scenario("obstacles")
        self.assertEqual(s.problem.robots[0]["target"]["kind"], "polynomial")   # its waypoints, solved
        self.assertEqual(len(s.problem.obstacles), 4)
        loop = s.make_controller().run(s.starts, 200)
        self.assertTrue(np.all(loop.outcome == tvo.Outcome.APPLIED))

    def test_export_command(self):
        run = subprocess.run([sys.executable, "-m", "tvo", "export", "formation-max", "--gains", "30,11"],
                             capture_output=True, text=True, check=True)
        self.assertIn("static inline tvo_status_t formation_max_problem_desc(tvo_problem_desc_t *desc)", run.stdout)
        self.assertIn("cfg->gain_kp = TVO_R(0x1.e000000000000p+4);", run.stdout)   # 30
        run = subprocess.run([sys.executable, "-m", "tvo", "export", "obstacles", "--duration-s", "100"],
                             capture_output=True, text=True)
        self.assertEqual(run.returncode, 2)
        self.assertIn("obstacles.yaml:", run.stderr)   # tvo_sim's file:line:col of the last waypoint

    def test_bad_scenario_names_the_file(self):
        with self.assertRaises(ValueError) as caught:
            tvo.load_scenario("no-such-scenario")
        self.assertIn("no-such-scenario", str(caught.exception))


if __name__ == "__main__":
    unittest.main(verbosity=2)
