/*
 * A node of a multi-robot session (the fleet build: up to 8 robots), driving one robot (own_robot k)
 * or every robot: a valid session (robot count, own robot, clock and a ring of distance bounds from the
 * first input byte), then a stream of per-robot samples (built from a few fuzzed bytes, so that
 * periods line up), raw bytes on every channel the node takes, and the node's clock advancing by
 * fuzzed steps. Beside a node of robot k runs a node of every robot on the same input. Invariants:
 * every command decodes, is a driven robot's, finite, within the session's limits, a safe stop all
 * zero, status 0 only on a computed command; a node of every robot publishes all robot_count rows of
 * an answer and its telemetry's digest is theirs; and, while both run the same session, the node of
 * robot k publishes exactly the other node's command and telemetry for robot k, byte for byte.
 * Record format after the variant byte: kind (1 byte: 0 a sample, 1 raw sample bytes, 2 raw session
 * bytes, 3 raw target bytes), length (2 bytes LE), clock step (1 byte, x 500 us), then `length` bytes.
 * A sample's bytes: robot, sequence step (int8 from the last), x, y, heading, speed (int16 LE, mm or
 * mrad), flags (bit 0 heading measured, bit 1 speed measured, bit 2 another session).
 */
#include "fuzz_support.h"

#define FLEET_MAX_MESSAGES 64

typedef struct {
    int channel;
    uint32_t length;
    uint8_t data[TVO_NODE_BUFFER_BYTES];
} message_t;

/* What a node published during one handle or poll call. */
typedef struct {
    tvo_node_t node;
    message_t message[FLEET_MAX_MESSAGES];
    uint32_t count;
} subject_t;

static subject_t member;        /* own_robot k, or every robot when k is -1 */
static subject_t central;       /* every robot, beside a member of robot k */
static tvo_lcm_session_t session;
static uint64_t reference_hash; /* the reference START's: its limits bind the rows while it runs */
static uint8_t buffer[16384];

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    subject_t *subject = (subject_t *)context;
    if (channel == TVO_NODE_CH_NODE) {
        return; /* announcements: the node's own (they differ by own_robot) */
    }
    if (subject->count >= FLEET_MAX_MESSAGES || length > TVO_NODE_BUFFER_BYTES) {
        fuzz_fail("more messages in one call than an answer has");
    }
    message_t *m = &subject->message[subject->count++];
    m->channel = channel;
    m->length = length;
    memcpy(m->data, data, length);
}

/* The invariants of one subject's messages of one call. */
static void check_subject(const subject_t *subject)
{
    const tvo_node_session_t *running = tvo_node_session(&subject->node);
    const int reference_limits = running != NULL && running->content_hash == reference_hash;
    const int8_t own = subject->node.own_robot;
    double speed[TVO_MAX_ROBOTS];
    double turn[TVO_MAX_ROBOTS];
    int32_t rows = 0;
    int32_t telemetry = 0;
    for (uint32_t i = 0; i < subject->count; ++i) {
        const message_t *m = &subject->message[i];
        tvo_lcm_command_header_t header;
        if (m->channel == TVO_NODE_CH_COMMAND) {
            tvo_lcm_unicycle_command_t cmd;
            if (tvo_lcm_unicycle_command_t_decode(m->data, 0, (int)m->length, &cmd) != (int)m->length) {
                fuzz_fail("a command that does not decode");
            }
            fuzz_check_unicycle_command(&cmd, reference_limits ? &session : NULL);
            header = cmd.header;
            if ((own >= 0 && header.robot != own) || header.robot < 0 || header.robot >= TVO_MAX_ROBOTS ||
                (own < 0 && header.robot != rows)) {
                fuzz_fail("a command of a robot the node does not drive, or out of robot order");
            }
            if (rows < TVO_MAX_ROBOTS) {
                speed[rows] = (double)cmd.speed_mps;
                turn[rows] = (double)cmd.turn_rate_radps;
            }
            ++rows;
        } else if (m->channel == TVO_NODE_CH_TELEMETRY) {
            tvo_lcm_telemetry_t tel;
            if (tvo_lcm_telemetry_t_decode(m->data, 0, (int)m->length, &tel) != (int)m->length) {
                fuzz_fail("telemetry that does not decode");
            }
            if (own < 0 && running != NULL && rows == (int32_t)running->schedule.timing.robot_count &&
                tvo_joint_digest(speed, turn, rows) != (uint64_t)tel.joint_digest) {
                fuzz_fail("the telemetry's digest is not the answer's rows'");
            }
            ++telemetry;
        } else if (fuzz_check_published_command(m->channel, m->data, m->length, NULL, &header)) {
            fuzz_fail("a chain command from a unicycle fleet");
        }
    }
    if (own < 0 && running != NULL && rows > 0 && rows != (int32_t)running->schedule.timing.robot_count) {
        fuzz_fail("an answer without every robot's row");
    }
    if (telemetry > 0 && telemetry != (own < 0 ? rows : 1)) {
        fuzz_fail("telemetry not one per driven robot");
    }
}

/* The robot a published command or telemetry is for (both lead with command_header_t), or -1. */
static int32_t robot_of(const message_t *m)
{
    if (m->channel == TVO_NODE_CH_COMMAND) {
        tvo_lcm_unicycle_command_t cmd;
        return tvo_lcm_unicycle_command_t_decode(m->data, 0, (int)m->length, &cmd) == (int)m->length ? cmd.header.robot : -1;
    }
    if (m->channel == TVO_NODE_CH_TELEMETRY) {
        tvo_lcm_telemetry_t tel;
        return tvo_lcm_telemetry_t_decode(m->data, 0, (int)m->length, &tel) == (int)m->length ? tel.header.robot : -1;
    }
    return -1;
}

/* The member (of robot k) published exactly the central node's commands and telemetry for robot k. */
static void compare_with_central(void)
{
    const int32_t own = member.node.own_robot;
    uint32_t c = 0u;
    for (uint32_t i = 0; i < member.count; ++i) {
        const message_t *m = &member.message[i];
        if (m->channel != TVO_NODE_CH_COMMAND && m->channel != TVO_NODE_CH_TELEMETRY) {
            continue; /* acks carry the node's own robot */
        }
        while (c < central.count && (central.message[c].channel != m->channel || robot_of(&central.message[c]) != own)) {
            ++c;
        }
        if (c == central.count) {
            fuzz_fail("a node of robot k answered what the node of every robot did not");
        }
        const message_t *o = &central.message[c++];
        if (o->length != m->length || memcmp(o->data, m->data, m->length) != 0) {
            fuzz_fail("a node of robot k computed another row than the node of every robot");
        }
    }
    for (; c < central.count; ++c) {
        if (robot_of(&central.message[c]) == own) {
            fuzz_fail("the node of every robot answered robot k where its node did not");
        }
    }
}

/* The fleet's session: fuzz_session's unicycle variant with `robots` robots on ellipses apart, and a
 * ring of distance bounds (bit 4), as tools/fleet's scenarios have. */
static void fleet_session(tvo_lcm_session_t *s, uint8_t variant, int32_t robots)
{
    fuzz_session(s, (uint8_t)(variant & ~2u & ~8u & ~16u)); /* unicycles */
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

/* Both subjects take the same message, then the same timer call (each of which answers at most one
 * period), and are checked after each. */
static void deliver(int channel, const uint8_t *message, uint32_t length, int64_t now, int with_central, int *diverged)
{
    for (int phase = 0; phase < 2; ++phase) {
        member.count = 0u;
        central.count = 0u;
        if (phase == 0) {
            (void)tvo_node_handle(&member.node, channel, message, length, now);
        } else {
            (void)tvo_node_poll(&member.node, now);
        }
        check_subject(&member);
        if (!with_central) {
            continue;
        }
        if (phase == 0) {
            (void)tvo_node_handle(&central.node, channel, message, length, now);
        } else {
            (void)tvo_node_poll(&central.node, now);
        }
        check_subject(&central);
        const tvo_node_session_t *a = tvo_node_session(&member.node);
        const tvo_node_session_t *b = tvo_node_session(&central.node);
        if ((a == NULL) != (b == NULL) ||
            (a != NULL && (a->session_id != b->session_id || a->content_hash != b->content_hash))) {
            *diverged = 1; /* they took different STARTs (a fuzzed one named only one of them): now two nodes */
        }
        if (!*diverged) {
            compare_with_central();
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) {
        return 0;
    }
    const int32_t robots = 2 + data[0] % (TVO_NODE_MAX_ROBOTS - 1);
    const int8_t own = (int8_t)((int32_t)((data[0] >> 3) % (uint32_t)(robots + 1)) - 1);
    const int with_central = own >= 0;
    if (tvo_node_init(&member.node, own, FUZZ_BOOT, publish, &member) != 0 ||
        tvo_node_init(&central.node, -1, FUZZ_BOOT, publish, &central) != 0) {
        fuzz_fail("node init");
    }
    int diverged = 0;
    fleet_session(&session, data[0], robots);
    int64_t now = 5000000;
    const int n = tvo_lcm_session_t_encode(buffer, 0, sizeof(buffer), &session);
    deliver(TVO_NODE_CH_SESSION, buffer, (uint32_t)n, now, with_central, &diverged);
    if (tvo_node_session(&member.node) == NULL) {
        fuzz_fail("the reference fleet session was refused");
    }
    reference_hash = tvo_node_session(&member.node)->content_hash;
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
            tvo_lcm_unicycle_sample_t s;
            memset(&s, 0, sizeof(s));
            s.header.robot = (int8_t)((length > 0) ? (int32_t)(p[0] % (uint32_t)robots) : robots - 1);
            sequence += (length > 1) ? (int8_t)p[1] : 0;
            sequence = sequence < 0 ? 0 : (sequence > INT32_MAX - 200 ? INT32_MAX - 200 : sequence);
            s.header.sequence = (int32_t)sequence;
            s.header.utime = session.epoch_utime + (sequence + 1) * session.period_us - session.delay_us;
            s.position_m[0] = 1e-3 * int16_at(p, length, 2);
            s.position_m[1] = 1e-3 * int16_at(p, length, 4);
            s.heading_rad = 1e-3f * (float)int16_at(p, length, 6);
            s.speed_mps = 1e-3f * (float)int16_at(p, length, 8);
            const uint8_t flags = (length > 10) ? p[10] : 3u;
            s.has = (int8_t)((flags & 1u) ? TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING : 0) |
                    (int8_t)((flags & 2u) ? TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED : 0);
            s.header.session_id = (flags & 4u) ? session.session_id + 1 : session.session_id;
            const int m = tvo_lcm_unicycle_sample_t_encode(buffer, 0, sizeof(buffer), &s);
            deliver(TVO_NODE_CH_SAMPLE, buffer, (uint32_t)m, now, with_central, &diverged);
        } else {
            const int channel = kind == 1u ? TVO_NODE_CH_SAMPLE : kind == 2u ? TVO_NODE_CH_SESSION : TVO_NODE_CH_TARGET;
            deliver(channel, p, (uint32_t)length, now, with_central, &diverged);
        }
        i += length;
    }
    return 0;
}
