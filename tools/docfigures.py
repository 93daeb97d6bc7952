#!/usr/bin/python3
"""The READMEs' figures and protocol tables, generated: never copied by hand.

  tools/docfigures.py                 rewrite every marked block from the committed inputs
  tools/docfigures.py --check         change nothing; exit 1 (with a diff) if a block is out of date,
                                      README.md is over 300 lines or links a file that does not exist
  tools/docfigures.py --bench PATH    take a new `tools/bench --json PATH` run (copied to
                                      tools/figures/bench.json), then rewrite
  tools/docfigures.py --runs          re-run the demo and scenario rows with build/host/tvo_sim
                                      (tools/demo or tools/build builds it), and the fleet's columns with
                                      tools/fleet --local, into tools/figures/summaries/, then rewrite
  tools/docfigures.py --snippet README.md -o FILE.c   write README.md's C snippet to FILE.c
  tools/docfigures.py --snippet R.md --name N -o F   the block marked <!-- snippet:N begin/end --> instead

A block is the text between `<!-- figures:NAME begin -->` and `<!-- figures:NAME end -->` in
README.md or a folder's README.md; NAME says what fills it (BLOCKS below). Inputs, all committed:
  tools/figures/bench.json        the `tools/bench --json` output the cost and footprint figures come from
  tools/figures/summaries/*.json  tvo_sim's summary.json of each demo and scenario row (RUNS below)
  tools/figures/study.json        a `tools/study --json tools/figures/study.json` run
  tools/figures/agree.json        a `tools/agree --os --fp-contract-fast --cost --accuracy --json
                                  tools/figures/agree.json` run (agreement across machines, accuracy)
  lcm_types/*.lcm                 the wire's constants (status codes, flags, parameter ids, parts)
  firmware/edge/channels.c        the session_t field each parameter id stands for
  firmware/edge/step_codec.c      which core reasons, edge statuses and core errors map to each status
"""
import argparse
import difflib
import json
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parent.parent
FIGURES = REPO / "tools/figures"
BENCH_JSON = FIGURES / "bench.json"
RUNS_DIR = FIGURES / "summaries"
STUDY_JSON = FIGURES / "study.json"
AGREE_JSON = FIGURES / "agree.json"
READMES = ["README.md", "firmware/README.md", "lcm_types/README.md", "host/README.md",
           "tests/README.md", "tools/README.md"]
MAX_TOP_LINES = 300
BLOCK = re.compile(r"(<!-- figures:([\w-]+) begin -->\n)(.*?)(<!-- figures:\2 end -->)", re.S)

PROBLEMS = [("unicycle", "unconstrained unicycle (the demo)"),
            ("obstacles4", "one unicycle, 4 obstacles"),
            ("formation2", "two unicycles, 1 ≤ ‖y1 − y2‖ ≤ 3"),
            ("chain_k3", "integrator chain, k = 3")]
SHORT = {"unicycle": "unicycle", "obstacles4": "4 obstacles", "formation2": "two-robot formation",
         "chain_k3": "chain k = 3"}
TARGETS = [("cortex-m4f", "Cortex-M4F"), ("cortex-m0plus", "Cortex-M0+"),
           ("cortex-m7", "Cortex-M7 (double)"), ("rv32imac", "RV32IMAC")]

# Each demo and scenario row: (file stem in tools/figures/summaries, tvo_sim arguments).
RUNS = {
    "demo": [],
    "demo-sigma": ["--sigma", "1e-3"],
    "demo-no-compensation": ["--no-compensation"],
    "demo-delay0": ["--delay-s", "0"],
    "demo-position-only": ["--position-only"],
    "demo-drop": ["--drop-prob", "0.05"],
    "demo-zoh-aware": ["--zoh-aware"],
}
SCENARIOS = ["formation-max", "formation-bilateral", "obstacles", "obstacles-infeasible-target",
             "infeasible-start", "formation-equality"]
for _name in SCENARIOS:
    RUNS[_name] = ["--scenario", _name]
    RUNS[_name + "-noisy"] = ["--scenario", _name, "--sigma", "1e-3", "--position-only"]
NOISY = "`--sigma 1e-3 --position-only`"
# The central node's run of the 4-robot fleet scenario, for the fleet's comparison.
RUNS["fleet-formation-central"] = ["--scenario", str(REPO / "host/scenarios/fleet-formation.yaml")]
# Each fleet column: (file stem in tools/figures/summaries, scenario, tools/fleet arguments); "KEY" is
# replaced by a key tools/keygen makes for the run. On loopback (--local): the figures are the same in
# network namespaces (tests/fleet runs both).
FLEET4 = "host/scenarios/fleet-formation.yaml"
FLEET8 = "host/scenarios/fleet/fleet-formation8.yaml"
FLEET_RUNS = [("fleet4", FLEET4, []), ("fleet4-loss", FLEET4, ["--loss", "0.1"]),
              ("fleet4-loss-until-8s", FLEET4, ["--loss", "0.1", "--loss-until-s", "8"]),
              ("fleet8", FLEET8, []), ("fleet8-loss", FLEET8, ["--loss", "0.1"]),
              ("fleet8-keyed", FLEET8, ["--key-file", "KEY"])]
# Keys of tools/fleet's JSON that say where and how fast it ran, not what the fleet did.
FLEET_UNKEPT = ("node_link_rx_packets_min", "scenario", "digest_mismatch_per_period")


def n(value):
    """An integer with thousands separators."""
    return f"{int(value):,}"


def g(value, digits=2):
    """A float in the READMEs' style: 1.3e-4, 0.0193."""
    if value is None:
        return "never"
    if value == 0:
        return "0"
    if 1e-2 <= abs(value) < 1e4:
        return f"{value:.{digits + 1}g}"
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


# ---- the bench (tools/bench --json) ------------------------------------------------------------

def cost_m4f(b):
    opt = b["instr_per_step_opt"]
    other = [o for o in b["instr_per_step_by_opt"] if o != opt]
    rows = [(label, n(b["instr_per_step"][p]["min"]), n(b["instr_per_step"][p]["median"]),
             n(b["instr_per_step"][p]["max"])) for p, label in PROBLEMS]
    text = table(["problem", "min", "median", "max"], rows)
    for o in other:
        medians = " / ".join(n(b["instr_per_step_by_opt"][o][p]["median"]) for p, _ in PROBLEMS)
        text += (f"\nCortex-M4F, float32, -{opt} (the level with the smaller total median), 400 steps each. "
                 f"At -{o} the medians are {medians}.\n")
    return text


def cost_m0plus(b):
    m0 = b["instr_per_step_cortex_m0plus"]
    m4 = b["instr_per_step"]
    rows = []
    for p, label in PROBLEMS:
        f = m0["problems"].get(p)
        if f is None:
            rows.append((label, "skipped", "", "", ""))
        else:
            rows.append((label, n(f["min"]), n(f["median"]), n(f["max"]),
                         f"{f['median'] / m4[p]['median']:.1f}×"))
    return (table(["problem", "min", "median", "max", "M0+/M4F (median)"], rows)
            + f"\n{m0['limits']} limits, -{m0['opt']}, {m0['float']}.\n")


def host_callgrind(b):
    h = b["host_callgrind_mean_instr_per_step"]
    return ("x86-64 under `valgrind --tool=callgrind`, mean instructions per step: "
            + ", ".join(f"{SHORT[p]} {n(h[p])}" for p, _ in PROBLEMS) + ".\n")


def ipopt(b):
    i = b["host_ipopt_comparison"]
    a = i["agreement"]
    return (table(["x86-64", "step", "Ipopt solve", "Ipopt / step"],
                  [("instructions per call (callgrind)", n(i["step_instr_per_call"]),
                    n(i["ipopt_instr_per_solve"]), f"{i['instr_ratio_ipopt_over_step']:,}×"),
                   (f"median ns ({i['ns_repetitions']} closed loops; machine and load dependent)",
                    n(i["step_median_ns"]), n(i["ipopt_median_ns"]), f"{i['ns_ratio_ipopt_over_step']:,}×")])
            + f"\n{i['problem']}, {i['periods']} periods, Ipopt warm-started each period "
              f"({i['ipopt_mean_iterations']:g} iterations on mean). Agreement check: from t = "
              f"{a['window_s'][0]:g} s to {a['window_s'][1]:g} s the robot and Ipopt's minimiser stay within "
              f"{a['max_distance_m'] * 1e3:.2g} mm (tolerance {a['tolerance_m'] * 1e3:g} mm).\n")


def core_text(b):
    t = b["core_text_bytes_by_opt"]
    return ("Text of the whole `libtvo_core.a` for Cortex-M4F (every function, before the link drops any): "
            + ", ".join(f"-{o} {n(v)} B" for o, v in t.items()) + ".\n")


def footprint(b):
    rows = []
    for key, label in TARGETS:
        f = b["footprint"][key]
        for limits, entry in (("default (4 robots)", f), ("one robot", f["single_robot"])):
            rows.append((label, limits, n(entry["flash_bytes"]), n(entry["ram_bytes"]), n(entry["stack_bytes"]),
                         n(entry["controller_instance_bytes"]), n(entry["problem_instance_bytes"]),
                         n(entry["tracking_firmware"]["flash_bytes"]), n(entry["tracking_firmware"]["stack_bytes"]),
                         n(entry["tracking_firmware_both_sources"]["flash_bytes"])))
    return table(["target", "limits", "flash (B)", "static RAM (B)", "step stack (B)", "controller (B)",
                  "problem (B)", "tracking firmware: flash (B)", "its step stack (B)",
                  "both sources: flash (B)"], rows)


def stack_written(b):
    s = b["step_stack_written_bytes"]
    bound = b["footprint"]["cortex-m4f"]
    rows = []
    for p in [p for p, _ in PROBLEMS] + ["hostile"]:
        limit = bound["chain_stack_bytes"] if p == "chain_k3" else bound["stack_bytes"]
        def cell(v):
            return "–" if v is None else n(v)
        rows.append((p, *(cell(s["cortex-m4f"][o].get(p)) for o in s["cortex-m4f"]),
                     cell(s["cortex-m0plus"]["O2"].get(p)), n(limit)))
    return table(["problem", *(f"M4F -{o}" for o in s["cortex-m4f"]), "M0+ -O2", "M4F -Os static bound"], rows)


def key_figures(b, runs):
    m4 = b["instr_per_step"]
    f = b["footprint"]["cortex-m4f"]
    one = f["single_robot"]
    demo = runs["demo"]
    medians = " / ".join(n(m4[p]["median"]) for p, _ in PROBLEMS)
    return table(["figure", "value"], [
        (f"control step on Cortex-M4F (float32, -{b['instr_per_step_opt']}), median instructions: "
         + " / ".join(SHORT[p] for p, _ in PROBLEMS), medians),
        ("one-robot tracking firmware on Cortex-M4F (-Os): flash, step stack",
         f"{n(one['tracking_firmware']['flash_bytes'])} B, {n(one['tracking_firmware']['stack_bytes'])} B"),
        ("the whole core on Cortex-M4F (-Os): flash for one robot / four",
         f"{n(one['flash_bytes'])} B / {n(f['flash_bytes'])} B"),
        ("static RAM of the core; your controller and problem instances (four robots)",
         f"{n(f['ram_bytes'])} B; {n(f['controller_instance_bytes'])} B and {n(f['problem_instance_bytes'])} B"),
        ("Ipopt's instructions per solve / the step's (obstacles problem, x86-64)",
         f"{b['host_ipopt_comparison']['instr_ratio_ipopt_over_step']:,}×"),
        ("the demo (one unicycle on an ellipse, h = 10 ms): final error, RMS over the last 5 s",
         f"{g(demo['final_error_m'])} m, {g(demo['rms_error_last5s_m'])} m"),
    ])


# ---- the demo and scenario runs (tools/figures/summaries/*.json) -------------------------------------

def demo_runs(runs):
    labels = [("demo", "(defaults)"),
              ("demo-sigma", "`--sigma 1e-3` (1 mm position, 1 mrad heading, 1 mm/s speed noise)"),
              ("demo-no-compensation", "`--no-compensation`"),
              ("demo-delay0", "`--delay-s 0`"),
              ("demo-position-only", "`--position-only` (dirty-derivative filter, T_f = 0.05 s)"),
              ("demo-drop", "`--drop-prob 0.05` (5 % of measurements lost)"),
              ("demo-zoh-aware", "`--zoh-aware`")]
    rows = [(label, g(runs[k]["final_error_m"]), g(runs[k]["rms_error_last5s_m"]), runs[k]["faults"],
             runs[k].get("drops", 0)) for k, label in labels]
    return table(["options", "final error (m)", "RMS error, last 5 s (m)", "faults", "measurements lost"], rows)


def scenario_rows(runs, names, columns):
    rows = []
    for name in names:
        for suffix, setting in (("", "defaults"), ("-noisy", NOISY)):
            s = runs[name + suffix]
            rows.append((f"{name}, {setting}", *(fmt(s) for _, fmt in columns)))
    return table(["run", *(h for h, _ in columns)], rows)


def fleet(runs):
    heads = ["4 robots, no loss", "10 % per link", "10 % until 8 s", "8 robots, no loss", "10 % per link",
             "8, keyed"]
    cols = [runs[stem] for stem, _, _ in FLEET_RUNS]
    central = runs["fleet-formation-central"]

    def row(label, fmt):
        return (label, *(fmt(c) for c in cols))
    rows = [
        row("final tracking error (m)", lambda c: g(c["final_error_m"], 4)),
        row("collisions, bound violation, limit violations",
            lambda c: f"{c['collisions']}, {g(c['max_violation_frac'])}, {c['limit_violations']}"),
        row("closest pair, sample instants (m)", lambda c: f"{c['min_pair_distance_sampled_m']:.4f}"),
        row("periods whose digests differ", lambda c: f"{n(c['digest_mismatch_periods'])} of {n(c['compared_periods'])}"),
        row("the last of them; longest run", lambda c: (f"{c['last_mismatch_period']}; {c['longest_disagreement_periods']}"
                                                          if c["digest_mismatch_periods"] else "none")),
        row("samples lost, rows lost, rows held, samples predicted",
            lambda c: f"{n(c['dropped_samples'])}, {n(c['dropped_commands'])}, {n(c['held_rows'])}, "
                      f"{n(c['predicted_samples'])}"),
        row("run's digest (`command_digest_run`)", lambda c: f"`{c['command_digest_run']}`"),
    ]
    return (table(["figure", *heads], rows)
            + f"\nThe central node (one `tvo_firmware_node`: `tvo_sim --scenario {FLEET4}`) ends the 4-robot "
              f"run at {g(central['final_error_m'], 4)} m. `tools/fleet FILE --local --json OUT` with the column's "
              f"options (`--loss 0.1`, `--loss-until-s 8`, `--key-file K`), {n(cols[0]['periods'])} and "
              f"{n(cols[3]['periods'])} periods; loss decided per link and period by a seeded hash (`--seed 1`); "
              f"the digests are the nodes' telemetry's `joint_digest`, every period.\n")


def formation(runs):
    return scenario_rows(runs, ["formation-max", "formation-bilateral"], [
        ("min distance while crossing (m)", lambda s: f"{s['min_distance_crossing_m']:.4f}"),
        ("final distance (m)", lambda s: f"{s['final_distance_m']:.4f}"),
        ("max violation", lambda s: g(s["max_violation_frac"])),
        ("final error (m)", lambda s: f"{s['final_error_m']:.3f}"),
        ("regularised solves", lambda s: s["regularized_steps"])])


def obstacles(runs):
    return scenario_rows(runs, ["obstacles", "obstacles-infeasible-target"], [
        ("collisions", lambda s: s["collisions"]),
        ("min clearance (m)", lambda s: g(s["min_clearance_m"], 3)),
        ("final error (m)", lambda s: g(s["final_error_m"])),
        ("RMS error, last 5 s (m)", lambda s: g(s["rms_error_last5s_m"]))])


def infeasible_start(runs):
    return scenario_rows(runs, ["infeasible-start"], [
        ("violation at the start", lambda s: f"{s['initial_violation_frac']:.2f}"),
        ("time to feasibility (s)", lambda s: g(s["time_to_feasible_s"])),
        ("max violation after", lambda s: g(s["max_violation_frac"])),
        ("min / final distance (m)", lambda s: f"{s['min_distance_m']:.3f} / {s['final_distance_m']:.3f}"),
        ("regularised solves", lambda s: s["regularized_steps"])])


def formation_equality(runs):
    return scenario_rows(runs, ["formation-equality"], [
        ("equality residual, t ≥ 5 s (m)", lambda s: g(s["equality_residual_m"])),
        ("final error (m)", lambda s: g(s["final_error_m"])),
        ("RMS error, last 5 s (m)", lambda s: g(s["rms_error_last5s_m"]))])


# ---- the wire's constants (lcm_types/*.lcm) -----------------------------------------------------

CONST = re.compile(r"^\s*const\s+int\w*\s+(\w+)\s*=\s*(0x[0-9a-fA-F]+|-?\d+)\s*;\s*(?://\s*(.*))?$")


def lcm_constants(message, prefix):
    rows = []
    for line in (REPO / "lcm_types" / f"{message}.lcm").read_text().splitlines():
        m = CONST.match(line)
        if m and m.group(1).startswith(prefix):
            rows.append((m.group(1), int(m.group(2), 0), m.group(2), (m.group(3) or "").strip()))
    if not rows:
        sys.exit(f"docfigures: no {prefix}* constants in lcm_types/{message}.lcm")
    return rows


def codec_sources():
    """The codec's tables (firmware/edge/step_codec.c): each wire status's C sources, in table order: the
    core's reasons (TVO_REASON_*), the edge's statuses (TVO_NODE_*) and the core's call errors (TVO_ERR_*)."""
    text = (REPO / "firmware/edge/step_codec.c").read_text()
    sources = {}
    for kind in ("TVO_REASON_", "TVO_NODE_", "TVO_ERR_"):
        for c_name, wire in re.findall(r"\[(" + kind + r"\w+)\] = WIRE\((\w+)\)", text):
            sources.setdefault("STATUS_" + wire, []).append(c_name)
    if not sources:
        sys.exit("docfigures: no WIRE(...) table rows in firmware/edge/step_codec.c")
    return sources


def status_codes(_b=None, _r=None):
    sources = codec_sources()
    return table(["code", "`command_header_t.`", "from (C, `step_codec.c`'s tables)", "meaning"],
                 [(v, f"`{name}`", ", ".join(f"`{c}`" for c in sources.get(name, [])) or "(none)",
                   why or "success: the command was computed from this measurement")
                  for name, v, _, why in lcm_constants("command_header_t", "STATUS_")])


def flags(_b=None, _r=None):
    outcome = {"FLAG_HOLDING": "`TVO_OUTCOME_HELD`", "FLAG_SAFE_STOP": "`TVO_OUTCOME_STOPPED`"}
    return table(["bit", "`command_header_t.`", "C (`tvo/status.h`)", "meaning"],
                 [(text, f"`{name}`", outcome.get(name, f"`TVO_{name}`"), why)
                  for name, _, text, why in lcm_constants("command_header_t", "FLAG_")])


def wire_param_names():
    """tvo_protocol_param_str's text per parameter (firmware/edge/channels.c)."""
    text = (REPO / "firmware/edge/channels.c").read_text()
    return dict(re.findall(r'case TVO_LCM_SESSION_ACK_T_(PARAM_\w+): return "([^"]*)";', text))


def params(_b=None, _r=None):
    fields = wire_param_names()
    return table(["`bad_param`", "`session_ack_t.`", "C (`session_codec.h`)", "`session_t` field(s) (`tvo_protocol_param_str`)"],
                 [(v, f"`{name}`", f"`TVO_SESSION_{name}`", fields.get(name, why))
                  for name, v, _, why in lcm_constants("session_ack_t", "PARAM_")])


def parts(_b=None, _r=None):
    return table(["`bad_part`", "`session_ack_t.`", "what"],
                 [(v, f"`{name}`", why or name[len("PART_"):].lower())
                  for name, v, _, why in lcm_constants("session_ack_t", "PART_")])


def session_constants(_b=None, _r=None):
    rows = []
    for prefix in ("ACTION_", "CLOCK_", "PLANT_", "VELOCITY_", "MAX_"):
        rows += [(f"`{name}`", v, why) for name, v, _, why in lcm_constants("session_t", prefix)]
    return table(["`session_t.`", "value", "meaning"], rows)


# ---- the sampled-data study (tools/study --json tools/figures/study.json) ------------------------

def study(s):
    def three(values, digits=3):
        return ", ".join(f"{v:.{digits}f}" for v in values) + " s"
    tau0 = {row["h_s"]: row["max_err_m"] for row in s["per_tau"][0]["table"]}
    zoh = {row["h_s"]: row["max_err_m"] for row in s["zoh_aware"][0]["table"]}
    tf = s["study3"]["tf_search"]
    rows = [
        ("order of the τ = 0 error, fit h = 1–20 ms", "`order_tau0`", f"{s['order_tau0']:.3f}", "O(h)"),
        ("τ = h/2 : τ = 0, τ = h : τ = 0 at h ≤ 20 ms", "`ratio_tau_half`, `ratio_tau_full`",
         f"{s['ratio_tau_half']:.3f}, {s['ratio_tau_full']:.3f}", "2.0, 3.0"),
        ("compensated τ = h/2 : τ = 0, τ = h : τ = 0", "`comp_ratio_tau_half`, `comp_ratio_tau_full`",
         f"{s['comp_ratio_tau_half']:.4f}, {s['comp_ratio_tau_full']:.4f}", ""),
        ("worst-case error at h = 10 ms, τ = 0; ZOH-aware", "`per_tau`, `zoh_aware` tables",
         f"{g(tau0[0.01])} m; {g(zoh[0.01])} m", ""),
        ("ZOH-aware order, fit h = 10–100 ms", "`zoh_aware_order`", f"{s['zoh_aware_order']:.3f}", ""),
        ("continuous-time baseline (RK4, 0.1 ms)", "`study1.continuous_baseline_m`",
         f"{g(s['study1']['continuous_baseline_m'])} m", ""),
        ("stability edge, exact (ρ = 1), τ = 0, h/2, h", "`edge_exact_s`", three(s["edge_exact_s"]),
         ", ".join(f"{v:g}" for v in s["paper_edge_s"]) + " s"),
        ("the same, 20 s run, \|e\| > 10 \|e(0)\|", "`edge_sim_s`", three(s["edge_sim_s"]), ""),
        ("the same, 20 s run, \|e\| > 10³ \|e(0)\|", "`edge_sim_threshold_1e3_s`",
         three(s["edge_sim_threshold_1e3_s"]), ""),
        ("the same, 200 s run, \|e\| > 10 \|e(0)\|", "`per_tau[].edge_sim_200s_s`",
         three([c["edge_sim_200s_s"] for c in s["per_tau"]]), ""),
        ("compensated edges, τ = 0, h/2, h", "`comp_edge_exact_s`", three(s["comp_edge_exact_s"]), ""),
        ("ZOH-aware edge (any τ, compensated)", "`zoh_aware[].edge_exact_s`",
         f"{s['zoh_aware'][-1]['edge_exact_s']:.3f} s", ""),
        ("bias floor at T_f = 0.05 s, k = 2 / k = 3", "`floor_k2_tf005`, `floor_k3_tf005`",
         f"{g(s['floor_k2_tf005'], 3)} / {g(s['floor_k3_tf005'], 3)} m", ""),
        ("floor ratio k = 3 : k = 2 (predicted)", "`floor_ratio_k3_k2_tf005`",
         f"{s['floor_ratio_k3_k2_tf005']:.3f} ({s['predicted_floor_ratio_k3_k2_tf005']:.3f})", "1.8"),
        (f"T_f minimising the RMS error at σ = {tf['sigma_m']:g} m, h = 1 ms", "`best_tf_s`, `best_rms_m`",
         f"{g(tf['best_tf_s'])} s{' (the search’s lower end)' if tf['best_at_lower_bound'] else ''}, "
         f"{g(tf['best_rms_m'])} m; command noise {tf['best_u_dev_rms_mps2']:.0f} m/s²", ""),
        (f"the same with command noise ≤ {tf['u_budget_mps2']:g} m/s²", "`budget_tf_s`, `budget_rms_m`",
         f"{g(tf['budget_tf_s'])} s, {g(tf['budget_rms_m'], 3)} m", ""),
    ]
    return table(["figure", "JSON key", "measured", "paper"], rows)


def scaling(b):
    s = b["instr_per_step_scaling"]
    text = ""
    for family, label in (("formation", "robots (a ring of distance bounds)"), ("obstacles", "obstacles (one robot)")):
        rows = [r for r in s["rows"] if r["family"] == family]
        lines = [["median instructions per step"] + [n(r["median"]) for r in rows]]
        if family == "formation":
            lines.append(["largest single step (the start)"] + [n(r["max"]) for r in rows])
        text += table([label] + [str(r["count"]) for r in rows], lines) + "\n"
    targets = ", ".join(f"{p} ≤ {n(t)}" for p, t in s["formation_target_instr"].items())
    verdict = "meets" if s["meets_targets"] else "misses"
    swarm = sorted(r["count"] for r in s["rows"] if r.get("limits") == "swarm")
    return text + (f"Cortex-M4F, float32, -{s['opt']}, 400 steps each; one build with `{s['limits']}` (up to 8 "
                   f"robots), one with `{s['swarm_limits']}` ({' and '.join(map(str, swarm))} robots). "
                   f"The formations {verdict} their targets ({targets}, each run's largest step at most "
                   f"{s['largest_over_median_target']:g}× its median).\n")


def auth(b):
    a = b["auth"]
    m4 = a.get("cortex-m4f", {})
    if "sign_instr" not in m4:
        return f"Not measured: {m4.get('skipped', 'no figures in the bench run')}.\n"
    per_period = list(m4["sign_instr"])
    others = list(m4["other_messages"])
    rows = [(f"`{name}`", n(m4["message_bytes"][name]), n(m4["sign_instr"][name]), n(m4["verify_instr"][name]),
             n(m4["mbedtls_chachapoly_instr"][name])) for name in per_period]
    rows += [(name, n(f["message_bytes"]), n(f["sign_instr"]), n(f["verify_instr"]),
              n(m4["mbedtls_chachapoly_instr"][name])) for name, f in m4["other_messages"].items()]
    verdict = "within" if m4["meets_target"] else "over"
    worst = max(max(m4["sign_instr"].values()), max(m4["verify_instr"].values()))
    parts = m4["mbedtls_fixed_parts_instr"]
    text = (table(["message (LCM-encoded)", "bytes", "sign", "verify", "Mbed TLS's chachapoly"], rows)
            + f"\nOn {m4['board']}; {m4['statistic']}, resolution {m4['resolution_instr']:g}. The messages of every "
              f"period ({', '.join(f'`{x}`' for x in per_period)}) are {verdict} the target of "
              f"{n(m4['target_instr'])} instructions each (the most: {n(worst)}); the others ({', '.join(others)}) "
              f"are not per period. The last column is Mbed TLS's chachapoly on the same message (starts, the AAD, "
              f"finish: the tag the bench checks ours against), of which an empty message's "
              f"{n(parts['tag_empty_message'])} go to its ChaCha20 key stream block "
              f"({n(parts['chacha20_key_stream_block'])}, a 64-byte block XORed into zeros), poly1305_starts "
              f"({n(parts['poly1305_starts'])}), the AAD, its padding, the lengths block and the tag "
              f"({n(parts['aad_padding_lengths_finish'])}); auth.c's tag of the same costs "
              f"{n(parts['tvo_auth_sign_empty_message'])}. Flash of the node's authentication code: "
              f"{n(m4['flash_bytes'])} B.\n")
    forged = m4.get("forged_frame_instr", {})
    host = a.get("host", {}).get("forged_frame_ns", {})
    if forged:
        text += ("\nWhat a forged frame costs the node, through its link, checks in the order of "
                 "[lcm_types/README.md](../lcm_types/README.md#an-authenticated-bus): "
                 + ", ".join(f"{k.replace('_', ' ')} {n(v)}" for k, v in forged.items())
                 + " instructions on the Cortex-M4F (median of 33)"
                 + (f"; on the host ({a['host']['machine']}), " + ", ".join(f"{n(v)} ns" for v in host.values())
                    + " (the fastest of 5 batches; LCM's own handling of each datagram comes on top)" if host else "")
                 + ".\n")
    period = b.get("keyed_period_instr", {})
    if "details" in period:
        d = period["details"]
        verdict = "within" if period["meets_target"] else "over"
        text += ("\n" + table(["keyed period", "mean", "median", "min", "max"],
                               [(f"`{name}`", n(x["mean"]), n(x["median"]), n(x["min"]), n(x["max"]))
                                for name, x in d.items()])
                 + f"\nOne keyed period through the real receive path (a signed sample in, the auth link, the node, "
                   f"the step, the command signed out, telemetry every {d['unicycle']['telemetry_every']} periods); "
                   f"{period['statistic']}. `unicycle`: one robot on the default build, {verdict} its target of "
                   f"{n(period['target_unicycle_instr'])}; `fleet8`: robot 7's node of an 8-robot formation "
                   f"(8 sample verifies, the joint step, its command) on the fleet build.\n")
    m0 = a.get("cortex-m0plus", {})
    if "sign_instr" in m0:
        rows = [(f"`{name}`", n(m0["sign_instr"][name]), n(m0["verify_instr"][name])) for name in m0["sign_instr"]]
        text += ("\n" + table(["message (ARMv6-M)", "sign", "verify"], rows)
                 + f"\nThe same code on {m0['board']} (resolution {m0['resolution_instr']:g}).\n")
    return text


# ---- agreement across machines and the core's own functions (tools/agree --json) -----------------

def agree(a):
    problems = list(next(iter(a["runs"].values()))["problems"])
    rows = []
    for name, r in a["runs"].items():
        cells = []
        for p in problems:
            c = r["problems"][p]
            cells.append("0" if c["periods_differ"] == 0 else
                         f"{c['periods_differ']} (from {c['first_period_differ']}; "
                         f"{g(c['max_abs_diff']['speed_mps'])} m/s, {g(c['max_abs_diff']['turn_rate_radps'])} rad/s)")
        same = all(r["functions_same_bits"].values())
        rows.append([name] + cells + ["the host's" if same else "other bits"])
    text = table(["machine, against x86-64"] + problems + ["functions' bits"], rows)
    boards = "; ".join(f"{name}: {r['board']}" for name, r in a["runs"].items() if "fp-contract" not in name)
    stacks = ", ".join(f"{name} {n(r['stack']['deepest_bytes'])} of {n(r['stack']['reserve_bytes'])} B"
                       for name, r in a["runs"].items() if r.get("stack"))
    text += (f"\nPeriods of {n(next(iter(a['runs'].values()))['problems'][problems[0]]['periods'])} whose speed or "
             f"turn-rate bits differ from the host's ({a['host']}), the first, the largest differences. {boards}; "
             f"{a['toolchain']}; limits `{a['limits']}`. Functions: {', '.join(a['host_functions'])} over "
             f"sweeps of {' / '.join(n(f['arguments']) for f in a['host_functions'].values())} arguments. "
             f"Deepest stack: {stacks}.\n")
    cost = a.get("cost_median_instr_per_step")
    if cost:
        names = list(cost)
        rows = [[p] + [n(cost[b][p]) for b in names] for p in cost[names[0]]]
        text += ("\n" + table(["median instructions per step (default limits)"] + names, rows))
    return text


def libm_accuracy(a):
    acc = a["accuracy"]
    rows = []
    for name, f in acc["functions"].items():
        rows.append([f"`{name}`", n(f["arguments"]), n(f["not_nearest"]), f"{f['max_ulp']:.3f}",
                     n(f["glibc_not_nearest"]), f"{f['glibc_max_ulp']:.3f}", n(f["differ_from_glibc"]),
                     n(f["undecided"])])
    text = table(["function", "arguments", "not the nearest float", "max error (ulp)", "glibc's: not the nearest",
                  "glibc's max error (ulp)", "results other than glibc's", "undecided"], rows)
    integer = acc["functions"].get("tvo_expf", {}).get("integer_path_differs")
    text += (f"\nReference: {acc['reference']}. Undecided: the exact value within 2^-60 of a midpoint, too near "
             f"for the reference. "
             + ("" if integer is None else
                f"`tvo_expf_integer` (the soft-float targets' whole `tvo_expf`) differs from `tvo_expf` for "
                f"{n(integer)} floats.") + "\n")
    return text


AGREE_BLOCKS = {"agree": agree, "libm-accuracy": libm_accuracy}

BENCH_BLOCKS = {"cost-m4f": cost_m4f, "cost-m0plus": cost_m0plus, "host-callgrind": host_callgrind,
                "ipopt": ipopt, "core-text": core_text, "footprint": footprint, "stack-written": stack_written,
                "scaling": scaling, "auth": auth}
RUN_BLOCKS = {"demo-runs": demo_runs, "formation": formation, "obstacles": obstacles, "fleet": fleet,
              "infeasible-start": infeasible_start, "formation-equality": formation_equality}
WIRE_BLOCKS = {"status-codes": status_codes, "flags": flags, "params": params, "parts": parts,
               "session-constants": session_constants}


def render(name, bench, runs):
    if name in BENCH_BLOCKS or name == "key":
        if bench is None:
            raise KeyError(str(BENCH_JSON.relative_to(REPO)))
    if name in BENCH_BLOCKS:
        return BENCH_BLOCKS[name](bench)
    if name in RUN_BLOCKS:
        return RUN_BLOCKS[name](runs)
    if name in WIRE_BLOCKS:
        return WIRE_BLOCKS[name]()
    if name == "key":
        return key_figures(bench, runs)
    if name == "study":
        return study(json.loads(STUDY_JSON.read_text()))
    if name in AGREE_BLOCKS:
        if not AGREE_JSON.exists():
            raise KeyError(str(AGREE_JSON.relative_to(REPO)))
        return AGREE_BLOCKS[name](json.loads(AGREE_JSON.read_text()))
    raise KeyError(name)


def load_inputs():
    bench = json.loads(BENCH_JSON.read_text()) if BENCH_JSON.exists() else None
    runs = {p.stem: json.loads(p.read_text()) for p in sorted(RUNS_DIR.glob("*.json"))}
    return bench, runs


def rewritten(text, bench, runs, where):
    def fill(m):
        try:
            body = render(m.group(2), bench, runs)
        except KeyError as e:
            sys.exit(f"docfigures: {where}: block '{m.group(2)}': no generator or no input for {e}")
        return m.group(1) + body + m.group(4)
    return BLOCK.sub(fill, text)


def anchors(path):
    """GitHub's anchors of a Markdown file's headings."""
    slugs = set()
    for heading in re.findall(r"^#+ (.*)$", path.read_text(), re.M):
        slug = re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")
        slugs.add(slug)
    return slugs


def structure_problems():
    """README.md's length, its links to the folders' READMEs, and every local link and anchor of them all."""
    problems = []
    top = (REPO / "README.md").read_text()
    lines = top.count("\n")
    if lines > MAX_TOP_LINES:
        problems.append(f"README.md has {lines} lines, more than {MAX_TOP_LINES}")
    for readme in READMES:
        path = REPO / readme
        if not path.exists():
            continue
        for target, anchor in re.findall(r"\]\(([^)#\s]*)(?:#([^)\s]+))?\)", path.read_text()):
            if "://" in target:
                continue
            linked = (path.parent / target).resolve() if target else path
            if not linked.exists():
                problems.append(f"{readme} links {target}, which does not exist")
            elif anchor and linked.suffix == ".md" and anchor not in anchors(linked):
                problems.append(f"{readme} links {target}#{anchor}: no such heading")
    for readme in READMES[1:]:
        if f"]({readme})" not in top:
            problems.append(f"README.md does not link {readme}")
    return problems


def snippet(readme, out, name="core"):
    """The code block between <!-- snippet:NAME begin --> and end (any language) into out."""
    text = pathlib.Path(readme).read_text()
    m = re.search(rf"<!-- snippet:{re.escape(name)} begin -->\n```\w+\n(.*?)```\n<!-- snippet:{re.escape(name)} end -->",
                  text, re.S)
    if not m:
        sys.exit(f"docfigures: {readme} has no code block between <!-- snippet:{name} begin --> and end")
    pathlib.Path(out).write_text(m.group(1))


def run_rows(sim, firmware):
    RUNS_DIR.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for stem, args in RUNS.items():
            out = pathlib.Path(tmp) / stem
            cmd = [sim, "--firmware", firmware, "--lcm-url", "udpm://239.255.76.67:7813?ttl=0",
                   "--out-dir", out, *args]
            print("docfigures: tvo_sim", " ".join(map(str, args)), file=sys.stderr)
            result = subprocess.run(cmd, text=True, capture_output=True)
            if result.returncode not in (0, 3):
                sys.exit(f"docfigures: {' '.join(map(str, cmd))} failed (exit {result.returncode}):\n"
                         + result.stdout + result.stderr)
            summary = json.loads((out / "summary.json").read_text())
            summary.pop("steps_per_s", None)  # wall clock: not a figure the READMEs give
            (RUNS_DIR / f"{stem}.json").write_text(json.dumps(summary, indent=2, sort_keys=True) + "\n")
        key = pathlib.Path(tmp) / "fleet.key"
        subprocess.run([REPO / "tools/keygen", key], check=True, capture_output=True)
        for stem, scenario, args in FLEET_RUNS:
            out = pathlib.Path(tmp) / stem
            cmd = [REPO / "tools/fleet", REPO / scenario, "--local", "--port", "7815", "--json", out.with_suffix(".json"),
                   "--out-dir", out, *[str(key) if a == "KEY" else a for a in args]]
            print("docfigures: tools/fleet", scenario, " ".join(args), file=sys.stderr)
            result = subprocess.run(cmd, text=True, capture_output=True)
            if result.returncode != 0:
                sys.exit(f"docfigures: {' '.join(map(str, cmd))} failed (exit {result.returncode}):\n"
                         + result.stdout + result.stderr)
            figures = json.loads(out.with_suffix(".json").read_text())
            for unkept in FLEET_UNKEPT:
                figures.pop(unkept, None)
            (RUNS_DIR / f"{stem}.json").write_text(json.dumps(figures, indent=2, sort_keys=True) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 if anything is out of date")
    parser.add_argument("--bench", help="a new tools/bench --json output to take (copied to tools/figures/bench.json)")
    parser.add_argument("--runs", action="store_true", help="re-run the demo and scenario rows (needs build/)")
    parser.add_argument("--snippet", metavar="README", help="write README's C snippet to -o FILE and exit")
    parser.add_argument("--name", default="core", help="which snippet of --snippet (default core)")
    parser.add_argument("-o", dest="out", help="output of --snippet")
    args = parser.parse_args()

    if args.snippet:
        if not args.out:
            sys.exit("docfigures: --snippet needs -o FILE")
        snippet(args.snippet, args.out, args.name)
        return 0
    if args.bench:
        shutil.copyfile(args.bench, BENCH_JSON)
    if args.runs:
        run_rows(REPO / "build/host/tvo_sim", REPO / "build/firmware/tvo_firmware_node")

    bench, runs = load_inputs()
    stale = []
    for rel in READMES:
        path = REPO / rel
        if not path.exists():
            stale.append(f"{rel} does not exist")
            continue
        text = path.read_text()
        new = rewritten(text, bench, runs, rel)
        if new == text:
            continue
        if args.check:
            diff = difflib.unified_diff(text.splitlines(True), new.splitlines(True), f"{rel} (committed)",
                                        f"{rel} (from tools/docfigures.py)")
            sys.stdout.writelines(diff)
            stale.append(f"{rel}: a figures block differs from what tools/docfigures.py makes of its inputs")
        else:
            path.write_text(new)
            print(f"docfigures: rewrote {rel}")
    stale += structure_problems()
    for problem in stale:
        print(f"docfigures: {problem}", file=sys.stderr)
    if stale:
        if args.check:
            print("docfigures: run tools/docfigures.py to regenerate the blocks", file=sys.stderr)
        return 1
    if args.check:
        print("docfigures: every figures block is up to date; README.md is "
              f"{(REPO / 'README.md').read_text().count(chr(10))} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
