// The lockstep (CLOCK_PLANT) cases of the campaign. Every faulted run injects its faults between
// 3 s and 6 s of a 10 s run, so the loop has 4 s to track again; where the faults are extra messages
// (strays, garbage, duplicates, session requests) a run without them is the reference its genuine
// answers must equal bit for bit: nothing from a refused message may be kept.
#include "cases.hpp"
#include "tvo/controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

namespace campaign {

namespace {
constexpr std::int64_t kUsPerS = 1000000;
constexpr std::int64_t kEpochLimitUs = TVO_SESSION_EPOCH_SPAN_US;   // |epoch - start.utime| at most
constexpr std::int64_t kInt64Min = std::numeric_limits<std::int64_t>::min();
constexpr std::int32_t kInt32Max = std::numeric_limits<std::int32_t>::max();
constexpr std::int32_t kInt32Min = std::numeric_limits<std::int32_t>::min();
constexpr std::int32_t kAny = Expect::kAnyStatus;
constexpr std::uint64_t kSeed = 20240609;
// LCM's encoding: the 8-byte fingerprint, then the fields in order, big-endian (nested types inline).
// unicycle_sample_t and target_t begin with sample_header_t: utime (8 bytes), session_id (4);
// session_t with utime, protocol_version (4), session_id (4), action (1).
constexpr std::size_t kSampleSessionIdOffset = 16;
constexpr std::size_t kSampleSequenceOffset = 20;
constexpr std::size_t kSampleRobotOffset = 24;
constexpr std::size_t kActionOffset = 24;

}  // namespace

LockstepConfig base_config(Context& ctx)
{
    LockstepConfig c;
    c.session_id = ctx.new_session_id();
    c.start_pose.position_m = Eigen::Vector2d(-1.0, -2.0);
    c.start_pose.heading_rad = 0.0;
    return c;
}

namespace {

/// The same run without the faults (hook: what it sends instead, e.g. the same drops).
std::unique_ptr<LockstepRun> run_reference(Context& ctx, const LockstepRun::Hook& hook = {})
{
    auto ref = std::make_unique<LockstepRun>(ctx, base_config(ctx));
    ref->start();
    ref->run(hook);
    ref->stop();
    check_tracking(ctx.report, *ref, "reference run without the faults");
    return ref;
}

Sample restamped(Sample m, std::int64_t delta_us)
{
    m.header.utime += delta_us;
    return m;
}

Sample resequenced(Sample m, std::int32_t sequence)
{
    m.header.sequence = sequence;
    return m;
}

void put_be32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::int32_t value)
{
    const auto u = static_cast<std::uint32_t>(value);
    for (std::size_t i = 0; i < 4; ++i) {
        bytes[offset + i] = static_cast<std::uint8_t>(u >> (24 - 8 * i));
    }
}

/// The message's valid fingerprint followed by random bytes.
std::vector<std::uint8_t> random_body(std::mt19937_64& rng, std::vector<std::uint8_t> bytes)
{
    for (std::size_t i = 8; i < bytes.size(); ++i) {
        bytes[i] = static_cast<std::uint8_t>(rng());
    }
    return bytes;
}

template <class M>
M decoded(const std::vector<std::uint8_t>& bytes)
{
    M msg{};
    msg.decode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return msg;
}

/// Publishes raw bytes on TVO_SESSION and waits for the ack to (id, action).
tvo_lcm::session_ack_t raw_request(Context& ctx, const std::vector<std::uint8_t>& bytes)
{
    const auto msg = decoded<tvo_lcm::session_t>(bytes);
    const std::size_t first = ctx.bus.acks.size();
    std::size_t found = 0;
    auto acked = [&] {
        for (std::size_t i = first; i < ctx.bus.acks.size(); ++i) {
            if (ctx.bus.acks[i].session_id == msg.session_id && ctx.bus.acks[i].action == msg.action) {
                found = i;
                return true;
            }
        }
        return false;
    };
    ctx.bus.publish_raw(TVO_CHANNEL_SESSION, bytes);
    if (!ctx.bus.wait_until(acked, std::chrono::seconds(10))) {
        throw std::runtime_error("no ack to a session message with id " + std::to_string(msg.session_id) +
                                 " and action " + std::to_string(msg.action));
    }
    return ctx.bus.acks[found];
}

std::string ack_text(const tvo_lcm::session_ack_t& a)
{
    std::ostringstream out;
    out << status_text(a.status) << ", bad_param " << a.bad_param << " ("
        << tvo_protocol_param_str(a.bad_param) << "), part " << a.bad_part << " ("
        << tvo_protocol_part_str(a.bad_part) << "), index " << a.bad_index << ", running " << a.running_session_id
        << ", echoes id " << a.session_id << " action " << static_cast<int>(a.action) << " utime " << a.utime
        << ", boot " << a.boot_id;
    return out.str();
}

/// A refused START: the ack names what it should, and the running session is still `running`.
void check_refused_start(Report& report, const tvo_lcm::session_t& start, const tvo_lcm::session_ack_t& ack,
                         std::int32_t running, std::int32_t status, std::int32_t param, std::int32_t part,
                         std::int32_t index, const std::string& what)
{
    const bool ok = (status == kAny ? ack.status != 0 : ack.status == status) &&
                    (param < 0 || ack.bad_param == param) && (part < 0 || ack.bad_part == part) &&
                    (index < -1 || ack.bad_index == index) && ack.running_session_id == running &&
                    ack.session_id == start.session_id && ack.action == start.action && ack.utime == start.utime &&
                    ack.boot_id == start.node_boot_id[0] && ack.own_robot == -1;
    report.check(ok, what, ack_text(ack));
}

void finish(Context& ctx, const LockstepRun& run, const std::vector<std::int64_t>& faults,
            const LockstepRun* reference, long expected_accepted = -1)
{
    check_outcomes(ctx.report, run);
    check_genuine(ctx.report, run, faults, expected_accepted);
    if (reference != nullptr) {
        check_same_as_reference(ctx.report, *reference, run);
    }
    check_counters(ctx.report, run);
    check_tracking(ctx.report, run, "after the faults");
}
}  // namespace

// ---- Stamps --------------------------------------------------------------------------------------

void case_stray_future_stamp(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    run.run([](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        if (n == 300) {
            r.send_stray(restamped(m, kUsPerS), Header::STATUS_ERR_IMPLAUSIBLE_STAMP,
                         "a copy of sample 300 stamped +1 s, before the genuine one: refused, implausible stamp");
        } else if (n == 400) {
            r.send_stray(restamped(m, 20 * kUsPerS), Header::STATUS_ERR_IMPLAUSIBLE_STAMP,
                         "a copy of sample 400 stamped +20 s: refused, implausible stamp");
        } else if (n == 500) {
            auto bad = restamped(m, kUsPerS);
            bad.position_m[0] = std::numeric_limits<double>::quiet_NaN();
            r.send_stray(bad, kAny, "a sample with a NaN position stamped +1 s: refused");
        } else if (n == 550) {
            auto bad = restamped(m, kUsPerS);
            bad.header.robot = 7;
            r.send_refused_unanswered(bad, "a sample of robot 7 (the session has one) stamped +1 s: refused, "
                                           "counted, not answered (it steps no period)");
        }
        r.send_genuine(m);
        if (n == 600) {
            r.send_stray(restamped(m, kUsPerS), Header::STATUS_ERR_IMPLAUSIBLE_STAMP,
                         "a copy of sample 600 stamped +1 s, after the genuine one: refused, implausible stamp");
        }
    });
    run.stop();
    finish(ctx, run, {300, 400, 500, 550, 600}, ref.get());
}

void case_stray_past_stamp(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    const std::int64_t epoch = run.session().epoch_utime;
    const std::int64_t h = run.session().period_us;
    run.run([epoch, h](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        if (n == 0) {
            r.send_stray(restamped(m, -kUsPerS), Header::STATUS_ERR_IMPLAUSIBLE_STAMP,
                         "before the first genuine sample, a copy stamped 1 s before the epoch: refused, implausible");
        } else if (n == 300) {
            r.send_stray(restamped(m, -kUsPerS), Header::STATUS_ERR_OUT_OF_ORDER,
                         "a copy of sample 300 stamped -1 s: refused, out of order");
        } else if (n == 350) {
            r.send_stray(restamped(m, -h), Header::STATUS_ERR_OUT_OF_ORDER,
                         "a copy of sample 350 with the previous period's stamp: refused, out of order");
        } else if (n == 400) {
            auto bad = m;
            bad.header.utime = epoch - kUsPerS;
            r.send_stray(bad, Header::STATUS_ERR_IMPLAUSIBLE_STAMP, "a copy stamped 1 s before the epoch: refused, implausible");
        } else if (n == 450) {
            auto bad = m;
            bad.header.utime = 0;
            r.send_stray(bad, Header::STATUS_ERR_IMPLAUSIBLE_STAMP, "a copy stamped 0 (the wire's minimum): refused, implausible");
        } else if (n == 500) {
            auto bad = m;
            bad.header.utime = -1;
            r.send_stray(bad, kAny, "a copy stamped -1 (out of the wire range): refused", true);
        } else if (n == 550) {
            auto bad = m;
            bad.header.utime = kInt64Min;
            r.send_stray(bad, kAny, "a copy stamped INT64_MIN: refused", true);
        }
        r.send_genuine(m);
    });
    run.stop();
    finish(ctx, run, {0, 300, 350, 400, 450, 500, 550}, ref.get());
}

// ---- Garbage -------------------------------------------------------------------------------------

void case_garbage(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepConfig config = base_config(ctx);
    config.node_stderr_path = "fault_campaign_garbage_node.stderr";
    std::remove(config.node_stderr_path.c_str());
    LockstepRun run(ctx, config);
    run.start();
    std::mt19937_64 rng(kSeed);
    long undecodable_sure = 0;    // cannot decode: truncated, wrong fingerprint
    long undecodable_maybe = 0;   // over-long (a node may decode the prefix), empty, a burst UDP may thin
    long other_session_sent = 0;
    long targets_of_ours_sent = 0;
    const std::int32_t ours = run.session().session_id;
    const tvo_lcm::session_t session_template = run.session();
    // A random body but a plausible head (a START that names the node's boot and this protocol, so the
    // node checks it): what a corrupted or hostile START would need to be answered at all.
    auto session_garbage = [&](std::int8_t action, bool our_id) {
        tvo_lcm::session_t head = decoded<tvo_lcm::session_t>(random_body(rng, encode(session_template)));
        head.protocol_version = tvo_lcm::node_status_t::PROTOCOL_VERSION;
        head.action = action;
        head.robot_count = 1 + std::abs(head.robot_count % tvo_lcm::session_t::MAX_ROBOTS);  // names a boot
        for (std::int32_t r = 0; r < tvo_lcm::session_t::MAX_ROBOTS; ++r) {
            head.node_boot_id[r] = session_template.node_boot_id[0];
        }
        head.session_id = our_id ? ours : std::abs(head.session_id % 1000000) + 1;
        auto bytes = encode(head);
        bytes[kActionOffset] = static_cast<std::uint8_t>(action);
        return bytes;
    };
    run.run([&](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        const auto genuine_bytes = encode(m);
        Expect ignored;
        ignored.kind = Expect::Kind::Ignored;
        if (n >= 300 && n < 305) {
            const auto bytes = random_body(rng, genuine_bytes);
            const auto d = decoded<Sample>(bytes);
            ignored.session_id = d.header.session_id;
            ignored.sequence = d.header.sequence;
            ignored.label = n == 300 ? "valid unicycle_sample_t fingerprint, random body (so another session id): no answer"
                                     : "";
            r.send_raw(TVO_CHANNEL_SAMPLE, bytes, ignored);
            ++other_session_sent;
        } else if (n >= 310 && n < 315) {
            auto bytes = random_body(rng, genuine_bytes);
            put_be32(bytes, kSampleSessionIdOffset, ours);
            bytes[kSampleSequenceOffset] &= 0x7fu; // a sequence >= 0: a negative one is refused unanswered
            bytes[kSampleRobotOffset] = 0;   // robot 0: the period's last robot, whose sample is answered
            Expect refused;
            refused.kind = Expect::Kind::Refused;
            refused.match_by_order = true;
            refused.label = "valid fingerprint, random body with this session's id and robot 0 (" +
                            std::to_string(n - 309) + "/5): refused";
            r.send_raw(TVO_CHANNEL_SAMPLE, bytes, refused);
        } else if (n == 320) {
            // Truncated copies carry a sequence no genuine sample has: an answer to one would show.
            const auto copy = encode(resequenced(m, static_cast<std::int32_t>(n + 2000)));
            ignored.session_id = ours;
            ignored.sequence = n + 2000;
            for (const std::size_t length : {std::size_t{7}, std::size_t{8}, copy.size() / 2, copy.size() - 1}) {
                ignored.label = "a sample truncated to " + std::to_string(length) + " of " +
                                std::to_string(copy.size()) + " bytes: no answer";
                r.send_raw(TVO_CHANNEL_SAMPLE,
                           std::vector<std::uint8_t>(copy.begin(), copy.begin() + static_cast<long>(length)), ignored);
                ++undecodable_sure;
            }
            ignored.label = "an empty message on TVO_SAMPLE: no answer";
            r.send_raw(TVO_CHANNEL_SAMPLE, {}, ignored);
            ++undecodable_maybe;
        } else if (n == 330) {
            // A valid sample followed by extra bytes: not its channel's length, so no message of it
            // (lcm_types/README.md: a frame whose length is not its channel's size is malformed).
            for (const std::size_t extra : {std::size_t{1}, std::size_t{100}, std::size_t{3000}}) {
                auto prefix = encode(resequenced(m, static_cast<std::int32_t>(n + 1000)));
                std::vector<std::uint8_t> tail(extra);
                for (auto& b : tail) {
                    b = static_cast<std::uint8_t>(rng());
                }
                prefix.insert(prefix.end(), tail.begin(), tail.end());
                ignored.session_id = ours;
                ignored.sequence = n + 1000;
                ignored.label = "an over-long buffer (a valid sample + " + std::to_string(extra) +
                                " bytes): malformed, no answer";
                r.send_raw(TVO_CHANNEL_SAMPLE, prefix, ignored);
                ++undecodable_sure;
            }
        } else if (n == 340) {
            auto bytes = encode(resequenced(m, static_cast<std::int32_t>(n + 2000)));
            bytes[0] ^= 0xff;
            ignored.session_id = ours;
            ignored.sequence = n + 2000;
            ignored.label = "a genuine sample with a wrong fingerprint: no answer";
            r.send_raw(TVO_CHANNEL_SAMPLE, bytes, ignored);
            auto session_bytes = encode(session_template);
            session_bytes[0] ^= 0xff;
            ctx.bus.publish_raw(TVO_CHANNEL_SESSION, session_bytes);
            tvo_lcm::target_t target{};
            target.header.session_id = ours;
            auto target_bytes = encode(target);
            target_bytes[0] ^= 0xff;
            ctx.bus.publish_raw(TVO_CHANNEL_TARGET, target_bytes);
            undecodable_sure += 3;
            ctx.bus.publish_raw(TVO_CHANNEL_SESSION, {});
            ctx.bus.publish_raw(TVO_CHANNEL_TARGET, {});
            undecodable_maybe += 2;
        } else if (n == 350) {
            const auto bytes = session_garbage(0x55, false);
            const auto ack = raw_request(ctx, bytes);
            check_refused_start(ctx.report, decoded<tvo_lcm::session_t>(bytes), ack, ours, Header::STATUS_ERR_PARAM, -1, -1, -2,
                                "session_t with a random body and action 0x55: acked Header::STATUS_ERR_PARAM, session runs on");
        } else if (n >= 351 && n < 354) {
            const auto bytes = session_garbage(tvo_lcm::session_t::ACTION_START, false);
            const auto ack = raw_request(ctx, bytes);
            check_refused_start(ctx.report, decoded<tvo_lcm::session_t>(bytes), ack, ours, kAny, -1, -1, -2,
                                "a START with a random body (" + std::to_string(n - 350) +
                                    "/3): refused, the running session runs on");
        } else if (n == 354) {
            const auto bytes = session_garbage(tvo_lcm::session_t::ACTION_STOP, false);
            const auto ack = raw_request(ctx, bytes);
            check_refused_start(ctx.report, decoded<tvo_lcm::session_t>(bytes), ack, ours, Header::STATUS_ERR_NO_SESSION, -1, -1,
                                -2,
                                "a STOP with a random body (another id): acked Header::STATUS_ERR_NO_SESSION, session runs on");
        } else if (n == 355) {
            const auto bytes = session_garbage(tvo_lcm::session_t::ACTION_START, true);
            const auto ack = raw_request(ctx, bytes);
            check_refused_start(ctx.report, decoded<tvo_lcm::session_t>(bytes), ack, ours, kAny, -1, -1, -2,
                                "a START with a random body and the running id: refused, the session runs on");
        } else if (n == 356) {
            const auto bytes = encode(session_template);
            ctx.bus.publish_raw(TVO_CHANNEL_SESSION, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 30));
            ctx.bus.publish_raw(TVO_CHANNEL_SESSION, std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 1));
            undecodable_sure += 2;
        } else if (n >= 360 && n < 364) {
            tvo_lcm::target_t target{};
            auto bytes = random_body(rng, encode(target));
            if (n >= 362) {
                put_be32(bytes, kSampleSessionIdOffset, ours);
                ++targets_of_ours_sent;   // a target to a session without streamed targets: refused, counted
            } else {
                ++other_session_sent;
            }
            ctx.bus.publish_raw(TVO_CHANNEL_TARGET, bytes);
        } else if (n == 364) {
            const auto bytes = encode(tvo_lcm::target_t{});
            ctx.bus.publish_raw(TVO_CHANNEL_TARGET, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 20));
            ctx.bus.publish_raw(TVO_CHANNEL_TARGET, std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 1));
            undecodable_sure += 2;
        } else if (n == 400) {
            // A burst, for the node's stderr: its lines are rate-limited, not one per message. Paced
            // in tens, as a burst of hundreds overflows a socket's receive buffer (seen: the genuine
            // sample behind it lost); the genuine sample is sent again until answered.
            const auto half = static_cast<long>(genuine_bytes.size() / 2);
            const std::vector<std::uint8_t> truncated(genuine_bytes.begin(), genuine_bytes.begin() + half);
            for (int i = 0; i < 200; ++i) {
                ctx.bus.publish_raw(TVO_CHANNEL_SAMPLE, truncated);
                if (i % 10 == 9) {
                    ctx.bus.pump(std::chrono::milliseconds(2));
                }
            }
            undecodable_maybe += 200;
            r.send_genuine_until_answered(m);
            return;
        }
        r.send_genuine(m);
    });
    run.stop();
    finish(ctx, run, {300, 301, 302, 303, 304, 310, 311, 312, 313, 314, 320, 330, 340, 350, 351, 352, 353, 354, 355,
                      356, 360, 361, 362, 363, 364, 400},
           ref.get());
    const auto& c = run.counters();
    const long malformed = c ? c->malformed : -1;
    ctx.report.check(malformed >= undecodable_sure && malformed <= undecodable_sure + undecodable_maybe,
                     "malformed messages counted",
                     std::to_string(malformed) + " counted; sent " + std::to_string(undecodable_sure) +
                         " that are no message of their channel + " + std::to_string(undecodable_maybe) +
                         " empty or in a burst");
    const long other = c ? c->other_session : -1;
    ctx.report.check(other == other_session_sent, "samples and targets of another session id counted, ignored",
                     std::to_string(other) + " counted of " + std::to_string(other_session_sent) + " sent");
    const long targets = c ? c->targets_refused : -1;
    ctx.report.check(targets == targets_of_ours_sent, "targets with this session's id and a random body refused, counted",
                     std::to_string(targets) + " counted of " + std::to_string(targets_of_ours_sent) + " sent");
    const long lines = count_lines(config.node_stderr_path);
    // ~215 undecodable messages within a second or two: one line per reason per second leaves a few.
    ctx.report.check(lines <= 40, "the node's stderr is rate-limited",
                     std::to_string(lines) + " lines for about " +
                         std::to_string(undecodable_sure + undecodable_maybe) + " undecodable messages");
}

void case_huge_sequence(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    run.run([](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        if (n == 300) {
            r.send_stray(resequenced(m, std::int32_t{1} << 30), Header::STATUS_ERR_IMPLAUSIBLE_STAMP,
                         "a copy of sample 300 with sequence 2^30, genuine stamp: refused, implausible");
        } else if (n == 350) {
            r.send_stray(resequenced(m, kInt32Max), Header::STATUS_ERR_IMPLAUSIBLE_STAMP,
                         "sequence INT32_MAX (the wire's largest): refused, implausible");
        } else if (n == 400) {
            // Unanswered: an answer would echo it, and sequence -1 is the node's own stop.
            r.send_refused_unanswered(resequenced(m, -1), "sequence -1: refused, counted, not answered");
        } else if (n == 450) {
            r.send_refused_unanswered(resequenced(m, kInt32Min), "sequence INT32_MIN: refused, counted, not answered");
        }
        r.send_genuine(m);
        if (n == 600) {
            // Its stamp is the genuine one's: its period is already served (the spec checks that first).
            r.send_stray(resequenced(m, std::int32_t{1} << 30), Header::STATUS_ERR_OUT_OF_ORDER,
                         "sequence 2^30 after the genuine sample 600 (same stamp): refused, out of order");
        }
    });
    run.stop();
    finish(ctx, run, {300, 350, 400, 450, 600}, ref.get());
}

void case_duplicates(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    std::vector<Sample> sent;
    run.run([&sent](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        if (n == 450) {
            r.send_stray(sent.back(), Header::STATUS_ERR_OUT_OF_ORDER,
                         "sample 449 again, before sample 450: refused, out of order");
        }
        r.send_genuine(m);
        sent.push_back(m);
        if (n == 300) {
            r.send_stray(m, Header::STATUS_ERR_OUT_OF_ORDER, "sample 300 twice: the copy refused, out of order");
        } else if (n == 350) {
            for (int k = 1; k <= 3; ++k) {
                r.send_stray(m, Header::STATUS_ERR_OUT_OF_ORDER,
                             "sample 350 four times: copy " + std::to_string(k) + " refused, out of order");
            }
        } else if (n == 400) {
            r.send_stray(sent[sent.size() - 6], Header::STATUS_ERR_OUT_OF_ORDER,
                         "sample 395 again after 400: refused, out of order");
        }
    });
    run.stop();
    finish(ctx, run, {300, 350, 400, 450}, ref.get());
}

void case_reordering(Context& ctx)
{
    // The reference loses the two samples the faulted run delivers late: a late sample's refusal
    // must leave the node exactly as if it had never arrived.
    const auto late = [](std::int64_t n) { return n == 300 || n == 400; };
    const auto ref = run_reference(ctx, [&late](LockstepRun& r, std::int64_t n) {
        if (!late(n)) {
            r.send_genuine(r.measure(n));
        }
    });
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    Sample withheld{};
    run.run([&](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        if (late(n)) {
            withheld = m;
            return;
        }
        r.send_genuine(m);
        if (late(n - 1)) {
            r.send_genuine_refused(withheld, Header::STATUS_ERR_OUT_OF_ORDER,
                                   "sample " + std::to_string(n - 1) + " delivered after sample " + std::to_string(n) +
                                       ": refused, out of order");
        }
    });
    run.stop();
    finish(ctx, run, {301, 401}, ref.get(), run.genuine_sent - 2);
}

// ---- Loss ----------------------------------------------------------------------------------------

void case_loss(Context& ctx)
{
    for (const int percent : {0, 10, 30, 50}) {
        LockstepRun run(ctx, base_config(ctx));
        run.start();
        std::mt19937_64 rng(kSeed + static_cast<std::uint64_t>(percent));
        long dropped = 0;
        const std::int64_t lossy_from = 300;
        const std::int64_t lossy_to = 600;   // samples lost from 3 s (converged) to 6 s, then 4 s without
        run.run([&](LockstepRun& r, std::int64_t n) {
            if (n >= lossy_from && n < lossy_to && static_cast<int>(rng() % 100) < percent) {
                ++dropped;
                return;
            }
            r.send_genuine(r.measure(n));
        });
        run.stop();
        const std::string tag = std::to_string(percent) + " % lost: ";
        ctx.report.note(tag + "samples dropped (seeded) between 3 s and 6 s", std::to_string(dropped) + " of " +
                                                                               std::to_string(lossy_to - lossy_from));
        check_genuine(ctx.report, run, {});
        check_counters(ctx.report, run);
        // While samples are lost the robot holds each command over the gap: the error grows with the
        // gaps (measured: 1.3e-4 m without loss, 3 mm at 10 %, 7 mm at 30 %, 1.6 cm at 50 %). 5 cm says
        // the loop still tracks: a robot that stopped falls behind a target moving at 1-2 m/s by
        // metres over these 3 s.
        const double lossy = run.max_error_between(run.apply_utime(lossy_from), run.apply_utime(lossy_to));
        ctx.report.check(std::isfinite(lossy) && lossy < 0.05, tag + "the loop keeps tracking while samples are lost",
                         "max error from 3 s to 6 s " + fmt(lossy) + " m, bound 0.05 m");
        check_tracking(ctx.report, run, tag + "after the loss");
    }
}

// ---- The CLOCK_PLANT watchdog --------------------------------------------------------------------

void case_refusal_watchdog(Context& ctx)
{
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    const std::int64_t wd = run.session().watchdog_periods;
    Sample previous{};
    run.run([&](LockstepRun& r, std::int64_t n) {
        const auto m = r.measure(n);
        if (n >= 300 && n < 300 + wd + 2) {
            // Instead of its sample, the plant's link repeats the last one: refused every period.
            r.send_stray(previous, Header::STATUS_ERR_OUT_OF_ORDER,
                         "refusal " + std::to_string(n - 299) + " of " + std::to_string(wd + 2) +
                             " in a row (sample 299 repeated)");
            return;
        }
        if (n >= 300 + wd + 2 && n < 300 + wd + 4) {
            // The stream jumped wd + 3 periods past sample 299, more than the watchdog's span: served
            // once three samples agree on it, so its first two are refused, after the streak with a stop.
            r.send_genuine_refused(m, Header::STATUS_ERR_WATCHDOG,
                                   "after the streak, genuine sample " + std::to_string(n - 300 - wd - 1) +
                                       " of 2 before three agree on the jump: a safe stop");
            previous = m;
            return;
        }
        r.send_genuine(m);
        previous = m;
    });
    run.stop();
    long first_safe_stop = -1;
    long index = 0;
    for (const auto& o : run.outcomes()) {
        ++index;
        if ((o.flags & static_cast<std::int32_t>(Header::FLAG_SAFE_STOP)) != 0 && first_safe_stop < 0) {
            first_safe_stop = index;
        }
    }
    ctx.report.check(first_safe_stop == wd || first_safe_stop == wd + 1,
                     "after watchdog_periods consecutive refusals the answer is a safe stop",
                     "first safe stop answers refusal " + std::to_string(first_safe_stop) + ", watchdog_periods " +
                         std::to_string(wd));
    // The two genuine samples refused while three agree on the jump are held periods of their own.
    finish(ctx, run, {300, 300 + wd + 2, 300 + wd + 3}, nullptr, run.genuine_sent - 2);
}

// ---- Sessions ------------------------------------------------------------------------------------

void case_rejected_start_during_run(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    const std::int32_t ours = run.session().session_id;
    struct BadStart {
        std::int64_t at;
        std::function<void(tvo_lcm::session_t&)> spoil;
        std::int32_t status;
        std::int32_t param;
        std::int32_t part;
        std::int32_t index;
        std::string what;
    };
    const std::vector<BadStart> bad = {
        {300, [](tvo_lcm::session_t& s) { s.gain_kp = -1.0; }, Header::STATUS_ERR_PARAM, tvo_lcm::session_ack_t::PARAM_GAINS, -1, -2,
         "a START with a new id and gain_kp = -1: refused naming the gains"},
        {320, [](tvo_lcm::session_t& s) { s.watchdog_periods = 0; }, Header::STATUS_ERR_PARAM, tvo_lcm::session_ack_t::PARAM_WATCHDOG, -1, -2,
         "a START with watchdog_periods = 0: refused naming the watchdog"},
        {340, [](tvo_lcm::session_t& s) { s.period_us = std::int64_t{1} << 31; }, Header::STATUS_ERR_PARAM, tvo_lcm::session_ack_t::PARAM_PERIOD,
         -1, -2, "a START with period_us = 2^31 (out of the wire range): refused naming the period"},
        {360, [](tvo_lcm::session_t& s) { s.delay_us = s.period_us + 1; }, Header::STATUS_ERR_PARAM, tvo_lcm::session_ack_t::PARAM_DELAY, -1, -2,
         "a START with delay_us = period_us + 1: refused naming the delay"},
        {380,
         [](tvo_lcm::session_t& s) {
             s.robot_count = tvo_lcm::session_t::MAX_ROBOTS;
             std::fill(std::begin(s.node_boot_id), std::end(s.node_boot_id), s.node_boot_id[0]);
         },
         kAny,
         tvo_lcm::session_ack_t::PARAM_ROBOT_COUNT, -1, -2,
         "a START of 32 robots (every one naming this node's boot) to a node of fewer: refused naming the robot count"},
        {400,
         [](tvo_lcm::session_t& s) { s.robot[0].target.semi_axis_m[0] = std::numeric_limits<double>::quiet_NaN(); },
         kAny, -1, tvo_lcm::session_ack_t::PART_ROBOTS, 0,
         "a START with a NaN semi-axis in robot 0's target: refused naming part robots, index 0"},
        {420, [](tvo_lcm::session_t& s) { s.clock_source = 7; }, kAny, -1, -1, -2,
         "a START with clock_source = 7: refused"},
        {440, [](tvo_lcm::session_t& s) { s.epoch_utime = -1; }, Header::STATUS_ERR_PARAM, -1, -1, -2,
         "a START with epoch_utime = -1 (out of the wire range): refused"},
        {460, [](tvo_lcm::session_t& s) { s.protocol_version = 2; }, Header::STATUS_ERR_PARAM,
         tvo_lcm::session_ack_t::PARAM_PROTOCOL_VERSION, -1, -2,
         "a START of protocol version 2: refused naming the protocol version"},
        {480, [](tvo_lcm::session_t& s) { s.telemetry_every = -1; }, Header::STATUS_ERR_PARAM,
         tvo_lcm::session_ack_t::PARAM_TELEMETRY_EVERY, -1, -2,
         "a START with telemetry_every = -1: refused naming the telemetry rate"},
    };
    long other_boot_acks = -1;
    run.run([&](LockstepRun& r, std::int64_t n) {
        r.send_genuine(r.measure(n));
        r.settle();
        for (const BadStart& b : bad) {
            if (b.at == n) {
                tvo_lcm::session_t start = r.session();
                start.session_id = ctx.new_session_id();
                start.utime = r.now_us();
                b.spoil(start);
                const auto ack = r.request(start);
                check_refused_start(ctx.report, start, ack, ours, b.status, b.param, b.part, b.index, b.what);
            }
        }
        if (n == 500) {
            // A START and a STOP that name another boot of the node (a recording from before a restart, or
            // meant for another node), and a START of no robot (it names no boot): dropped unanswered,
            // counted wrong_boot.
            const std::size_t acks = ctx.bus.acks.size();
            tvo_lcm::session_t start = r.session();
            start.session_id = ctx.new_session_id();
            start.utime = r.now_us();
            start.node_boot_id[0] = r.boot() + 1000;
            ctx.bus.publish(start);
            tvo_lcm::session_t stop = r.session();
            stop.action = tvo_lcm::session_t::ACTION_STOP;
            stop.utime = r.now_us();
            stop.node_boot_id[0] = r.boot() + 1000;
            ctx.bus.publish(stop);
            tvo_lcm::session_t none = r.session();
            none.session_id = ctx.new_session_id();
            none.utime = r.now_us();
            none.robot_count = 0;
            ctx.bus.publish(none);
            ctx.bus.pump(std::chrono::milliseconds(200));
            other_boot_acks = static_cast<long>(ctx.bus.acks.size() - acks);
        }
    });
    run.stop();
    const long wrong_boot = run.counters() ? run.counters()->wrong_boot : -1;
    ctx.report.check(other_boot_acks == 0 && wrong_boot == 3,
                     "a START (new id) and a STOP of the running id that name another boot, and a START of no robot: "
                     "no ack, counted wrong_boot, the session runs on",
                     std::to_string(other_boot_acks) + " acks in 200 ms, wrong_boot " + std::to_string(wrong_boot));
    finish(ctx, run, {300, 320, 340, 360, 380, 400, 420, 440, 460, 480, 500}, ref.get());
}

void case_same_id_start(Context& ctx)
{
    const auto ref = run_reference(ctx);
    LockstepRun run(ctx, base_config(ctx));
    run.start();
    const std::int32_t ours = run.session().session_id;
    run.run([&](LockstepRun& r, std::int64_t n) {
        r.send_genuine(r.measure(n));
        r.settle();
        tvo_lcm::session_t start = r.session();
        start.utime = r.now_us();
        if (n == 300 || n == 400 || n == 450) {
            std::string what;
            if (n == 300) {
                start.gain_kp = 30.0;
                what = "the running id with gain_kp 30 instead of 40";
            } else if (n == 400) {
                start.clock_source = tvo_lcm::session_t::CLOCK_NODE;
                what = "the running id with clock_source CLOCK_NODE";
            } else {
                start.robot[0].target.phase_rad = 0.5;
                what = "the running id with another target phase";
            }
            const auto ack = r.request(start);
            check_refused_start(ctx.report, start, ack, ours, Header::STATUS_ERR_SESSION_CONFLICT, -1, -1, -2,
                                "a START with " + what + ": refused Header::STATUS_ERR_SESSION_CONFLICT, runs on");
        } else if (n == 350 || n == 500) {
            const auto ack = r.request(start);
            const auto& original = r.start_ack();
            const bool same = ack.status == original.status && ack.bad_param == original.bad_param &&
                              ack.bad_part == original.bad_part && ack.bad_index == original.bad_index &&
                              ack.running_session_id == ours && ack.session_id == ours &&
                              ack.action == tvo_lcm::session_t::ACTION_START;
            ctx.report.check(same,
                             "a START identical but for its utime (" + std::to_string(start.utime) +
                                 "): the original ack repeated, no restart",
                             ack_text(ack) + "; original ack utime " + std::to_string(original.utime));
        }
    });
    run.stop();
    // The genuine answers equal the reference's bit for bit: no restart, no parameter taken over.
    finish(ctx, run, {300, 350, 400, 450, 500}, ref.get());
}

void case_implausible_epoch(Context& ctx)
{
    LockstepConfig config = base_config(ctx);
    // A session whose epoch is as far before its START as the wire allows.
    config.start_utime_us = 2000 * kUsPerS;
    config.epoch_utime_us = config.start_utime_us - kEpochLimitUs;
    const std::int64_t h = config.timing.period_us;
    const std::int64_t first_period = (config.start_utime_us - config.epoch_utime_us + config.timing.delay_us) / h + 1;
    config.first_sequence = first_period - 1;
    config.periods = 600;
    LockstepRun run(ctx, config);
    run.prepare();
    const std::int64_t start_utime = config.start_utime_us;
    auto refused_epoch = [&](std::int64_t epoch, std::int32_t running, const std::string& what) {
        tvo_lcm::session_t start = demo_session(ctx.new_session_id(), start_utime, epoch, config.timing, run.boot());
        const auto ack = run.request(start, std::chrono::milliseconds(100));
        check_refused_start(ctx.report, start, ack, running, Header::STATUS_ERR_PARAM, tvo_lcm::session_ack_t::PARAM_EPOCH, -1, -2, what);
    };
    refused_epoch(start_utime - 20 * 60 * kUsPerS, -1,
                  "no session: a START whose epoch is 20 min before it: refused naming the epoch");
    refused_epoch(start_utime + 20 * 60 * kUsPerS, -1,
                  "no session: a START whose epoch is 20 min after it: refused naming the epoch");
    refused_epoch(start_utime - kEpochLimitUs - 1, -1,
                  "no session: a START whose epoch is 1 us further before it than TVO_SESSION_EPOCH_SPAN_US: refused naming the epoch");
    run.start();
    ctx.report.check(run.start_ack().status == 0 && run.start_ack().running_session_id == run.session().session_id,
                     "a START whose epoch is TVO_SESSION_EPOCH_SPAN_US before it (the limit): acked OK",
                     "epoch " + std::to_string(config.epoch_utime_us) + ", START utime " + std::to_string(start_utime) +
                         ": " + ack_text(run.start_ack()));
    const std::int32_t ours = run.session().session_id;
    run.run([&](LockstepRun& r, std::int64_t n) {
        r.send_genuine(r.measure(n));
        if (n == config.first_sequence + 200) {
            r.settle();
            refused_epoch(r.now_us() - 20 * 60 * kUsPerS, ours,
                          "during a run: a START with a new id and an epoch 20 min before it: refused naming the "
                          "epoch, the session runs on");
        }
    });
    run.stop();
    const auto& answers = run.genuine_answers();
    const auto first = answers.find(config.first_sequence);
    ctx.report.check(first != answers.end() && first->second.status == 0,
                     "the first sample after that START (stamped " +
                         std::to_string(run.sample_utime(config.first_sequence) - start_utime) +
                         " us after it) is accepted: an epoch the START accepts is one the session can serve",
                     first == answers.end() ? "no answer" : status_text(first->second.status));
    // The robot starts 4.5 m from its target here too; tracked after 6 s as in every case.
    finish(ctx, run, {config.first_sequence + 200}, nullptr);
}

void case_node_restart(Context& ctx)
{
    if (ctx.node_path.empty()) {
        throw std::runtime_error("node-restart kills and restarts the node: it needs --node PATH");
    }
    LockstepConfig config = base_config(ctx);
    config.node_stderr_path = "fault_campaign_node_restart_node.stderr";
    std::remove(config.node_stderr_path.c_str());
    LockstepRun run(ctx, config);
    run.start();
    const std::int64_t crash_at = 400;
    std::int64_t old_boot = 0;
    run.run([&](LockstepRun& r, std::int64_t n) {
        if (n != crash_at) {
            r.send_genuine(r.measure(n));
            return;
        }
        r.settle();
        old_boot = r.boot();
        r.crash_node_and_restart();   // returns once the new process announced its (new) boot
        // The plant's sample before it acts on the announcement: the new node has no session and drops
        // it unanswered (counted idle). No safe stop either: the plant learns the restart from TVO_NODE.
        r.send_expecting(r.measure(n), Expect::Kind::Ignored,
                         "node killed (SIGKILL) and restarted: the next sample is dropped unanswered");
        r.settle();
        r.restart_session();   // rule 5: START again naming the new boot, then go on
        ctx.report.check(r.start_ack().status == 0 && r.start_ack().running_session_id == r.session().session_id &&
                             r.boot() > old_boot && r.start_ack().boot_id == r.boot(),
                         "the new node announces a new boot; the plant's START naming it is acked OK",
                         "boot " + std::to_string(old_boot) + " then " + std::to_string(r.boot()) + "; " +
                             ack_text(r.start_ack()));
    });
    run.stop();
    check_outcomes(ctx.report, run);
    check_genuine(ctx.report, run, {crash_at}, run.genuine_sent - 1);
    const long idle = run.final_counters() ? run.final_counters()->idle : -1;
    ctx.report.check(idle == 1, "the new boot counted the sample it dropped while idle (its counters since it started)",
                     "idle " + std::to_string(idle));
    check_tracking(ctx.report, run, "after the node restart");
}

void case_plant_restart(Context& ctx)
{
    LockstepConfig config_a = base_config(ctx);
    config_a.keep_running = true;
    config_a.periods = 400;
    LockstepRun old_plant(ctx, config_a);
    old_plant.start();
    old_plant.run();   // the plant process dies here, without STOP
    // The new plant process: its robot stopped where the old one left it (the robot's own watchdog),
    // a new session id, its own epoch.
    LockstepConfig config_b = base_config(ctx);
    config_b.spawn_node = false;
    config_b.keep_running = true;
    config_b.start_utime_us = old_plant.now_us() + kUsPerS;
    config_b.epoch_utime_us = config_b.start_utime_us;
    config_b.start_pose = old_plant.robot();
    LockstepRun plant(ctx, config_b);
    plant.start();
    ctx.report.check(plant.start_ack().status == 0 && plant.start_ack().running_session_id == config_b.session_id,
                     "the restarted plant's START (new id) replaces the running session", ack_text(plant.start_ack()));
    const std::int32_t old_id = config_a.session_id;
    std::int32_t old_sequence = 400;
    long old_sent = 0;
    plant.run([&](LockstepRun& r, std::int64_t n) {
        if (n < 200 && n % 10 == 0) {
            // The old plant's samples still arrive (a lagging link, a zombie process): ignored.
            Sample stale = old_plant.measure(old_sequence);
            stale.header.utime = old_plant.sample_utime(old_sequence);
            ++old_sequence;
            r.send_expecting(stale, Expect::Kind::Ignored,
                             n == 0 ? "the old session's samples: no answer (20 of them)" : "");
            ++old_sent;
        }
        if (n == 50) {
            tvo_lcm::target_t target{};
            target.header.session_id = old_id;
            target.header.utime = old_plant.sample_utime(old_sequence);
            target.header.robot = 0;
            ctx.bus.publish(target);
            ++old_sent;
        }
        r.send_genuine(r.measure(n));
        if (n == 100) {
            r.settle();
            tvo_lcm::session_t stop = old_plant.session();
            stop.action = tvo_lcm::session_t::ACTION_STOP;
            stop.utime = old_plant.sample_utime(old_sequence);
            const auto ack = r.request(stop);
            check_refused_start(ctx.report, stop, ack, config_b.session_id, Header::STATUS_ERR_NO_SESSION, -1, -1, -2,
                                "the old session's STOP: acked Header::STATUS_ERR_NO_SESSION, the new session runs on");
        }
    });
    plant.stop();
    check_outcomes(ctx.report, plant);
    check_genuine(ctx.report, plant, {});
    check_counters(ctx.report, plant);
    const long other = plant.counters() ? plant.counters()->other_session : -1;
    ctx.report.check(other == old_sent, "the old session's samples and target are counted as another session's",
                     std::to_string(other) + " counted of " + std::to_string(old_sent) + " sent");
    ctx.report.check(old_plant.node() == nullptr || old_plant.node()->running(),
                     "with --keep-running the node serves on after the new session's STOP",
                     old_plant.node() == nullptr ? "external node" : "still running");
    check_tracking(ctx.report, plant, "the restarted plant");
}

// ---- A plant that lies about its speed ------------------------------------------------------------

void case_speed_mismatch(Context& ctx)
{
    auto flagged = [](const LockstepRun& run, std::int64_t from, std::int64_t to) {
        const auto mismatch = static_cast<std::int32_t>(TVO_FLAG_SPEED_MISMATCH);
        long count = 0;
        std::int64_t first = -1;
        for (const auto& [seq, answer] : run.genuine_answers()) {
            if (seq >= from && seq < to && (answer.flags & mismatch) != 0) {
                first = first < 0 ? seq : first;
                ++count;
            }
        }
        return std::make_pair(count, first);
    };
    const auto ref = run_reference(ctx);
    const auto [false_alarms, first_false] = flagged(*ref, 0, 1000);
    ctx.report.check(false_alarms == 0,
                     "no speed mismatch flagged in the run without faults (start from rest included)",
                     std::to_string(false_alarms) + " flagged" +
                         (first_false >= 0 ? ", first at sample " + std::to_string(first_false) : ""));
    const std::int64_t from = 300;
    const std::int64_t to = 500;   // 2 s
    struct Variant {
        bool stall;
        std::string what;
    };
    for (const Variant& v : {Variant{false, "a plant that reports 0 m/s while it moves as commanded"},
                             Variant{true, "stalled wheels: the robot stands still and reports 0 m/s"}}) {
        LockstepRun run(ctx, base_config(ctx));
        run.start();
        run.run([&](LockstepRun& r, std::int64_t n) {
            r.set_stalled(v.stall && n >= from && n < to);
            auto m = r.measure(n);
            if (n >= from && n < to) {
                m.speed_mps = 0.0f;
            }
            r.send_genuine(m);
        });
        run.stop();
        const auto [during, first] = flagged(run, from, to);
        const double error = run.max_error_between(run.apply_utime(from), run.apply_utime(to));
        ctx.report.check(first >= from && first <= from + static_cast<std::int64_t>(TVO_SPEED_MISMATCH_PERIODS),
                         v.what + " for 2 s: flagged TVO_FLAG_SPEED_MISMATCH within its periods",
                         "first flagged at sample " + (first < 0 ? std::string("none") : std::to_string(first)) +
                             " (from " + std::to_string(from) + "), " + std::to_string(during) + " of " +
                             std::to_string(to - from) + " flagged; meanwhile the error reached " + fmt(error) + " m");
        // Acted on: stopped (status 0, SAFE_STOP with the flag) within the stop's periods, and held
        // stopped for the holdoff's periods each time.
        const auto stop_flags = static_cast<std::int32_t>(Header::FLAG_SAFE_STOP | TVO_FLAG_SPEED_MISMATCH);
        std::int64_t first_stop = -1;
        long stopped = 0;
        long stopped_in_run = 0;
        long bad_status = 0;
        for (const auto& [seq, answer] : run.genuine_answers()) {
            const bool stop = (answer.flags & stop_flags) == stop_flags;
            stopped_in_run += stop ? 1 : 0;
            bad_status += stop && answer.status != 0 ? 1 : 0;
            if (seq >= from && seq < to && stop) {
                first_stop = first_stop < 0 ? seq : first_stop;
                ++stopped;
            }
        }
        const auto holdoff = static_cast<long>(TVO_SPEED_MISMATCH_HOLDOFF_PERIODS);
        const long room = first_stop < 0 ? 0 : static_cast<long>(to - first_stop);
        ctx.report.check(first_stop >= from &&
                             first_stop <= from + static_cast<std::int64_t>(TVO_SPEED_MISMATCH_STOP_PERIODS) &&
                             stopped >= std::min(room, holdoff) && bad_status == 0,
                         v.what + ": the robot is stopped within TVO_SPEED_MISMATCH_STOP_PERIODS, for the holdoff",
                         "first stop at sample " + (first_stop < 0 ? std::string("none") : std::to_string(first_stop)) +
                             ", " + std::to_string(stopped) + " stopped periods of " + std::to_string(to - from) +
                             ", " + std::to_string(bad_status) + " of them with a status other than 0");
        const auto [all_flagged, first_any] = flagged(run, 0, run.genuine_sent);
        const long counted = run.counters() ? run.counters()->speed_mismatch : -1;
        ctx.report.check(counted == all_flagged, "the node counts the flagged steps (counters.speed_mismatch)",
                         std::to_string(counted) + " counted, " +
                             std::to_string(all_flagged) + " flagged in the run (first at " +
                             std::to_string(first_any) + ")");
        check_genuine(ctx.report, run, {}, -1, stopped_in_run); // the holdoff's stops outlast the fault a little
        check_tracking(ctx.report, run, "4 s after the speed is true again");
    }
}

// ---- What CLOCK_PLANT cannot tell (notes, no checks) -----------------------------------------------

void case_clock_plant_limits(Context& ctx)
{
    // 1. A stray whose stamp and sequence agree with each other (+1 s, sequence + 100): without a
    //    clock of its own the node cannot tell it from a genuine sample after 100 lost ones.
    // 2. A stray stamped +20 s arriving before the first genuine sample: it anchors the sequence.
    // 3. watchdog_periods strays within one period: the watchdog counts refusals, not periods.
    struct Variant {
        std::int64_t at;
        std::int64_t stamp_shift_us;
        std::int64_t sequence_shift;
        int copies;
        std::string what;
    };
    const std::vector<Variant> variants = {
        {300, kUsPerS, 100, 1, "at 3 s, a stray stamped +1 s with sequence +100 (consistent with each other)"},
        {0, 20 * kUsPerS, 0, 1, "before the first genuine sample, a stray stamped +20 s (sequence 0)"},
        {300, kUsPerS, 0, 10, "at 3 s, 10 strays stamped +1 s within one period (watchdog_periods = 10)"},
    };
    for (const Variant& v : variants) {
        LockstepRun run(ctx, base_config(ctx));
        run.start();
        run.run([&v](LockstepRun& r, std::int64_t n) {
            const auto m = r.measure(n);
            if (n == v.at) {
                auto stray = restamped(m, v.stamp_shift_us);
                stray.header.sequence += static_cast<std::int32_t>(v.sequence_shift);
                for (int k = 0; k < v.copies; ++k) {
                    r.send_expecting(stray, Expect::Kind::Optional, "");
                }
            }
            r.send_genuine(m);
        });
        run.stop();
        ctx.report.note(v.what,
                        std::to_string(run.genuine_accepted) + " of " + std::to_string(run.genuine_sent) +
                            " genuine samples accepted, " + std::to_string(run.genuine_held) + " held, " +
                            std::to_string(run.safe_stop_answers) + " safe stops, max error from 3 s to 4 s " +
                            fmt(run.max_error_between(run.apply_utime(300), run.apply_utime(400))) +
                            " m, final error " + fmt(run.max_error_last(100)) + " m" +
                            (run.problems.empty() ? "" : "; first: " + run.problems.front()));
    }
}

}  // namespace campaign
