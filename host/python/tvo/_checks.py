"""The Python API's own shape and index checks: a mistake is refused before it reaches the core, with a
message that names the culprit (the robot count, the entry, the expected shape), as tvo_sim's scenario
files do. What the core itself refuses is diagnosed after the fact (_problem.py), so the core stays the
one judge of what is valid."""
import numbers

import numpy as np


def robots_text(n):
    return f"{n} robot" if n == 1 else f"{n} robots"


def robot_index(robot, robots, what):
    """robot as an int in 0 .. robots - 1, else IndexError naming the problem's robot count."""
    if isinstance(robot, bool) or not isinstance(robot, numbers.Integral):
        raise TypeError(f"{what}: a robot is an index 0 .. {robots - 1}, got {robot!r}")
    if not 0 <= robot < robots:
        raise IndexError(f"{what}: robot {robot}, but the problem has {robots_text(robots)} (0 .. {robots - 1})")
    return int(robot)


def robot_pair(robot_a, robot_b, robots, what):
    a = robot_index(robot_a, robots, what)
    b = robot_index(robot_b, robots, what)
    if a == b:
        raise ValueError(f"{what}: two different robots are needed (got {a} twice)")
    return a, b


def real(value, what):
    """value as a Python float, else TypeError naming it."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{what} must be a number, got {value!r}")
    return float(value)


def pair(value, what):
    """Two numbers (x, y) as a list of floats, else ValueError naming what and what it got."""
    a = np.asarray(value, dtype=np.float64)
    if a.shape != (2,):
        raise ValueError(f"{what} must be two numbers (x, y), got {np.shape(value) or value!r}")
    return [float(v) for v in a]


def per_robot(value, what, robots, columns=None):
    """value as float64 of shape (robots,) or (robots, len(columns)); one robot's values may come
    without the robot axis. Otherwise ValueError naming the robot count and the expected shape."""
    a = np.asarray(value, dtype=np.float64)
    width = None if columns is None else len(columns)
    want = (robots,) if width is None else (robots, width)
    if a.shape == want:
        return a
    if robots == 1 and a.shape == want[1:]:
        return a.reshape(want)
    each = "one value per robot" if width is None else f"{', '.join(columns)} per robot"
    expected = f"expected shape {want}: {each}"
    if a.ndim == len(want) and a.shape[1:] == want[1:]:
        raise ValueError(f"{what}: values for {robots_text(a.shape[0])} (shape {a.shape}), but this controller drives "
                         f"{robots_text(robots)} (its problem's robot count); {expected}")
    if width is not None and a.ndim == 1 and a.size % width == 0 and a.size > width:
        raise ValueError(f"{what}: values for {robots_text(a.size // width)} as one flat row (shape {a.shape}), but "
                         f"this controller drives {robots_text(robots)}; {expected}")
    raise ValueError(f"{what}: shape {a.shape}, but this controller drives {robots_text(robots)}; {expected}")
