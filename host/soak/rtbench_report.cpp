// tvo_rtbench_report: the figures of one tools/rtbench run (tvo_sim --realtime against
// tvo_firmware_node, lcm-logger recording the same LCM URL) from its two LCM logs:
//   --sim-log     tvo_sim's run.lcmlog: every message it published (logged when sent) and every one
//                 it received;
//   --logger-log  lcm-logger's file: what an independent subscriber recorded (the protocol's
//                 channels are counted; others, e.g. LCM's own LCM_SELF_TEST, separately).
// Writes one JSON object (--json) and prints it as a table.
//
// log_events_expected: what the two processes published. The simulator's own sends come from its
// log (SESSION, SAMPLE, TARGET: logged as they are published). The node's come from its own counters
// in its newest announcement (node_status_t; the node was started for the run): every sample of the
// session it handled (accepted or refused) is answered by one command per robot and, the run asking
// telemetry every period (tools/rtbench passes --telemetry-every 1), one telemetry per robot; on top,
// the safe stops its timer published (one command per robot, sequence -1, no telemetry), its session
// acks and its announcements, as seen by whichever receiver saw more of them (the node keeps no count
// of those; the simulator's log takes at most one announcement a second).
//
// Jitter of the node's answers: lcm-logger stamps each event with the time it received it. Sample n
// is due at the nominal sample instant epoch + (n + 1) h - tau (plant clock; epoch, h and tau from the
// simulator's START), so stamp - nominal = clock offset + lateness, with one constant clock offset
// (the logger's clock minus the plant's). The constant is removed by taking the lateness relative to
// the run's earliest answer: jitter_n = latency_n - min_m latency_m, i.e. how much later than its best
// case each answer reached an independent subscriber (the simulator waking late to sample, LCM's
// transit both ways and the node waking late, together).
#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>

#include "tvo_lcm/node_status_t.hpp"
#include "tvo_lcm/session_ack_t.hpp"
#include "tvo_lcm/session_t.hpp"
#include "tvo_lcm/telemetry_t.hpp"
#include "tvo_lcm/unicycle_command_t.hpp"

extern "C" {
#include "channels.h"
#include "tvo/status.h"
}

#include "command_line.hpp"

namespace {

constexpr const char* kProgram = "tvo_rtbench_report";

struct Options {
    std::string sim_log;
    std::string logger_log;
    std::string json_path;
};

/// Per channel, the events of one log; and what the protocol messages in it say.
struct LogContents {
    std::map<std::string, std::uint64_t> events;
    std::uint64_t total{0};                          // on every channel
    std::uint64_t undecodable{0};
    std::optional<tvo_lcm::session_t> start;        // the first START in the log
    std::uint64_t timer_safe_stops{0};               // of the START's session
    std::uint64_t acks{0};
    std::uint64_t announcements{0};                  // of the START's node
    std::optional<tvo_lcm::node_status_t> newest_status;  // of the START's node, by its clock
    std::vector<std::pair<std::int64_t, std::int32_t>> answers;  // (receive stamp, sequence) of the session's
};

template <class Msg>
bool decode(const lcm::LogEvent& event, Msg* msg)
{
    return msg->decode(event.data, 0, event.datalen) >= 0;
}

/// Reads a log; the START (and so the session id) comes from `start` if given, else from this log.
LogContents read_log(const std::string& path, const std::optional<tvo_lcm::session_t>& start)
{
    lcm::LogFile log(path, "r");
    if (!log.good()) {
        throw std::runtime_error("cannot read the LCM log " + path);
    }
    LogContents out;
    out.start = start;
    std::vector<tvo_lcm::unicycle_command_t> commands;
    std::vector<std::int64_t> command_stamps;
    std::vector<tvo_lcm::node_status_t> statuses;
    for (const lcm::LogEvent* event = log.readNextEvent(); event != nullptr; event = log.readNextEvent()) {
        ++out.total;
        ++out.events[event->channel];
        bool ok = true;
        if (event->channel == TVO_CHANNEL_SESSION && !out.start) {
            tvo_lcm::session_t session;
            ok = decode(*event, &session);
            if (ok && session.action == tvo_lcm::session_t::ACTION_START) {
                out.start = session;
            }
        } else if (event->channel == TVO_CHANNEL_SESSION_ACK) {
            tvo_lcm::session_ack_t ack;
            ok = decode(*event, &ack);
            out.acks += ok ? 1u : 0u;
        } else if (event->channel == TVO_CHANNEL_COMMAND) {
            tvo_lcm::unicycle_command_t command;
            ok = decode(*event, &command);
            if (ok) {
                commands.push_back(command);
                command_stamps.push_back(event->timestamp);
            }
        } else if (event->channel == TVO_CHANNEL_TELEMETRY) {
            tvo_lcm::telemetry_t telemetry;
            ok = decode(*event, &telemetry);
        } else if (event->channel == TVO_CHANNEL_NODE) {
            tvo_lcm::node_status_t status;
            ok = decode(*event, &status);
            if (ok) {
                statuses.push_back(status);
            }
        }
        out.undecodable += ok ? 0u : 1u;
    }
    if (!out.start) {
        return out;
    }
    const std::int32_t id = out.start->session_id;
    for (std::size_t i = 0; i < commands.size(); ++i) {
        const tvo_lcm::command_header_t& c = commands[i].header;
        if (c.session_id != id) {
            continue;
        }
        if (c.measurement_sequence < 0 && (c.flags & static_cast<std::int32_t>(tvo_lcm::command_header_t::FLAG_SAFE_STOP)) != 0) {
            ++out.timer_safe_stops;
        } else if (c.measurement_sequence >= 0) {
            out.answers.emplace_back(command_stamps[i], c.measurement_sequence);
        }
    }
    const std::int64_t boot = out.start->node_boot_id[0];
    for (const tvo_lcm::node_status_t& s : statuses) {
        if (s.boot_id != boot) {
            continue;
        }
        ++out.announcements;
        if (!out.newest_status || s.utime >= out.newest_status->utime) {
            out.newest_status = s;
        }
    }
    return out;
}

std::uint64_t answered_measurements(const tvo_lcm::node_counters_t& c)
{
    std::int64_t n = std::max<std::int32_t>(c.accepted, 0);
    for (const std::int32_t refused : c.refused) {
        n += std::max<std::int32_t>(refused, 0);
    }
    return static_cast<std::uint64_t>(n);
}

/// The q-quantile (0..1) of values by nearest rank; values is reordered.
double quantile(std::vector<double>& values, double q)
{
    const auto rank = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
    return values[rank];
}

nlohmann::ordered_json report(const LogContents& sim, const LogContents& logger)
{
    nlohmann::ordered_json j;
    const tvo_lcm::session_t& start = *sim.start;
    const auto robots = static_cast<std::uint64_t>(std::max<std::int32_t>(start.robot_count, 1));
    // The simulator's own publications (logged as sent).
    std::uint64_t sim_sent = 0;
    for (const char* channel : {TVO_CHANNEL_SESSION, TVO_CHANNEL_SAMPLE, TVO_CHANNEL_TARGET}) {
        const auto it = sim.events.find(channel);
        sim_sent += it != sim.events.end() ? it->second : 0u;
    }
    // The node's: answers from its counters, timer safe stops, acks and announcements as seen by either
    // receiver.
    const std::optional<tvo_lcm::node_status_t>& newest =
        (logger.newest_status && (!sim.newest_status || logger.newest_status->utime >= sim.newest_status->utime))
            ? logger.newest_status
            : sim.newest_status;
    const std::uint64_t answers = newest ? answered_measurements(newest->counters) : 0u;
    const std::uint64_t timer_safe_stops = std::max(sim.timer_safe_stops, logger.timer_safe_stops);
    const std::uint64_t acks = std::max(sim.acks, logger.acks);
    const std::uint64_t announcements = std::max(sim.announcements, logger.announcements);
    const std::uint64_t node_sent = 2u * answers * robots + timer_safe_stops + acks + announcements;

    std::vector<double> latency_us;
    latency_us.reserve(logger.answers.size());
    for (const auto& [stamp, sequence] : logger.answers) {
        const std::int64_t nominal_sample = start.epoch_utime + (sequence + 1) * start.period_us - start.delay_us;
        latency_us.push_back(static_cast<double>(stamp - nominal_sample));
    }
    // Only the protocol's channels: each LCM instance also publishes LCM_SELF_TEST once when it starts.
    std::uint64_t recorded = 0;
    for (const char* channel : {TVO_CHANNEL_SESSION, TVO_CHANNEL_SESSION_ACK, TVO_CHANNEL_SAMPLE, TVO_CHANNEL_TARGET,
                                TVO_CHANNEL_COMMAND, TVO_CHANNEL_TELEMETRY, TVO_CHANNEL_NODE}) {
        const auto it = logger.events.find(channel);
        recorded += it != logger.events.end() ? it->second : 0u;
    }
    j["log_events_expected"] = sim_sent + node_sent;
    j["log_events_recorded"] = recorded;
    j["log_events_other_channels"] = logger.total - recorded;
    j["log_events_simulator_sent"] = sim_sent;
    j["log_events_node_sent"] = node_sent;
    j["node_answered_measurements"] = answers;
    j["node_timer_safe_stops"] = timer_safe_stops;
    j["node_acks"] = acks;
    j["node_announcements"] = announcements;
    j["log_events_simulator_log"] = sim.total;
    nlohmann::ordered_json by_channel;
    for (const auto& [channel, count] : logger.events) {
        by_channel[channel] = count;
    }
    j["log_events_recorded_by_channel"] = by_channel;
    j["log_undecodable"] = logger.undecodable + sim.undecodable;
    j["jitter_samples"] = latency_us.size();
    if (!latency_us.empty()) {
        const double floor_us = *std::min_element(latency_us.begin(), latency_us.end());
        for (double& v : latency_us) {
            v -= floor_us;
        }
        j["jitter_p50_us"] = quantile(latency_us, 0.50);
        j["jitter_p99_us"] = quantile(latency_us, 0.99);
        j["jitter_max_us"] = *std::max_element(latency_us.begin(), latency_us.end());
    }
    j["period_us"] = start.period_us;
    j["delay_us"] = start.delay_us;
    return j;
}

}  // namespace

int main(int argc, char** argv)
{
    Options o;
    CLI::App app{"Figures of a tools/rtbench run from tvo_sim's LCM log and lcm-logger's file.", "tvo_rtbench_report"};
    app.add_option("--sim-log", o.sim_log, "tvo_sim's run.lcmlog")->required();
    app.add_option("--logger-log", o.logger_log, "lcm-logger's file of the same run")->required();
    app.add_option("--json", o.json_path, "write the figures to this JSON file");
    const int parsed = tvo_options::parse_command_line(app, argc, argv, kProgram);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    return tvo_options::run_reporting_errors(kProgram, [&o] {
        const LogContents sim = read_log(o.sim_log, std::nullopt);
        if (!sim.start) {
            std::cerr << kProgram << ": error: no session START in " << o.sim_log << '\n';
            return 1;
        }
        const LogContents logger = read_log(o.logger_log, sim.start);
        const nlohmann::ordered_json j = report(sim, logger);
        for (const auto& [key, value] : j.items()) {
            std::cout << "  " << std::left << std::setw(34) << key << value.dump() << '\n';
        }
        if (!o.json_path.empty()) {
            std::ofstream file(o.json_path);
            file << j.dump(2) << '\n';
            if (!file.flush()) {
                std::cerr << kProgram << ": error: writing " << o.json_path << " failed\n";
                return 1;
            }
        }
        return 0;
    });
}
