/*
 * A fleet node (fleet_link.c in front of node.c, the fleet's limits: up to 8 robots): a valid fleet
 * session (robot count, own robot, clock and a ring of distance bounds from the first input byte),
 * then a stream of per-robot samples (built from a few fuzzed bytes, so that periods line up), raw
 * bytes on every channel the link takes, and the node's clock advancing by fuzzed steps. Invariants of
 * every fleet command: it decodes and names the own robot, every row finite and within the session's
 * limits, a safe stop all zero, status 0 only on a computed command, and the digest is the digest of
 * the rows it carries.
 * Record format after the variant byte: kind (1 byte: 0 a sample, 1 raw sample bytes, 2 raw session
 * bytes, 3 raw target bytes), length (2 bytes LE), clock step (1 byte, x 500 us), then `length` bytes.
 * A sample's bytes: robot, sequence step (int8 from the last), x, y, heading, speed (int16 LE, mm or
 * mrad), flags (bit 0 heading valid, bit 1 speed valid, bit 2 another session).
 */
#include "fleet_link.h"
#include "fuzz_support.h"

static tvo_node_t node;
static tvo_fleet_link_t link;
static tvo_lcm_session_t session;
static tvo_lcm_fleet_command_t answer;
static uint64_t reference_hash; /* the reference START's: its limits bind the rows while it runs */
static uint8_t buffer[8192];

static void check_answer(const tvo_lcm_fleet_command_t *m)
{
    const double slack = 1e-6;
    const int stopped = (m->flags & (int32_t)TVO_LCM_COMMAND_T_FLAG_SAFE_STOP) != 0;
    if (m->robot != link.own_robot || m->robot_count < 0 || m->robot_count > TVO_FLEET_MAX_ROBOTS) {
        fuzz_fail("a fleet command of another robot, or of more robots than the build drives");
    }
    const tvo_node_session_t *running = tvo_node_session(&node);
    const int reference_limits = running != NULL && running->content_hash == reference_hash;
    tvo_fleet_joint_command_t rows;
    memset(&rows, 0, sizeof(rows));
    for (int32_t r = 0; r < m->robot_count; ++r) {
        rows.speed_mps[r] = m->joint_speed_mps[r];
        rows.turn_rate_radps[r] = m->joint_turn_rate_radps[r];
        if (!isfinite(rows.speed_mps[r]) || !isfinite(rows.turn_rate_radps[r])) {
            fuzz_fail("a row not finite");
        }
        if (reference_limits && (fabs(rows.speed_mps[r]) > fuzz_core_limit(session.speed_max_mps) * (1.0 + slack) ||
                                 fabs(rows.turn_rate_radps[r]) > fuzz_core_limit(session.omega_max_radps) * (1.0 + slack))) {
            fuzz_fail("a row beyond the session's limits");
        }
        if (stopped && (rows.speed_mps[r] != 0.0 || rows.turn_rate_radps[r] != 0.0)) {
            fuzz_fail("safe stop not all zero");
        }
    }
    if (m->robot < m->robot_count &&
        (m->speed_mps != rows.speed_mps[m->robot] || m->turn_rate_radps != rows.turn_rate_radps[m->robot])) {
        fuzz_fail("the own row is not the joint command's");
    }
    if ((uint64_t)m->joint_digest != tvo_fleet_digest(&rows, m->robot_count)) {
        fuzz_fail("the digest is not the rows'");
    }
    if (reference_limits && m->status == 0 && m->robot_count != session.robot_count) {
        fuzz_fail("a computed command of another robot count than the session's");
    }
    const int32_t mismatch_stop = (int32_t)(TVO_LCM_COMMAND_T_FLAG_SAFE_STOP | TVO_FLAG_SPEED_MISMATCH);
    if (m->status == 0 && ((m->flags & (int32_t)TVO_LCM_COMMAND_T_FLAG_HOLDING) != 0 ||
                           (stopped && (m->flags & mismatch_stop) != mismatch_stop))) {
        fuzz_fail("status OK on a holding or stop command");
    }
}

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    if (channel == TVO_FLEET_CH_COMMAND) {
        if (tvo_lcm_fleet_command_t_decode(data, 0, (int)length, &answer) != (int)length) {
            fuzz_fail("the link published a fleet command that does not decode");
        }
        check_answer(&answer);
    }
}

/* The fleet's session: fuzz_session's unicycle variant with `robots` robots on ellipses apart, and a
 * ring of distance bounds (bit 4), as tools/fleet's scenarios have. */
static void fleet_session(tvo_lcm_session_t *s, uint8_t variant, int32_t robots)
{
    fuzz_session(s, (uint8_t)(variant & ~2u & ~8u & ~16u)); /* a fleet node drives unicycles */
    s->robot_count = robots;
    for (int32_t r = 0; r < robots; ++r) {
        s->robot[r] = s->robot[0];
        s->robot[r].target.center_m[0] = 3.0 * r;
    }
    if (variant & 16u) {
        s->distance_count = robots;
        for (int32_t r = 0; r < robots; ++r) {
            s->distance[r].robot_a = r;
            s->distance[r].robot_b = (r + 1) % robots;
            s->distance[r].min_m = 0.5;
            s->distance[r].max_m = 6.0 * robots;
        }
    }
}

static int16_t int16_at(const uint8_t *p, size_t length, size_t at)
{
    return (at + 1 < length) ? (int16_t)(uint16_t)(p[at] | (p[at + 1] << 8)) : 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) {
        return 0;
    }
    const int32_t robots = 2 + data[0] % (TVO_FLEET_MAX_ROBOTS - 1);
    const int32_t own = (int32_t)((data[0] >> 3) % (uint32_t)robots);
    if (tvo_fleet_link_init(&link, &node, own, publish, NULL) != 0) {
        fuzz_fail("fleet link init");
    }
    fleet_session(&session, data[0], robots);
    int64_t now = 5000000;
    const int n = tvo_lcm_session_t_encode(buffer, 0, sizeof(buffer), &session);
    (void)tvo_fleet_link_receive(&link, &node, TVO_NODE_CH_SESSION, buffer, (uint32_t)n, now);
    if (tvo_node_session(&node) == NULL) {
        fuzz_fail("the reference fleet session was refused");
    }
    reference_hash = tvo_node_session(&node)->content_hash;
    int64_t sequence = 0;
    size_t i = 1;
    while (i + 4 <= size) {
        const uint8_t kind = data[i] % 4u;
        size_t length = (size_t)data[i + 1] | ((size_t)data[i + 2] << 8);
        now += 500 * (int64_t)data[i + 3];
        i += 4;
        if (length > size - i) {
            length = size - i;
        }
        const uint8_t *p = data + i;
        if (kind == 0u) {
            tvo_lcm_fleet_sample_t s;
            memset(&s, 0, sizeof(s));
            s.robot = (length > 0) ? (int32_t)(p[0] % (uint32_t)robots) : own;
            sequence += (length > 1) ? (int8_t)p[1] : 0;
            s.sequence = sequence;
            s.utime = session.epoch_utime + (sequence + 1) * session.period_us - session.delay_us;
            s.robot_count = robots;
            s.position_m[0] = 1e-3 * int16_at(p, length, 2);
            s.position_m[1] = 1e-3 * int16_at(p, length, 4);
            s.heading_rad = 1e-3 * int16_at(p, length, 6);
            s.speed_mps = 1e-3 * int16_at(p, length, 8);
            const uint8_t flags = (length > 10) ? p[10] : 3u;
            s.heading_valid = (flags & 1u) != 0;
            s.speed_valid = (flags & 2u) != 0;
            s.session_id = (flags & 4u) ? session.session_id + 1 : session.session_id;
            const int m = tvo_lcm_fleet_sample_t_encode(buffer, 0, sizeof(buffer), &s);
            (void)tvo_fleet_link_receive(&link, &node, TVO_FLEET_CH_SAMPLE, buffer, (uint32_t)m, now);
        } else {
            const int channel = kind == 1u ? TVO_FLEET_CH_SAMPLE : kind == 2u ? TVO_NODE_CH_SESSION : TVO_NODE_CH_TARGET;
            (void)tvo_fleet_link_receive(&link, &node, channel, p, (uint32_t)length, now);
        }
        (void)tvo_node_poll(&node, now);
        i += length;
    }
    return 0;
}
