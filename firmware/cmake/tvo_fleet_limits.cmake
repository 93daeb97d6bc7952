# The size limits of a fleet of up to 8 robots (tvo/config.h: 16 outputs, a ring of 8 distance bounds,
# 16 obstacles). Written once here: the host twin tvo_core_fleet and its node tvo_firmware_node_fleet
# (one node per robot of a fleet of up to 8: lcm_types/README.md "A fleet"), tools/bench's scaling
# table and tools/agree's builds (which parse the line below) read it.
set(TVO_FLEET_LIMITS "TVO_MAX_OUTPUT_DIM=16,TVO_MAX_TERMS=32,TVO_MAX_DISTANCE_BOUNDS=8,TVO_MAX_OBSTACLES=16")
