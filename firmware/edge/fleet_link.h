/*
 * A fleet link in front of the node: one node per robot, each evaluating the joint law and applying
 * its own robot's row (lcm_types/README.md, "A fleet").
 *
 *   in   TVO_FLEET_SAMPLE_R<own>  fleet_sample_t, one robot's sample each. The others' samples of a
 *                                 period are kept until the own robot's sample of that period
 *                                 arrives; that one steps the node with the joint measurement
 *                                 (tvo_node_measure: as many robots as the build drives). A robot whose sample for the period is missing (lost, or
 *                                 not yet arrived: late) is predicted from its last known state along
 *                                 the exact unicycle arc of the joint commands this node computed
 *                                 (deterministic: nodes that heard the same samples predict alike).
 *        TVO_SESSION, TVO_TARGET  handed to the node unchanged.
 *   out  TVO_FLEET_COMMAND_R<own> fleet_command_t: the own robot's row, the joint command's digest
 *                                 (the node answers the link, tvo_node_set_answer, not in command_t).
 *        TVO_SESSION_ACK_R<own>, TVO_TELEMETRY_R<own>  the node's own messages, named by robot.
 *
 * A node steps only once it has heard every robot (a robot never heard cannot be predicted): until
 * then the own sample is answered with the wire's STATUS_ERR_NO_MEASUREMENT and the command in force (FLAG_HOLDING).
 * A prediction spans at most the session's watchdog_periods periods; a robot unheard for longer is
 * not predicted either (same answer), since the plant stops robots whose commands stop.
 * Transport-independent, like node.c and auth_link.c; the LCM process is tvo_firmware_node --own-robot.
 */
#ifndef TVO_FLEET_LINK_H
#define TVO_FLEET_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "node.h"
#include "tvo_lcm_fleet_command_t.h"
#include "tvo_lcm_fleet_sample_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Robots of a fleet: as many as the build drives (tvo_core's TVO_MAX_ROBOTS; the fleet messages carry 8). */
#define TVO_FLEET_MAX_ROBOTS TVO_MAX_ROBOTS

/** The fleet's own channels (after the node's: they share the numbering of tvo_node_channel_t). */
typedef enum {
    TVO_FLEET_CH_SAMPLE = 11,        /* TVO_FLEET_SAMPLE_R<own>: in */
    TVO_FLEET_CH_COMMAND = 12,       /* TVO_FLEET_COMMAND_R<own>: out */
    TVO_FLEET_CH_SESSION_ACK = 13,   /* TVO_SESSION_ACK_R<own>: out */
    TVO_FLEET_CH_TELEMETRY = 14      /* TVO_TELEMETRY_R<own>: out */
} tvo_fleet_channel_t;

/** Longest channel name with its robot number and terminator. */
#define TVO_FLEET_CHANNEL_NAME_BYTES 32

/** Writes the LCM name of a fleet channel for `robot` (e.g. "TVO_FLEET_SAMPLE_R2"); 0, or -1 if unknown. */
int tvo_fleet_channel_name(int channel, int32_t robot, char *out, size_t size);

/**
 * A keyed fleet node's channel names for its auth link (tvo_auth_link_namer_fn; context: the link):
 * the fleet's channels carry the own robot, the node's keep their names. 0, or -1 if unknown.
 */
int tvo_fleet_link_channel_name(void *link, int channel, char *out, size_t size);

/** What the link knows of one robot at a sampling instant. */
typedef struct {
    double position_m[2];
    double heading_rad;
    double speed_mps;
    int64_t sequence;        /* the sample's sequence; -1: never heard */
} tvo_fleet_robot_t;

/** A joint command in force from the period its measurement sequence serves on (zero-order hold). */
typedef struct {
    int64_t sequence;        /* -1: none yet (robots at rest) */
    double speed_mps[TVO_FLEET_MAX_ROBOTS];
    double turn_rate_radps[TVO_FLEET_MAX_ROBOTS];
} tvo_fleet_joint_command_t;

/** FNV-1a 64 of a joint command: speed then turn rate of robots 0 .. robot_count-1, each double's
 *  IEEE-754 bits least significant byte first (the same on every machine). */
uint64_t tvo_fleet_digest(const tvo_fleet_joint_command_t *command, int32_t robot_count);

typedef struct {
    int32_t own_robot;
    tvo_node_publish_fn transport_publish;   /* where the fleet's channels go; channel: tvo_fleet_channel_t */
    void *transport_context;
    int64_t session_id;                      /* of the samples being gathered; -1 before the first */
    int64_t last_step;                       /* sequence of the last own sample stepped; -1 none */
    tvo_fleet_robot_t known[TVO_FLEET_MAX_ROBOTS];     /* latest state per robot (measured or predicted) */
    uint8_t known_measured[TVO_FLEET_MAX_ROBOTS];      /* known[r] came from r's own sample */
    tvo_lcm_fleet_sample_t pending[TVO_FLEET_MAX_ROBOTS]; /* the newest sample of a period not yet stepped */
    uint8_t has_pending[TVO_FLEET_MAX_ROBOTS];
    tvo_fleet_joint_command_t commands[2];   /* [0] the newest joint command this node computed, [1] the one before */
    int32_t predicted;                       /* robots predicted in the step being answered */
    int64_t answering;                       /* the sequence being stepped; -1 outside a step */
    uint8_t answered_ok;                     /* the node computed a command for it (status 0) */
    /* Counts since init, for logs and tests. */
    uint32_t samples_taken;
    uint32_t samples_late;                   /* of a period already stepped (improve the next prediction only) */
    uint32_t samples_refused;                /* did not decode, not finite, robot out of range */
    uint32_t predictions;                    /* robot-periods predicted */
    uint32_t unheard_steps;                  /* own samples answered NO_MEASUREMENT: a robot never heard */
    tvo_lcm_fleet_sample_t rx;               /* scratch: decoded in place, not on the stack */
    tvo_step_measurement_t joint;            /* the node's input being built */
    tvo_lcm_fleet_command_t out;
    uint8_t buffer[TVO_NODE_BUFFER_BYTES];
} tvo_fleet_link_t;

/**
 * A link and its node (initialised here: tvo_node_init with the link as its publisher and answer)
 * driving own_robot (0 .. TVO_FLEET_MAX_ROBOTS-1), publishing through transport_publish.
 * Returns 0, or -1 for own_robot out of range or a NULL argument (then neither is initialised).
 */
int tvo_fleet_link_init(tvo_fleet_link_t *link, tvo_node_t *node, int32_t own_robot,
                        tvo_node_publish_fn transport_publish, void *transport_context);

/**
 * A received message: TVO_FLEET_CH_SAMPLE is gathered (and the own robot's steps the node);
 * TVO_NODE_CH_SESSION and TVO_NODE_CH_TARGET go to the node. Returns the channel, or 0 if it was
 * not taken (counted in samples_refused for a sample).
 */
int tvo_fleet_link_receive(tvo_fleet_link_t *link, tvo_node_t *node, int channel, const uint8_t *data,
                           uint32_t length, int64_t now_us);

#ifdef __cplusplus
}
#endif

#endif /* TVO_FLEET_LINK_H */
