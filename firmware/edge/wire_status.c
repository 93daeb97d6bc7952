/*
 * The wire's status texts (command_header_t.STATUS_*), each phrase written once: a code that is one of
 * the core's errors or reasons reads as the core's own text (tvo_status_str, tvo_reason_str); only the
 * node's own codes have theirs here. The node's statuses reach the wire through step_codec.c's one
 * table, so they need no texts of their own. Apart from channels.c so that only programs that print a
 * status link the core's texts.
 */
#include "channels.h"

#include "tvo/status.h"
#include "tvo_lcm_command_header_t.h"

#define WIRE(name) TVO_LCM_COMMAND_HEADER_T_STATUS_##name

const char *tvo_protocol_status_str(int32_t status)
{
    switch (status) {
    case WIRE(OK): return tvo_status_str(TVO_OK);
    case WIRE(ERR_NULL): return tvo_status_str(TVO_ERR_NULL);
    case WIRE(ERR_NOT_FINITE): return tvo_status_str(TVO_ERR_NOT_FINITE);
    case WIRE(ERR_DIMENSION): return tvo_status_str(TVO_ERR_DIMENSION);
    case WIRE(ERR_PARAM): return tvo_status_str(TVO_ERR_PARAM);
    case WIRE(ERR_CAPACITY): return tvo_status_str(TVO_ERR_CAPACITY);
    case WIRE(ERR_NOT_INITIALIZED): return tvo_status_str(TVO_ERR_NOT_INITIALIZED);
    case WIRE(ERR_NOT_POSITIVE_DEFINITE): return tvo_status_str(TVO_ERR_NOT_POSITIVE_DEFINITE);
    case WIRE(ERR_NUMERIC): return tvo_status_str(TVO_ERR_NUMERIC);
    case WIRE(ERR_STALE): return tvo_reason_str(TVO_REASON_STALE);
    case WIRE(ERR_OUT_OF_ORDER): return "timestamp did not advance";
    case WIRE(ERR_FUTURE_STAMP): return tvo_reason_str(TVO_REASON_FUTURE_STAMP);
    case WIRE(ERR_NO_MEASUREMENT): return "no sample (of every robot) this period";
    case WIRE(ERR_MISSING_FIELD): return tvo_reason_str(TVO_REASON_MISSING_FIELD);
    case WIRE(ERR_TARGET_NOT_READY): return tvo_reason_str(TVO_REASON_TARGET_NOT_READY);
    case WIRE(ERR_WATCHDOG): return tvo_reason_str(TVO_REASON_WATCHDOG);
    case WIRE(ERR_IMPLAUSIBLE_STAMP): return "stamp does not fit the session's schedule";
    case WIRE(ERR_SESSION_CONFLICT): return "session id already running with other parameters";
    case WIRE(ERR_NO_SESSION): return "no such session running";
    case WIRE(ERR_IMPLAUSIBLE_MEASUREMENT): return tvo_reason_str(TVO_REASON_IMPLAUSIBLE_MEASUREMENT);
    default: return tvo_status_str(TVO_STATUS_COUNT); /* the core's "unknown status" */
    }
}
