# Scenario files (host/README.md, "Your own scenario"); included by tests/closed_loop/CMakeLists.txt. The
# built-in runs' figures are checked by the closed-loop scenario tests there, which load the same files
# by name.
set(tvo_sf_dir ${PROJECT_SOURCE_DIR}/tests/scenario_files)

# Each built-in file loads by its name, and --list-scenarios lists them all with their descriptions,
# as tools/scenario --list does without a build.
add_test(NAME scenario_files_builtins_load
  COMMAND ${CMAKE_COMMAND} -DSIM=$<TARGET_FILE:tvo_sim> -DSCENARIO_DIR=${PROJECT_SOURCE_DIR}/host/scenarios
    -DSCENARIO_TOOL=${PROJECT_SOURCE_DIR}/tools/scenario -DWORK=${CMAKE_CURRENT_BINARY_DIR}/scenario_files_builtins_load
    -P ${tvo_sf_dir}/builtins_load.cmake)
set_tests_properties(scenario_files_builtins_load PROPERTIES LABELS "closed_loop;host" TIMEOUT 60)

# tvo_scenario_file_run(NAME <name> FILE <file> [BUILTIN <name>] [CHECKS ...])
function(tvo_scenario_file_run)
  cmake_parse_arguments(T "" "NAME;FILE;BUILTIN" "CHECKS" ${ARGN})
  tvo_test_lcm_url(url)
  string(REPLACE ";" "|" checks "${T_CHECKS}")
  add_test(NAME ${T_NAME}
    COMMAND ${CMAKE_COMMAND}
      -DSCENARIO_TOOL=${PROJECT_SOURCE_DIR}/tools/scenario -DBUILD_DIR=${PROJECT_BINARY_DIR}
      -DSIM=$<TARGET_FILE:tvo_sim> -DFIRMWARE=$<TARGET_FILE:tvo_firmware_node>
      "-DLCM_URL=${url}" -DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}
      -DFILE=${T_FILE} "-DBUILTIN=${T_BUILTIN}" "-DCHECKS=${checks}"
      -P ${tvo_sf_dir}/file_like_builtin.cmake)
  set_tests_properties(${T_NAME} PROPERTIES LABELS closed_loop TIMEOUT 240)
endfunction()

# A user's file (two robots, three new obstacles, a waypoint target and a circle, a distance bound,
# its own h and noise) runs through tools/scenario and gives what the same file gives as a built-in.
# Measured: no contact, 0.62 m min clearance, 4.0e-3 m final error (sigma = 1 mm), 3.6 m min
# distance; the bounds leave room for noise but not for a robot that hits a pillar or stops.
tvo_scenario_file_run(NAME scenario_file_user_runs FILE ${tvo_sf_dir}/warehouse.yaml
  CHECKS "steps==800" "collisions==0" "min_clearance_m>0.3" "final_error_m<0.02" "max_violation_frac<=0.01"
         "faults==0")
# A built-in's file given as a path runs exactly as the built-in given by name.
tvo_scenario_file_run(NAME scenario_file_builtin_as_path FILE ${PROJECT_SOURCE_DIR}/host/scenarios/obstacles.yaml
  BUILTIN obstacles CHECKS "collisions==0" "final_error_m<1e-2")

# tvo_scenario_message(NAME <name> EXIT <code> ARGS ... [STDERR <text>] [STDOUT <text>])
function(tvo_scenario_message)
  cmake_parse_arguments(T "" "NAME;EXIT;STDERR;STDOUT" "ARGS" ${ARGN})
  string(REPLACE ";" "|" args "${T_ARGS}")
  set(defs -DSIM=$<TARGET_FILE:tvo_sim> "-DSIM_ARGS=${args}" -DEXPECT_EXIT=${T_EXIT})
  if(DEFINED T_STDERR)
    list(APPEND defs "-DEXPECT_STDERR=${T_STDERR}")
  endif()
  if(DEFINED T_STDOUT)
    list(APPEND defs "-DEXPECT_STDOUT=${T_STDOUT}")
  endif()
  add_test(NAME ${T_NAME} COMMAND ${CMAKE_COMMAND} ${defs} -P ${tvo_sf_dir}/check_message.cmake)
  set_tests_properties(${T_NAME} PROPERTIES LABELS "closed_loop;host" TIMEOUT 60)
endfunction()

# A broken file exits 2 naming the file, line, column and field; the text is asserted as a whole.
set(tvo_broken ${tvo_sf_dir}/broken)
tvo_scenario_message(NAME scenario_file_bad_value EXIT 2 ARGS --scenario ${tvo_broken}/bad_value.yaml
  STDERR "${tvo_broken}/bad_value.yaml:10:15: obstacles[1].radius_m: must be > 0 (got -1)")
tvo_scenario_message(NAME scenario_file_unknown_key EXIT 2 ARGS --scenario ${tvo_broken}/unknown_key.yaml
  STDERR "${tvo_broken}/unknown_key.yaml:8:24: obstacles[0].raduis_m: unknown key (obstacles[0] takes center_m, radius_m)")
tvo_scenario_message(NAME scenario_file_wrong_type EXIT 2 ARGS --scenario ${tvo_broken}/wrong_type.yaml
  STDERR "${tvo_broken}/wrong_type.yaml:8:13: timing.period_s: expected a finite number (got 'fast')")
tvo_scenario_message(NAME scenario_file_syntax_error EXIT 2 ARGS --scenario ${tvo_broken}/syntax_error.yaml
  STDERR "${tvo_broken}/syntax_error.yaml:4:30: not valid YAML: illegal flow end")
tvo_scenario_message(NAME scenario_file_missing_key EXIT 2 ARGS --scenario ${tvo_broken}/missing_robots.yaml
  STDERR "${tvo_broken}/missing_robots.yaml:2:1: robots: missing (required)")
tvo_scenario_message(NAME scenario_file_bad_robot EXIT 2 ARGS --scenario ${tvo_broken}/bad_robot_index.yaml
  STDERR "${tvo_broken}/bad_robot_index.yaml:9:18: distance_bounds[0].robots[1]: must be in [0, 1] (got 2)")
# A key kept from a base file is that file's: its error names the base, at the key's line.
tvo_scenario_message(NAME scenario_file_base_error EXIT 2 ARGS --scenario ${tvo_broken}/base_one_robot.yaml
  STDERR "${tvo_broken}/../warehouse.yaml:26:18: distance_bounds[0].robots[1]: must be in [0, 0] (got 1)")
# Checks between sections (host/README.md, "Scenario file checks"), each at the node of the field at fault.
tvo_scenario_message(NAME scenario_file_start_in_obstacle EXIT 2 ARGS --scenario ${tvo_broken}/start_in_obstacle.yaml
  STDERR "${tvo_broken}/start_in_obstacle.yaml:7:25: robots[1].start.position_m: robot 1 starts inside obstacles[1] (${tvo_broken}/start_in_obstacle.yaml:12:5): [2.3, 0] is 0.3 m from its centre [2, 0], less than its radius 0.5 m + robot_radius_m 0.1 m")
tvo_scenario_message(NAME scenario_file_start_beyond_wall EXIT 2 ARGS --scenario ${tvo_broken}/start_beyond_wall.yaml
  STDERR "${tvo_broken}/start_beyond_wall.yaml:5:25: robots[0].start.position_m: robot 0 starts beyond the wall halfspaces[1] (${tvo_broken}/start_beyond_wall.yaml:9:5): normal^T [0, 0.5] = 0.5 > bound_m 0 at t = 0")
tvo_scenario_message(NAME scenario_file_overlapping_obstacles EXIT 2 ARGS --scenario ${tvo_broken}/overlapping_obstacles.yaml
  STDERR "${tvo_broken}/overlapping_obstacles.yaml:10:5: obstacles[2]: overlaps obstacles[0] (${tvo_broken}/overlapping_obstacles.yaml:8:5): centres 1 m apart, less than the radii's sum 1.2 m")
tvo_scenario_message(NAME scenario_file_waypoints_out_of_order EXIT 2 ARGS --scenario ${tvo_broken}/waypoints_out_of_order.yaml
  STDERR "${tvo_broken}/waypoints_out_of_order.yaml:10:17: robots[0].target.through[2].t_s: waypoint times must increase strictly: got 5 after robots[0].target.through[1].t_s = 8")
# A run past the last waypoint: the file's duration_s, the default 20 s, --duration-s (no hold: refused).
tvo_scenario_message(NAME scenario_file_duration_past_waypoint EXIT 2 ARGS --scenario ${tvo_broken}/duration_past_waypoint.yaml
  STDERR "${tvo_broken}/duration_past_waypoint.yaml:3:13: duration_s: must be at most the last waypoint's time, robots[0].target.through[1].t_s = 10 s (${tvo_broken}/duration_past_waypoint.yaml:9:17), got 30")
tvo_scenario_message(NAME scenario_file_default_duration_past_waypoint EXIT 2
  ARGS --scenario ${tvo_broken}/default_duration_past_waypoint.yaml
  STDERR "${tvo_broken}/default_duration_past_waypoint.yaml:8:17: robots[0].target.through[1].t_s: the last waypoint, at 10 s, comes before the run's end, 20 s (the default duration, no duration_s given)")
tvo_scenario_message(NAME scenario_file_option_duration_past_waypoint EXIT 2
  ARGS --scenario ${tvo_sf_dir}/warehouse.yaml --duration-s 30 --dry-run
  STDERR "${tvo_sf_dir}/warehouse.yaml:13:17: robots[0].target.through[2].t_s: the last waypoint, at 16 s, comes before the run's end, 30 s (--duration-s)")
# The size limit, before parsing (the limit read from scenario_file.hpp).
add_test(NAME scenario_file_size_limit
  COMMAND ${CMAKE_COMMAND} -DSIM=$<TARGET_FILE:tvo_sim> -DHEADER=${PROJECT_SOURCE_DIR}/host/src/scenario_file.hpp
    -DBASE=${tvo_sf_dir}/warehouse.yaml -DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/scenario_file_size_limit
    -P ${tvo_sf_dir}/size_limit.cmake)
set_tests_properties(scenario_file_size_limit PROPERTIES LABELS "closed_loop;host" TIMEOUT 60)
# The ranges of tvo_sim's settings are the options' own: sigma as --sigma's [0, 1].
tvo_scenario_message(NAME scenario_file_option_range EXIT 2 ARGS --scenario ${tvo_broken}/option_range.yaml
  STDERR "${tvo_broken}/option_range.yaml:8:10: sensing.sigma: must be in [0, 1] (got 2)")
tvo_scenario_message(NAME scenario_file_option_range_cli EXIT 2 ARGS --scenario demo --sigma 2
  STDERR "--sigma: got '2', expected a number in [0, 1]")
tvo_scenario_message(NAME scenario_file_unknown_name EXIT 2 ARGS --scenario no-such-scenario
  STDERR "--scenario: no scenario 'no-such-scenario'")
# A folder where a file belongs is named as a folder, not as a missing file.
tvo_scenario_message(NAME scenario_file_is_folder EXIT 2 ARGS --scenario ${tvo_broken}
  STDERR "--scenario: ${tvo_broken} is a folder, not a scenario file: give one of its .yaml files")
# Nesting past yaml-cpp's depth guard (its own text is only "bad file") is named as such, where it stops.
tvo_scenario_message(NAME scenario_file_deeply_nested EXIT 2 ARGS --scenario ${tvo_broken}/deeply_nested.yaml
  STDERR "${tvo_broken}/deeply_nested.yaml:3:1209: not valid YAML for a scenario: nested deeper than the parser's limit of 500 levels")

# The command line overrides the file: warehouse.yaml's h = 20 ms (800 periods of its 16 s) gives
# way to --period-s 0.01 (1600) and its duration to --duration-s 4.
tvo_scenario_message(NAME scenario_file_own_timing EXIT 0
  ARGS --scenario ${tvo_sf_dir}/warehouse.yaml --dry-run STDOUT "h = 20000 us, 800 periods (16 s)")
tvo_scenario_message(NAME scenario_file_option_overrides EXIT 0
  ARGS --scenario ${tvo_sf_dir}/warehouse.yaml --dry-run --period-s 0.01 --duration-s 4
  STDOUT "h = 10000 us, 400 periods (4 s)")
# Variants: --robots and --target circle apply only to a file that offers them (the demo).
tvo_scenario_message(NAME scenario_file_no_robots_variant EXIT 2 ARGS --scenario formation-max --robots 2
  STDERR "--robots: scenario formation-max has its own robots (its file has no variants.robots)")
tvo_scenario_message(NAME scenario_file_demo_variants EXIT 0 ARGS --scenario demo --robots 3 --target circle --dry-run
  STDOUT "dry run: scenario demo, 3 robot(s)")

# A run that completes with a collision exits 3, after writing every output; tools/scenario passes the
# code through after plotting it (run.png, the collision marked from summary.json's collision_events).
# Its 3 s are the whole run of the RMS error.
tvo_closed_loop_test(NAME scenario_file_collision_exit
  ARGS --scenario ${tvo_sf_dir}/collision.yaml EXPECT_EXIT 3
  EXPECT_STDERR "the run ended with [1-9][0-9]* collision\\(s\\) \\(exit code 3\\)"
  CHECKS "collisions>=1" "steps==300" EXPECT_FILES run.csv summary.json scenario.json)
tvo_test_lcm_url(tvo_sf_url)
set(tvo_sf_tool_out ${CMAKE_CURRENT_BINARY_DIR}/scenario_file_collision_exit_tool)
add_test(NAME scenario_file_collision_exit_tool
  COMMAND /bin/sh -c "TVO_DEMO_NO_BUILD=1 TVO_BUILD_DIR='${PROJECT_BINARY_DIR}' '${PROJECT_SOURCE_DIR}/tools/scenario' \
'${tvo_sf_dir}/collision.yaml' --lcm-url '${tvo_sf_url}' --out-dir '${tvo_sf_tool_out}' >'${tvo_sf_tool_out}.log' 2>&1; \
rc=$?; cat '${tvo_sf_tool_out}.log'; echo \"exit code $rc\"; test $rc -eq 3 && \
grep -q 'RMS tracking error, whole run' '${tvo_sf_tool_out}.log' && test -s '${tvo_sf_tool_out}/run.png' && \
grep -q 'collision_events' '${tvo_sf_tool_out}/summary.json' && \
/usr/bin/python3 '${PROJECT_SOURCE_DIR}/tools/plot_run.py' '${tvo_sf_tool_out}/run.csv' -o '${tvo_sf_tool_out}/again.png' \
| grep '(1 collision marked)'")
set_tests_properties(scenario_file_collision_exit_tool PROPERTIES LABELS closed_loop TIMEOUT 120)

# host/README.md's complete example is a scenario file that loads as written.
add_test(NAME scenario_file_readme_example
  COMMAND ${CMAKE_COMMAND} -DSIM=$<TARGET_FILE:tvo_sim> -DREADME=${PROJECT_SOURCE_DIR}/host/README.md
    -DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/scenario_file_readme_example -P ${tvo_sf_dir}/readme_example.cmake)
set_tests_properties(scenario_file_readme_example PROPERTIES LABELS "closed_loop;host" TIMEOUT 60)
