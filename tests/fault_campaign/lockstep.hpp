// One session of the campaign's own plant in lockstep (CLOCK_PLANT): an exact unicycle tracking the
// default ellipse, sampling period n at a_{n+1} - tau with sequence n and waiting for the answers.
// A case adds its faults through a hook per period; every message sent carries its expected
// answer, and every command that arrives is matched to one in arrival order (the node answers in
// the order it receives), so the run knows which answer is genuine and checks each. The run's START
// names the node's boot, heard on TVO_NODE; the node's counters are read from its announcements.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "plant.hpp"
#include "support.hpp"

namespace campaign {

/// What the node must do with one message the plant sent.
struct Expect {
    enum class Kind {
        Accepted,   // a genuine sample: stepped, status 0, applied at a_j
        Refused,    // answered with the held command, HOLDING (or a watchdog safe stop), a status
        Ignored,    // no answer at all (another session's message, undecodable bytes, a node without a session)
        Optional    // may be answered or not (the spec leaves it open): reported, not judged
    };
    static constexpr std::int32_t kAnyStatus = -1;

    Kind kind{Kind::Accepted};
    bool genuine{false};          // the plant's own sample (counts as a period of holding if refused)
    bool counted_refusal{false};  // Ignored: the node refuses it without an answer (counted in refused[])
    bool match_by_order{false};   // its answer cannot echo its fields (they are out of the wire range)
    std::int32_t session_id{0};
    std::int64_t sequence{0};
    std::int32_t robot{0};        // a command answers the sample of its robot only
    std::int64_t utime{0};
    std::int64_t apply_utime{0};  // Accepted: a_j
    std::int32_t status{kAnyStatus};
    std::string label;            // non-empty: the outcome is printed as a check of its own
};

struct LockstepConfig {
    Timing timing;
    std::int32_t session_id{1};
    std::int64_t epoch_utime_us{1000000};
    std::int64_t start_utime_us{1000000};
    std::int64_t first_sequence{0};   // sequence n serves period n + 1 (sampled at a_{n+1} - tau)
    std::int64_t periods{1000};
    tvo_host::UnicycleState start_pose;
    bool spawn_node{true};            // start a node for this run (when the campaign has a path)
    bool keep_running{false};         // pass --keep-running to it
    std::string node_stderr_path;     // non-empty: the node's stderr goes to this file
};

/// Shared by the runs of a case.
struct Context {
    Bus& bus;
    Report& report;
    CommandAudit& audit;
    std::string node_path;            // empty: a node is already running on the URL (--keep-running)
    std::string lcm_url;
    std::int32_t next_session_id{1};
    std::string key_file;             // non-empty: nodes start with --key-file (the case keys the bus too)

    /// A fresh session id per run (the plant rule).
    std::int32_t new_session_id() { return next_session_id++; }
};

/// A node's counters (node_counters_t) as numbers, and the difference of two announcements' counters.
struct NodeCounts {
    long accepted{0};
    long refused{0};  // every status
    long malformed{0};
    long unauthenticated{0};
    long replayed{0};
    long wrong_boot{0};
    long idle{0};
    long other_session{0};
    long safe_stops{0};
    long targets_refused{0};
    long speed_mismatch{0};
    std::string refused_by_status;  // " [status]=n" for each status counted
};
NodeCounts counts_of(const tvo_lcm::node_counters_t& c);
/// later - earlier, counter by counter.
NodeCounts counts_between(const tvo_lcm::node_counters_t& earlier, const tvo_lcm::node_counters_t& later);

class LockstepRun {
public:
    LockstepRun(Context& ctx, const LockstepConfig& config);
    ~LockstepRun();

    using Hook = std::function<void(LockstepRun& run, std::int64_t n)>;

    /// Starts the node (if configured), hears its boot and empties the bus; start() does it when not done
    /// before.
    void prepare();
    /// Starts the node (if configured), hears its boot and sends START naming it until acknowledged;
    /// checks status 0.
    void start();
    /// Runs periods [first_sequence, first_sequence + periods); the hook (default: the genuine sample)
    /// sends what period n sends.
    void run(const Hook& hook = {});
    /// One period.
    void step(std::int64_t n, const Hook& hook = {});
    /// Sends STOP, checks its ack (status 0) and, for a node this run started, that it exits with 0; reads
    /// the node's counters from its announcement after the STOP.
    void stop();

    // ---- What a hook uses.
    /// The genuine sample of period n at the current plant time.
    Sample measure(std::int64_t n) const;
    void send_genuine(const Sample& m);
    /// A genuine sample the node must refuse (a late or repeated one).
    void send_genuine_refused(const Sample& m, std::int32_t status, const std::string& label);
    void send_stray(const Sample& m, std::int32_t status, const std::string& label, bool match_by_order = false);
    /// A sample the node refuses without an answer (it steps no period: another robot's, say), counted.
    void send_refused_unanswered(const Sample& m, const std::string& label);
    /// kind Ignored of this session's own sample: a genuine sample that gets no answer (a node without a
    /// session drops it).
    void send_expecting(const Sample& m, Expect::Kind kind, const std::string& label);
    void send_raw(const char* channel, const std::vector<std::uint8_t>& bytes, Expect expect);
    /// Publishes a session message (again every `repeat` until acked) and waits for its ack (10 s);
    /// throws if none comes.
    tvo_lcm::session_ack_t request(const tvo_lcm::session_t& msg,
                                   std::chrono::milliseconds repeat = std::chrono::milliseconds(1000));
    /// Publishes m again every 200 ms until a command arrives (a node whose socket a burst overflowed);
    /// a second answer, if any, is optional.
    void send_until_answered(const Sample& m, Expect::Kind kind, const std::string& label);
    void send_genuine_until_answered(const Sample& m);
    /// Waits until every message sent so far has its answer (or is known to get none).
    void settle();
    /// Restarts the node: SIGKILL, then a fresh process, whose new boot (announced) is heard.
    void crash_node_and_restart();
    /// Stalled wheels: while set, the robot stands still whatever it is commanded.
    void set_stalled(bool stalled) { stalled_ = stalled; }
    /// Sends START (same id and content) naming the node's current boot until acknowledged: what a plant
    /// does when its node announces a new boot.
    void restart_session();
    /// The node's boot the run's START names.
    std::int64_t boot() const { return boot_; }

    Context& context() { return ctx_; }
    NodeProcess* node() { return node_.get(); }
    const tvo_host::UnicycleState& robot() const { return plant_.state(0); }
    const tvo_lcm::session_ack_t& start_ack() const { return start_ack_; }
    const tvo_lcm::session_t& session() const { return session_; }
    std::int64_t now_us() const { return now_us_; }
    std::int64_t apply_utime(std::int64_t n) const;
    std::int64_t sample_utime(std::int64_t n) const;

    // ---- Results.
    struct Answer {
        double speed_mps;
        double turn_rate_radps;
        std::int64_t utime;
        std::int32_t status;
        std::int32_t flags;
        bool operator==(const Answer& o) const;
    };
    struct Outcome {
        std::string label;
        bool ok;
        std::string figure;
        std::int32_t status;
        std::int32_t flags;
    };
    const std::map<std::int64_t, Answer>& genuine_answers() const { return genuine_answers_; }
    const std::vector<Outcome>& outcomes() const { return outcomes_; }
    /// Largest position error over the last `periods` periods, metres.
    double max_error_last(std::int64_t periods) const;
    double max_error_between(std::int64_t from_utime, std::int64_t to_utime) const;
    /// The node's counters over the run: from its announcement when it took the START to its
    /// announcement after the STOP (stop() reads it); nullopt if one of them did not come.
    const std::optional<NodeCounts>& counters() const { return counters_; }
    /// The node's counters since it started (its boot), from its announcement after the STOP.
    const std::optional<NodeCounts>& final_counters() const { return final_counters_; }

    long genuine_sent{0};
    long genuine_accepted{0};
    long genuine_held{0};          // genuine samples answered with HOLDING or a non-zero status
    std::vector<std::int64_t> held_steps;   // the period (step n) in which each of those was answered
    long genuine_wrong{0};         // genuine samples whose answer broke the rules of Accepted
    long unexpected_answers{0};    // commands that answer nothing sent, or an ignored message
    long stamped_before_measurement{0};   // answers stamped before the measurement they answer
    long literal_plant_diffs{0};   // commands a plant applying the spec's rule literally treats otherwise
    long plant_watchdog_stops{0};
    long refusal_answers{0};       // answers with a non-zero status to this session's measurements
    long silent_refusals{0};       // samples the node refuses without an answer (another robot's, say)
    long safe_stop_answers{0};     // commands of this session flagged SAFE_STOP
    std::vector<std::string> problems;   // first descriptions of what went wrong

private:
    struct Pending {
        std::int64_t apply_us;
        tvo_host::UnicycleInput input;
    };
    void advance_to(std::int64_t t_us);
    void process(const ReceivedCommand& received);
    void verify(const Expect& e, const Command& cmd);
    void apply(const Command& cmd, std::int64_t at_us, bool answers_own_sample);
    void shadow_literal_plant(const Command& cmd, bool applied);
    void problem(const std::string& text);
    void publish_expect(const Sample& m, Expect e);
    void resend_until_answered(const Sample& m, std::size_t commands_before, const std::string& label);
    void unanswered(const Expect& e);

    Context& ctx_;
    LockstepConfig config_;
    tvo_lcm::session_t session_;
    std::unique_ptr<NodeProcess> node_;
    tvo_host::UnicyclePlant plant_;
    std::int64_t now_us_;
    std::vector<Pending> pending_;
    std::int64_t in_force_sequence_{-1};
    std::int64_t last_applied_us_;
    Answer held_{0.0, 0.0, 0, 0, 0};
    std::deque<Expect> expected_;
    std::size_t processed_{0};      // bus.commands handled so far
    std::set<std::int64_t> sent_sequences_;
    std::int64_t literal_in_force_{-1};
    long consecutive_refusals_{0};
    std::int64_t current_step_{0};
    bool prepared_{false};
    bool stalled_{false};
    bool applied_safe_stop_for_own_{false};   // the command being processed answers the plant's own sample
    tvo_lcm::session_ack_t start_ack_{};
    std::int64_t boot_{0};
    std::optional<tvo_lcm::node_counters_t> start_counters_;  // the node's announcement when it took the START
    std::optional<NodeCounts> counters_;
    std::optional<NodeCounts> final_counters_;
    std::map<std::int64_t, Answer> genuine_answers_;
    std::vector<Outcome> outcomes_;
    std::vector<std::pair<std::int64_t, double>> errors_;   // (utime, metres) at each a_j
};

// ---- Checks shared by the cases.
/// The loop tracks: the error over the last second below the bound (justified in cases.cpp).
void check_tracking(Report& report, const LockstepRun& run, const std::string& what);
/// Genuine samples: each meant to be accepted is; at most one period of holding after each bad message
/// (fault_steps: the periods where one is injected; none: no holding at all); no unexpected answer.
/// expected_stopped: accepted samples the controller answered with a stop of its own (status 0,
/// FLAG_SAFE_STOP: a speed mismatch), counted apart from the accepted ones.
void check_genuine(Report& report, const LockstepRun& run, const std::vector<std::int64_t>& fault_steps,
                   long expected_accepted = -1, long expected_stopped = 0);
/// Every genuine answer bit for bit as in a run without the faults: nothing was kept from them.
void check_same_as_reference(Report& report, const LockstepRun& reference, const LockstepRun& run);
/// The labelled outcomes as checks.
void check_outcomes(Report& report, const LockstepRun& run);
/// The node's counters (its announcements) agree with what the plant saw: accepted, refused, safe stops.
void check_counters(Report& report, const LockstepRun& run);
/// Lines the node wrote to its stderr file.
long count_lines(const std::string& path);

}  // namespace campaign
