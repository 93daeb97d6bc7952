#!/usr/bin/python3
"""Plots a tvo_sim run: the paths (targets and robots, start markers; obstacles as grey disks,
half-space walls as lines and the robot's footprint every second when the scenario has them), the
scenario's constraint over time (inter-robot distance with its bounds dashed, clearance to the obstacles, or the formation-offset
residual) and the tracking error over time on a log scale.

Reads the run's CSV (see host/src/run_recorder.hpp) and, when present next to it, the scenario's
geometry in scenario.json and the run's summary.json (host/src/summary.hpp): each entry into contact
it lists (collision_events) is marked with a red cross on the paths and a red line over time. Writes
a PNG and prints its path (and how many collisions it marked).

Usage: tools/plot_run.py RUN_CSV [-o PNG]   (default PNG: next to the CSV, same name .png)
Runs under Debian's /usr/bin/python3 with python3-matplotlib (no display needed).
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only: works over SSH and in CI without a display
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)

# Values of exactly zero cannot sit on a log axis: clamp them to this floor.
LOG_FLOOR = 1e-12
# Footprints and time labels along the paths every this many seconds.
MARK_EVERY_S = 1.0
COLUMNS = ("t_s", "x_m", "y_m", "target_x_m", "target_y_m", "error_m")
OPTIONAL_COLUMNS = ("barrier_slack",)


def read_run(path):
    """Rows grouped per robot: {robot: {column: [values]}}."""
    robots = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            series = robots.setdefault(int(row["robot"]), {})
            for key in COLUMNS:
                series.setdefault(key, []).append(float(row[key]))
            for key in OPTIONAL_COLUMNS:
                if key in row:
                    series.setdefault(key, []).append(float(row[key]))
    if not robots:
        raise ValueError(f"{path}: no rows")
    return robots


def read_scenario(csv_path):
    """scenario.json next to the CSV, or None (a demo run from before it existed)."""
    path = os.path.join(os.path.dirname(os.path.abspath(csv_path)), "scenario.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def read_collisions(csv_path):
    """summary.json's collision_events next to the CSV: [{t_s, robot, with, position_m}], or []."""
    path = os.path.join(os.path.dirname(os.path.abspath(csv_path)), "summary.json")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return json.load(f).get("collision_events", [])


def mark_collisions_on_paths(ax, collisions):
    for k, c in enumerate(collisions):
        x, y = c["position_m"]
        ax.plot(x, y, "x", color="red", ms=12, mew=2.5, zorder=5,
                label="collision (robot entering contact)" if k == 0 else None)
        ax.annotate(f"robot {c['robot']} / {c['with']}, t = {c['t_s']:.2f} s", (x, y), fontsize=7, color="red",
                    xytext=(6, -10), textcoords="offset points")


def mark_collisions_in_time(ax, collisions):
    for k, c in enumerate(collisions):
        ax.axvline(c["t_s"], color="red", lw=1.2, label="collision" if k == 0 else None)


def marks(times):
    """Indices of the samples closest to every MARK_EVERY_S."""
    out, next_t = [], 0.0
    for i, t in enumerate(times):
        if t >= next_t - 1e-9:
            out.append(i)
            next_t += MARK_EVERY_S
    return out


def wall_points(h, t_s):
    """Two points of the wall (normal + normal_rate t)^T y = bound_m + bound_rate_mps t, or None."""
    a = [h["normal"][k] + h["normal_rate"][k] * t_s for k in range(2)]
    b = h["bound_m"] + h["bound_rate_mps"] * t_s
    norm2 = a[0] ** 2 + a[1] ** 2
    if norm2 == 0.0:
        return None
    p0 = (a[0] * b / norm2, a[1] * b / norm2)
    return p0, (p0[0] - a[1], p0[1] + a[0])


def plot_walls(ax, scenario):
    """Each half-space wall as a dark line (its robot in the legend), at t = 0 (solid) and, if it moves,
    at T (dotted). Infinite lines: they do not change the limits."""
    duration = scenario.get("duration_s", 0.0)
    for k, h in enumerate(scenario.get("halfspaces", [])):
        color = f"{0.15 + 0.15 * (k % 4):.2f}"  # greys apart from the robots' colours
        moves = any(h["normal_rate"]) or h["bound_rate_mps"] != 0.0
        for t_s, style in [(0.0, "-")] + ([(duration, ":")] if moves else []):
            points = wall_points(h, t_s)
            if points is None:
                continue
            label = f"wall {k} (robot {h['robot']})" + (f", t = {t_s:g} s" if moves else "")
            ax.axline(points[0], points[1], color=color, ls=style, lw=2.0, label=label)


def plot_paths(ax, robots, scenario):
    radius = scenario.get("robot_radius_m", 0.0) if scenario else 0.0
    # With formation offsets each robot's reference is the constrained minimiser, not a target.
    ref_name = "reference" if scenario and scenario.get("offsets") else "target"
    for o in (scenario or {}).get("obstacles", []):
        ax.add_patch(plt.Circle(o["center_m"], o["radius_m"], color="0.55", alpha=0.6, lw=0))
    for robot, s in sorted(robots.items()):
        color = f"C{robot % 10}"
        # Wide and pale under a thin robot line, so a converged robot stays visible on its target.
        ax.plot(s["target_x_m"], s["target_y_m"], "-", color=color, lw=4, alpha=0.3, label=f"{ref_name} {robot}")
        ax.plot(s["x_m"], s["y_m"], "-", color=color, lw=1.2, label=f"robot {robot}")
        ax.plot(s["target_x_m"][0], s["target_y_m"][0], "o", color=color, mfc="none", ms=8)
        ax.plot(s["x_m"][0], s["y_m"][0], "s", color=color, ms=7)
        for i in marks(s["t_s"]):
            if radius > 0.0:
                ax.add_patch(plt.Circle((s["x_m"][i], s["y_m"][i]), radius, color=color, alpha=0.15, lw=0))
            if scenario and scenario.get("name") != "demo" and int(round(s["t_s"][i])) % 2 == 0:
                ax.annotate(f"{s['t_s'][i]:.0f}", (s["target_x_m"][i], s["target_y_m"][i]), fontsize=6,
                            color=color, xytext=(2, 2), textcoords="offset points")
    if scenario:
        plot_walls(ax, scenario)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    title = "paths (square: robot start, circle: target start"
    title += ", discs: footprint every 1 s)" if radius > 0.0 else ")"
    ax.set_title(title, fontsize="medium")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def plot_distance(ax, robots, scenario):
    """Inter-robot distance of each bounded pair, its bounds dashed, the crossing window shaded."""
    for k, b in enumerate(scenario["distance_bounds"]):
        a, c = robots[b["robot_a"]], robots[b["robot_b"]]
        t = a["t_s"]
        d = [math.hypot(a["x_m"][i] - c["x_m"][i], a["y_m"][i] - c["y_m"][i]) for i in range(len(t))]
        ax.plot(t, d, color=f"C{k}", label=f"|y{b['robot_a']} - y{b['robot_b']}|")
        if b["max_m"] > 0.0:
            ax.plot(t, [b["max_m"] + b["max_rate_mps"] * x for x in t], "k--", lw=1, label="bounds")
            slack = a.get("barrier_slack")
            if slack and max(slack) > 0.0:
                # The slacked bound the barrier enforces while s(t) > 0: |D|^2 <= d_max^2 + s(t).
                relaxed = [math.sqrt((b["max_m"] + b["max_rate_mps"] * x) ** 2 + s) for x, s in zip(t, slack)]
                ax.plot(t, relaxed, ":", color="0.4", lw=1, label="sqrt(d_max^2 + s(t))")
        if b["min_m"] > 0.0:
            ax.plot(t, [b["min_m"] + b["min_rate_mps"] * x for x in t], "k--", lw=1)
    if "crossing_window_s" in scenario:
        w = scenario["crossing_window_s"]
        ax.axvspan(w[0], w[1], color="0.85", label="targets < 1 m apart")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("distance (m)")
    ax.set_title("inter-robot distance", fontsize="medium")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def plot_clearance(ax, robots, scenario):
    """Smallest gap between each robot's disk and any obstacle."""
    r = scenario["robot_radius_m"]
    for robot, s in sorted(robots.items()):
        gaps = [min(math.hypot(x - o["center_m"][0], y - o["center_m"][1]) - r - o["radius_m"]
                    for o in scenario["obstacles"]) for x, y in zip(s["x_m"], s["y_m"])]
        ax.plot(s["t_s"], gaps, color=f"C{robot % 10}", label=f"robot {robot}")
    ax.axhline(0.0, color="k", ls="--", lw=1, label="contact")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("clearance (m)")
    ax.set_title("clearance to the nearest obstacle (per period)", fontsize="medium")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def plot_residual(ax, robots, scenario):
    """|y_a - y_b - d(t)|, with d(t) = ref_a - ref_b (the references satisfy the offsets exactly)."""
    for k, e in enumerate(scenario["offsets"]):
        a, b = robots[e["robot_a"]], robots[e["robot_b"]]
        res = [max(LOG_FLOOR, math.hypot((a["x_m"][i] - b["x_m"][i]) - (a["target_x_m"][i] - b["target_x_m"][i]),
                                         (a["y_m"][i] - b["y_m"][i]) - (a["target_y_m"][i] - b["target_y_m"][i])))
               for i in range(len(a["t_s"]))]
        ax.semilogy(a["t_s"], res, color=f"C{k}", label=f"|y{e['robot_a']} - y{e['robot_b']} - d(t)|")
    ax.axvline(scenario["settle_time_s"], color="k", ls="--", lw=1, label="residual counted from here")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("residual (m)")
    ax.set_title("formation-offset residual", fontsize="medium")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def constraint_panel(scenario):
    """The function that draws the scenario's constraint over time, or None."""
    if not scenario:
        return None
    if scenario.get("distance_bounds"):
        return plot_distance
    if scenario.get("obstacles"):
        return plot_clearance
    if scenario.get("offsets"):
        return plot_residual
    return None


def plot_error(ax, robots, scenario):
    for robot, s in sorted(robots.items()):
        errors = [max(e, LOG_FLOOR) for e in s["error_m"]]
        ax.semilogy(s["t_s"], errors, color=f"C{robot % 10}", label=f"robot {robot}")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("|y - y_ref| (m)")
    offsets = scenario and scenario.get("offsets")
    ax.set_title("error to the constrained minimiser" if offsets else "tracking error", fontsize="medium")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def plot(robots, scenario, png_path, title, collisions=()):
    middle = constraint_panel(scenario)
    panels = 3 if middle else 2
    fig, axes = plt.subplots(1, panels, figsize=(6 * panels, 5))
    plot_paths(axes[0], robots, scenario)
    if middle:
        middle(axes[1], robots, scenario)
    plot_error(axes[-1], robots, scenario)
    if collisions:
        mark_collisions_on_paths(axes[0], collisions)
        for ax in axes[1:]:
            mark_collisions_in_time(ax, collisions)
        for ax in axes:
            ax.legend(loc="best", fontsize="small")
        title += f": {len(collisions)} collision{'s' if len(collisions) > 1 else ''} (red)"
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(description="Plot a tvo_sim run (paths, constraint, tracking error).")
    parser.add_argument("csv", help="run CSV written by tvo_sim (e.g. runs/demo/run.csv)")
    parser.add_argument("-o", "--output", help="PNG to write (default: the CSV's path with .png)")
    args = parser.parse_args(argv)
    png_path = args.output or os.path.splitext(args.csv)[0] + ".png"
    try:
        robots = read_run(args.csv)
        scenario = read_scenario(args.csv)
        collisions = read_collisions(args.csv)
    except (OSError, ValueError, KeyError) as e:
        print(f"plot_run: error: cannot read {args.csv}: {e}", file=sys.stderr)
        return 1
    title = (scenario or {}).get("name") or os.path.basename(os.path.dirname(os.path.abspath(args.csv))) or "tvo_sim run"
    plot(robots, scenario, png_path, title, collisions)
    print(png_path + (f" ({len(collisions)} collision{'s' if len(collisions) != 1 else ''} marked)" if collisions else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
