/*
 * One controller interface for the edge: a tagged union of the core's controllers with a small
 * table of operations (as tvo_term_t does for objective terms). The node never asks which plant a
 * session runs; adding a plant is one more table.
 */
#ifndef TVO_EDGE_CONTROLLER_H
#define TVO_EDGE_CONTROLLER_H

#include <stdint.h>

#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"

#include "session_codec.h"
#include "step_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef union {
    tvo_measurement_t unicycle;
    tvo_chain_measurement_t chain;
} tvo_edge_measurement_t;

typedef union {
    tvo_command_t unicycle;
    tvo_chain_command_t chain;
} tvo_edge_command_t;

typedef struct tvo_edge_controller tvo_edge_controller_t;

/** What a command says of its period, whichever the plant. */
typedef struct {
    uint32_t flags;         /* TVO_FLAG_* */
    tvo_outcome_t outcome;
    tvo_reason_t reason;
} tvo_edge_mark_t;

/** A period's samples, as the plant's controller reads them. */
typedef struct {
    const tvo_step_period_t *unicycle;       /* PLANT_UNICYCLE: every robot's row (sampled or predicted) */
    const tvo_lcm_chain_sample_t *chain;     /* PLANT_CHAIN: the one robot's sample */
} tvo_edge_samples_t;

typedef struct {
    const char *name;
    int sample_channel;     /* where its samples arrive (TVO_NODE_CH_SAMPLE, TVO_NODE_CH_CHAIN_SAMPLE) */
    int command_channel;    /* where its commands go (TVO_NODE_CH_COMMAND, TVO_NODE_CH_CHAIN_COMMAND) */
    /** Relative degree of the flat output (bounds the barrier's m_r below). */
    uint8_t (*relative_degree)(const tvo_lcm_session_t *msg);
    /** Configuration from the START, then the core's init (which names the culprit in *why). */
    tvo_status_t (*init)(tvo_edge_controller_t *ctl, const tvo_lcm_session_t *msg, const tvo_objective_t *objective,
                         uint32_t epoch_tick, tvo_session_reject_t *why);
    /** The period's samples as the core's measurement: TVO_NODE_OK, or the edge's refusal (they lack
     *  what ctl's configuration reads: TVO_NODE_MISSING_DERIVATIVES). */
    tvo_node_status_t (*measurement)(const tvo_edge_controller_t *ctl, const tvo_edge_samples_t *samples,
                                     uint8_t robot_count, uint32_t stamp_tick, tvo_edge_measurement_t *meas);
    /* The core's sampled-data loop, the same for every plant (edge_controller.c's EDGE_LOOP_OPS): init
     * (above), step, miss, safe_stop, refuse, check, mark, clock. The others map the wire to the plant. */
    /** The core's step: a transaction (a whole period committed, or nothing changed and the refusal's
     *  command: the one in force, or the watchdog's stop). */
    tvo_status_t (*step)(tvo_edge_controller_t *ctl, const tvo_edge_measurement_t *meas, uint32_t apply_tick,
                         tvo_edge_command_t *cmd);
    /** The core's count of a period without a good step: its watchdog decides hold or stop. */
    tvo_status_t (*miss)(tvo_edge_controller_t *ctl, uint32_t apply_tick, tvo_edge_command_t *cmd);
    tvo_status_t (*safe_stop)(tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd);
    /** A sample the node refused (the core never saw it): the core's answer, the command in force
     *  (TVO_REASON_REFUSED: the node's status says why) or its watchdog's stop (a lockstep session
     *  counts refusals). */
    tvo_status_t (*refuse)(tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd);
    /** What the core's step would say of this measurement, changing nothing (tvo_controller_check). */
    tvo_status_t (*check)(const tvo_edge_controller_t *ctl, const tvo_edge_measurement_t *meas, uint32_t apply_tick,
                          tvo_reason_t *reason);
    /** A command's flags, outcome and reason: what the core's answer says (whether it took the period's
     *  sample included: node_period.c reads it in one place). */
    tvo_edge_mark_t (*mark)(const tvo_edge_command_t *cmd);
    /** Robot `robot`'s command (the chain: robot 0's u) encoded into buffer: its length, or <= 0. */
    int (*encode_command)(const tvo_edge_command_t *cmd, const tvo_step_stamp_t *stamp, int32_t robot, uint8_t *buffer,
                          uint32_t capacity);
    /** The joint command's digest (telemetry_t.joint_digest) and its rows as doubles, for prediction
     *  (the chain: its inputs; it has one robot, never predicted). */
    uint64_t (*digest)(const tvo_edge_command_t *cmd, uint8_t robot_count);
    void (*rows)(const tvo_edge_command_t *cmd, uint8_t robot_count, double *speed_mps, double *turn_rate_radps);
    /** Robot `robot`'s part of the telemetry: the controller's last good step (the chain keeps none). */
    void (*telemetry_to_lcm)(const tvo_edge_controller_t *ctl, const tvo_problem_t *problem, uint8_t robot,
                             tvo_lcm_telemetry_t *msg);
    tvo_sample_clock_t *(*clock)(tvo_edge_controller_t *ctl);
} tvo_edge_controller_ops_t;

struct tvo_edge_controller {
    const tvo_edge_controller_ops_t *ops;
    union {
        tvo_controller_t unicycle;
        tvo_chain_controller_t chain;
    } u;
};

/**
 * Zeroes the controller's work area (scratch its step writes before reading, holding no state
 * between steps), so two controllers in the same state compare equal byte for byte (tests, fuzzing).
 */
void tvo_edge_controller_clear_scratch(tvo_edge_controller_t *ctl);

/** The operations for a session's plant kind (session_t.PLANT_*), NULL if there are none. */
const tvo_edge_controller_ops_t *tvo_edge_controller_ops(int32_t plant_kind);

#ifdef __cplusplus
}
#endif

#endif /* TVO_EDGE_CONTROLLER_H */
