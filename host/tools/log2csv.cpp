// tvo_log2csv: an LCM event log (.lcmlog; tvo_sim's run.lcmlog, or lcm-logger's from a real robot) as
// the run CSV that tools/plot_run.py reads, written by the simulator's own RunRecorder (one header).
//
// One row per robot per period of the session (each robot's unicycle_sample_t of that sequence), in
// sequence order, then robot order:
//   t_s        the sample's time from the session's epoch (session_t.epoch_utime of its START)
//   pose       as measured (heading nan when the sample carries none)
//   target     the session's target at t_s (on-board path from its START, or the robot's streamed
//              sample of the same sequence); with formation offsets the constrained minimiser, as tvo_sim
//   command    the robot's command answering this period (same session, sequence and robot); a sample
//              the node did not answer keeps the robot's previous command (what the plant holds) and is
//              counted
//   telemetry  the robot's telemetry of the step that answered it, else its previous one (a node sends
//              telemetry every session_t.telemetry_every-th period)
// Messages that do not decode, duplicates and other sessions are counted and reported, not fatal.
// A keyed bus's recording (lcm-logger's; its frames end in a 28-byte authentication trailer) converts
// as it is, the trailers ignored and unchecked (reported); with --key-file only the frames that open
// are read, the others counted (forged or altered: unauthenticated; a used counter: replayed).
//
// Exit codes: 0 done; 1 the output cannot be written or the session has no sample;
// 2 bad command line, or a log that is missing, unreadable or holds no LCM event.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>

#include "auth_key_file.h"
#include "command_line.hpp"
#include "lcm_messages.hpp"
#include "run_recorder.hpp"
#include "scenario.hpp"
#include "summary.hpp"

namespace {

using tvo_host::kMaxRobots;

constexpr double kSPerUs = 1e-6;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A period waits this many later periods for its commands and telemetry before its rows are
// written: answers arrive within a period or two; the window keeps memory bounded on day-long logs.
constexpr std::int64_t kAnswerWindow = 256;

constexpr const char* kProgram = "log2csv";

int usage_error(const std::string& what)
{
    std::cerr << kProgram << ": error: " << what << '\n';
    return tvo_options::kBadCommandLine;
}

/// What the first pass learns about one session.
struct SessionInfo {
    std::uint64_t samples{0};                 // unicycle_sample_t messages, every robot's
    std::int32_t top_robot{-1};               // the largest robot index sampled
    std::optional<tvo_lcm::session_t> start;  // its first START
};

struct Counts {
    std::map<std::string, std::uint64_t> undecodable;     // by channel
    std::map<std::string, std::uint64_t> other_channels;  // not the protocol's
    std::uint64_t events{0};
    std::uint64_t other_session{0};
    std::uint64_t bad_robot{0};       // samples and answers naming no robot of the session
    std::uint64_t duplicates{0};
    std::uint64_t missing_samples{0}; // robots without a sample in a period another robot's sample has
    std::uint64_t unanswered{0};
    std::uint64_t late_answers{0};  // answers to rows already written
    std::uint64_t safe_stops{0};
    std::uint64_t rows{0};
    std::uint64_t unchecked_trailers{0};  // without --key-file: frames one trailer longer than their message
    std::uint64_t unauthenticated{0};     // with --key-file: frames whose tag did not verify (dropped)
    std::uint64_t replayed{0};            // with --key-file: frames with a counter already used (dropped)
};

/// A log's events, in order. With a key, only the frames that open (auth.h: tag, then the counter
/// per sender, from a fresh receiver each pass), their trailers stripped; the others counted once.
class EventReader {
public:
    EventReader(const std::string& path, const tvo_auth_t* key, Counts* counts) : log_(path, "r"), counts_(counts)
    {
        if (key != nullptr) {
            auth_ = *key;
        }
    }
    ~EventReader() { tvo_auth_clear(&auth_); }
    EventReader(const EventReader&) = delete;
    EventReader& operator=(const EventReader&) = delete;

    bool good() const { return log_.good(); }

    const lcm::LogEvent* next()
    {
        for (const lcm::LogEvent* event = log_.readNextEvent(); event != nullptr; event = log_.readNextEvent()) {
            if (auth_.keyed == 0u || tvo_node_channel_of(event->channel.c_str()) == 0) {
                return event;   // unkeyed; or another channel, which is not ours to check
            }
            std::size_t length = 0;
            const tvo_auth_status_t status =
                tvo_auth_open(&auth_, event->channel.c_str(), static_cast<const std::uint8_t*>(event->data),
                              static_cast<std::size_t>(std::max<std::int32_t>(event->datalen, 0)), &length);
            if (status == TVO_AUTH_OK) {
                event_ = *event;
                event_.datalen = static_cast<std::int32_t>(length);
                return &event_;
            }
            if (counts_ != nullptr) {
                ++(status == TVO_AUTH_ERR_REPLAY ? counts_->replayed : counts_->unauthenticated);
            }
        }
        return nullptr;
    }

private:
    lcm::LogFile log_;
    Counts* counts_;
    tvo_auth_t auth_{};
    lcm::LogEvent event_{};
};

// LCM's decoders read the message and leave what follows (an unchecked authentication trailer).
template <class Msg>
bool decode(const lcm::LogEvent& event, Msg* msg)
{
    return msg->decode(event.data, 0, event.datalen) >= 0;
}

/// A wire path_t as the host's TargetPath (the inverse of session.cpp's wire_path).
tvo_host::TargetPath host_path(const tvo_lcm::path_t& wire)
{
    if (wire.kind == tvo_lcm::path_t::KIND_POLYNOMIAL) {
        tvo_host::PolyCoeffs coeff{};
        for (std::size_t axis = 0; axis < 2; ++axis) {
            for (std::size_t j = 0; j < tvo_host::kPolyCoeffs; ++j) {
                coeff[axis][j] = wire.coeff[axis][j];
            }
        }
        return tvo_host::TargetPath::polynomial(coeff);
    }
    if (wire.kind == tvo_lcm::path_t::KIND_CIRCLE) {
        return tvo_host::TargetPath::circle({wire.center_m[0], wire.center_m[1]}, wire.semi_axis_m[0],
                                            wire.omega_radps, wire.phase_rad);
    }
    tvo_host::EllipseTarget e;
    e.center_m = {wire.center_m[0], wire.center_m[1]};
    e.semi_axis_m = {wire.semi_axis_m[0], wire.semi_axis_m[1]};
    e.omega_radps = wire.omega_radps;
    e.phase_rad = wire.phase_rad;
    e.rotation_rad = wire.rotation_rad;
    return tvo_host::TargetPath::ellipse(e);
}

std::size_t clamp_count(std::int32_t count, std::size_t capacity)
{
    return count < 0 ? 0 : std::min(static_cast<std::size_t>(count), capacity);
}

bool has_robots(const tvo_host::Scenario& sc, std::int32_t a, std::int32_t b)
{
    const auto valid = [&sc](std::int32_t r) { return r >= 0 && static_cast<std::size_t>(r) < sc.robot_count; };
    return valid(a) && valid(b) && a != b;
}

/// The problem a START describes, as a Scenario: what the references and the plot's geometry need.
/// Entries naming a robot the session does not have are left out (the node refuses such a START).
tvo_host::Scenario scenario_of(const tvo_lcm::session_t& s)
{
    tvo_host::Scenario sc;
    sc.name = "session " + std::to_string(s.session_id);
    sc.robot_count = std::max<std::size_t>(1, clamp_count(s.robot_count, kMaxRobots));
    for (std::size_t r = 0; r < sc.robot_count; ++r) {
        const tvo_lcm::robot_t& robot = s.robot[r];
        sc.streamed = sc.streamed || robot.target.kind == tvo_lcm::path_t::KIND_STREAMED;
        if (robot.target.kind != tvo_lcm::path_t::KIND_STREAMED) {
            sc.targets[r] = host_path(robot.target);
        }
        sc.weights[r] = {robot.tracking_weight[0], robot.tracking_weight[1]};
    }
    for (std::size_t i = 0; i < clamp_count(s.distance_count, tvo_lcm::session_t::MAX_DISTANCE_BOUNDS); ++i) {
        const tvo_lcm::distance_bound_t& w = s.distance[i];
        if (!has_robots(sc, w.robot_a, w.robot_b)) {
            continue;
        }
        sc.distances.push_back({static_cast<std::size_t>(w.robot_a), static_cast<std::size_t>(w.robot_b), w.min_m,
                                w.min_rate_mps, w.max_m, w.max_rate_mps});
    }
    sc.robot_radius_m = s.robot_radius_m;
    for (std::size_t i = 0; i < clamp_count(s.obstacle_count, tvo_lcm::session_t::MAX_OBSTACLES); ++i) {
        sc.obstacles.push_back({{s.obstacle[i].center_m[0], s.obstacle[i].center_m[1]}, s.obstacle[i].radius_m});
    }
    for (std::size_t i = 0; i < clamp_count(s.offset_count, tvo_lcm::session_t::MAX_OFFSETS); ++i) {
        const tvo_lcm::offset_t& w = s.offset[i];
        if (!has_robots(sc, w.robot_a, w.robot_b)) {
            continue;
        }
        tvo_host::OffsetEquality offset;
        offset.robot_a = static_cast<std::size_t>(w.robot_a);
        offset.robot_b = static_cast<std::size_t>(w.robot_b);
        offset.offset = host_path(w.offset);
        sc.offsets.push_back(offset);
    }
    return sc;
}

/// True if the event decodes as the message type of its protocol channel.
bool decodes(int channel, const lcm::LogEvent& event)
{
    switch (channel) {
    case TVO_NODE_CH_SESSION_ACK: { tvo_lcm::session_ack_t m{}; return decode(event, &m); }
    case TVO_NODE_CH_TARGET: { tvo_lcm::target_t m{}; return decode(event, &m); }
    case TVO_NODE_CH_COMMAND: { tvo_lcm::unicycle_command_t m{}; return decode(event, &m); }
    case TVO_NODE_CH_TELEMETRY: { tvo_lcm::telemetry_t m{}; return decode(event, &m); }
    case TVO_NODE_CH_NODE: { tvo_lcm::node_status_t m{}; return decode(event, &m); }
    case TVO_NODE_CH_CHAIN_SAMPLE: { tvo_lcm::chain_sample_t m{}; return decode(event, &m); }
    case TVO_NODE_CH_CHAIN_COMMAND: { tvo_lcm::chain_command_t m{}; return decode(event, &m); }
    default: return true;  // samples and sessions: decoded by the caller
    }
}

/// The encoded size of the fixed-size message of a protocol channel (0 for another channel).
int encoded_size(int channel)
{
    switch (channel) {
    case TVO_NODE_CH_SESSION: return tvo_lcm::session_t{}.getEncodedSize();
    case TVO_NODE_CH_SAMPLE: return tvo_lcm::unicycle_sample_t{}.getEncodedSize();
    case TVO_NODE_CH_TARGET: return tvo_lcm::target_t{}.getEncodedSize();
    case TVO_NODE_CH_SESSION_ACK: return tvo_lcm::session_ack_t{}.getEncodedSize();
    case TVO_NODE_CH_COMMAND: return tvo_lcm::unicycle_command_t{}.getEncodedSize();
    case TVO_NODE_CH_TELEMETRY: return tvo_lcm::telemetry_t{}.getEncodedSize();
    case TVO_NODE_CH_NODE: return tvo_lcm::node_status_t{}.getEncodedSize();
    case TVO_NODE_CH_CHAIN_SAMPLE: return tvo_lcm::chain_sample_t{}.getEncodedSize();
    case TVO_NODE_CH_CHAIN_COMMAND: return tvo_lcm::chain_command_t{}.getEncodedSize();
    default: return 0;
    }
}

/// First pass: the sessions in the log (by their samples and STARTs) and what does not decode.
std::map<std::int32_t, SessionInfo> scan_sessions(EventReader& log, Counts* counts)
{
    std::map<std::int32_t, SessionInfo> sessions;
    for (const lcm::LogEvent* event = log.next(); event != nullptr; event = log.next()) {
        ++counts->events;
        const int channel = tvo_node_channel_of(event->channel.c_str());
        if (channel != 0 && event->datalen == encoded_size(channel) + static_cast<int>(TVO_AUTH_TRAILER_BYTES)) {
            ++counts->unchecked_trailers;   // LCM's decoders read the message and leave the trailer
        }
        bool ok = decodes(channel, *event);
        if (channel == TVO_NODE_CH_SAMPLE) {
            tvo_lcm::unicycle_sample_t m{};
            ok = decode(*event, &m);
            if (ok) {
                SessionInfo& info = sessions[m.header.session_id];
                ++info.samples;
                info.top_robot = std::max<std::int32_t>(info.top_robot, m.header.robot);
            }
        } else if (channel == TVO_NODE_CH_SESSION) {
            tvo_lcm::session_t s{};
            ok = decode(*event, &s);
            if (ok && s.action == tvo_lcm::session_t::ACTION_START && !sessions[s.session_id].start) {
                sessions[s.session_id].start = s;
            }
        } else if (channel == 0) {
            ++counts->other_channels[event->channel];
        }
        if (!ok) {
            ++counts->undecodable[event->channel];
        }
    }
    return sessions;
}

/// One period waiting for its answers: per robot its sample, command, telemetry and streamed target.
struct PendingPeriod {
    std::array<std::optional<tvo_lcm::unicycle_sample_t>, kMaxRobots> sample;
    std::array<std::optional<tvo_lcm::unicycle_command_t>, kMaxRobots> command;
    std::array<std::optional<tvo_host::StepTelemetry>, kMaxRobots> telemetry;
    std::array<std::optional<tvo_lcm::target_t>, kMaxRobots> target;
};

/// Second pass: the rows of one session, written through RunRecorder.
class Converter {
public:
    Converter(std::int32_t session_id, const SessionInfo& info, tvo_host::RunRecorder& out, Counts& counts)
        : session_id_(session_id), start_(info.start), out_(out), counts_(counts)
    {
        if (start_) {
            scenario_ = scenario_of(*start_);
            epoch_utime_ = start_->epoch_utime;
            robots_ = scenario_.robot_count;
        } else {
            robots_ = static_cast<std::size_t>(std::clamp<std::int32_t>(info.top_robot + 1, 1,
                                                                        static_cast<std::int32_t>(kMaxRobots)));
        }
    }

    void on_event(const lcm::LogEvent& event)
    {
        switch (tvo_node_channel_of(event.channel.c_str())) {
        case TVO_NODE_CH_SAMPLE: {
            tvo_lcm::unicycle_sample_t m{};
            if (decode(event, &m) && m.header.session_id == session_id_) {
                on_sample(m);
            }
            break;
        }
        case TVO_NODE_CH_COMMAND: on_answer<tvo_lcm::unicycle_command_t>(event); break;
        case TVO_NODE_CH_TELEMETRY: on_answer<tvo_lcm::telemetry_t>(event); break;
        case TVO_NODE_CH_TARGET: {
            tvo_lcm::target_t t{};
            if (decode(event, &t) && t.header.session_id == session_id_ && robot_of(t.header.robot)) {
                pending_target_[t.header.sequence][static_cast<std::size_t>(t.header.robot)] = t;
                while (pending_target_.size() > static_cast<std::size_t>(kAnswerWindow)) {
                    pending_target_.erase(pending_target_.begin());
                }
            }
            break;
        }
        default: break;
        }
    }

    void finish() { flush_through(std::numeric_limits<std::int64_t>::max()); }
    double last_t_s() const { return last_t_s_; }

private:
    using Targets = std::array<std::optional<tvo_lcm::target_t>, kMaxRobots>;

    bool robot_of(std::int32_t robot) const { return robot >= 0 && static_cast<std::size_t>(robot) < robots_; }

    void on_sample(const tvo_lcm::unicycle_sample_t& m)
    {
        const std::int64_t n = m.header.sequence;
        if (!robot_of(m.header.robot)) {
            ++counts_.bad_robot;
            return;
        }
        const auto r = static_cast<std::size_t>(m.header.robot);
        const auto period = pending_.find(n);
        if (n <= written_through_ || (period != pending_.end() && period->second.sample[r])) {
            ++counts_.duplicates;
            return;
        }
        if (!epoch_utime_) {
            epoch_utime_ = m.header.utime;  // no START in the log: time from the first sample
        }
        PendingPeriod& row = pending_[n];
        row.sample[r] = m;
        const auto targets = pending_target_.find(n);
        if (targets != pending_target_.end()) {
            row.target[r] = targets->second[r];
        }
        flush_through(n - kAnswerWindow);
    }

    template <class Msg>
    void on_answer(const lcm::LogEvent& event)
    {
        Msg msg{};
        if (!decode(event, &msg)) {
            return;  // counted by the first pass
        }
        const tvo_lcm::command_header_t& h = msg.header;
        if (h.session_id != session_id_) {
            ++counts_.other_session;
            return;
        }
        if (h.measurement_sequence < 0) {
            counts_.safe_stops += std::is_same<Msg, tvo_lcm::unicycle_command_t>::value ? 1u : 0u;
            return;
        }
        if (!robot_of(h.robot)) {
            ++counts_.bad_robot;
            return;
        }
        const auto row = pending_.find(h.measurement_sequence);
        if (row == pending_.end()) {
            counts_.late_answers += h.measurement_sequence <= written_through_ ? 1u : 0u;
            return;
        }
        attach(msg, static_cast<std::size_t>(h.robot), &row->second);
    }

    // The first computed answer wins over a refusal; a refusal is kept only if nothing else came.
    static void attach(const tvo_lcm::unicycle_command_t& c, std::size_t r, PendingPeriod* row)
    {
        if (!row->command[r] || (row->command[r]->header.status != 0 && c.header.status == 0)) {
            row->command[r] = c;
        }
    }
    static void attach(const tvo_lcm::telemetry_t& t, std::size_t r, PendingPeriod* row)
    {
        if (!row->telemetry[r]) {
            row->telemetry[r] = tvo_host::StepTelemetry{t.barrier_c, t.barrier_slack, t.regularization};
        }
    }

    /// The reference of each robot at t_s: the START's paths, or the streamed samples held constant.
    std::array<Eigen::Vector2d, kMaxRobots> references(double t_s, const PendingPeriod& row)
    {
        std::array<Eigen::Vector2d, kMaxRobots> none;
        none.fill(Eigen::Vector2d::Constant(kNaN));
        if (scenario_.streamed || !start_) {
            for (std::size_t r = 0; r < robots_; ++r) {
                if (!row.target[r]) {
                    return none;
                }
                tvo_host::PolyCoeffs constant{};
                constant[0][0] = row.target[r]->position_m[0];
                constant[1][0] = row.target[r]->position_m[1];
                scenario_.targets[r] = tvo_host::TargetPath::polynomial(constant);
            }
            if (!start_) {
                scenario_.robot_count = robots_;
                scenario_.weights.fill(Eigen::Vector2d::Ones());
            }
        }
        return scenario_.references(t_s);
    }

    void flush_through(std::int64_t sequence)
    {
        while (!pending_.empty() && pending_.begin()->first <= sequence) {
            write(pending_.begin()->second);
            written_through_ = pending_.begin()->first;
            pending_.erase(pending_.begin());
        }
    }

    void write(const PendingPeriod& row)
    {
        const tvo_lcm::unicycle_sample_t* first = nullptr;
        for (std::size_t r = 0; r < robots_ && first == nullptr; ++r) {
            first = row.sample[r] ? &*row.sample[r] : nullptr;
        }
        const double t_s = static_cast<double>(first->header.utime - *epoch_utime_) * kSPerUs;
        last_t_s_ = t_s;
        const auto refs = references(t_s, row);
        for (std::size_t r = 0; r < robots_; ++r) {
            if (!row.sample[r]) {
                ++counts_.missing_samples;
                continue;
            }
            const tvo_lcm::unicycle_sample_t& m = *row.sample[r];
            if (row.command[r]) {
                held_[r] = *row.command[r];
            } else {
                ++counts_.unanswered;
            }
            if (row.telemetry[r]) {
                telemetry_[r] = *row.telemetry[r];
            }
            tvo_host::UnicycleState pose;
            pose.position_m = {m.position_m[0], m.position_m[1]};
            pose.heading_rad = (m.has & tvo_lcm::unicycle_sample_t::HAS_HEADING) != 0 ? m.heading_rad : kNaN;
            const tvo_host::UnicycleInput command{held_[r].speed_mps, held_[r].turn_rate_radps};
            out_.row(t_s, r, pose, refs[r], (pose.position_m - refs[r]).norm(), command, held_[r].header.status,
                     held_[r].header.flags, telemetry_[r]);
            ++counts_.rows;
        }
    }

    std::int32_t session_id_;
    std::optional<tvo_lcm::session_t> start_;
    tvo_host::Scenario scenario_;
    std::size_t robots_{1};
    std::optional<std::int64_t> epoch_utime_;
    tvo_host::RunRecorder& out_;
    Counts& counts_;
    std::map<std::int64_t, PendingPeriod> pending_;
    std::map<std::int64_t, Targets> pending_target_;
    std::int64_t written_through_{-1};
    std::array<tvo_lcm::unicycle_command_t, kMaxRobots> held_{};  // before the first answer: zero command, status 0
    std::array<tvo_host::StepTelemetry, kMaxRobots> telemetry_{};
    double last_t_s_{0.0};
};

std::string join(const std::map<std::string, std::uint64_t>& by_channel)
{
    std::ostringstream out;
    for (const auto& [channel, n] : by_channel) {
        out << (out.tellp() > 0 ? ", " : "") << channel << ' ' << n;
    }
    return out.str();
}

std::string session_list(const std::map<std::int32_t, SessionInfo>& sessions)
{
    std::ostringstream out;
    for (const auto& [id, info] : sessions) {
        out << "\n  " << id << ": " << info.samples << " samples" << (info.start ? "" : ", no START");
    }
    return out.str();
}

}  // namespace

int main(int argc, char** argv)
{
    std::string log_path;
    std::string csv_path;
    std::string scenario_json;
    std::int32_t session_id = 0;
    CLI::App app{"Turns an LCM event log (tvo_sim's run.lcmlog, or lcm-logger's recording of a robot) into the "
                 "run CSV that tools/plot_run.py plots: one row per robot per sample period of the session, paired "
                 "with the robot's command and telemetry by session, sequence and robot.",
                 "log2csv"};
    app.add_option("log", log_path, "the .lcmlog to read")->required();
    app.add_option("-o,--output", csv_path, "CSV to write [default: <log>.csv]");
    CLI::Option* session = app.add_option("--session", session_id, "the session to convert when the log holds "
                                          "several (the error message lists them)");
    app.add_option("--scenario-json", scenario_json, "also write the session's geometry (obstacles, bounds, "
                   "offsets, from its START) here; name it scenario.json next to the CSV for plot_run.py");
    std::string key_file;
    app.add_option("--key-file", key_file, "a keyed bus's key (tools/keygen): read only the frames whose "
                   "authentication trailer verifies, and count the others");
    const int parsed = tvo_options::parse_command_line(app, argc, argv, kProgram);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    if (csv_path.empty()) {
        csv_path = log_path + ".csv";
    }

    // lcm_eventlog_create does not say why it failed: look first, so the message can.
    std::error_code error;
    if (std::filesystem::is_directory(log_path, error)) {
        return usage_error(log_path + " is a folder, not an LCM log");
    }
    std::FILE* probe = std::fopen(log_path.c_str(), "rb");
    if (probe == nullptr) {
        return usage_error("cannot read " + log_path + ": " + std::strerror(errno));
    }
    std::fclose(probe);

    tvo_auth_t key{};
    const tvo_auth_t* keyed = nullptr;
    if (!key_file.empty()) {
        std::uint8_t bytes[TVO_AUTH_KEY_BYTES];
        char why[300];
        if (tvo_auth_key_file_read(key_file.c_str(), bytes, why, sizeof(why)) != 0) {
            return usage_error(why);
        }
        const tvo_auth_status_t status = tvo_auth_init(&key, bytes, 0u, 1u);   // opens only: its own id unused
        std::fill(std::begin(bytes), std::end(bytes), std::uint8_t{0});
        if (status != TVO_AUTH_OK) {
            return usage_error(std::string("authentication set-up failed: ") + tvo_auth_status_str(status));
        }
        keyed = &key;
    }
    struct KeyWipe {
        tvo_auth_t* key;
        ~KeyWipe() { tvo_auth_clear(key); }
    } wipe{&key};

    Counts counts;
    std::map<std::int32_t, SessionInfo> sessions;
    {
        EventReader log(log_path, keyed, &counts);
        if (!log.good()) {
            return usage_error("cannot open " + log_path + " as an LCM log");
        }
        sessions = scan_sessions(log, &counts);
    }
    if (counts.events == 0 && counts.unauthenticated + counts.replayed > 0) {
        std::cerr << kProgram << ": error: no frame of " << log_path << " opens with " << key_file << " ("
                  << counts.unauthenticated << " unauthenticated, " << counts.replayed
                  << " replayed): another key, or an unkeyed recording\n";
        return 1;
    }
    if (counts.events == 0) {
        return usage_error(log_path + " holds no LCM event (not an LCM event log, or empty)");
    }
    for (auto it = sessions.begin(); it != sessions.end();) {  // a START alone is not a run
        it = it->second.samples == 0 ? sessions.erase(it) : std::next(it);
    }
    if (session->count() > 0 && sessions.count(session_id) == 0) {
        return usage_error("--session " + std::to_string(session_id) + ": no sample of it in " + log_path +
                           "; sessions with samples:" + (sessions.empty() ? " none" : session_list(sessions)));
    }
    if (session->count() == 0) {
        if (sessions.empty()) {
            std::cerr << kProgram << ": error: " << log_path << " holds no decodable sample on "
                      << TVO_CHANNEL_SAMPLE << " (" << counts.events << " events)\n";
            return 1;
        }
        if (sessions.size() > 1) {
            return usage_error(log_path + " holds " + std::to_string(sessions.size()) +
                               " sessions: pick one with --session ID" + session_list(sessions));
        }
        session_id = sessions.begin()->first;
    }
    const SessionInfo& info = sessions.at(session_id);

    const int converted = tvo_options::run_reporting_errors(kProgram, [&] {
        tvo_host::RunRecorder out(csv_path);
        Converter converter(session_id, info, out, counts);
        EventReader log(log_path, keyed, nullptr);   // counted in the first pass
        for (const lcm::LogEvent* event = log.next(); event != nullptr; event = log.next()) {
            converter.on_event(*event);
        }
        converter.finish();
        if (!out.close()) {
            std::cerr << kProgram << ": error: writing " << csv_path << " failed\n";
            return 1;
        }
        if (!scenario_json.empty()) {
            if (!info.start) {
                std::cerr << kProgram << ": error: --scenario-json: the log holds no START of session " << session_id
                          << " (start lcm-logger before the session)\n";
                return 1;
            }
            tvo_host::write_scenario_json(scenario_json, scenario_of(*info.start), converter.last_t_s());
        }
        return 0;
    });
    if (converted != 0) {
        return converted;
    }

    std::cout << "log2csv: session " << session_id << ": " << counts.rows << " rows (" << info.samples
              << " samples) -> " << csv_path << '\n';
    if (!info.start) {
        std::cout << "log2csv: no START of the session in the log: time counts from the first sample and the "
                     "reference is the streamed target where there is one, else nan\n";
    }
    const std::pair<const char*, std::uint64_t> notes[] = {
        {"samples without an answer (the robot's previous command kept)", counts.unanswered},
        {"answers that came after their row was written", counts.late_answers},
        {"duplicate samples (ignored)", counts.duplicates},
        {"samples and answers naming no robot of the session (ignored)", counts.bad_robot},
        {"robots without a sample in a period of the others' (no row)", counts.missing_samples},
        {"commands and telemetry of other sessions (ignored)", counts.other_session},
        {"safe stops of the node", counts.safe_stops},
        {"frames dropped by --key-file: their tag did not verify (forged, altered, another key)",
         counts.unauthenticated},
        {"frames dropped by --key-file: a counter already used (replays)", counts.replayed},
        {"frames carry an authentication trailer, not checked (a keyed bus: give --key-file to check them)",
         counts.unchecked_trailers},
    };
    for (const auto& [what, n] : notes) {
        if (n > 0) {
            std::cout << "log2csv: " << n << ' ' << what << '\n';
        }
    }
    if (!counts.undecodable.empty()) {
        std::cout << "log2csv: messages that did not decode (skipped): " << join(counts.undecodable) << '\n';
    }
    if (!counts.other_channels.empty()) {
        std::cout << "log2csv: events on other channels (skipped): " << join(counts.other_channels) << '\n';
    }
    return 0;
}
