// The keyed bus under attack (issue 25): the campaign's plant and the node hold the key, as tvo_sim
// and tvo_firmware_node --key-file do; an attacker on the same bus has no key (it sends plain LCM,
// or signs with a key of its own) or only recordings of genuine frames. Each attack is injected in
// a period of its own, before that period's genuine sample, and each must be: not answered (no
// command, no ack: the period's only command answers the genuine sample), counted (the node's
// counters, read from its announcements just before and after the period, move by exactly the frames
// sent: a frame without a trailer or cut short is malformed, a tag that does not verify
// unauthenticated, a used counter replayed; and nothing else moves), and without effect (every
// genuine answer bit for bit as in a keyed run without the attacks). Without the key, each of these
// frames would be answered (or win a re-anchor vote).
#include "cases.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "test_key_file.hpp"

extern "C" {
#include "auth_key_file.h"
}

namespace campaign {

namespace {
constexpr std::int64_t kUsPerS = 1000000;

/// The genuine key (a test key, written to the key file the node reads) and the attacker's own.
void fill_key(std::uint8_t (&key)[TVO_AUTH_KEY_BYTES], std::uint8_t seed)
{
    for (unsigned i = 0; i < TVO_AUTH_KEY_BYTES; ++i) {
        key[i] = static_cast<std::uint8_t>(seed + 29u * i);
    }
}

/// Keys the bus and the nodes of the case for its duration: the key file (mode 0600, as the node
/// requires) and the plant's signing context; unkeyed again at the end of the case.
class KeyedCase {
public:
    /// name: the case's, so cases run side by side (CTest -j) each have their own file.
    KeyedCase(Context& ctx, const std::string& name) : ctx_(ctx), path_("fault_campaign_" + name + ".key")
    {
        std::uint8_t key[TVO_AUTH_KEY_BYTES];
        fill_key(key, 0x5a);
        if (!tvo_test::write_key_file(path_, key)) {
            throw std::runtime_error("cannot write the key file " + path_);
        }
        ctx_.bus.set_key(key, TVO_AUTH_SENDER_PLANT);
        ctx_.key_file = path_;
    }
    ~KeyedCase()
    {
        ctx_.bus.clear_key();
        ctx_.key_file.clear();
        std::remove(path_.c_str());  // a test's key is not left behind
    }
    KeyedCase(const KeyedCase&) = delete;
    KeyedCase& operator=(const KeyedCase&) = delete;

private:
    Context& ctx_;
    std::string path_;
};

/// The attacker's signer: another key, and the plant's own sender id with a counter far ahead (were
/// it accepted, every genuine frame after it would look like a replay).
class Forger {
public:
    Forger()
    {
        std::uint8_t key[TVO_AUTH_KEY_BYTES];
        fill_key(key, 0xa5);
        if (tvo_auth_init(&auth_, key, TVO_AUTH_SENDER_PLANT, tvo_auth_wall_clock_counter() + 1000 * kUsPerS) !=
            TVO_AUTH_OK) {
            throw std::runtime_error("forger set-up failed");
        }
    }
    ~Forger() { tvo_auth_clear(&auth_); }
    Forger(const Forger&) = delete;
    Forger& operator=(const Forger&) = delete;

    std::vector<std::uint8_t> sign(const char* channel, std::vector<std::uint8_t> message)
    {
        return signed_frame(&auth_, channel, std::move(message));
    }

private:
    tvo_auth_t auth_{};
};

/// One attack: what it sends in its period and how the node must count it.
struct Attack {
    std::string what;
    std::vector<Frame> frames;
    int unauthenticated{0};
    int replayed{0};
    int malformed{0};
    int wrong_boot{0};
    int idle{0};
    bool genuine_sample{true};  // the period's genuine sample follows (and is accepted)
};

/// The node's counters from its next announcement (every 1 s while it runs, 250 ms while idle): a
/// snapshot of everything it handled before it.
std::optional<tvo_lcm::node_counters_t> next_counters(Context& ctx, std::int64_t boot)
{
    const tvo_lcm::node_status_t* next =
        ctx.bus.await_announcement(ctx.bus.announcements.size(), boot, [](const auto&) { return true; },
                                   std::chrono::seconds(3));
    return next != nullptr ? std::optional<tvo_lcm::node_counters_t>(next->counters) : std::nullopt;
}

/// Runs one period with an attack before its genuine sample and checks it: not answered, counted,
/// nothing else moved.
void attack_period(Context& ctx, LockstepRun& r, std::int64_t n, const Attack& attack)
{
    r.settle();
    const auto before = next_counters(ctx, r.boot());
    const std::size_t commands_before = ctx.bus.commands.size();
    const std::size_t acks_before = ctx.bus.acks.size();
    for (const Frame& f : attack.frames) {
        ctx.bus.publish_raw(f.channel.c_str(), f.bytes);
    }
    if (attack.genuine_sample) {
        r.send_genuine(r.measure(n));
    }
    r.settle();
    ctx.bus.pump(std::chrono::milliseconds(50));   // an answer to an attack frame, if any, shows up
    const auto after = next_counters(ctx, r.boot());   // announced after every attack frame was handled
    const std::size_t commands = ctx.bus.commands.size() - commands_before;
    const std::size_t acks = ctx.bus.acks.size() - acks_before;
    const std::size_t want_commands = attack.genuine_sample ? 1u : 0u;
    std::ostringstream figure;
    figure << attack.frames.size() << " frames; " << commands << " commands in the period (the genuine sample's: "
           << want_commands << "), " << acks << " acks";
    ctx.report.check(commands == want_commands && acks == 0, attack.what + ": not answered", figure.str());
    if (!before || !after) {
        ctx.report.check(false, attack.what + ": counted", "no announcement of the node around it");
        return;
    }
    const NodeCounts d = counts_between(*before, *after);
    const long others = d.other_session + d.targets_refused + d.safe_stops + d.refused;
    std::ostringstream counted;
    counted << "malformed +" << d.malformed << " (want +" << attack.malformed << "), unauthenticated +"
            << d.unauthenticated << " (want +" << attack.unauthenticated << "), replayed +" << d.replayed << " (want +"
            << attack.replayed << "), wrong_boot +" << d.wrong_boot << " (want +" << attack.wrong_boot << "), idle +"
            << d.idle << " (want +" << attack.idle << "), accepted +" << d.accepted << " (the genuine sample: "
            << want_commands << "), other counters +" << others;
    ctx.report.check(d.malformed == attack.malformed && d.unauthenticated == attack.unauthenticated &&
                         d.replayed == attack.replayed && d.wrong_boot == attack.wrong_boot && d.idle == attack.idle &&
                         d.accepted == static_cast<long>(want_commands) && others == 0,
                     attack.what + ": counted, nothing else moved", counted.str());
}

/// The genuine plant opened every frame of the node (none forged, none a used counter).
void check_plant_opened_all(Context& ctx)
{
    ctx.report.check(ctx.bus.dropped_unauthenticated == 0 && ctx.bus.dropped_replayed == 0,
                     "the plant opened every frame the node sent (tags verify, counters rise)",
                     std::to_string(ctx.bus.dropped_unauthenticated) + " unauthenticated, " +
                         std::to_string(ctx.bus.dropped_replayed) + " replayed");
}

/// A keyed run of the default session; hook as LockstepRun::run's.
std::unique_ptr<LockstepRun> keyed_run(Context& ctx, const LockstepRun::Hook& hook)
{
    auto run = std::make_unique<LockstepRun>(ctx, base_config(ctx));
    run->start();
    run->run(hook);
    run->stop();
    return run;
}

std::vector<std::uint8_t> flipped(std::vector<std::uint8_t> frame, std::size_t from_end, std::uint8_t mask)
{
    frame[frame.size() - from_end] ^= mask;
    return frame;
}

/// A frame whose trailer counter is one higher (the tag, computed over the old nonce, no longer verifies).
std::vector<std::uint8_t> counter_raised(std::vector<std::uint8_t> frame)
{
    const std::size_t last = frame.size() - TVO_AUTH_TAG_BYTES - 1;   // the counter's lowest byte
    for (std::size_t i = 0; i < 8; ++i) {
        if (++frame[last - i] != 0) {
            break;
        }
    }
    return frame;
}

std::vector<std::uint8_t> truncated(std::vector<std::uint8_t> frame, std::size_t bytes)
{
    frame.resize(frame.size() - bytes);
    return frame;
}

/// The last frame the plant sent on channel.
const Frame& last_sent(const Context& ctx, const char* channel)
{
    for (auto it = ctx.bus.sent.rbegin(); it != ctx.bus.sent.rend(); ++it) {
        if (it->channel == channel) {
            return *it;
        }
    }
    throw std::runtime_error(std::string("the plant sent nothing on ") + channel);
}
}  // namespace

void case_auth_attacks(Context& ctx)
{
    KeyedCase keyed(ctx, "auth-attacks");
    Forger forger;
    const auto reference = keyed_run(ctx, {});
    check_tracking(ctx.report, *reference, "keyed reference run without the attacks");
    std::vector<std::int64_t> steps;
    long unauthenticated = 0;
    long replayed = 0;
    long malformed = 0;
    // Every attack as the attacker builds it in its period n (m: the genuine sample of period n).
    // Every attack as the attacker builds it in its period n (m: the genuine sample of period n).
    // Forgeries go twice: unsigned in period `at`, signed with another key in period at + 10.
    const auto build = [&](LockstepRun& r, std::int64_t n) -> std::optional<Attack> {
        const Sample m = r.measure(n);
        const char* measurement_ch = TVO_CHANNEL_SAMPLE;
        const std::int64_t at = n - n % 20;
        std::string what;
        const char* channel = measurement_ch;
        std::vector<std::vector<std::uint8_t>> forged;
        if (at == 300) {
            tvo_lcm::session_t start = r.session();
            start.session_id = ctx.new_session_id();
            start.utime = r.now_us();
            what = "a forged START (new id)";
            channel = TVO_CHANNEL_SESSION;
            forged.push_back(encode(start));
        } else if (at == 320) {
            tvo_lcm::session_t stop = r.session();
            stop.action = tvo_lcm::session_t::ACTION_STOP;
            stop.utime = r.now_us();
            what = "a forged STOP of the running session";
            channel = TVO_CHANNEL_SESSION;
            forged.push_back(encode(stop));
        } else if (at == 340) {
            Sample next = m;   // the next period's sequence, 0.5 m off, a plausible stamp
            next.header.sequence = static_cast<std::int32_t>(n + 1);
            next.position_m[0] += 0.5;
            what = "a forged sample (next sequence, 0.5 m off)";
            forged.push_back(encode(next));
        } else if (at == 360) {
            tvo_lcm::target_t target{};
            target.header.utime = r.now_us();
            target.header.session_id = r.session().session_id;
            target.header.robot = 0;
            target.position_m[0] = 10.0;
            what = "a forged target";
            channel = TVO_CHANNEL_TARGET;
            forged.push_back(encode(target));
        } else if (at == 440) {
            // Three samples that agree with each other, 20 s ahead: without a key they win the re-anchor vote.
            for (int k = 1; k <= 3; ++k) {
                Sample v = m;
                v.header.sequence = static_cast<std::int32_t>(n + 2000 + k);
                v.header.utime = m.header.utime + 20 * kUsPerS + k * r.session().period_us;
                forged.push_back(encode(v));
            }
            what = "a forged vote of three (agreeing samples 20 s ahead)";
        }
        Attack a;
        if (!forged.empty() && (n == at || n == at + 10)) {
            // Unsigned, a frame has no trailer: not its channel's keyed length, malformed before any crypto.
            a.what = what + (n == at ? ", unsigned" : ", signed with another key");
            for (auto& bytes : forged) {
                a.frames.push_back({channel, n == at ? bytes : forger.sign(channel, bytes)});
            }
            (n == at ? a.malformed : a.unauthenticated) = static_cast<int>(forged.size());
            return a;
        }
        switch (n) {
        case 380:
            a.what = "the genuine sample of the last period replayed";
            a.frames = {last_sent(ctx, measurement_ch)};
            a.replayed = 1;
            break;
        case 390:
            a.what = "the genuine START of the running session replayed";
            a.frames = {last_sent(ctx, TVO_CHANNEL_SESSION)};
            a.replayed = 1;
            break;
        case 400: {
            // A genuine frame of this period's sample, altered in flight (the genuine one follows).
            const auto frame = ctx.bus.sign(measurement_ch, encode(m));
            a.what = "a genuine frame with one bit of its tag flipped (first, then last tag byte)";
            a.frames = {{measurement_ch, flipped(frame, TVO_AUTH_TAG_BYTES, 0x80)}, {measurement_ch, flipped(frame, 1, 0x01)}};
            a.unauthenticated = 2;
            break;
        }
        case 410:
            a.what = "the last genuine sample replayed with its counter raised by one (the tag no longer verifies)";
            a.frames = {{measurement_ch, counter_raised(last_sent(ctx, measurement_ch).bytes)}};
            a.unauthenticated = 1;
            break;
        case 420: {
            // Every one is not its channel's keyed length: malformed, before any crypto.
            const auto frame = ctx.bus.sign(measurement_ch, encode(m));
            a.what = "a genuine frame truncated by 1, 8, 16, 27 and 28 bytes, and a 10-byte frame";
            a.frames = {{measurement_ch, truncated(frame, 1)},
                        {measurement_ch, truncated(frame, 8)},
                        {measurement_ch, truncated(frame, 16)},
                        {measurement_ch, truncated(frame, 27)},
                        {measurement_ch, truncated(frame, 28)},
                        {measurement_ch, std::vector<std::uint8_t>(frame.begin(), frame.begin() + 10)}};
            a.malformed = 6;
            break;
        }
        default:
            return std::nullopt;
        }
        return a;
    };
    auto run = keyed_run(ctx, [&](LockstepRun& r, std::int64_t n) {
        if (const auto attack = build(r, n)) {
            steps.push_back(n);
            unauthenticated += attack->unauthenticated;
            replayed += attack->replayed;
            malformed += attack->malformed;
            attack_period(ctx, r, n, *attack);
            return;
        }
        r.send_genuine(r.measure(n));
    });
    ctx.report.check(steps.size() == 15, "every attack was injected", std::to_string(steps.size()) + " of 15");
    check_genuine(ctx.report, *run, {});
    check_same_as_reference(ctx.report, *reference, *run);
    check_counters(ctx.report, *run);
    check_tracking(ctx.report, *run, "after the attacks");
    const auto& c = run->counters();
    ctx.report.check(c && c->unauthenticated == unauthenticated && c->replayed == replayed && c->malformed == malformed,
                     "the session's counters: every frame without a trailer or cut short malformed, every forged or "
                     "altered one unauthenticated, every replay replayed",
                     !c ? "no announcement at START or after STOP"
                        : "malformed " + std::to_string(c->malformed) + " of " + std::to_string(malformed) +
                              ", unauthenticated " + std::to_string(c->unauthenticated) + " of " +
                              std::to_string(unauthenticated) + ", replayed " + std::to_string(c->replayed) + " of " +
                              std::to_string(replayed));
    check_plant_opened_all(ctx);
}

void case_auth_node_restart(Context& ctx)
{
    if (ctx.node_path.empty()) {
        throw std::runtime_error("auth-node-restart kills and restarts the node: it needs --node PATH");
    }
    KeyedCase keyed(ctx, "auth-node-restart");
    constexpr std::int64_t kCrashAt = 400;
    constexpr std::int64_t kReplayAt = 420;
    // Genuine samples of the old node's time, replayed with its START.
    constexpr std::size_t kRecorded = 20;
    // The plant's frames before the crash: the recording an attacker made.
    std::vector<Frame> recording;
    const auto restart = [&](LockstepRun& r, std::int64_t n, bool replay) {
        if (n == kCrashAt) {
            r.settle();
            // The START the plant sent this run and its last kRecorded samples.
            const std::size_t first = ctx.bus.sent.size() - std::min(ctx.bus.sent.size(), kRecorded);
            recording.clear();
            for (auto it = ctx.bus.sent.rbegin(); it != ctx.bus.sent.rend(); ++it) {
                if (it->channel == TVO_CHANNEL_SESSION) {
                    recording.push_back(*it);
                    break;
                }
            }
            recording.insert(recording.end(), ctx.bus.sent.begin() + static_cast<std::ptrdiff_t>(first),
                             ctx.bus.sent.end());
            r.crash_node_and_restart();   // returns once the new boot announced itself
            if (replay) {
                // At once, before the genuine plant speaks again: the recording's sender is new to the new
                // boot, so its tags are checked and verify, and still nothing runs: the START names the old
                // boot (wrong_boot), the samples find no session (idle).
                Attack a;
                a.what = "right after the restart, before the plant's next frame: the old boot's START and " +
                         std::to_string(recording.size() - 1) + " samples replayed";
                a.frames = recording;
                a.wrong_boot = 1;
                a.idle = static_cast<int>(recording.size() - 1);
                a.genuine_sample = false;
                attack_period(ctx, r, n, a);
            }
            r.send_expecting(r.measure(n), Expect::Kind::Ignored,
                             "keyed node killed and restarted: the next sample is dropped unanswered (no session)");
            r.settle();
            r.restart_session();   // rule 5: START naming the new boot
            return;
        }
        if (n == kReplayAt && replay) {
            Attack a;
            a.what = "amid the new session: the old boot's START and " + std::to_string(recording.size() - 1) +
                     " samples replayed";
            a.frames = recording;
            a.replayed = static_cast<int>(recording.size());   // the plant's newer frames came first
            attack_period(ctx, r, n, a);
            return;
        }
        r.send_genuine(r.measure(n));
    };
    auto reference = std::make_unique<LockstepRun>(ctx, base_config(ctx));
    reference->start();
    reference->run([&](LockstepRun& r, std::int64_t n) { restart(r, n, false); });
    reference->stop();
    LockstepConfig config = base_config(ctx);
    config.node_stderr_path = "fault_campaign_auth_node_restart_node.stderr";
    std::remove(config.node_stderr_path.c_str());
    LockstepRun run(ctx, config);
    run.start();
    run.run([&](LockstepRun& r, std::int64_t n) { restart(r, n, true); });
    run.stop();
    ctx.report.check(recording.size() == kRecorded + 1 && recording.front().channel == TVO_CHANNEL_SESSION,
                     "the recording: the START and the samples before the crash",
                     std::to_string(recording.size()) + " frames");
    check_outcomes(ctx.report, run);
    check_genuine(ctx.report, run, {kCrashAt}, run.genuine_sent - 1);
    check_same_as_reference(ctx.report, *reference, run);
    check_tracking(ctx.report, run, "after the node restart and the replays");
    // The restarted node signs (boot << 40) | n, above every counter of its old boot: the plant, which
    // remembers the old boot's last counter, opens every frame of the new one.
    check_plant_opened_all(ctx);
}

}  // namespace campaign
