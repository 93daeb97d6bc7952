"""python -m tvo export SCENARIO [--name NAME] [-o FILE] [tvo_sim options ...]

Writes the scenario (a built-in name or a .yaml file; `through` waypoints solved by the host's code)
as a C header a firmware compiles: NAME_problem_desc(), NAME_controller_config(), NAME_start[][3]
(tvo.export_c). Further options are tvo_sim's (--gains 30,11, --period-s 0.005, --robots 2, ...).
Exit codes: 0 written; 2 bad arguments or scenario (tvo_sim's file:line:col message).
"""
import argparse
import re
import sys

from . import export_c, load_scenario


def main(argv):
    parser = argparse.ArgumentParser(prog="python -m tvo", description=__doc__.split("\n\n")[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    export = sub.add_parser("export", help="a scenario as a C header")
    export.add_argument("scenario")
    export.add_argument("--name", help="prefix of the C names (default: the scenario's, as an identifier)")
    export.add_argument("-o", "--output", help="file to write (default: standard output)")
    args, sim_options = export.parse_known_args(argv[1:]) if argv[:1] == ["export"] else parser.parse_known_args(argv)
    try:
        scenario = load_scenario(args.scenario, *sim_options)
    except ValueError as e:
        print(f"tvo export: {e}", file=sys.stderr)
        return 2
    name = args.name or re.sub(r"\W|^(?=\d)", "_", scenario.name)
    text = export_c(scenario, name)
    if args.output:
        with open(args.output, "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
