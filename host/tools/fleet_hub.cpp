// tvo_fleet_hub: the test's radio between tvo_sim and a fleet of nodes (tvo_firmware_node --own-robot k),
// each node on its own LCM URL, so that the loss of every link can be chosen per period and the run
// still repeats exactly (host/README.md, "A fleet"). Without loss it only forwards.
//
// Plant bus (tvo_sim's URL)             Node k's bus (its own URL)
//   TVO_SESSION, TVO_TARGET     ->        forwarded as tvo_sim signed them, to every node
//   TVO_SAMPLE (per robot)      ->        forwarded to node k unless the link (robot j -> node k) loses
//                                         that period's (robot robot_count - 1's sample steps a node)
//   TVO_COMMAND, TVO_TELEMETRY  <-        node k's own robot's, forwarded as the node signed them, as
//     one of each robot per period        they come (a keyed receiver takes each sender's frames only in
//                                         the order it signed them); where it did not step, refused, or
//                                         the link (node k -> plant) lost it, the row robot k holds
//                                         (zero-order hold: status 0, no flags) and its last telemetry,
//                                         signed by the hub once the period is complete, so tvo_sim never
//                                         waits on a message the hub dropped
//   TVO_SESSION_ACK, TVO_NODE   <-        forwarded as the nodes signed them
//
// Loss per link (--loss P): each sample link (robot j -> node k) and each command link (node k ->
// plant) drops a period's message with probability P, decided by a seeded hash of (link, period).
// Agreement (--json): per period, the joint digests (telemetry_t.joint_digest: fleet runs ask every
// period's telemetry) of the nodes that computed a command (the periods they differed in, and how
// many nodes stood outside the largest group of equal digests); the nodes' counters from their last
// announcements. Keyed (--key-file, auth.h): every frame the hub takes is opened first (a forged or
// replayed one is dropped and counted, never forwarded); what it writes itself it signs as --sender-id.
#include <sys/select.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>

#include "auth.h"
#include "auth_key_file.h"
#include "command_line.hpp"
#include "lcm_messages.hpp"

extern "C" {
#include "session_codec.h"  // TVO_SESSION_TELEMETRY_DEFAULT_US: the node's default telemetry interval
}

namespace {

constexpr const char* kProgram = "tvo_fleet_hub";

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

constexpr int kMaxRobots = tvo_lcm::session_t::MAX_ROBOTS;
// The hub's own sender id on a keyed bus (tvo_sim 2, node k 256 + k): what it writes itself.
constexpr std::uint32_t kHubSenderId = 3;
// After every node acked the STOP: how long the hub still forwards (each node's announcement after STOP).
constexpr std::chrono::milliseconds kLinger{300};
using Header = tvo_lcm::command_header_t;

std::uint64_t splitmix64(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

struct Options {
    std::string plant_url;
    std::vector<std::string> node_urls;  // node k's: it drives robot k
    double loss{0.0};
    double loss_until_s{-1.0};  // < 0: loss for the whole run
    std::uint64_t seed{1};
    std::string json_path;
    std::string key_file;  // empty: unauthenticated buses
    std::uint32_t sender_id{kHubSenderId};
};

// Opening (and signing) on a keyed bus (auth.h), a pass-through on an unkeyed one.
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
            status = tvo_auth_follow_clock(&auth_, tvo_auth_wall_clock_counter);
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
    std::array<std::uint8_t, 512 + TVO_AUTH_TRAILER_BYTES> frame_{};  // commands and telemetry only
    std::uint64_t unauthenticated_{0};
    std::uint64_t replayed_{0};
};

// Node k's answer to the period: its command and telemetry as decoded, and whether they went on to tvo_sim.
struct Answer {
    bool command{false};
    bool telemetry{false};
    bool forwarded{false};  // the command was computed (status 0) and its link did not lose it: passed on
    tvo_lcm::unicycle_command_t cmd{};
    tvo_lcm::telemetry_t tel{};
};

class Hub {
public:
    explicit Hub(const Options& o) : o_(o), nodes_(static_cast<int>(o.node_urls.size())), plant_(o.plant_url)
    {
        if (!plant_.good()) {
            throw std::runtime_error("cannot open LCM on " + o.plant_url);
        }
        for (const std::string& url : o.node_urls) {
            node_bus_.push_back(std::make_unique<lcm::LCM>(url));
            if (!node_bus_.back()->good()) {
                throw std::runtime_error("cannot open LCM on " + url);
            }
        }
        // Unbounded queues: LCM drops past 30 queued messages per subscription, silently (a period of 32
        // robots brings 32 samples, targets, commands at once).
        plant_.subscribe(TVO_CHANNEL_SESSION, &Hub::on_plant_session, this)->setQueueCapacity(0);
        plant_.subscribe(TVO_CHANNEL_TARGET, &Hub::on_plant_target, this)->setQueueCapacity(0);
        plant_.subscribe(TVO_CHANNEL_SAMPLE, &Hub::on_plant_sample, this)->setQueueCapacity(0);
        for (int k = 0; k < nodes_; ++k) {
            node_ends_.push_back(std::make_unique<NodeEnd>(NodeEnd{this, k}));
            lcm::LCM& bus = *node_bus_[static_cast<std::size_t>(k)];
            for (const char* channel : {TVO_CHANNEL_SESSION_ACK, TVO_CHANNEL_NODE, TVO_CHANNEL_COMMAND, TVO_CHANNEL_TELEMETRY}) {
                bus.subscribe(channel, &NodeEnd::on_frame, node_ends_.back().get())->setQueueCapacity(0);
            }
        }
        last_status_.resize(static_cast<std::size_t>(nodes_));
        node_open_.resize(static_cast<std::size_t>(nodes_));
        for (auto& end : node_open_) {
            end = std::make_unique<AuthEnd>();
        }
        if (!o.key_file.empty()) {
            std::uint8_t key[TVO_AUTH_KEY_BYTES];
            char why[300];
            if (tvo_auth_key_file_read(o.key_file.c_str(), key, why, sizeof(why)) != 0) {
                throw std::runtime_error(why);
            }
            plant_auth_.key(key, o.sender_id);
            for (auto& end : node_open_) {
                end->key(key, o.sender_id);  // opens only: the hub signs towards tvo_sim with plant_auth_
            }
            std::fill(std::begin(key), std::end(key), std::uint8_t{0});
        }
    }

    bool finished() const { return stopped_at_.has_value(); }

    void run()
    {
        std::vector<int> fds{plant_.getFileno()};
        for (const auto& bus : node_bus_) {
            fds.push_back(bus->getFileno());
        }
        const int top = *std::max_element(fds.begin(), fds.end());
        while (!g_stop && !(stopped_at_ && std::chrono::steady_clock::now() - *stopped_at_ > kLinger)) {
            fd_set readable;
            FD_ZERO(&readable);
            for (const int fd : fds) {
                FD_SET(fd, &readable);
            }
            timeval tv{0, 50000};
            if (select(top + 1, &readable, nullptr, nullptr, &tv) <= 0) {
                continue;
            }
            for (std::size_t k = 0; k < node_bus_.size(); ++k) {  // the nodes' first: answers before new samples
                if (FD_ISSET(fds[k + 1], &readable)) {
                    node_bus_[k]->handle();
                }
            }
            if (FD_ISSET(fds[0], &readable)) {
                plant_.handle();
            }
        }
    }

    void write_json() const
    {
        nlohmann::json j;
        j["robots"] = robots_;
        j["nodes"] = nodes_;
        j["loss"] = o_.loss;
        j["periods"] = periods_;
        j["compared_periods"] = compared_periods_;
        j["digest_mismatch_periods"] = mismatch_periods_;
        j["last_mismatch_period"] = last_mismatch_period_;
        if (o_.loss_until_s >= 0.0) {
            j["loss_end_period"] = loss_end_period();
            // Periods after the loss ended until the digests agree for good (0: at once).
            j["periods_to_reagree"] = std::max<std::int64_t>(0, last_mismatch_period_ + 1 - loss_end_period());
        }
        j["longest_disagreement_periods"] = longest_streak_;
        // Each period whose digests differed: [period (the sample's sequence), nodes outside the
        // largest group of equal digests]; the first kMaxSeries of them.
        j["digest_mismatch_per_period"] = mismatch_series_;
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
        std::uint64_t hub_unauthenticated = plant_auth_.unauthenticated();
        std::uint64_t hub_replayed = plant_auth_.replayed();
        for (const auto& end : node_open_) {
            hub_unauthenticated += end->unauthenticated();
            hub_replayed += end->replayed();
        }
        j["hub_unauthenticated"] = hub_unauthenticated;
        j["hub_replayed"] = hub_replayed;
        // Each node's counters since it started, from its last announcement (after STOP: the final ones).
        nlohmann::json unauthenticated = nlohmann::json::array();
        nlohmann::json replayed = nlohmann::json::array();
        nlohmann::json malformed = nlohmann::json::array();
        for (const auto& status : last_status_) {
            unauthenticated.push_back(status ? nlohmann::json(status->counters.unauthenticated) : nlohmann::json(nullptr));
            replayed.push_back(status ? nlohmann::json(status->counters.replayed) : nlohmann::json(nullptr));
            malformed.push_back(status ? nlohmann::json(status->counters.malformed) : nlohmann::json(nullptr));
        }
        j["node_unauthenticated"] = unauthenticated;
        j["node_replayed"] = replayed;
        j["node_malformed"] = malformed;
        if (o_.json_path.empty()) {
            std::cout << j.dump(2) << '\n';
            return;
        }
        std::ofstream out(o_.json_path);
        out << j.dump(2) << '\n';
    }

private:
    // Node k's bus: LCM calls a member function with no room for k, so each node has its own receiver.
    struct NodeEnd {
        Hub* hub;
        int k;
        void on_frame(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
        {
            if (channel == TVO_CHANNEL_COMMAND) {
                hub->on_command(k, rbuf, channel);
            } else if (channel == TVO_CHANNEL_TELEMETRY) {
                hub->on_telemetry(k, rbuf, channel);
            } else if (channel == TVO_CHANNEL_SESSION_ACK) {
                hub->on_ack(k, rbuf, channel);
            } else if (channel == TVO_CHANNEL_NODE) {
                hub->on_announcement(k, rbuf, channel);
            }
        }
    };

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

    bool telemetry_due(std::int64_t sequence) const
    {
        const std::int64_t every = start_.telemetry_every > 0
                                       ? start_.telemetry_every
                                       : (TVO_SESSION_TELEMETRY_DEFAULT_US + start_.period_us - 1) /
                                             std::max<std::int64_t>(start_.period_us, 1);
        return sequence % every == 0;
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

    void to_every_node(const std::string& channel, const lcm::ReceiveBuffer* rbuf)
    {
        for (const auto& bus : node_bus_) {
            bus->publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));  // as signed by tvo_sim
        }
    }

    void on_plant_session(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        const int length = plant_auth_.open(rbuf, channel);
        if (length < 0) {
            return;
        }
        tvo_lcm::session_t s;
        if (s.decode(rbuf->data, 0, length) == length && s.action == tvo_lcm::session_t::ACTION_START) {
            start_ = s;
            robots_ = std::min(s.robot_count, kMaxRobots);
        }
        to_every_node(channel, rbuf);
    }

    void on_plant_target(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        if (plant_auth_.open(rbuf, channel) >= 0) {
            to_every_node(channel, rbuf);
        }
    }

    // tvo_sim's samples, a period's in robot order: robot j's to node k unless the link (j, k) loses it;
    // the last robot's starts the period (it steps every node that hears it).
    void on_plant_sample(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        const int length = plant_auth_.open(rbuf, channel);
        tvo_lcm::unicycle_sample_t s;
        if (length < 0 || s.decode(rbuf->data, 0, length) != length || s.header.robot < 0 ||
            s.header.robot >= robots_ || robots_ != nodes_) {
            std::cerr << "tvo_fleet_hub: a sample that does not decode or is not one of " << robots_
                      << " robots with a node each (ignored)\n";
            return;
        }
        const int j = s.header.robot;
        const std::int64_t n = s.header.sequence;
        samples_[static_cast<std::size_t>(j)] = s;
        for (int k = 0; k < nodes_; ++k) {
            if (dropped(0, j, k, n)) {
                ++dropped_samples_;
                continue;
            }
            node_bus_[static_cast<std::size_t>(k)]->publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));
        }
        if (j == robots_ - 1) {
            begin_period(s);
        }
    }

    void begin_period(const tvo_lcm::unicycle_sample_t& trigger)
    {
        period_ = trigger.header;
        answers_.assign(static_cast<std::size_t>(nodes_), Answer{});
        expected_.assign(static_cast<std::size_t>(nodes_), false);
        with_telemetry_ = telemetry_due(period_.sequence);
        for (int a = 0; a < robots_; ++a) {
            for (int b = a + 1; b < robots_; ++b) {
                const auto& pa = samples_[static_cast<std::size_t>(a)].position_m;
                const auto& pb = samples_[static_cast<std::size_t>(b)].position_m;
                min_pair_m_ = std::min(min_pair_m_, std::hypot(pa[0] - pb[0], pa[1] - pb[1]));
            }
        }
        for (int k = 0; k < nodes_; ++k) {
            expected_[static_cast<std::size_t>(k)] = !dropped(0, robots_ - 1, k, period_.sequence);
        }
        awaiting_ = true;
        complete_if_answered();
    }

    // Node k's answer to the period being awaited, else -1.
    int answering(int k, const Header& h) const
    {
        if (!awaiting_ || !expected_[static_cast<std::size_t>(k)] || h.session_id != period_.session_id ||
            h.measurement_sequence != period_.sequence || h.robot != k) {
            return -1;
        }
        return k;
    }

    void on_command(int k, const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::unicycle_command_t c;
        const int length = node_open_[static_cast<std::size_t>(k)]->open(rbuf, channel);
        if (length < 0 || c.decode(rbuf->data, 0, length) != length || answering(k, c.header) < 0) {
            return;
        }
        Answer& a = answers_[static_cast<std::size_t>(k)];
        a.command = true;
        a.cmd = c;
        a.forwarded = c.header.status == Header::STATUS_OK && !dropped(1, k, nodes_, period_.sequence);
        if (a.forwarded) {
            plant_.publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));  // as the node signed it
        }
        complete_if_answered();
    }

    void on_telemetry(int k, const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::telemetry_t tel;
        const int length = node_open_[static_cast<std::size_t>(k)]->open(rbuf, channel);
        if (length < 0 || tel.decode(rbuf->data, 0, length) != length || answering(k, tel.header) < 0) {
            return;
        }
        Answer& a = answers_[static_cast<std::size_t>(k)];
        a.telemetry = true;
        a.tel = tel;
        if (a.forwarded) {
            plant_.publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));  // follows its command
        }
        complete_if_answered();
    }

    void on_ack(int k, const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::session_ack_t ack;
        const int length = node_open_[static_cast<std::size_t>(k)]->open(rbuf, channel);
        if (length < 0 || ack.decode(rbuf->data, 0, length) != length) {
            return;
        }
        plant_.publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));  // as the node signed it
        if (ack.action == tvo_lcm::session_t::ACTION_STOP && ack.status == Header::STATUS_OK) {
            stop_acked_ |= 1ull << k;
            if (stop_acked_ == (1ull << nodes_) - 1u && !stopped_at_) {
                stopped_at_ = std::chrono::steady_clock::now();
            }
        }
    }

    void on_announcement(int k, const lcm::ReceiveBuffer* rbuf, const std::string& channel)
    {
        tvo_lcm::node_status_t status;
        const int length = node_open_[static_cast<std::size_t>(k)]->open(rbuf, channel);
        if (length < 0 || status.decode(rbuf->data, 0, length) != length) {
            return;
        }
        last_status_[static_cast<std::size_t>(k)] = status;
        plant_.publish(channel, rbuf->data, static_cast<unsigned int>(rbuf->data_size));
    }

    void complete_if_answered()
    {
        if (!awaiting_) {
            return;
        }
        for (int k = 0; k < nodes_; ++k) {
            const Answer& a = answers_[static_cast<std::size_t>(k)];
            if (expected_[static_cast<std::size_t>(k)] && !(a.command && (a.telemetry || !with_telemetry_))) {
                return;
            }
        }
        awaiting_ = false;
        ++periods_;
        compare();
        answer_plant();
    }

    // Agreement among the nodes that computed a command this period (status 0), by their joint digests.
    void compare()
    {
        std::vector<const tvo_lcm::telemetry_t*> computed;
        for (int k = 0; k < nodes_; ++k) {
            const Answer& a = answers_[static_cast<std::size_t>(k)];
            if (expected_[static_cast<std::size_t>(k)] && a.telemetry && a.tel.header.status == Header::STATUS_OK) {
                computed.push_back(&a.tel);
                predicted_ += static_cast<std::uint64_t>(std::max<int>(a.tel.predicted_robots, 0));
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
        // The nodes outside the largest group of equal digests (0: every node computed the same command).
        std::size_t largest = 0;
        for (const auto* t : computed) {
            const auto same_as_t = std::count_if(computed.begin(), computed.end(), [t](const tvo_lcm::telemetry_t* u) {
                return u->joint_digest == t->joint_digest;
            });
            largest = std::max(largest, static_cast<std::size_t>(same_as_t));
        }
        const std::size_t off = computed.size() - largest;
        if (off > 0) {
            last_mismatch_period_ = period_.sequence;
            ++mismatch_periods_;
            if (mismatch_series_.size() < kMaxSeries) {
                mismatch_series_.push_back({period_.sequence, static_cast<std::int64_t>(off)});
            }
            ++streak_;
            longest_streak_ = std::max(longest_streak_, streak_);
        } else {
            streak_ = 0;
        }
    }

    // One command per robot to tvo_sim, the period's joint command: robot r's from its own node, else the
    // row it holds (status 0, no flags: the plant applies it as the command in force); its telemetry likewise.
    void answer_plant()
    {
        const double h_s = static_cast<double>(start_.period_us) * 1e-6;
        for (int r = 0; r < robots_; ++r) {
            const Answer& a = answers_[static_cast<std::size_t>(r)];
            const bool came = expected_[static_cast<std::size_t>(r)] && a.command;
            const bool lost = came && dropped(1, r, nodes_, period_.sequence);
            dropped_commands_ += lost ? 1u : 0u;
            const bool fresh = came && !lost && a.cmd.header.status == Header::STATUS_OK;
            refused_rows_ += (came && a.cmd.header.status != Header::STATUS_OK) ? 1u : 0u;
            auto& held = held_[static_cast<std::size_t>(r)];
            if (fresh) {
                check_limits(r, a.cmd, h_s);
                held = {static_cast<double>(a.cmd.speed_mps), static_cast<double>(a.cmd.turn_rate_radps)};
            } else {
                if (came && !lost && (static_cast<std::uint32_t>(a.cmd.header.flags) &
                                      static_cast<std::uint32_t>(Header::FLAG_SAFE_STOP)) != 0u) {
                    held = {0.0, 0.0};
                } else {
                    ++held_rows_;
                }
                tvo_lcm::unicycle_command_t row{};
                row.header = held_header(r);
                row.speed_mps = static_cast<float>(held[0]);
                row.turn_rate_radps = static_cast<float>(held[1]);
                plant_auth_.publish(plant_, TVO_CHANNEL_COMMAND, row);
            }
            if (!with_telemetry_) {
                continue;
            }
            auto& last_tel = held_telemetry_[static_cast<std::size_t>(r)];
            if (fresh && a.telemetry) {
                last_tel = a.tel;  // passed on when it came
            } else {
                tvo_lcm::telemetry_t tel = last_tel;  // what robot r's node last said, restamped
                tel.header = held_header(r);
                plant_auth_.publish(plant_, TVO_CHANNEL_TELEMETRY, tel);
            }
        }
    }

    Header held_header(int r) const
    {
        Header h{};
        h.utime = period_.utime + start_.delay_us;
        h.session_id = period_.session_id;
        h.measurement_sequence = period_.sequence;
        h.robot = static_cast<std::int8_t>(r);
        h.status = Header::STATUS_OK;
        h.flags = 0;
        return h;
    }

    // A computed command against the session's limits; the speed step against the same node's last one.
    void check_limits(int r, const tvo_lcm::unicycle_command_t& c, double h_s)
    {
        const double v = c.speed_mps;
        const double w = c.turn_rate_radps;
        max_speed_ = std::max(max_speed_, std::fabs(v));
        max_turn_ = std::max(max_turn_, std::fabs(w));
        const double tol = 1e-6;
        bool bad = std::fabs(v) > start_.speed_max_mps * (1.0 + tol) || std::fabs(w) > start_.omega_max_radps * (1.0 + tol);
        auto& last = last_row_[static_cast<std::size_t>(r)];
        if (last && last->first == c.header.measurement_sequence - 1) {
            const double dv = std::fabs(v - last->second);
            max_speed_step_ = std::max(max_speed_step_, dv);
            bad = bad || dv > start_.accel_max_mps2 * h_s * (1.0 + tol) + 1e-9;
        }
        last = std::make_pair(static_cast<std::int64_t>(c.header.measurement_sequence), v);
        limit_violations_ += bad ? 1u : 0u;
    }

    const Options& o_;
    const int nodes_;
    lcm::LCM plant_;
    std::vector<std::unique_ptr<lcm::LCM>> node_bus_;
    std::vector<std::unique_ptr<NodeEnd>> node_ends_;
    AuthEnd plant_auth_;                              // tvo_sim's bus: opens its frames, signs the hub's own
    std::vector<std::unique_ptr<AuthEnd>> node_open_; // node k's bus: opens its frames
    std::vector<std::optional<tvo_lcm::node_status_t>> last_status_;
    std::uint64_t run_digest_{0xcbf29ce484222325ull};
    tvo_lcm::session_t start_{};
    int robots_{0};
    std::uint64_t stop_acked_{0};
    std::optional<std::chrono::steady_clock::time_point> stopped_at_;
    bool awaiting_{false};
    bool with_telemetry_{false};
    std::array<tvo_lcm::unicycle_sample_t, kMaxRobots> samples_{};  // the newest of each robot
    tvo_lcm::sample_header_t period_{};                             // the period's trigger
    std::vector<Answer> answers_;
    std::vector<bool> expected_;
    std::array<std::array<double, 2>, kMaxRobots> held_{};
    std::array<tvo_lcm::telemetry_t, kMaxRobots> held_telemetry_{};
    std::array<std::optional<std::pair<std::int64_t, double>>, kMaxRobots> last_row_{};
    std::uint64_t periods_{0}, compared_periods_{0}, mismatch_periods_{0}, streak_{0}, longest_streak_{0};
    std::uint64_t predicted_{0}, dropped_samples_{0}, dropped_commands_{0}, held_rows_{0}, refused_rows_{0};
    std::uint64_t limit_violations_{0};
    std::int64_t last_mismatch_period_{-1};
    static constexpr std::size_t kMaxSeries = 100000;
    std::vector<std::array<std::int64_t, 2>> mismatch_series_;
    double max_speed_{0.0}, max_turn_{0.0}, max_speed_step_{0.0};
    double min_pair_m_{std::numeric_limits<double>::infinity()};
};

}  // namespace

int main(int argc, char** argv)
{
    Options o;
    CLI::App app{"tvo_fleet_hub: the radio between tvo_sim and a fleet of per-robot nodes, each on its own LCM URL, "
                 "with loss per link"};
    app.add_option("--plant-url", o.plant_url, "LCM URL shared with tvo_sim")->required();
    app.add_option("--node-url", o.node_urls, "node k's LCM URL (it runs --own-robot k), once per node in robot order")
        ->required();
    app.add_option("--loss", o.loss, "probability that a link drops a period's message")->check(CLI::Range(0.0, 1.0));
    app.add_option("--loss-until-s", o.loss_until_s, "the links lose nothing from this plant time on (re-agreement)");
    app.add_option("--seed", o.seed, "seed of the loss pattern");
    app.add_option("--json", o.json_path, "write the agreement figures here (default: stdout)");
    app.add_option("--key-file", o.key_file, "open every frame on every bus with this key (tools/keygen); sign the "
                   "hub's own");
    app.add_option("--sender-id", o.sender_id, "the hub's sender id on a keyed bus (unique per key holder)")
        ->capture_default_str();
    const int parsed = tvo_options::parse_command_line(app, argc, argv, kProgram);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    if (o.node_urls.size() > static_cast<std::size_t>(kMaxRobots)) {
        return tvo_options::option_error(kProgram, "--node-url",
                                         "at most " + std::to_string(kMaxRobots) + " nodes (session_t.MAX_ROBOTS)");
    }
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    return tvo_options::run_reporting_errors(kProgram, [&o] {
        Hub hub(o);
        hub.run();
        hub.write_json();
        return hub.finished() ? 0 : 1;
    });
}
