// CSV of the run and the bound on a run's files; see run_recorder.hpp.
#include "run_recorder.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "lcm_messages.hpp"

namespace tvo_host {

namespace {
// One large stdio buffer: rows are written every period and must not cost a syscall each.
constexpr std::size_t kBufferBytes = 1 << 20;

constexpr char kHeader[] = "t_s,robot,x_m,y_m,heading_rad,target_x_m,target_y_m,error_m,"
                           "cmd_speed_mps,cmd_turn_rate_radps,status,flags,barrier_c,barrier_slack,regularization\n";
constexpr char kRowFormat[] = "%.6f,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d,%.9g,%.9g,%.9g\n";

constexpr std::size_t occurrences(const char* text, const char* what)
{
    std::size_t count = 0;
    for (; *text != '\0'; ++text) {
        std::size_t i = 0;
        while (what[i] != '\0' && text[i] == what[i]) {
            ++i;
        }
        count += (what[i] == '\0') ? 1 : 0;
    }
    return count;
}

// The widest text of each conversion in kRowFormat: "%.9g" of a double is at most sign, 9 digits, the
// point and "e-308" (16; the fixed form "-0.000123456789" is shorter, "-inf" too); "%d" of an
// int32 "-2147483648". "%.6f" (time) and "%zu" (robot) depend on the run.
constexpr std::size_t kRealFields = occurrences(kRowFormat, "%.9g");
constexpr std::size_t kIntFields = occurrences(kRowFormat, "%d");
constexpr std::size_t kMaxRealChars = 16;
constexpr std::size_t kMaxIntChars = 11;
constexpr std::size_t kTimeDecimals = 6;
constexpr std::size_t kLiteralChars = occurrences(kRowFormat, ",") + 1;  // separators and the newline
static_assert(occurrences(kRowFormat, "%") == occurrences(kHeader, ",") + 1, "one conversion per CSV column");
static_assert(kRealFields + kIntFields + 2 == occurrences(kRowFormat, "%"), "kRowFormat: only the conversions bounded here");

std::uint64_t decimal_digits(std::uint64_t value)
{
    std::uint64_t digits = 1;
    for (; value >= 10; value /= 10) {
        ++digits;
    }
    return digits;
}

// LCM's log format: each event is a sync word (4 bytes), its number (8), timestamp (8), channel length
// (4) and data length (4), then the channel name and the data.
constexpr std::uint64_t kLcmLogEventHeaderBytes = 28;

template <class Msg>
std::uint64_t log_event_bytes(const char* channel)
{
    return kLcmLogEventHeaderBytes + std::strlen(channel) + static_cast<std::uint64_t>(Msg{}.getEncodedSize());
}

// summary.json and scenario.json: a few kB each (scenario.json grows with the scenario's obstacles).
constexpr std::uint64_t kJsonBytes = 1 << 20;
}  // namespace

RunRecorder::RunRecorder(const std::string& path) : file_(std::fopen(path.c_str(), "w"))
{
    if (file_ == nullptr) {
        throw std::runtime_error("cannot write " + path);
    }
    std::setvbuf(file_, nullptr, _IOFBF, kBufferBytes);
    std::fputs(kHeader, file_);
}

RunRecorder::~RunRecorder()
{
    close();
}

void RunRecorder::row(double t_s, std::size_t robot, const UnicycleState& state, const Eigen::Vector2d& target_m,
                      double error_m, const UnicycleInput& command, std::int32_t status, std::int32_t flags,
                      const StepTelemetry& telemetry)
{
    const int written = std::fprintf(file_, kRowFormat, t_s, robot, state.position_m.x(), state.position_m.y(),
                                     state.heading_rad, target_m.x(), target_m.y(), error_m, command.speed_mps,
                                     command.turn_rate_radps, static_cast<int>(status), static_cast<int>(flags),
                                     telemetry.barrier_c, telemetry.barrier_slack, telemetry.regularization);
    ok_ = ok_ && written > 0;
}

bool RunRecorder::close()
{
    if (file_ != nullptr) {
        ok_ = (std::fclose(file_) == 0) && ok_;
        file_ = nullptr;
    }
    return ok_;
}

std::uint64_t RunRecorder::max_bytes(std::int64_t steps, std::size_t robots, double t_max_s)
{
    const auto whole_seconds = static_cast<std::uint64_t>(std::floor(std::max(t_max_s, 0.0)));
    const std::uint64_t time_chars = decimal_digits(whole_seconds) + 1 + kTimeDecimals;
    const std::uint64_t robot_chars = decimal_digits(robots > 0 ? robots - 1 : 0);
    const std::uint64_t row_bytes =
        kLiteralChars + time_chars + robot_chars + kRealFields * kMaxRealChars + kIntFields * kMaxIntChars;
    const std::uint64_t rows = (static_cast<std::uint64_t>(std::max<std::int64_t>(steps, 0)) + 1) * robots;
    return (sizeof(kHeader) - 1) + rows * row_bytes;
}

OutputBound bound_outputs(std::int64_t steps, std::int64_t period_us, std::size_t robots, bool streamed,
                          bool realtime)
{
    const std::uint64_t command = robots * log_event_bytes<tvo_lcm::unicycle_command_t>(TVO_CHANNEL_COMMAND);
    const std::uint64_t sample = robots * log_event_bytes<tvo_lcm::unicycle_sample_t>(TVO_CHANNEL_SAMPLE);
    const std::uint64_t target = robots * log_event_bytes<tvo_lcm::target_t>(TVO_CHANNEL_TARGET);
    const std::uint64_t telemetry = robots * log_event_bytes<tvo_lcm::telemetry_t>(TVO_CHANNEL_TELEMETRY);
    const std::uint64_t per_period = sample + (streamed ? target : 0) + command * (realtime ? 2 : 1) + telemetry;
    // A node per robot at most, and the node of every robot: one per interval, and one per change (a
    // session message changes a node's state at most once).
    const std::uint64_t run_us = static_cast<std::uint64_t>(std::max<std::int64_t>(steps, 0)) *
                                 static_cast<std::uint64_t>(std::max<std::int64_t>(period_us, 0));
    const std::uint64_t announcements =
        (robots + 1) * (run_us / static_cast<std::uint64_t>(kLoggedAnnouncementIntervalUs) + 2 + kLoggedSessionMessages) *
        log_event_bytes<tvo_lcm::node_status_t>(TVO_CHANNEL_NODE);
    const std::uint64_t session =
        kLoggedSessionMessages * (log_event_bytes<tvo_lcm::session_t>(TVO_CHANNEL_SESSION) +
                                  robots * log_event_bytes<tvo_lcm::session_ack_t>(TVO_CHANNEL_SESSION_ACK)) +
        announcements;
    const std::uint64_t periods = static_cast<std::uint64_t>(std::max<std::int64_t>(steps, 0));
    OutputBound bound;
    bound.csv_bytes = RunRecorder::max_bytes(steps, robots, static_cast<double>(steps) * static_cast<double>(period_us) * 1e-6);
    bound.lcm_log_bytes = periods * per_period + session;
    bound.json_bytes = kJsonBytes;
    return bound;
}

}  // namespace tvo_host
