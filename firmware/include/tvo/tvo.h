/*
 * Everything a firmware calls, in one include: the version, the status codes, the problem (targets,
 * constraints, the objective it builds), and the two controllers. firmware/README.md ("The API")
 * gives the call sequence; the other headers of this folder are what these include.
 */
#ifndef TVO_TVO_H
#define TVO_TVO_H

#include "tvo/chain_controller.h"
#include "tvo/config.h"
#include "tvo/controller.h"
#include "tvo/defaults.h"
#include "tvo/problem.h"
#include "tvo/status.h"
#include "tvo/target.h"
#include "tvo/version.h"

#endif /* TVO_TVO_H */
