// tvo_fault_campaign: the edge's fault campaign over LCM (issue 9). Its own plant (an exact unicycle
// tracking the default ellipse session) drives tvo_firmware_node, injects faults at known instants
// and checks every answer. One line per check; exit 0 only if every check passed.
//
//   tvo_fault_campaign --lcm-url URL [--node PATH] [--case NAME]... [--list]
//
// --node PATH spawns the node for each run (--exit-with-parent, --keep-running where a case needs
// it); without it the campaign talks to a node already running on URL, started with --keep-running
// (node-restart and the exit checks need --node).
#include <unistd.h>

#include <ctime>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cases.hpp"

namespace campaign {

const std::vector<Case>& all_cases()
{
    static const std::vector<Case> cases = {
        {"stray-future-stamp", "copies of genuine samples stamped +1 s and +20 s; NaN and robot 7 stamped +1 s",
         case_stray_future_stamp, false},
        {"stray-past-stamp", "copies stamped -1 s, one period back, before the epoch, 0, -1, INT64_MIN",
         case_stray_past_stamp, false},
        {"garbage", "valid fingerprints with random bodies on every channel, truncated, over-long, empty, a burst",
         case_garbage, false},
        {"huge-sequence", "sequence 2^30, INT32_MAX, -1, INT32_MIN with genuine stamps",
         case_huge_sequence, false},
        {"duplicates", "samples delivered twice, four times, and old ones again", case_duplicates, false},
        {"reordering", "two consecutive samples swapped, twice", case_reordering, false},
        {"loss", "0, 10, 30 and 50 % of the samples lost (seeded) for 5 s", case_loss, false},
        {"refusal-watchdog", "CLOCK_PLANT: watchdog_periods + 2 refusals in a row, then genuine samples again",
         case_refusal_watchdog, false},
        {"speed-mismatch", "the plant reports 0 m/s while moving for 50 periods (speed_valid set)",
         case_speed_mismatch, false},
        {"link-loss-node-clock", "CLOCK_NODE on the wall clock: 1 s without samples (h = 50 ms, watchdog 4)",
         case_link_loss_node_clock, false},
        {"rejected-start-during-run",
         "STARTs with new ids and a bad parameter (protocol, telemetry rate too), and a START and STOP naming "
         "another boot, while a session runs",
         case_rejected_start_during_run, false},
        {"same-id-start", "STARTs with the running id: other content, identical content", case_same_id_start, false},
        {"implausible-epoch", "epochs 20 min before and after START, 1 us beyond the limit, at the limit",
         case_implausible_epoch, false},
        {"node-restart", "the node killed (SIGKILL) mid-run and started again", case_node_restart, true},
        {"plant-restart", "a new session id mid-run (--keep-running); the old session's messages still arrive",
         case_plant_restart, false},
        {"auth-attacks",
         "keyed bus: forged START/STOP/measurement/target (unsigned, another key), replays, a flipped tag, "
         "truncated tags, a forged vote of three",
         case_auth_attacks, false},
        {"auth-node-restart",
         "keyed bus: the node restarted; the old boot's recording replayed to the new one at once and amid its session",
         case_auth_node_restart, true},
        {"clock-plant-limits", "NOTES only: strays CLOCK_PLANT cannot tell from genuine samples",
         case_clock_plant_limits, false},
    };
    return cases;
}

}  // namespace campaign

namespace {

int usage(const std::string& error)
{
    std::cerr << "tvo_fault_campaign: " << error
              << "\nusage: tvo_fault_campaign --lcm-url URL [--node PATH] [--case NAME]... [--list]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace campaign;
    std::string url;
    std::string node_path;
    std::vector<std::string> selected;
    bool list = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&](std::string* out) {
            if (i + 1 >= argc) {
                return false;
            }
            *out = argv[++i];
            return true;
        };
        std::string v;
        if (arg == "--lcm-url" && value(&v)) {
            url = v;
        } else if (arg == "--node" && value(&v)) {
            node_path = v == "none" ? "" : v;
        } else if (arg == "--case" && value(&v)) {
            selected.push_back(v);
        } else if (arg == "--list") {
            list = true;
        } else if (arg == "-h" || arg == "--help") {
            std::cout << "usage: tvo_fault_campaign --lcm-url URL [--node PATH] [--case NAME]... [--list]\n";
            return 0;
        } else {
            return usage("unknown or incomplete argument '" + arg + "'");
        }
    }
    if (list) {
        for (const Case& c : all_cases()) {
            std::cout << c.name << "  " << c.summary << "\n";
        }
        return 0;
    }
    if (url.empty()) {
        return usage("--lcm-url is required (use a port of your own: the campaign publishes faults on it)");
    }
    std::vector<const Case*> to_run;
    for (const std::string& name : selected) {
        const Case* found = nullptr;
        for (const Case& c : all_cases()) {
            found = c.name == name ? &c : found;
        }
        if (found == nullptr) {
            return usage("unknown case '" + name + "' (--list shows them)");
        }
        to_run.push_back(found);
    }
    if (to_run.empty()) {
        for (const Case& c : all_cases()) {
            to_run.push_back(&c);
        }
    }
    Report report;
    try {
        Bus bus(url);
        // A fresh session id per run (the plant rule; session_t.session_id is an int32 >= 0), so a node
        // left running by an earlier campaign never mistakes a run for a repeat of its session: the
        // clock's seconds and the process id, room for 1000 runs above.
        const auto first_id = static_cast<std::int32_t>(
            (static_cast<std::int64_t>(std::time(nullptr)) % 1000000 * 1000 + getpid() % 1000) % 2000000);
        for (const Case* c : to_run) {
            report.begin_case(c->name);
            CommandAudit audit;
            audit.omega_max_radps = demo_session(0, 0, 0, Timing{}).omega_max_radps;
            audit.speed_max_mps = demo_session(0, 0, 0, Timing{}).speed_max_mps;
            Context ctx{bus, report, audit, node_path, url, first_id * 1000, ""};  // < 2^31
            try {
                if (c->needs_spawn && node_path.empty()) {
                    report.check(false, "case needs --node PATH", "it kills and restarts the node");
                    continue;
                }
                c->run(ctx);
            } catch (const std::exception& e) {
                report.check(false, "case ran to its end", std::string("aborted: ") + e.what());
            }
            audit.report(report);
        }
    } catch (const std::exception& e) {
        std::cerr << "tvo_fault_campaign: " << e.what() << "\n";
        return 1;
    }
    std::cout << report.checks() - report.failures() << " checks passed, " << report.failures() << " failed"
              << std::endl;
    return report.failures() == 0 ? 0 : 1;
}
