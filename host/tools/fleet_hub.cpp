// tvo_fleet_hub: the radio between tvo_sim --fleet and a fleet of nodes (tvo_firmware_node --own-robot k),
// so that tvo_sim's plant, metrics and outputs serve a fleet unchanged (host/README.md, "A fleet").
//
// Plant bus (tvo_sim's URL)               Fleet bus (the nodes' URL)
//   TVO_SESSION, TVO_TARGET       ->        the same, to every node
//   TVO_FLEET_SAMPLE (per robot,  ->        fleet_sample_t per robot and node on TVO_FLEET_SAMPLE_R<k>:
//     a period's back to back)              the other robots' first, node k's own robot last (its step)
//   TVO_FLEET_COMMAND (per robot) <-        fleet_command_t on TVO_FLEET_COMMAND_R<k>: row k from node k;
//     one row per robot and period:         a robot whose row did not come holds its last (zero-order hold),
//     node r's or the held one              so tvo_sim never waits on a lost row
//   TVO_TELEMETRY                 <-        TVO_TELEMETRY_R<k>: the lowest-numbered answering node's
//   TVO_SESSION_ACK               <-        TVO_SESSION_ACK_R<k>: once every node acked (a refusal at once)
//
// Loss per link (--loss P): each sample link (robot j -> node k) and each command link (node k ->
// plant) drops a period's message with probability P, decided by a seeded hash of (link, period),
// so the hub knows which answers to await and the run stays lockstep and repeatable.
// Agreement: per period, the digests of the nodes that computed a command are compared, and the
// largest spread of any robot's row across them is recorded (--json).
// Keyed (--key-file, auth.h): every frame on both buses is opened or dropped and counted, never
// answered. The plant's SESSION/TARGET frames go to the nodes as tvo_sim signed them (SENDER_PLANT);
// robot j's samples are signed as SENDER_FLEET_ROBOT + j (each robot its own counter stream); to
// tvo_sim the hub signs as SENDER_NODE, the node it stands for; tvo_sim's samples open as its own.
#include <sys/select.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>

#include "auth.h"
#include "auth_key_file.h"
#include "channels.h"
#include "lcm_messages.hpp"
#include "tvo_lcm/fleet_command_t.hpp"
#include "tvo_lcm/fleet_sample_t.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

constexpr int kMaxRobots = tvo_lcm::fleet_sample_t::MAX_ROBOTS;

std::string robot_channel(const char* base, int robot) { return std::string(base) + "_R" + std::to_string(robot); }

std::uint64_t splitmix64(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

struct Options {
    std::string plant_url;
    std::string fleet_url;
    int robots{0};
    double loss{0.0};
    double loss_until_s{-1.0};  // < 0: loss for the whole run
    std::uint64_t seed{1};
    std::string json_path;
    std::string key_file;  // empty: unauthenticated buses
};

// One signing or opening end on a keyed bus (auth.h), or a pass-through on an unkeyed one.
class AuthEnd {
public:
    AuthEnd() = default;
    AuthEnd(const AuthEnd&) = delete;
    AuthEnd& operator=(const AuthEnd&) = delete;
    ~AuthEnd() { tvo_auth_clear(&auth_); }

    void key(const std::uint8_t (&key)[TVO_AUTH_KEY_BYTES], std::uint32_t sender_id)
    {
        tvo_auth_status_t status = tvo_auth_init(&auth_, key, sender_id, 1u);
        if (status == TVO_AUTH_OK) {
            status = tvo_auth_follow_clock(&auth_, tvo_auth_wall_clock_counter, TVO_AUTH_NEW_SENDER_WINDOW_US);
        }
        if (status != TVO_AUTH_OK) {
            throw std::runtime_error(std::string("authentication set-up failed: ") + tvo_auth_status_str(status));
        }
        keyed_ = true;
    }

    // The message's length in a received frame, or -1 (dropped and counted) if it does not open.
    int open(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        if (!keyed_) {
            return static_cast<int>(rbuf->data_size);
        }
        std::size_t length = 0;
        const tvo_auth_status_t status = tvo_auth_open(&auth_, channel.c_str(), static_cast<const std::uint8_t*>(rbuf->data),
                                                       rbuf->data_size, &length);
        if (status != TVO_AUTH_OK) {
            ++(status == TVO_AUTH_ERR_REPLAY ? replayed_ : unauthenticated_);
            return -1;
        }
        return static_cast<int>(length);
    }

    template <class Msg>
    void publish(lcm::LCM& bus, const std::string& channel, const Msg& msg)
    {
        const int length = msg.encode(frame_.data(), 0, static_cast<int>(frame_.size() - TVO_AUTH_TRAILER_BYTES));
        std::size_t frame_length = length > 0 ? static_cast<std::size_t>(length) : 0u;
        if (length <= 0 || (keyed_ && tvo_auth_sign(&auth_, channel.c_str(), frame_.data(), frame_length, frame_.size(),
                                                   &frame_length) != TVO_AUTH_OK)) {
            throw std::runtime_error("cannot encode or sign a message for " + channel);
        }
        bus.publish(channel, frame_.data(), static_cast<unsigned int>(frame_length));
    }

    std::uint64_t unauthenticated() const { return unauthenticated_; }
    std::uint64_t replayed() const { return replayed_; }

private:
    tvo_auth_t auth_{};
    bool keyed_{false};
    std::array<std::uint8_t, 4096 + TVO_AUTH_TRAILER_BYTES> frame_{};
    std::uint64_t unauthenticated_{0};
    std::uint64_t replayed_{0};
};

struct Answer {
    bool command{false};
    bool telemetry{false};
    tvo_lcm::fleet_command_t row{};
    tvo_lcm::telemetry_t tel{};
};

class Hub {
public:
    explicit Hub(const Options& o) : o_(o), plant_(o.plant_url), fleet_(o.fleet_url)
    {
        if (!plant_.good() || !fleet_.good()) {
            throw std::runtime_error("cannot open LCM on " + o.plant_url + " or " + o.fleet_url);
        }
        plant_.subscribe(TVO_CHANNEL_SESSION, &Hub::on_plant_raw, this);
        plant_.subscribe(TVO_CHANNEL_TARGET, &Hub::on_plant_raw, this);
        plant_.subscribe(TVO_CHANNEL_FLEET_SAMPLE, &Hub::on_plant_sample, this);
        fleet_.subscribe(TVO_CHANNEL_SESSION_ACK "_R[0-9]+", &Hub::on_ack, this);
        fleet_.subscribe(TVO_CHANNEL_FLEET_COMMAND "_R[0-9]+", &Hub::on_row, this);
        fleet_.subscribe(TVO_CHANNEL_TELEMETRY "_R[0-9]+", &Hub::on_telemetry, this);
        sample_channels_.resize(static_cast<std::size_t>(o.robots));
        for (int k = 0; k < o.robots; ++k) {
            sample_channels_[static_cast<std::size_t>(k)] = robot_channel(TVO_CHANNEL_FLEET_SAMPLE, k);
        }
        if (!o.key_file.empty()) {
            std::uint8_t key[TVO_AUTH_KEY_BYTES];
            char why[300];
            if (tvo_auth_key_file_read(o.key_file.c_str(), key, why, sizeof(why)) != 0) {
                throw std::runtime_error(why);
            }
            plant_auth_.key(key, TVO_AUTH_SENDER_NODE);
            fleet_auth_.key(key, TVO_AUTH_SENDER_FLEET_ROBOT + kMaxRobots);  // opens only: its id signs nothing
            for (int j = 0; j < o.robots; ++j) {
                robot_auth_[static_cast<std::size_t>(j)].key(key, TVO_AUTH_SENDER_FLEET_ROBOT + static_cast<std::uint32_t>(j));
            }
            std::fill(std::begin(key), std::end(key), std::uint8_t{0});
        }
    }

    bool finished() const { return stopped_; }

    void run()
    {
        const int fds[2] = {plant_.getFileno(), fleet_.getFileno()};
        while (!g_stop && !stopped_) {
            fd_set readable;
            FD_ZERO(&readable);
            FD_SET(fds[0], &readable);
            FD_SET(fds[1], &readable);
            timeval tv{0, 100000};
            const int ready = select(std::max(fds[0], fds[1]) + 1, &readable, nullptr, nullptr, &tv);
            if (ready > 0 && FD_ISSET(fds[1], &readable)) {
                fleet_.handle();
            }
            if (ready > 0 && FD_ISSET(fds[0], &readable)) {
                plant_.handle();
            }
        }
    }

    void write_json() const
    {
        nlohmann::json j;
        j["robots"] = robots_;
        j["nodes"] = o_.robots;
        j["loss"] = o_.loss;
        j["periods"] = periods_;
        j["compared_periods"] = compared_periods_;
        j["max_command_disagreement"] = max_disagreement_;
        j["digest_mismatch_periods"] = mismatch_periods_;
        j["max_speed_disagreement_mps"] = max_speed_spread_;
        j["max_speed_disagreement_period"] = max_speed_spread_period_;
        j["max_turn_rate_disagreement_radps"] = max_turn_spread_;
        j["max_turn_rate_disagreement_period"] = max_turn_spread_period_;
        std::vector<double> sorted = spreads_;
        std::sort(sorted.begin(), sorted.end());
        const auto quantile = [&sorted](double q) {
            return sorted.empty() ? 0.0 : sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
        };
        j["median_command_disagreement"] = quantile(0.5);
        j["p99_command_disagreement"] = quantile(0.99);
        j["last_mismatch_period"] = last_mismatch_period_;
        if (o_.loss_until_s >= 0.0) {
            j["loss_end_period"] = loss_end_period();
            // Periods after the loss ended until the digests agree for good (0: at once).
            j["periods_to_reagree"] = std::max<std::int64_t>(0, last_mismatch_period_ + 1 - loss_end_period());
        }
        j["longest_disagreement_periods"] = longest_streak_;
        j["predicted_samples"] = predicted_;
        j["dropped_samples"] = dropped_samples_;
        j["dropped_commands"] = dropped_commands_;
        j["held_rows"] = held_rows_;
        j["refused_rows"] = refused_rows_;
        j["limit_violations"] = limit_violations_;
        j["max_speed_mps"] = max_speed_;
        j["max_abs_turn_rate_radps"] = max_turn_;
        j["max_speed_step_mps"] = max_speed_step_;
        j["min_pair_distance_sampled_m"] =
            std::isfinite(min_pair_m_) ? nlohmann::json(min_pair_m_) : nlohmann::json(nullptr);
        j["command_digest_run"] = run_digest_hex();
        j["keyed"] = !o_.key_file.empty();
        j["hub_unauthenticated"] = plant_auth_.unauthenticated() + fleet_auth_.unauthenticated();
        j["hub_replayed"] = plant_auth_.replayed() + fleet_auth_.replayed();
        if (o_.json_path.empty()) {
            std::cout << j.dump(2) << '\n';
            return;
        }
        std::ofstream out(o_.json_path);
        out << j.dump(2) << '\n';
    }

private:
    bool dropped(int kind, int from, int to, std::int64_t period) const
    {
        if (o_.loss <= 0.0 || (o_.loss_until_s >= 0.0 && period >= loss_end_period())) {
            return false;
        }
        const std::uint64_t key = o_.seed * 0x100000001b3ull ^ (static_cast<std::uint64_t>(kind) << 56) ^
                                  (static_cast<std::uint64_t>(from) << 48) ^ (static_cast<std::uint64_t>(to) << 40) ^
                                  static_cast<std::uint64_t>(period);
        return static_cast<double>(splitmix64(key) >> 11) * 0x1.0p-53 < o_.loss;
    }

    std::int64_t loss_end_period() const
    {
        return start_.period_us > 0 ? static_cast<std::int64_t>(std::llround(o_.loss_until_s * 1e6 /
                                                                              static_cast<double>(start_.period_us)))
                                    : 0;
    }

    // FNV-1a 64 over (sequence, digest) of every compared period: one figure for a whole run's commands.
    std::string run_digest_hex() const
    {
        char text[17];
        std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(run_digest_));
        return text;
    }

    void fold_run_digest(std::uint64_t value)
    {
        for (int b = 0; b < 8; ++b) {
            run_digest_ ^= (value >> (8 * b)) & 0xffu;
            run_digest_ *= 0x100000001b3ull;
        }
    }

    void on_plant_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        const int length = plant_auth_.open(rbuf, channel);
        if (length < 0) {
            return;
        }
        if (channel == TVO_CHANNEL_SESSION) {
            tvo_lcm::session_t s;
            if (s.decode(rbuf->data, 0, length) == length &&
                s.action == tvo_lcm::session_t::ACTION_START) {
                start_ = s;
                robots_ = s.robot_count;
            }
        }
        fleet_.publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));  // as signed by tvo_sim
    }

    void on_ack(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::session_ack_t ack;
        const int length = fleet_auth_.open(rbuf, channel);
        if (length < 0 || ack.decode(rbuf->data, 0, length) != length) {
            return;
        }
        const int k = std::stoi(channel.substr(channel.rfind('R') + 1));
        if (k < 0 || k >= o_.robots) {
            return;
        }
        if (ack.session_id != ack_session_ || ack.action != ack_action_) {
            ack_session_ = ack.session_id;
            ack_action_ = ack.action;
            ack_mask_ = 0u;
        }
        ack_mask_ |= 1u << k;
        if (ack.status != tvo_lcm::command_t::STATUS_OK || ack_mask_ == (1u << o_.robots) - 1u) {
            plant_auth_.publish(plant_, TVO_CHANNEL_SESSION_ACK, ack);
            ack_mask_ = 0u;
            if (ack.action == tvo_lcm::session_t::ACTION_STOP && ack.status == tvo_lcm::command_t::STATUS_OK) {
                stopped_ = true;
            }
        }
    }

    // tvo_sim's per-robot samples: a period's N come back to back; once all N of one (session, sequence)
    // are in, the period starts (a sample of another period drops an incomplete one).
    void on_plant_sample(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::fleet_sample_t s;
        const int length = plant_auth_.open(rbuf, channel);
        if (length < 0) {
            return;
        }
        if (s.decode(rbuf->data, 0, length) != length || s.robot_count != o_.robots || s.robot < 0 ||
            s.robot >= o_.robots) {
            std::cerr << "tvo_fleet_hub: a sample that does not decode or is not one of " << o_.robots
                      << " robots (ignored)\n";
            return;
        }
        if (gathered_ == 0u || s.session_id != period_.session_id || s.sequence != period_.sequence) {
            gathered_ = 0u;  // a new period: an incomplete one is never fanned out
        }
        gathered_ |= 1u << s.robot;
        samples_[static_cast<std::size_t>(s.robot)] = s;
        period_ = s;
        if (gathered_ == (1u << o_.robots) - 1u) {
            gathered_ = 0u;
            fan_out();
        }
    }

    // The period's samples to every node: robot j's to node k unless the link (j, k) drops it.
    void fan_out()
    {
        answers_.assign(static_cast<std::size_t>(o_.robots), Answer{});
        expected_.assign(static_cast<std::size_t>(o_.robots), false);
        awaiting_ = true;
        for (int a = 0; a < o_.robots; ++a) {
            for (int b = a + 1; b < o_.robots; ++b) {
                const auto& pa = samples_[static_cast<std::size_t>(a)].position_m;
                const auto& pb = samples_[static_cast<std::size_t>(b)].position_m;
                min_pair_m_ = std::min(min_pair_m_, std::hypot(pa[0] - pb[0], pa[1] - pb[1]));
            }
        }
        for (int k = 0; k < o_.robots; ++k) {
            for (int step = 1; step <= o_.robots; ++step) {
                const int j = (k + step) % o_.robots;  // the own robot (j == k) last: it steps the node
                if (dropped(0, j, k, period_.sequence)) {
                    ++dropped_samples_;
                    continue;
                }
                robot_auth_[static_cast<std::size_t>(j)].publish(fleet_, sample_channels_[static_cast<std::size_t>(k)],
                                                                 samples_[static_cast<std::size_t>(j)]);
                if (j == k) {
                    expected_[static_cast<std::size_t>(k)] = true;
                }
            }
        }
        complete_if_answered();
    }

    int answering_node(const std::string& channel, std::int64_t sequence) const
    {
        const int k = std::stoi(channel.substr(channel.rfind('R') + 1));
        if (!awaiting_ || k < 0 || k >= o_.robots || !expected_[static_cast<std::size_t>(k)] ||
            sequence != period_.sequence) {
            return -1;
        }
        return k;
    }

    void on_row(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::fleet_command_t row;
        const int length = fleet_auth_.open(rbuf, channel);
        if (length < 0 || row.decode(rbuf->data, 0, length) != length) {
            return;
        }
        const int k = answering_node(channel, row.measurement_sequence);
        if (k < 0 || row.robot != k) {
            return;
        }
        answers_[static_cast<std::size_t>(k)].command = true;
        answers_[static_cast<std::size_t>(k)].row = row;
        complete_if_answered();
    }

    void on_telemetry(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::telemetry_t tel;
        const int length = fleet_auth_.open(rbuf, channel);
        if (length < 0 || tel.decode(rbuf->data, 0, length) != length) {
            return;
        }
        const int k = answering_node(channel, tel.measurement_sequence);
        if (k < 0) {
            return;
        }
        answers_[static_cast<std::size_t>(k)].telemetry = true;
        answers_[static_cast<std::size_t>(k)].tel = tel;
        complete_if_answered();
    }

    void complete_if_answered()
    {
        if (!awaiting_) {
            return;
        }
        for (int k = 0; k < o_.robots; ++k) {
            const Answer& a = answers_[static_cast<std::size_t>(k)];
            if (expected_[static_cast<std::size_t>(k)] && !(a.command && a.telemetry)) {
                return;
            }
        }
        awaiting_ = false;
        ++periods_;
        compare();
        answer_plant();
    }

    // Agreement among the nodes that computed a command this period (status 0).
    void compare()
    {
        std::vector<const tvo_lcm::fleet_command_t*> computed;
        for (int k = 0; k < o_.robots; ++k) {
            const Answer& a = answers_[static_cast<std::size_t>(k)];
            if (expected_[static_cast<std::size_t>(k)] && a.row.status == tvo_lcm::command_t::STATUS_OK) {
                computed.push_back(&a.row);
                predicted_ += static_cast<std::uint64_t>(std::max(a.row.predicted, 0));
            }
        }
        if (!computed.empty()) {
            fold_run_digest(static_cast<std::uint64_t>(period_.sequence));
            fold_run_digest(static_cast<std::uint64_t>(computed.front()->joint_digest));
        }
        if (computed.size() < 2) {
            return;
        }
        ++compared_periods_;
        double spread_v = 0.0;
        double spread_w = 0.0;
        bool same = true;
        for (const auto* c : computed) {
            same = same && c->joint_digest == computed.front()->joint_digest;
        }
        for (int r = 0; r < robots_; ++r) {
            double v_lo = std::numeric_limits<double>::infinity(), v_hi = -v_lo, w_lo = v_lo, w_hi = -v_lo;
            for (const auto* c : computed) {
                v_lo = std::min(v_lo, c->joint_speed_mps[r]);
                v_hi = std::max(v_hi, c->joint_speed_mps[r]);
                w_lo = std::min(w_lo, c->joint_turn_rate_radps[r]);
                w_hi = std::max(w_hi, c->joint_turn_rate_radps[r]);
            }
            spread_v = std::max(spread_v, v_hi - v_lo);
            spread_w = std::max(spread_w, w_hi - w_lo);
        }
        if (spread_v > max_speed_spread_) {
            max_speed_spread_ = spread_v;
            max_speed_spread_period_ = period_.sequence;
        }
        if (spread_w > max_turn_spread_) {
            max_turn_spread_ = spread_w;
            max_turn_spread_period_ = period_.sequence;
        }
        max_disagreement_ = std::max({max_disagreement_, spread_v, spread_w});
        spreads_.push_back(std::max(spread_v, spread_w));
        if (!same) {
            last_mismatch_period_ = period_.sequence;
            ++mismatch_periods_;
            ++streak_;
            longest_streak_ = std::max(longest_streak_, streak_);
        } else {
            streak_ = 0;
        }
    }

    // One row per robot to tvo_sim, the period's joint command: each robot's row from its own node, else
    // the row it holds (status 0, no flags: the plant applies it as the command in force).
    void answer_plant()
    {
        const double h_s = static_cast<double>(start_.period_us) * 1e-6;
        std::optional<tvo_lcm::telemetry_t> tel;
        std::int32_t flags = 0;
        for (int r = 0; r < o_.robots; ++r) {
            const Answer& a = answers_[static_cast<std::size_t>(r)];
            const bool came = expected_[static_cast<std::size_t>(r)] && a.command;
            const bool lost = came && dropped(1, r, o_.robots, period_.sequence);
            dropped_commands_ += lost ? 1u : 0u;
            const bool fresh = came && !lost && a.row.status == tvo_lcm::command_t::STATUS_OK;
            refused_rows_ += (came && a.row.status != tvo_lcm::command_t::STATUS_OK) ? 1u : 0u;
            tvo_lcm::fleet_command_t row{};
            if (fresh) {
                check_limits(r, a.row, h_s);
                held_[static_cast<std::size_t>(r)] = {a.row.speed_mps, a.row.turn_rate_radps};
                row.flags = a.row.flags;
            } else if ((static_cast<std::uint32_t>(a.row.flags) & static_cast<std::uint32_t>(tvo_lcm::command_t::FLAG_SAFE_STOP)) != 0u && came && !lost) {
                held_[static_cast<std::size_t>(r)] = {0.0, 0.0};
            } else {
                ++held_rows_;
            }
            row.utime = period_.utime + start_.delay_us;
            row.session_id = period_.session_id;
            row.measurement_sequence = period_.sequence;
            row.robot = r;
            row.robot_count = o_.robots;
            row.status = tvo_lcm::command_t::STATUS_OK;
            row.speed_mps = held_[static_cast<std::size_t>(r)][0];
            row.turn_rate_radps = held_[static_cast<std::size_t>(r)][1];
            plant_auth_.publish(plant_, TVO_CHANNEL_FLEET_COMMAND, row);
            flags |= row.flags;
            if (!tel && came && !lost) {
                tel = a.tel;
            }
        }
        tvo_lcm::telemetry_t out = tel.value_or(tvo_lcm::telemetry_t{});
        out.utime = period_.utime + start_.delay_us;
        out.session_id = period_.session_id;
        out.measurement_sequence = period_.sequence;
        out.status = tvo_lcm::command_t::STATUS_OK;
        out.flags = flags;
        plant_auth_.publish(plant_, TVO_CHANNEL_TELEMETRY, out);
    }

    // A computed row against the session's limits; the speed step against the same node's last row.
    void check_limits(int r, const tvo_lcm::fleet_command_t& row, double h_s)
    {
        const double v = row.speed_mps;
        const double w = row.turn_rate_radps;
        max_speed_ = std::max(max_speed_, std::fabs(v));
        max_turn_ = std::max(max_turn_, std::fabs(w));
        const double tol = 1e-6;
        bool bad = std::fabs(v) > start_.speed_max_mps * (1.0 + tol) || std::fabs(w) > start_.omega_max_radps * (1.0 + tol);
        auto& last = last_row_[static_cast<std::size_t>(r)];
        if (last && last->first == row.measurement_sequence - 1) {
            const double dv = std::fabs(v - last->second);
            max_speed_step_ = std::max(max_speed_step_, dv);
            bad = bad || dv > start_.accel_max_mps2 * h_s * (1.0 + tol) + 1e-9;
        }
        last = std::make_pair(row.measurement_sequence, v);
        limit_violations_ += bad ? 1u : 0u;
    }

    const Options& o_;
    lcm::LCM plant_;
    lcm::LCM fleet_;
    std::vector<std::string> sample_channels_;
    AuthEnd plant_auth_;                           // tvo_sim's bus: opens its frames, signs as its node
    AuthEnd fleet_auth_;                           // the nodes' bus: opens their frames
    std::array<AuthEnd, kMaxRobots> robot_auth_;   // robot j's samples, each its own sender
    std::uint64_t run_digest_{0xcbf29ce484222325ull};
    tvo_lcm::session_t start_{};
    int robots_{0};
    std::int64_t ack_session_{-2};
    std::int8_t ack_action_{0};
    std::uint32_t ack_mask_{0};
    bool stopped_{false};
    bool awaiting_{false};
    std::array<tvo_lcm::fleet_sample_t, kMaxRobots> samples_{};  // the period's, by robot
    tvo_lcm::fleet_sample_t period_{};                            // the newest sample: its period's stamp
    std::uint32_t gathered_{0};                                   // bit r: robot r's sample of period_ is in
    std::vector<Answer> answers_;
    std::vector<bool> expected_;
    std::array<std::array<double, 2>, kMaxRobots> held_{};
    std::array<std::optional<std::pair<std::int64_t, double>>, kMaxRobots> last_row_{};
    std::uint64_t periods_{0}, compared_periods_{0}, mismatch_periods_{0}, streak_{0}, longest_streak_{0};
    std::uint64_t predicted_{0}, dropped_samples_{0}, dropped_commands_{0}, held_rows_{0}, refused_rows_{0};
    std::uint64_t limit_violations_{0};
    double max_speed_spread_{0.0}, max_turn_spread_{0.0};
    std::int64_t max_speed_spread_period_{-1}, max_turn_spread_period_{-1}, last_mismatch_period_{-1};
    std::vector<double> spreads_;
    double max_disagreement_{0.0}, max_speed_{0.0}, max_turn_{0.0}, max_speed_step_{0.0};
    double min_pair_m_{std::numeric_limits<double>::infinity()};
};

}  // namespace

int main(int argc, char** argv)
{
    Options o;
    CLI::App app{"tvo_fleet_hub: tvo_sim --fleet's per-robot messages to and from a fleet of per-robot nodes"};
    app.add_option("--plant-url", o.plant_url, "LCM URL shared with tvo_sim")->required();
    app.add_option("--fleet-url", o.fleet_url, "LCM URL shared with the nodes")->required();
    app.add_option("--robots", o.robots, "nodes, one per robot (robot k's node: --own-robot k)")
        ->required()
        ->check(CLI::Range(1, kMaxRobots));
    app.add_option("--loss", o.loss, "probability that a link drops a period's message")->check(CLI::Range(0.0, 1.0));
    app.add_option("--loss-until-s", o.loss_until_s, "the links lose nothing from this plant time on (re-agreement)");
    app.add_option("--seed", o.seed, "seed of the loss pattern");
    app.add_option("--json", o.json_path, "write the agreement figures here (default: stdout)");
    app.add_option("--key-file", o.key_file, "sign and open every message on both buses with this key (tools/keygen)");
    CLI11_PARSE(app, argc, argv);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    try {
        Hub hub(o);
        hub.run();
        hub.write_json();
        return hub.finished() ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "tvo_fleet_hub: error: " << e.what() << '\n';
        return 1;
    }
}
