// tvo_log2csv on logs written here, message by message, with what a recording of a real robot can hold:
// two sessions, a sample the node did not answer, a refusal then a computed answer, a refusal alone, a
// duplicate sample, a message that does not decode, a channel of someone else, a START and a sample
// naming robots that are not there, two robots with per-robot commands and telemetry (one robot's
// sample missing), a log without the session's START (streamed targets), and a keyed bus's recording
// (frames with authentication trailers, a forged and a replayed one among them), with and without
// --key-file. Plain checks (no framework): exit 0 = pass.
//
// Usage: tvo_log2csv_cases TVO_LOG2CSV WORK_DIR
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "auth.h"
#include "lcm_messages.hpp"
#include "test_key_file.hpp"

namespace {

int g_failures = 0;

void check(bool ok, const std::string& what)
{
    std::cout << (ok ? "ok   " : "FAIL ") << what << '\n';
    g_failures += ok ? 0 : 1;
}

constexpr std::int64_t kEpochUs = 5000000;
constexpr std::int64_t kPeriodUs = 10000;
constexpr std::int32_t kSession = 7;
constexpr std::int32_t kOtherSession = 8;
constexpr std::int8_t kRefusal = tvo_lcm::command_header_t::STATUS_ERR_STALE;

class LogWriter {
public:
    explicit LogWriter(const std::string& path) : log_(path, "w") {}
    bool good() const { return log_.good(); }

    template <class Msg>
    void put(const char* channel, const Msg& msg)
    {
        raw(channel, encoded(msg));
    }
    /// As put, the frame signed by signer (a keyed bus's frame as lcm-logger records it).
    template <class Msg>
    std::vector<char> put_signed(const char* channel, const Msg& msg, tvo_auth_t* signer)
    {
        std::vector<char> data = encoded(msg);
        const std::size_t length = data.size();
        data.resize(length + TVO_AUTH_TRAILER_BYTES);
        std::size_t signed_length = 0;
        if (tvo_auth_sign(signer, channel, reinterpret_cast<std::uint8_t*>(data.data()), length, data.size(),
                          &signed_length) != TVO_AUTH_OK) {
            check(false, std::string("signing for ") + channel);
        }
        raw(channel, data);
        return data;
    }
    template <class Msg>
    static std::vector<char> encoded(const Msg& msg)
    {
        std::vector<char> data(static_cast<std::size_t>(msg.getEncodedSize()));
        msg.encode(data.data(), 0, static_cast<int>(data.size()));
        return data;
    }
    void raw(const char* channel, std::vector<char> data)
    {
        lcm::LogEvent event{};
        event.timestamp = ++clock_;
        event.channel = channel;
        event.datalen = static_cast<std::int32_t>(data.size());
        event.data = data.data();
        log_.writeEvent(&event);
    }

private:
    lcm::LogFile log_;
    std::int64_t clock_{0};
};

tvo_lcm::session_t start(std::int32_t id, double target_x, double target_y, std::int32_t robots = 1)
{
    tvo_lcm::session_t s{};
    s.protocol_version = tvo_lcm::node_status_t::PROTOCOL_VERSION;
    s.session_id = id;
    s.action = tvo_lcm::session_t::ACTION_START;
    s.epoch_utime = kEpochUs;
    s.period_us = kPeriodUs;
    s.robot_count = robots;
    for (std::int32_t r = 0; r < robots; ++r) {
        s.robot[r].tracking_weight[0] = 1.0;
        s.robot[r].tracking_weight[1] = 1.0;
        s.robot[r].target.kind = tvo_lcm::path_t::KIND_POLYNOMIAL;
        s.robot[r].target.coeff[0][0] = target_x + r;  // a fixed point each
        s.robot[r].target.coeff[1][0] = target_y;
    }
    return s;
}

tvo_lcm::unicycle_sample_t sample(std::int32_t session, std::int32_t sequence, std::int8_t robot = 0)
{
    tvo_lcm::unicycle_sample_t m{};
    m.header.utime = kEpochUs + (sequence + 1) * kPeriodUs;
    m.header.session_id = session;
    m.header.sequence = sequence;
    m.header.robot = robot;
    m.has = tvo_lcm::unicycle_sample_t::HAS_HEADING;
    m.position_m[0] = static_cast<double>(sequence) + 100.0 * robot;
    return m;
}

tvo_lcm::unicycle_command_t command(std::int32_t sequence, float speed, std::int8_t status, std::int8_t robot = 0)
{
    tvo_lcm::unicycle_command_t c{};
    c.header.session_id = kSession;
    c.header.measurement_sequence = sequence;
    c.header.robot = robot;
    c.header.status = status;
    c.speed_mps = speed;
    return c;
}

tvo_lcm::telemetry_t telemetry(std::int32_t sequence, float barrier_c, std::int8_t robot)
{
    tvo_lcm::telemetry_t t{};
    t.header.session_id = kSession;
    t.header.measurement_sequence = sequence;
    t.header.robot = robot;
    t.barrier_c = barrier_c;
    return t;
}

struct Run {
    int exit_code{-1};
    std::string output;  // stdout and stderr
};

Run log2csv(const std::string& program, const std::string& args, const std::string& work_dir)
{
    const std::string out = work_dir + "/output.txt";
    const std::string cmd = "'" + program + "' " + args + " > '" + out + "' 2>&1";
    const int status = std::system(cmd.c_str());
    Run run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(out);
    std::stringstream text;
    text << in.rdbuf();
    run.output = text.str();
    std::cout << "$ log2csv " << args << "  -> exit " << run.exit_code << '\n' << run.output;
    return run;
}

using Row = std::map<std::string, std::string>;  // by the header's column names

std::vector<std::string> split(const std::string& line)
{
    std::vector<std::string> cells;
    std::stringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) {
        cells.push_back(cell);
    }
    return cells;
}

std::vector<Row> read_csv(const std::string& path)
{
    std::vector<Row> rows;
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = split(line);
    while (std::getline(in, line)) {
        const std::vector<std::string> cells = split(line);
        Row row;
        for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) {
            row[header[i]] = cells[i];
        }
        rows.push_back(row);
    }
    return rows;
}

double num(const Row& row, const char* column)
{
    const auto cell = row.find(column);
    return cell == row.end() ? std::nan("") : std::stod(cell->second);
}

bool contains(const std::string& text, const std::string& what)
{
    return text.find(what) != std::string::npos;
}

void two_sessions(const std::string& program, const std::string& dir)
{
    const std::string path = dir + "/two_sessions.lcmlog";
    {
        LogWriter log(path);
        check(log.good(), "the test log can be written");
        log.put(TVO_CHANNEL_SESSION, start(kSession, 1.0, 2.0));
        tvo_lcm::session_t other = start(kOtherSession, 0.0, 0.0);
        other.offset_count = 1;  // names a robot the session lacks: left out (used, it would index past
                                 // the reference's KKT matrix: silent in Release, an ASan finding)
        other.offset[0].robot_b = 5;
        log.put(TVO_CHANNEL_SESSION, other);
        log.raw("SOMEONE_ELSE", {'x'});
        log.put(TVO_CHANNEL_SAMPLE, sample(kSession, 0));
        log.put(TVO_CHANNEL_COMMAND, command(0, 1.0f, 0));
        log.put(TVO_CHANNEL_SAMPLE, sample(kSession, 1));  // never answered
        log.put(TVO_CHANNEL_SAMPLE, sample(kOtherSession, 0));
        log.put(TVO_CHANNEL_SAMPLE, sample(kOtherSession, 1, 3));  // session 8 has one robot
        log.put(TVO_CHANNEL_SAMPLE, sample(kSession, 2));
        log.put(TVO_CHANNEL_COMMAND, command(2, 9.0f, kRefusal));
        log.put(TVO_CHANNEL_COMMAND, command(2, 3.0f, 0));     // the computed answer wins
        log.put(TVO_CHANNEL_SAMPLE, sample(kSession, 2));  // duplicate
        log.put(TVO_CHANNEL_SAMPLE, sample(kSession, 3));
        log.put(TVO_CHANNEL_COMMAND, command(3, 4.0f, kRefusal));   // a refusal alone is kept
        log.raw(TVO_CHANNEL_COMMAND, {'b', 'a', 'd'});              // does not decode
    }
    const Run several = log2csv(program, "'" + path + "' -o '" + dir + "/none.csv'", dir);
    check(several.exit_code == 2 && contains(several.output, "--session") &&
              contains(several.output, "\n  7: 5 samples") && contains(several.output, "\n  8: 2"),
          "two sessions without --session: exit 2, both listed with their samples");

    const std::string csv = dir + "/session7.csv";
    const Run run = log2csv(program, "'" + path + "' --session 7 -o '" + csv + "'", dir);
    check(run.exit_code == 0, "--session 7 converts");
    const auto rows = read_csv(csv);
    check(rows.size() == 4, "one row per distinct sample of session 7 (4 of 4, the duplicate dropped)");
    if (rows.size() != 4) {
        return;
    }
    check(std::abs(num(rows[0], "t_s") - 0.01) < 1e-9 && std::abs(num(rows[3], "t_s") - 0.04) < 1e-9,
          "t_s is the sample's time from the START's epoch");
    check(num(rows[2], "x_m") == 2.0 && num(rows[2], "target_x_m") == 1.0 && num(rows[2], "target_y_m") == 2.0 &&
              std::abs(num(rows[2], "error_m") - std::sqrt(5.0)) < 1e-8,
          "pose as measured, reference from the START's path, error between them");
    check(num(rows[0], "cmd_speed_mps") == 1.0 && num(rows[1], "cmd_speed_mps") == 1.0 &&
              num(rows[1], "status") == 0.0,
          "a sample without an answer keeps the previous command");
    check(num(rows[2], "cmd_speed_mps") == 3.0 && num(rows[2], "status") == 0.0,
          "a computed answer wins over a refusal");
    check(num(rows[3], "cmd_speed_mps") == 4.0 && num(rows[3], "status") == kRefusal,
          "a refusal alone is shown with its status");
    check(contains(run.output, "1 samples without an answer") && contains(run.output, "1 duplicate") &&
              contains(run.output, "did not decode (skipped): TVO_COMMAND 1") &&
              contains(run.output, "other channels (skipped): SOMEONE_ELSE 1"),
          "unanswered, duplicate, undecodable and foreign messages are counted and reported");

    const Run other = log2csv(program, "'" + path + "' --session 8 -o '" + dir + "/session8.csv'", dir);
    check(other.exit_code == 0 && read_csv(dir + "/session8.csv").size() == 1 &&
              contains(other.output, "1 samples and answers naming no robot of the session"),
          "--session 8 picks the other one (its bad offset left out, its sample of robot 3 skipped)");
    const Run missing = log2csv(program, "'" + path + "' --session 9", dir);
    check(missing.exit_code == 2 && contains(missing.output, "--session 9"), "an absent session: exit 2, named");
}

void two_robots(const std::string& program, const std::string& dir)
{
    const std::string path = dir + "/two_robots.lcmlog";
    {
        LogWriter log(path);
        log.put(TVO_CHANNEL_SESSION, start(kSession, 1.0, 2.0, 2));
        for (std::int32_t seq = 0; seq < 3; ++seq) {
            for (std::int8_t r = 0; r < 2; ++r) {
                if (!(seq == 1 && r == 0)) {  // robot 0's sample of period 1 was not recorded
                    log.put(TVO_CHANNEL_SAMPLE, sample(kSession, seq, r));
                }
            }
            for (std::int8_t r = 0; r < 2; ++r) {
                log.put(TVO_CHANNEL_COMMAND, command(seq, static_cast<float>(seq + 10 * r), 0, r));
            }
            if (seq != 1) {  // telemetry of periods 0 and 2 only, as at a node's lower rate
                for (std::int8_t r = 0; r < 2; ++r) {
                    log.put(TVO_CHANNEL_TELEMETRY, telemetry(seq, static_cast<float>(seq + 0.5 * r), r));
                }
            }
        }
    }
    const std::string csv = dir + "/two_robots.csv";
    const Run run = log2csv(program, "'" + path + "' -o '" + csv + "'", dir);
    const auto rows = read_csv(csv);
    check(run.exit_code == 0 && rows.size() == 5 && contains(run.output, "1 robots without a sample"),
          "two robots: a row per robot and period sampled (5 of 6), the missing sample counted");
    if (rows.size() != 5) {
        return;
    }
    check(num(rows[0], "robot") == 0 && num(rows[1], "robot") == 1 && num(rows[2], "robot") == 1 &&
              num(rows[3], "robot") == 0 && num(rows[1], "x_m") == 100.0 && num(rows[1], "target_x_m") == 2.0,
          "rows in period, then robot order; each robot's own pose and target");
    check(num(rows[0], "cmd_speed_mps") == 0.0 && num(rows[1], "cmd_speed_mps") == 10.0 &&
              num(rows[2], "cmd_speed_mps") == 11.0 && num(rows[4], "cmd_speed_mps") == 12.0,
          "each robot's own command");
    check(num(rows[1], "barrier_c") == 0.5 && num(rows[2], "barrier_c") == 0.5 && num(rows[4], "barrier_c") == 2.5,
          "each robot's telemetry, its newest where its period carried none");
}

void without_start(const std::string& program, const std::string& dir)
{
    const std::string path = dir + "/no_start.lcmlog";
    {
        LogWriter log(path);
        for (std::int32_t seq = 0; seq < 2; ++seq) {
            if (seq == 0) {  // streamed only for the first sample
                tvo_lcm::target_t t{};
                t.header.session_id = kSession;
                t.header.sequence = seq;
                t.position_m[0] = 3.0;
                t.position_m[1] = 4.0;
                log.put(TVO_CHANNEL_TARGET, t);
            }
            log.put(TVO_CHANNEL_SAMPLE, sample(kSession, seq));
            log.put(TVO_CHANNEL_COMMAND, command(seq, 1.0f, 0));
        }
    }
    const std::string csv = dir + "/no_start.csv";
    const Run run = log2csv(program, "'" + path + "' -o '" + csv + "'", dir);
    const auto rows = read_csv(csv);
    check(run.exit_code == 0 && rows.size() == 2 && contains(run.output, "no START"), "a log without START converts");
    if (rows.size() == 2) {
        check(num(rows[0], "t_s") == 0.0 && std::abs(num(rows[1], "t_s") - 0.01) < 1e-9, "time from the first sample");
        check(num(rows[0], "target_x_m") == 3.0 && num(rows[0], "target_y_m") == 4.0 && num(rows[0], "error_m") == 5.0,
              "the streamed target is the reference");
        check(std::isnan(num(rows[1], "target_x_m")) && std::isnan(num(rows[1], "error_m")),
              "no target: reference and error are nan");
    }
}

void write_key_file(const std::string& path, const std::uint8_t (&key)[TVO_AUTH_KEY_BYTES])
{
    check(tvo_test::write_key_file(path, key), "the key file " + path + " can be written");
}

void keyed_bus(const std::string& program, const std::string& dir)
{
    std::uint8_t key[TVO_AUTH_KEY_BYTES];
    std::uint8_t other[TVO_AUTH_KEY_BYTES];
    for (unsigned i = 0; i < TVO_AUTH_KEY_BYTES; ++i) {
        key[i] = static_cast<std::uint8_t>(3u + 7u * i);
        other[i] = static_cast<std::uint8_t>(key[i] ^ 0x40u);
    }
    const std::string key_path = dir + "/robot.key";
    const std::string other_path = dir + "/other.key";
    write_key_file(key_path, key);
    write_key_file(other_path, other);
    tvo_auth_t plant{};
    tvo_auth_t node{};
    tvo_auth_init(&plant, key, TVO_AUTH_SENDER_PLANT, 1u);
    tvo_auth_init(&node, key, TVO_AUTH_SENDER_NODE, 1u);
    // The same run twice: plain (the reference) and as a keyed bus's recording, where an attacker also
    // sent an unsigned measurement of the next sequence and replayed a genuine one.
    const std::string plain_path = dir + "/plain.lcmlog";
    const std::string keyed_path = dir + "/keyed.lcmlog";
    {
        LogWriter plain(plain_path);
        LogWriter keyed(keyed_path);
        plain.put(TVO_CHANNEL_SESSION, start(kSession, 1.0, 2.0));
        keyed.put_signed(TVO_CHANNEL_SESSION, start(kSession, 1.0, 2.0), &plant);
        std::vector<char> first;
        for (std::int32_t seq = 0; seq < 4; ++seq) {
            plain.put(TVO_CHANNEL_SAMPLE, sample(kSession, seq));
            const auto frame = keyed.put_signed(TVO_CHANNEL_SAMPLE, sample(kSession, seq), &plant);
            if (seq == 0) {
                first = frame;
            }
            plain.put(TVO_CHANNEL_COMMAND, command(seq, 1.0f + static_cast<float>(seq), 0));
            keyed.put_signed(TVO_CHANNEL_COMMAND, command(seq, 1.0f + static_cast<float>(seq), 0), &node);
            if (seq == 1) {
                tvo_lcm::unicycle_sample_t forged = sample(kSession, 2);
                forged.position_m[0] = 50.0;
                keyed.put(TVO_CHANNEL_SAMPLE, forged);
                keyed.raw(TVO_CHANNEL_SAMPLE, first);
            }
        }
    }
    tvo_auth_clear(&plant);
    tvo_auth_clear(&node);
    const Run plain = log2csv(program, "'" + plain_path + "' -o '" + dir + "/plain.csv'", dir);
    const auto reference = read_csv(dir + "/plain.csv");
    check(plain.exit_code == 0 && reference.size() == 4, "the plain recording converts (4 rows)");

    const Run unchecked = log2csv(program, "'" + keyed_path + "' -o '" + dir + "/unchecked.csv'", dir);
    check(unchecked.exit_code == 0 && contains(unchecked.output, "10 frames carry an authentication trailer, not checked"),
          "without --key-file a keyed recording converts, its trailers ignored and reported unchecked");
    const auto unchecked_rows = read_csv(dir + "/unchecked.csv");
    check(unchecked_rows.size() == 4 && num(unchecked_rows[2], "x_m") == 50.0,
          "without --key-file the forged sample is read as genuine (what the key file is for)");

    const Run opened = log2csv(program, "'" + keyed_path + "' --key-file '" + key_path + "' -o '" + dir +
                                            "/keyed.csv'", dir);
    const auto rows = read_csv(dir + "/keyed.csv");
    check(opened.exit_code == 0 && rows == reference,
          "with --key-file the keyed recording converts to the plain recording's CSV, cell for cell");
    check(contains(opened.output, "1 frames dropped by --key-file: their tag did not verify") &&
              contains(opened.output, "1 frames dropped by --key-file: a counter already used") &&
              !contains(opened.output, "not checked"),
          "the forged and the replayed frame are dropped and counted");

    const Run wrong = log2csv(program, "'" + keyed_path + "' --key-file '" + other_path + "' -o '" + dir +
                                           "/wrong.csv'", dir);
    check(wrong.exit_code == 1 && contains(wrong.output, "no frame") && contains(wrong.output, "11 unauthenticated"),
          "another key: no frame opens, exit 1, said so");
}

void bad_files(const std::string& program, const std::string& dir)
{
    const Run absent = log2csv(program, "'" + dir + "/absent.lcmlog'", dir);
    check(absent.exit_code == 2 && contains(absent.output, "absent.lcmlog") && contains(absent.output, "No such file"),
          "a missing log: exit 2, named with the reason");
    const std::string text = dir + "/not_a_log.txt";
    std::ofstream(text) << "not an LCM log\n";
    const Run junk = log2csv(program, "'" + text + "'", dir);
    check(junk.exit_code == 2 && contains(junk.output, "no LCM event"), "a file that is not a log: exit 2");
    const Run folder = log2csv(program, "'" + dir + "'", dir);
    check(folder.exit_code == 2 && contains(folder.output, "folder"), "a folder: exit 2");
    const Run option = log2csv(program, "--no-such-option", dir);
    check(option.exit_code == 2, "an unknown option: exit 2");
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::cerr << "usage: tvo_log2csv_cases TVO_LOG2CSV WORK_DIR\n";
        return 2;
    }
    std::error_code error;
    std::filesystem::create_directories(argv[2], error);
    two_sessions(argv[1], argv[2]);
    two_robots(argv[1], argv[2]);
    without_start(argv[1], argv[2]);
    keyed_bus(argv[1], argv[2]);
    bad_files(argv[1], argv[2]);
    std::cout << (g_failures == 0 ? "all passed\n" : std::to_string(g_failures) + " failed\n");
    return g_failures == 0 ? 0 : 1;
}
