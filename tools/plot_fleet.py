#!/usr/bin/python3
"""Plots a fleet run (tools/fleet's run folder): the paths (targets, robots, obstacles, footprints,
each collision a red cross), the pair distances (each bounded pair with its bounds; without bounds every
pair) and the nodes' disagreement: each period the nodes' joint digests differed in, with the number of
nodes outside the largest group of equal digests (the hub's digest_mismatch_per_period: [period, nodes]
pairs). A v3 node's telemetry carries only its own robot's rows, so the hub sees in which periods the
nodes differed, not by how much.

Reads run.csv, scenario.json and summary.json of the folder (tools/fleet writes them; plot_run.py's
readers); writes run.png there, or -o PNG.

Usage: tools/plot_fleet.py RUN_FOLDER [-o PNG]
"""
import argparse
import itertools
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import plot_run  # noqa: E402  (matplotlib with the Agg backend, the readers and the panels)
from plot_run import plt  # noqa: E402  (matplotlib with the Agg backend)

SERIES_KEY = "digest_mismatch_per_period"


def legend_once(ax, **kwargs):
    """A legend with each label once (plot_run labels every bound line 'bounds')."""
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    ax.legend(unique.values(), unique.keys(), **kwargs)


def plot_pairs(ax, robots, scenario):
    """Every pair's distance when no pair is bounded (the closest pair shows where robots came near)."""
    ids = sorted(robots)
    for k, (a, b) in enumerate(itertools.combinations(ids, 2)):
        ra, rb = robots[a], robots[b]
        d = [math.hypot(ra["x_m"][i] - rb["x_m"][i], ra["y_m"][i] - rb["y_m"][i]) for i in range(len(ra["t_s"]))]
        ax.plot(ra["t_s"], d, lw=0.8, color=f"C{k % 10}", label=f"|y{a} - y{b}|" if len(ids) <= 4 else None)
    radius = scenario.get("robot_radius_m", 0.0) if scenario else 0.0
    if radius > 0.0:
        ax.axhline(2 * radius, color="k", ls="--", lw=1, label="contact (2 r)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("distance (m)")
    ax.set_title("distance of every pair of robots", fontsize="medium")
    ax.grid(True, alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize="small")


def plot_disagreement(ax, summary):
    """The periods the nodes' joint digests differed in, with how many nodes were outside the majority."""
    compared = summary.get("compared_periods", 0)
    differ = summary.get("digest_mismatch_periods", 0)
    series = summary.get(SERIES_KEY) or []
    if summary.get("one_bus"):
        note = "not compared on one bus\n(the hub compares the nodes' joint digests)"
    elif differ:
        note = f"digests differ in {differ:,} of {compared:,} periods"
    else:
        note = f"every node computed the same command\nin all {compared:,} periods, bit for bit"
    if series:
        ax.plot([p for p, _ in series], [n for _, n in series], ls="none", marker="|", ms=8, color="C3",
                label="nodes outside the largest group of equal digests")
        if "loss_end_period" in summary:
            ax.axvline(summary["loss_end_period"], color="k", ls=":", lw=1, label="loss ends")
        ax.set_ylim(0, max(n for _, n in series) + 1)
        ax.text(0.02, 0.98, note, transform=ax.transAxes, fontsize=8, va="top",
                bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        ax.legend(loc="lower right", fontsize="small")
    else:  # nothing to draw: say so in the middle
        ax.text(0.5, 0.5, note, transform=ax.transAxes, fontsize=10, ha="center", va="center")
    ax.set_xlabel("period")
    ax.set_ylabel("nodes that disagreed")
    ax.set_title("nodes' disagreement per period (joint digests)", fontsize="medium")
    ax.grid(True, alpha=0.3)


def plot(folder, png=None):
    folder = Path(folder)
    csv = folder / "run.csv"
    robots = plot_run.read_run(csv)
    scenario = plot_run.read_scenario(csv)
    collisions = plot_run.read_collisions(csv)
    summary = json.loads((folder / "summary.json").read_text())
    fig, axes = plt.subplots(1, 3, figsize=(19, 5.5))
    plot_run.plot_paths(axes[0], robots, scenario)
    if len(robots) > 4:
        axes[0].legend().remove()  # 2 lines a robot: the colours say which is which
    if scenario and scenario.get("distance_bounds"):
        plot_run.plot_distance(axes[1], robots, scenario)
        axes[1].set_title("distance of each bounded pair", fontsize="medium")
        legend_once(axes[1], loc="best", fontsize="small", ncol=2 if len(scenario["distance_bounds"]) > 4 else 1)
    else:
        plot_pairs(axes[1], robots, scenario)
    plot_disagreement(axes[2], summary)
    title = (f"{Path(summary.get('scenario', folder.name)).stem}: {summary.get('robots')} robots, one node each"
             + (f", {summary['loss']:.0%} loss per link" if summary.get("loss") else ""))
    if collisions:
        plot_run.mark_collisions_on_paths(axes[0], collisions)
        plot_run.mark_collisions_in_time(axes[1], collisions)
        axes[0].legend(loc="best", fontsize="small")
        title += f": {len(collisions)} collision{'s' if len(collisions) > 1 else ''} (red)"
    fig.suptitle(title)
    fig.tight_layout()
    png = Path(png or folder / "run.png")
    fig.savefig(png, dpi=100)
    plt.close(fig)
    return png


def main(argv):
    parser = argparse.ArgumentParser(description="Plot a tools/fleet run (paths, pair distances, disagreement).")
    parser.add_argument("folder", help="the run's folder (runs/NAME)")
    parser.add_argument("-o", "--output", help="PNG to write (default: FOLDER/run.png)")
    args = parser.parse_args(argv)
    try:
        print(plot(args.folder, args.output))
    except (OSError, ValueError, KeyError) as e:
        print(f"plot_fleet: error: cannot plot {args.folder}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
