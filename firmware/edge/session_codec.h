/*
 * Session codec: a START message (tvo_lcm_session_t) into what the core needs (timing, controller
 * configurations, the problem description), with every integer from the wire range-checked before
 * any arithmetic, and the session ack out. Pure functions: no state, no allocation.
 */
#ifndef TVO_SESSION_CODEC_H
#define TVO_SESSION_CODEC_H

#include <stdint.h>

#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"
#include "tvo/sample_clock.h"

#include "channels.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Ticks of the core's clock per second: ticks are microseconds, like LCM's utime. */
#define TVO_EDGE_TICK_HZ 1000000u

/** A START's parameters as the wire names them (session_ack_t.PARAM_*, the same numbers): the session's
 *  own fields, and the fields of both controllers' configurations mapped onto them (session_codec.c). */
typedef enum {
    TVO_SESSION_PARAM_NONE = 0,
    TVO_SESSION_PARAM_TICK_HZ = 1,
    TVO_SESSION_PARAM_PERIOD = 2,
    TVO_SESSION_PARAM_DELAY = 3,
    TVO_SESSION_PARAM_FILTER_TF = 4,
    TVO_SESSION_PARAM_GAINS = 5,
    TVO_SESSION_PARAM_OMEGA_MAX = 6,
    TVO_SESSION_PARAM_ACCEL_MAX = 7,
    TVO_SESSION_PARAM_SPEED_MAX = 8,
    TVO_SESSION_PARAM_MIN_SPEED = 9,
    TVO_SESSION_PARAM_WATCHDOG = 10,
    TVO_SESSION_PARAM_ROBOT_COUNT = 11,
    TVO_SESSION_PARAM_OBJECTIVE = 12,
    TVO_SESSION_PARAM_VELOCITY_SOURCE = 13,
    TVO_SESSION_PARAM_INITIAL_SPEED = 14,
    TVO_SESSION_PARAM_EPOCH = 15,
    TVO_SESSION_PARAM_CLOCK_SOURCE = 16,
    TVO_SESSION_PARAM_PLANT_KIND = 17,
    TVO_SESSION_PARAM_SESSION_ID = 18,
    TVO_SESSION_PARAM_PROTOCOL_VERSION = 19,
    TVO_SESSION_PARAM_TELEMETRY_EVERY = 20
} tvo_session_param_t;

/** The most periods between telemetry messages a START may ask for (session_t.telemetry_every). */
#define TVO_SESSION_TELEMETRY_EVERY_MAX ((int32_t)1 << 20)
/** The default telemetry rate (telemetry_every 0): every ceil(this / period_us)-th period, about 10 Hz. */
#define TVO_SESSION_TELEMETRY_DEFAULT_US 100000

/** Why a session message was refused: the edge's status, else the core's error, the parameter, the
 *  problem part and its entry (the ack carries their wire values: tvo_session_ack). */
typedef struct {
    tvo_node_status_t node;       /* the edge's own refusal (conflict, no session, unknown action) */
    tvo_status_t status;          /* else the core's (or the codec's) error */
    tvo_session_param_t param;    /* TVO_SESSION_PARAM_OBJECTIVE when the problem was at fault */
    int32_t part;                 /* TVO_LCM_SESSION_ACK_T_PART_*, PART_NONE if not the problem */
    int32_t index;                /* entry of that part (robot, bound, obstacle, offset), -1 if none */
} tvo_session_reject_t;

/** The session parameter a unicycle controller's init names. */
tvo_session_param_t tvo_session_param_of_unicycle(tvo_param_t param);

/** The session parameter a chain controller's init names. */
tvo_session_param_t tvo_session_param_of_chain(tvo_chain_param_t param);

/** The session's timing, checked: period 1 .. 2^30-1 us, delay 0 .. period, watchdog >= 1 (its span: the core's init). */
typedef struct {
    int32_t clock_source;   /* TVO_LCM_SESSION_T_CLOCK_PLANT or _CLOCK_NODE */
    int64_t epoch_utime;
    int64_t period_us;
    int64_t delay_us;
    uint32_t watchdog_periods;
    uint32_t telemetry_every; /* >= 1: telemetry after the answers to sequences that are multiples of it */
    uint8_t robot_count;
    int32_t plant_kind;     /* TVO_LCM_SESSION_T_PLANT_* */
} tvo_session_timing_t;

/**
 * The wire checks of a START that need no core: the protocol version, the session id, times within
 * TVO_WIRE_TIME_MAX_US, the epoch within TVO_SESSION_EPOCH_SPAN_US of the message's own utime, timing
 * ranges, the robot count (1 .. the build's TVO_MAX_ROBOTS; a chain: 1), plant kind, clock source,
 * telemetry_every (0 .. TVO_SESSION_TELEMETRY_EVERY_MAX; 0 becomes the default). TVO_OK or
 * TVO_ERR_PARAM with *why naming the parameter.
 */
tvo_status_t tvo_session_decode_timing(const tvo_lcm_session_t *msg, tvo_session_timing_t *timing,
                                       tvo_session_reject_t *why);

/** The unicycle controller's configuration (the core validates ranges when it is initialised). */
tvo_status_t tvo_session_decode_unicycle(const tvo_lcm_session_t *msg, tvo_controller_config_t *cfg,
                                         tvo_session_reject_t *why);

/** The chain controller's configuration (PLANT_CHAIN). */
tvo_status_t tvo_session_decode_chain(const tvo_lcm_session_t *msg, tvo_chain_config_t *cfg,
                                      tvo_session_reject_t *why);

/**
 * The problem description: targets and weights per robot, barrier, distance bounds, half-spaces,
 * obstacles, formation offsets. Counts and robot indices are checked here (why->part/index name
 * the entry); values are the core's to judge (tvo_problem_init).
 */
tvo_status_t tvo_session_decode_problem(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc,
                                        tvo_session_reject_t *why);

/** One path (a target or an offset) from the wire; TVO_ERR_PARAM for an unknown kind. */
tvo_status_t tvo_session_decode_path(const tvo_lcm_path_t *path, tvo_target_t *target);

/** Part of the problem named by tvo_problem_init's part index (session_ack_t.PART_*). */
int32_t tvo_session_part_from_problem(uint8_t problem_part);

/**
 * FNV-1a hash of an encoded session message past its fingerprint and utime: two STARTs with the
 * same hash differ at most in when they were sent (a repeat).
 */
uint64_t tvo_session_content_hash(const uint8_t *data, uint32_t length);

/** The ack of a session message by the node of boot boot_id driving own_robot (-1: every robot).
 *  running_session_id is -1 when no session runs. */
void tvo_session_ack(const tvo_lcm_session_t *msg, const tvo_session_reject_t *why, int32_t running_session_id,
                     int64_t boot_id, int8_t own_robot, tvo_lcm_session_ack_t *ack);

#ifdef __cplusplus
}
#endif

#endif /* TVO_SESSION_CODEC_H */
