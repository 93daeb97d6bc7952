// link-loss-node-clock: CLOCK_NODE on the wall clock. The plant samples at epoch + j h - tau of its
// own clock and goes silent for 1 s, three times. A node's safe stop can only be late, never early
// (asserted for every silence); its stamp says when it was published. On a loaded machine the node
// may be descheduled for longer than the period h = 50 ms that the bound leaves it (seen here: 130 ms
// stalls with both cores busy), so the upper bound must hold in at least one of the three silences,
// and every figure is printed.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "cases.hpp"

namespace campaign {

namespace {
// The plant's clock is CLOCK_MONOTONIC shifted by ~5.8 days, so a node that confused its clock with
// the plant's (or mapped it with the wrong sign) is off by days, not by a START's transit.
constexpr std::int64_t kPlantClockOffsetUs = 500000000000;
constexpr std::int64_t kEpochLeadUs = 300000;   // the epoch ahead of START, to get the ack first
constexpr std::int64_t kSilentPeriods = 20;     // 1 s without samples
constexpr std::int64_t kSilenceStarts[] = {61, 121, 181};   // after 3 s, 2 s and 2 s of tracking
constexpr std::int64_t kLastPeriod = 260;       // 3 s of tracking after the last silence
constexpr std::int64_t kSPerUs10 = 1000000;
// Error bound after the last silence at h = 50 ms: the wall-clock loop tracks at 0.6-0.9 mm here
// (measured, with load-delayed samples refused now and then); a robot that stayed stopped or lost
// track is decimetres to metres off within the 3 s.
constexpr double kTrackingBoundM = 0.02;

std::int64_t plant_now() { return monotonic_us() + kPlantClockOffsetUs; }

double ms(std::int64_t us) { return static_cast<double>(us) * 1e-3; }

struct Arrival {
    Command cmd;
    std::int64_t arrival_us;   // plant clock
};
}  // namespace

void case_link_loss_node_clock(Context& ctx)
{
    Timing timing;
    timing.clock_source = tvo_lcm::session_t::CLOCK_NODE;
    timing.period_us = 50000;
    timing.delay_us = 25000;
    timing.watchdog_periods = 4;
    const std::int64_t h = timing.period_us;
    const std::int64_t tau = timing.delay_us;
    const std::int64_t wd = timing.watchdog_periods;

    std::unique_ptr<NodeProcess> node;
    const std::int64_t known_boot = ctx.bus.node_boot();
    if (!ctx.node_path.empty()) {
        node = std::make_unique<NodeProcess>(ctx.node_path, ctx.lcm_url);
        node->spawn(false);
    }
    // Rule 1: the node's boot (a node just spawned announces a new one at once).
    const std::int64_t boot = node ? ctx.bus.await_boot(known_boot, std::chrono::seconds(20))
                                   : (known_boot != 0 ? known_boot : ctx.bus.await_boot(0, std::chrono::seconds(20)));
    if (boot == 0) {
        throw std::runtime_error("no node announced itself on " TVO_CHANNEL_NODE);
    }
    ctx.bus.clear();
    const std::int32_t id = ctx.new_session_id();
    tvo_lcm::session_t session = demo_session(id, plant_now(), plant_now() + kEpochLeadUs, timing, boot);
    const std::int64_t epoch = session.epoch_utime;

    // START stamped with the plant's clock, repeated every 100 ms until acknowledged.
    auto acked = [&] {
        return std::any_of(ctx.bus.acks.begin(), ctx.bus.acks.end(), [&](const tvo_lcm::session_ack_t& a) {
            return a.session_id == id && a.action == tvo_lcm::session_t::ACTION_START && a.boot_id == boot;
        });
    };
    const std::int64_t give_up = monotonic_us() + 20 * kSPerUs10;
    while (!acked()) {
        if (monotonic_us() > give_up) {
            throw std::runtime_error("no ack to the CLOCK_NODE START");
        }
        session.utime = plant_now();
        ctx.bus.publish(session);
        ctx.bus.wait_until(acked, std::chrono::milliseconds(100));
    }
    const auto ack = *std::find_if(ctx.bus.acks.begin(), ctx.bus.acks.end(), [&](const tvo_lcm::session_ack_t& a) {
        return a.session_id == id && a.action == tvo_lcm::session_t::ACTION_START;
    });
    if (ack.status != 0) {
        throw std::runtime_error("CLOCK_NODE START refused: " + status_text(ack.status));
    }

    // The plant: an exact unicycle; commands applied at their utime, or on arrival if late.
    std::array<tvo_host::UnicycleState, tvo_host::kMaxRobots> starts{};
    starts[0].position_m = Eigen::Vector2d(-1.0, -2.0);
    tvo_host::UnicyclePlant plant(1, starts);
    std::int64_t plant_us = plant_now();
    std::vector<std::pair<std::int64_t, tvo_host::UnicycleInput>> pending;
    std::int64_t in_force = -1;
    std::map<std::int64_t, std::int64_t> sent;   // sequence -> stamp
    std::vector<Arrival> arrivals;
    std::vector<std::pair<std::int64_t, double>> errors;
    std::size_t taken = 0;
    long late_commands = 0;
    auto take_commands = [&] {
        for (; taken < ctx.bus.commands.size(); ++taken) {
            const ReceivedCommand& rx = ctx.bus.commands[taken];
            const Command& cmd = rx.msg;
            const Header& ch = cmd.header;
            const std::int64_t arrival = rx.arrival_mono_us + kPlantClockOffsetUs;
            ctx.audit.add(cmd);
            arrivals.push_back({cmd, arrival});
            const bool safe_stop = (ch.flags & static_cast<std::int32_t>(Header::FLAG_SAFE_STOP)) != 0;
            const bool newer = sent.count(ch.measurement_sequence) != 0 && ch.measurement_sequence > in_force;
            if (ch.session_id != id || !(newer || safe_stop)) {
                continue;
            }
            in_force = std::max<std::int64_t>(in_force, ch.measurement_sequence);
            late_commands += (ch.utime < arrival && !safe_stop) ? 1 : 0;   // a safe stop is stamped now
            const std::int64_t at = std::max(ch.utime, arrival);
            const auto pos = std::upper_bound(pending.begin(), pending.end(), at,
                                              [](std::int64_t t, const auto& p) { return t < p.first; });
            pending.insert(pos, {at, tvo_host::UnicycleInput{cmd.speed_mps, cmd.turn_rate_radps}});
        }
    };
    auto advance = [&](std::int64_t t) {
        while (!pending.empty() && pending.front().first <= t) {
            const auto [at, input] = pending.front();
            pending.erase(pending.begin());
            if (at > plant_us) {
                plant.advance(static_cast<double>(at - plant_us) * 1e-6);
                plant_us = at;
            }
            plant.hold(0, input);
        }
        if (t > plant_us) {
            plant.advance(static_cast<double>(t - plant_us) * 1e-6);
            plant_us = t;
        }
    };
    auto sleep_until = [&](std::int64_t t) {
        while (plant_now() < t) {
            ctx.bus.wait_until(
                [&] {
                    take_commands();
                    return plant_now() >= t;
                },
                std::chrono::microseconds(std::max<std::int64_t>(t - plant_now(), 0)));
        }
        take_commands();
    };

    auto silent = [](std::int64_t j) {
        return std::any_of(std::begin(kSilenceStarts), std::end(kSilenceStarts),
                           [j](std::int64_t from) { return j >= from && j < from + kSilentPeriods; });
    };
    std::int64_t first_period = 1;
    while (epoch + first_period * h - tau <= plant_now() + 1000) {
        ++first_period;
    }
    for (std::int64_t j = first_period; j <= kLastPeriod; ++j) {
        sleep_until(epoch + j * h - tau);
        const std::int64_t now = plant_now();
        advance(now);
        double x = 0.0;
        double y = 0.0;
        demo_target(session, now, &x, &y);
        errors.emplace_back(now, (plant.state(0).position_m - Eigen::Vector2d(x, y)).norm());
        if (silent(j)) {
            continue;   // the link is down
        }
        Sample m{};
        m.header.utime = now;   // stamped when sampled, late or not
        m.header.session_id = id;
        m.header.sequence = static_cast<std::int32_t>(j - 1);
        m.header.robot = 0;
        m.has = tvo_lcm::unicycle_sample_t::HAS_HEADING | tvo_lcm::unicycle_sample_t::HAS_SPEED;
        m.position_m[0] = plant.state(0).position_m.x();
        m.position_m[1] = plant.state(0).position_m.y();
        m.heading_rad = static_cast<float>(std::remainder(plant.state(0).heading_rad, 2.0 * M_PI));
        m.speed_mps = static_cast<float>(plant.input(0).speed_mps);
        sent[m.header.sequence] = m.header.utime;
        ctx.bus.publish(m);
    }
    sleep_until(plant_now() + 300000);   // the last answers
    tvo_lcm::session_t stop = session;
    stop.action = tvo_lcm::session_t::ACTION_STOP;
    stop.utime = plant_now();
    ctx.bus.publish(stop);
    const bool stop_acked = ctx.bus.wait_until(
        [&] {
            return std::any_of(ctx.bus.acks.begin(), ctx.bus.acks.end(), [&](const tvo_lcm::session_ack_t& a) {
                return a.session_id == id && a.action == tvo_lcm::session_t::ACTION_STOP && a.status == 0;
            });
        },
        std::chrono::seconds(10));
    const int exit_code = node ? node->wait_exit(std::chrono::seconds(10)) : 0;
    take_commands();
    // Every command as the plant saw it, for a look at the timeline.
    std::ofstream csv("fault_campaign_link_loss_commands.csv");
    csv << "arrival_us,utime_us,sequence,status,flags,speed_mps,turn_rate_radps\n";
    for (const Arrival& a : arrivals) {
        const Header& ch = a.cmd.header;
        csv << a.arrival_us - epoch << ',' << ch.utime - epoch << ',' << ch.measurement_sequence << ','
            << static_cast<int>(ch.status) << ',' << ch.flags << ',' << a.cmd.speed_mps << ',' << a.cmd.turn_rate_radps
            << '\n';
    }
    std::ofstream samples_csv("fault_campaign_link_loss_samples.csv");
    samples_csv << "sequence,stamp_us\n";
    for (const auto& [sequence, stamp] : sent) {
        samples_csv << sequence << ',' << stamp - epoch << '\n';
    }
    Report& report = ctx.report;
    report.check(stop_acked && exit_code == 0, "run ends cleanly: STOP acked OK, the node exits with 0",
                 "exit code " + std::to_string(exit_code));

    // ---- The watchdog timer, per silence: the last accepted answer before it (its apply time), the
    // safe stops after that until the first accepted answer after the silence.
    struct Silence {
        std::int64_t last_accepted{-1};
        std::int64_t first_resumed{-1};
        std::vector<const Arrival*> stops;
    };
    std::vector<Silence> silences;
    for (const std::int64_t from : kSilenceStarts) {
        Silence sl;
        for (const Arrival& a : arrivals) {
            const Header& ch = a.cmd.header;
            const std::int64_t seq = ch.measurement_sequence;
            if (ch.session_id != id || ch.status != 0 || seq < 0) {
                continue;
            }
            if (seq <= from - 2) {   // sample j = seq + 1 before the silence
                sl.last_accepted = std::max(sl.last_accepted, ch.utime);
            } else if (seq >= from + kSilentPeriods - 1 && (sl.first_resumed < 0 || ch.utime < sl.first_resumed)) {
                sl.first_resumed = ch.utime;
            }
        }
        for (const Arrival& a : arrivals) {
            const Header& ch = a.cmd.header;
            if (ch.session_id == id && ch.measurement_sequence == -1 && ch.utime > sl.last_accepted &&
                (sl.first_resumed < 0 || ch.utime <= sl.first_resumed)) {
                sl.stops.push_back(&a);
            }
        }
        silences.push_back(sl);
    }
    long stops_total = 0;
    long stops_bad_fields = 0;
    long stamped_ahead = 0;
    std::int64_t max_latency = 0;
    for (const Arrival& a : arrivals) {
        const Header& ch = a.cmd.header;
        if (ch.session_id != id || ch.measurement_sequence != -1) {
            continue;
        }
        ++stops_total;
        stops_bad_fields += (ch.status != Header::STATUS_ERR_WATCHDOG ||
                             (ch.flags & static_cast<std::int32_t>(Header::FLAG_SAFE_STOP)) == 0 || ch.robot != 0)
                                ? 1
                                : 0;
        stamped_ahead += ch.utime > a.arrival_us ? 1 : 0;
        max_latency = std::max(max_latency, a.arrival_us - ch.utime);
    }
    bool never_early = true;
    bool one_in_time = false;
    bool all_repeat = true;
    std::ostringstream deltas;
    std::ostringstream repeats;
    for (const Silence& sl : silences) {
        const bool found = !sl.stops.empty() && sl.last_accepted >= 0;
        const std::int64_t delta = found ? sl.stops.front()->cmd.header.utime - sl.last_accepted : -1;
        never_early = never_early && found && delta >= wd * h;
        one_in_time = one_in_time || (found && delta >= wd * h && delta <= (wd + 1) * h);
        all_repeat = all_repeat && sl.stops.size() >= 2;
        deltas << (deltas.tellp() > 0 ? ", " : "") << (found ? fmt(ms(delta), 6) : std::string("none"));
        std::int64_t min_gap = 0;
        std::int64_t max_gap = 0;
        for (std::size_t i = 1; i < sl.stops.size(); ++i) {
            const std::int64_t gap = sl.stops[i]->cmd.header.utime - sl.stops[i - 1]->cmd.header.utime;
            min_gap = i == 1 ? gap : std::min(min_gap, gap);
            max_gap = std::max(max_gap, gap);
        }
        repeats << (repeats.tellp() > 0 ? "; " : "") << sl.stops.size() << " spaced " << fmt(ms(min_gap)) << ".."
                << fmt(ms(max_gap)) << " ms";
    }
    const std::string window =
        "[" + std::to_string(wd * h / 1000) + ", " + std::to_string((wd + 1) * h / 1000) + "] ms";
    report.check(never_early, "1 s without samples: never a safe stop before watchdog_periods*h (every silence)",
                 "first safe stop after the last accepted command's apply time: " + deltas.str() + " ms");
    report.check(one_in_time,
                 "1 s without samples: a safe stop within watchdog_periods*h + one period (the commands' stamps; "
                 "in at least one of the three silences)",
                 deltas.str() + " ms; window " + window);
    report.check(all_repeat && stops_bad_fields == 0,
                 "safe stops repeat during each silence, each STATUS_ERR_WATCHDOG, SAFE_STOP, sequence -1, robot 0",
                 repeats.str() + "; " + std::to_string(stops_bad_fields) + " of " + std::to_string(stops_total) +
                     " with other fields");
    report.check(stamped_ahead == 0, "safe stops stamped now (the node's clock mapped), never ahead of the plant's",
                 std::to_string(stamped_ahead) + " stamped after their arrival; arrival - stamp at most " +
                     fmt(ms(max_latency)) + " ms");

    // ---- Answers to samples.
    long answered = 0;
    long accepted_after = 0;
    long before_sample = 0;
    std::map<std::int32_t, long> refused;
    for (const Arrival& a : arrivals) {
        const Header& ch = a.cmd.header;
        if (ch.session_id != id || ch.measurement_sequence < 0) {
            continue;
        }
        ++answered;
        const auto it = sent.find(ch.measurement_sequence);
        before_sample += (it == sent.end() || ch.utime < it->second) ? 1 : 0;
        if (ch.status != 0) {
            ++refused[ch.status];
        } else if (ch.measurement_sequence >= kSilenceStarts[0] + kSilentPeriods - 1) {
            ++accepted_after;
        }
    }
    report.check(before_sample == 0, "no answer stamped before the sample it answers",
                 std::to_string(before_sample) + " of " + std::to_string(answered));
    std::string refusals;
    for (const auto& [status, count] : refused) {
        refusals += " " + status_text(status) + " x" + std::to_string(count);
    }
    report.note("samples refused (a loaded machine may delay some past their period)",
                refusals.empty() ? "none" : refusals);
    report.note("answers applied late (arrived after their utime, applied on arrival)", std::to_string(late_commands));
    const bool resumed =
        std::all_of(silences.begin(), silences.end(), [](const Silence& sl) { return sl.first_resumed >= 0; });
    report.check(resumed && accepted_after > 0, "samples are accepted again after each silence",
                 std::to_string(accepted_after) + " accepted after the first silence");
    double before_silence = 0.0;
    double final_error = 0.0;
    const std::int64_t silence_start = epoch + kSilenceStarts[0] * h;
    const std::int64_t end = errors.empty() ? 0 : errors.back().first;
    for (const auto& [t, e] : errors) {
        if (t < silence_start && t >= silence_start - kSPerUs10) {
            before_silence = std::max(before_silence, e);
        }
        if (t >= end - kSPerUs10) {
            final_error = std::max(final_error, e);
        }
    }
    report.note("error over the last second before the first silence", fmt(before_silence) + " m");
    report.check(std::isfinite(final_error) && final_error < kTrackingBoundM,
                 "the loop tracks again (error over the last 1 s)",
                 "max " + fmt(final_error) + " m, bound " + fmt(kTrackingBoundM) + " m");
}

}  // namespace campaign
