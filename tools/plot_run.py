#!/usr/bin/python3
"""Plots a tvo_sim run: the paths (targets and robots, start markers) and the tracking error over
time on a log scale. Reads the run's CSV (see host/src/run_recorder.hpp), writes a PNG.

Usage: tools/plot_run.py RUN_CSV [-o PNG]   (default PNG: next to the CSV, same name .png)
Runs under Debian's /usr/bin/python3 with python3-matplotlib (no display needed).
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only: works over SSH and in CI without a display
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)

# Error values of exactly zero cannot sit on a log axis: clamp them to this floor.
ERROR_FLOOR_M = 1e-12


def read_run(path):
    """Rows grouped per robot: {robot: {column: [values]}}."""
    robots = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            series = robots.setdefault(int(row["robot"]), {})
            for key in ("t_s", "x_m", "y_m", "target_x_m", "target_y_m", "error_m"):
                series.setdefault(key, []).append(float(row[key]))
    if not robots:
        raise ValueError(f"{path}: no rows")
    return robots


def plot(robots, png_path, title):
    fig, (ax_path, ax_err) = plt.subplots(1, 2, figsize=(12, 5))
    for robot, s in sorted(robots.items()):
        color = f"C{robot % 10}"
        # Wide and pale under a thin robot line, so a converged robot stays visible on its target.
        ax_path.plot(s["target_x_m"], s["target_y_m"], "-", color=color, lw=4, alpha=0.3, label=f"target {robot}")
        ax_path.plot(s["x_m"], s["y_m"], "-", color=color, lw=1.2, label=f"robot {robot}")
        ax_path.plot(s["target_x_m"][0], s["target_y_m"][0], "o", color=color, mfc="none", ms=8)
        ax_path.plot(s["x_m"][0], s["y_m"][0], "s", color=color, ms=7)
        errors = [max(e, ERROR_FLOOR_M) for e in s["error_m"]]
        ax_err.semilogy(s["t_s"], errors, color=color, label=f"robot {robot}")
    ax_path.set_aspect("equal", adjustable="datalim")
    ax_path.set_xlabel("x (m)")
    ax_path.set_ylabel("y (m)")
    ax_path.set_title("paths (square: robot start, circle: target start)")
    ax_path.grid(True, alpha=0.3)
    ax_path.legend(loc="best", fontsize="small")
    ax_err.set_xlabel("t (s)")
    ax_err.set_ylabel("|y - y_d| (m)")
    ax_err.set_title("tracking error")
    ax_err.grid(True, which="both", alpha=0.3)
    ax_err.legend(loc="best", fontsize="small")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(description="Plot a tvo_sim run (paths and tracking error).")
    parser.add_argument("csv", help="run CSV written by tvo_sim (e.g. runs/demo/run.csv)")
    parser.add_argument("-o", "--output", help="PNG to write (default: the CSV's path with .png)")
    args = parser.parse_args(argv)
    png_path = args.output or os.path.splitext(args.csv)[0] + ".png"
    try:
        robots = read_run(args.csv)
    except (OSError, ValueError, KeyError) as e:
        print(f"plot_run: error: cannot read {args.csv}: {e}", file=sys.stderr)
        return 1
    plot(robots, png_path, os.path.basename(os.path.dirname(os.path.abspath(args.csv))) or "tvo_sim run")
    print(png_path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
