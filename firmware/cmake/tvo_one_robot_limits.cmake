# The size limits of a one-robot product (tvo/config.h): one unicycle's outputs and no equality
# constraints (a formation offset needs two robots), so neither other robots' arrays nor the saddle
# solve are compiled. Written once here: the host twin tvo_core_one_robot, the package and one-robot
# cross-build tests, and tools/bench's one-robot footprint (which parses the line below) read it.
set(TVO_ONE_ROBOT_LIMITS "TVO_MAX_OUTPUT_DIM=2,TVO_MAX_EQUALITIES=0")
