#!/usr/bin/python3
"""Plots tvo_study's JSON as the paper's obstacles-figure panels (c) and (d), plus the T_f search.

  study_error_vs_h.png   (c) worst-case tracking error vs h, log-log: tau = 0, h/2, h (uncompensated,
                         the paper's convention), the compensated tau = h/2 and tau = h, the ZOH-aware
                         mode, the dashed continuous-time baseline; each curve up to its stability edge
                         (diverged points are not drawn; the exact edges are marked as vertical ticks).
  study_noise.png        (d) steady-state RMS error vs sigma, log-log: k = 2 exact derivatives, k = 2
                         and k = 3 with dirty-derivative filters at each T_f.
  study_tf_search.png    tracking RMS and command noise vs T_f (k = 2, sigma = 1e-2, h = 1e-3).

Usage: tools/plot_study.py STUDY_JSON [-o OUT_DIR]   (default: the JSON's folder)
Runs under Debian's /usr/bin/python3 with python3-matplotlib (no display needed).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "tau0": dict(color="C0", marker="o", ls="-"),
    "tau_half": dict(color="C1", marker="s", ls="-"),
    "tau_full": dict(color="C3", marker="^", ls="-"),
    "comp_tau_half": dict(color="C1", marker="x", ls=":", ms=8),
    "comp_tau_full": dict(color="C3", marker="+", ls=":", ms=10),
    "zoh_tau0": dict(color="C2", marker="D", ls="-"),
    "zoh_comp_tau_full": dict(color="C2", marker="+", ls=":", ms=10),
}
LABEL = {
    "tau0": r"$\tau = 0$",
    "tau_half": r"$\tau = h/2$",
    "tau_full": r"$\tau = h$",
    "comp_tau_half": r"$\tau = h/2$, compensated",
    "comp_tau_full": r"$\tau = h$, compensated",
    "zoh_tau0": r"ZOH-aware, $\tau = 0$",
    "zoh_comp_tau_full": r"ZOH-aware, $\tau = h$ comp.",
}


def plot_error_vs_h(d, path):
    s1 = d["study1"]
    fig, ax = plt.subplots(figsize=(8.8, 4.8))
    hs_all = []
    for c in s1["curves"]:
        pts = [(r["h_s"], r["max_err_m"]) for r in c["table"]
               if not r["diverged"] and not r.get("beyond_exact_edge") and r["max_err_m"]]
        if not pts:
            continue
        h, e = zip(*pts)
        hs_all += h
        extra = ""
        if c.get("order") is not None and c["name"] in ("tau0", "zoh_tau0"):
            extra = f" (order {c['order']:.2f})"
        ax.loglog(h, e, label=LABEL.get(c["name"], c["name"]) + extra, **STYLE.get(c["name"], {}))
        edge = c.get("edge_exact_s")
        if edge and not c["compensated"]:
            ax.axvline(edge, color=STYLE.get(c["name"], {}).get("color", "k"), lw=0.8, alpha=0.5, ls="--")
    ax.axhline(s1["continuous_baseline_m"], color="k", ls="--", lw=1.2, label="continuous-time baseline")
    ax.set_xlabel("sampling time h (s)")
    ax.set_ylabel("worst-case tracking error (m), last target period")
    ax.set_title("(c) error vs h, k = 2 (each curve up to its exact stability edge, dashed verticals)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def plot_noise(d, path):
    s3 = d["study3"]
    fig, ax = plt.subplots(figsize=(8.6, 4.8))
    tfs = sorted({c["tf_s"] for c in s3["configs"] if c["filtered"]})
    shades = {tf: 0.35 + 0.65 * i / max(1, len(tfs) - 1) for i, tf in enumerate(tfs)}
    for c in s3["configs"]:
        pts = [(r["sigma_m"], r["rms_m"]) for r in c["table"] if r["rms_m"]]
        if not pts:
            continue
        s, e = zip(*pts)
        if not c["filtered"]:
            ax.loglog(s, e, "k-o", ms=4, label="k = 2, exact derivatives")
        else:
            cmap = plt.cm.Blues if c["k"] == 2 else plt.cm.Oranges
            ls = "-" if c["k"] == 2 else "--"
            ax.loglog(s, e, ls, marker="s" if c["k"] == 2 else "^", ms=4, color=cmap(shades[c["tf_s"]]),
                      label=f"k = {c['k']}, filtered, $T_f$ = {c['tf_s']:g} s")
    ax.set_xlabel(r"measurement-noise std $\sigma$ (m)")
    ax.set_ylabel("steady-state RMS tracking error (m)")
    ax.set_title(f"(d) RMS error vs noise, h = {s3['h_s']:g} s", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def plot_tf_search(d, path):
    t = d["study3"]["tf_search"]
    pts = [(g["tf_s"], g["rms_m"], g["u_dev_rms_mps2"]) for g in t["grid"] if g["rms_m"]]
    tf, rms, udev = zip(*pts)
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.loglog(tf, rms, "C0-o", ms=3, label="tracking RMS (m)")
    ax.set_xlabel(r"filter time constant $T_f$ (s)")
    ax.set_ylabel("RMS tracking error (m)", color="C0")
    ax2 = ax.twinx()
    ax2.loglog(tf, udev, "C3-s", ms=3, label=r"command noise RMS $|u - \ddot y_d|$")
    ax2.set_ylabel(r"RMS $|u - \ddot y_d|$ (m/s$^2$)", color="C3")
    if t.get("budget_tf_s"):
        ax.axvline(t["budget_tf_s"], color="k", ls="--", lw=1)
        ax2.axhline(t["u_budget_mps2"], color="C3", ls=":", lw=1)
    ax.set_title(f"T_f search: k = 2, sigma = {t['sigma_m']:g} m, h = {d['study3']['h_s']:g} s "
                 f"(dashed: best T_f with command noise <= {t['u_budget_mps2']:g} m/s^2)", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("json")
    p.add_argument("-o", "--out-dir", default=None)
    a = p.parse_args()
    with open(a.json) as f:
        d = json.load(f)
    out = a.out_dir or os.path.dirname(os.path.abspath(a.json))
    os.makedirs(out, exist_ok=True)
    written = []
    if "study1" in d:
        written.append(os.path.join(out, "study_error_vs_h.png"))
        plot_error_vs_h(d, written[-1])
    if "study3" in d:
        written.append(os.path.join(out, "study_noise.png"))
        plot_noise(d, written[-1])
        written.append(os.path.join(out, "study_tf_search.png"))
        plot_tf_search(d, written[-1])
    if not written:
        print("plot_study: the JSON has neither study1 nor study3", file=sys.stderr)
        return 1
    for w in written:
        print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
