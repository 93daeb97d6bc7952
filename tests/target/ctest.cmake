# CTest registration of the on-target Unity tests (included by the top-level CMakeLists.txt):
# target_build builds every tests/unit/test_*.c for Cortex-M4F on the mps2-an386 board (a CTest
# fixture), then target_<name> runs each ELF in qemu-system-arm; semihosting passes Unity's
# failure count out as QEMU's exit code.
find_program(TVO_QEMU_ARM qemu-system-arm)
if(NOT TVO_QEMU_ARM)
  message(FATAL_ERROR "qemu-system-arm not found: install the Debian package qemu-system-arm (or run tools/setup)")
endif()
set(tvo_target_bin ${CMAKE_BINARY_DIR}/target)
add_test(NAME target_build
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_CURRENT_LIST_DIR} -DBINARY_DIR=${tvo_target_bin}
          -DTOOLCHAIN_FILE=${PROJECT_SOURCE_DIR}/tools/cmake/arm-none-eabi-cortex-m4f.cmake
          -DUNITY_DIR=${TVO_UNITY_DIR} "-DGENERATOR=${CMAKE_GENERATOR}"
          -P ${CMAKE_CURRENT_LIST_DIR}/build_target.cmake)
set_tests_properties(target_build PROPERTIES FIXTURES_SETUP tvo_target_elfs LABELS target TIMEOUT 600)

file(GLOB tvo_target_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/unit/test_*.c)
list(SORT tvo_target_sources)
foreach(source IN LISTS tvo_target_sources)
  get_filename_component(name ${source} NAME_WE)
  add_test(NAME target_${name}
    COMMAND ${TVO_QEMU_ARM} -M mps2-an386 -cpu cortex-m4 -nographic -monitor none
            -semihosting-config enable=on,target=native -kernel ${tvo_target_bin}/${name}.elf)
  set_tests_properties(target_${name} PROPERTIES FIXTURES_REQUIRED tvo_target_elfs LABELS target
    TIMEOUT 300 FAIL_REGULAR_EXPRESSION "FAIL")
endforeach()

# Processor in the loop: the PIL program (built by target_build with the tests) in QEMU, the bridge,
# and the plant simulator over LCM (tests/target/pil_check.py says what each variant proves): a clean
# lockstep run compared with the host build, a lockstep run with frames corrupted on the link, and a
# realtime run on the board's own clock through a link outage.
if(TARGET tvo_sim AND TARGET tvo_pil_bridge AND TARGET tvo_firmware_node)
  set(tvo_pil_elf ${tvo_target_bin}/firmware/apps/pil/tvo_pil.elf)
  foreach(variant IN ITEMS clean corrupted node-clock)
    string(REPLACE "-" "_" name ${variant})
    tvo_test_lcm_port(port COUNT 2) # pil_check.py: the PIL run on port, its host reference on port + 1
    add_test(NAME target_pil_${name}
      COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/pil_check.py --variant ${variant}
              --tools ${PROJECT_SOURCE_DIR}/tools --elf ${tvo_pil_elf} --bridge $<TARGET_FILE:tvo_pil_bridge>
              --sim $<TARGET_FILE:tvo_sim> --firmware $<TARGET_FILE:tvo_firmware_node>
              --out ${CMAKE_BINARY_DIR}/pil_${name} --port ${port})
    # One PIL run at a time: each picks a free TCP port for QEMU's serial socket, and two starting
    # together can be handed the same one (then the bridges cross); QEMU also needs the CPU.
    set_tests_properties(target_pil_${name} PROPERTIES FIXTURES_REQUIRED tvo_target_elfs LABELS "target;pil"
      TIMEOUT 300 RESOURCE_LOCK tvo_qemu_pil)
  endforeach()
endif()

# The firmware images that run on the board link no allocator (the PIL program includes LCM's
# generated encode/decode and the framing; the benchmark, the whole core).
find_program(TVO_ARM_NM arm-none-eabi-nm)
if(TVO_ARM_NM)
  add_test(NAME target_images_no_allocator
    COMMAND ${CMAKE_COMMAND} -DNM=${TVO_ARM_NM}
            "-DFILES=${tvo_target_bin}/firmware/apps/pil/tvo_pil.elf;${tvo_target_bin}/firmware/apps/bench/tvo_bench.elf"
            -P ${PROJECT_SOURCE_DIR}/tests/firmware_checks/check_no_allocator.cmake)
  set_tests_properties(target_images_no_allocator PROPERTIES FIXTURES_REQUIRED tvo_target_elfs LABELS "target;firmware"
    TIMEOUT 60)
endif()
