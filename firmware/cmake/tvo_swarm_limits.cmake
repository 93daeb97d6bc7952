# The size limits of a swarm of up to 32 robots (tvo/config.h: 64 outputs; 64 distance bounds, a ring of 32
# and as many more; 200 terms: a tracking term per robot, two per distance bound, a free space per robot and
# room to spare; 16 obstacles). The law's solve then follows the problem's coupling (tvo/linsolve.h's block
# plan), so a step costs about the same per robot at 32 as at 8. Written once here: tools/bench's scaling
# table (which parses the line below) and the host twin tvo_core_swarm (the block solve's unit tests at
# these limits) read it.
set(TVO_SWARM_LIMITS "TVO_MAX_OUTPUT_DIM=64,TVO_MAX_TERMS=200,TVO_MAX_DISTANCE_BOUNDS=64,TVO_MAX_OBSTACLES=16")
