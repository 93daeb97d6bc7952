# The control core as a package, from a user's side (driven by tests/package/CMakeLists.txt):
#
#   MODE=install       install the core into WORK/prefix (from BUILD_DIR with `cmake --install`, or a
#                      standalone host build of FIRMWARE_DIR with TVO_DOUBLE and LIMITS), then build
#                      the consumer project (consumer/) with find_package(tvo 1.0) and run it, and
#                      build the same main loop and version_check.c with C_COMPILER and
#                      `PKG_CONFIG --cflags --libs tvo` (the installed tvo.pc) and run them
#   MODE=subdirectory  the same consumer with add_subdirectory(FIRMWARE_DIR)
#   Every consumer's version_check must find TVO_VERSION_STRING (tvo/version.h) equal to the version
#   of FIRMWARE_DIR/cmake/tvo_version.cmake, as the package's tvo_VERSION and tvo.pc's Version.
#   MODE=cross         a standalone cross build of FIRMWARE_DIR with TOOLCHAIN_FILE installed into
#                      WORK/prefix; the main-loop example (EXAMPLE_DIR) built against it three times:
#                      with its weak stubs (no allocator symbol may be linked), with plant.c as the
#                      board (run in QEMU when QEMU is given: must exit 0), and with malloc_board.c
#                      (the same allocator check must fire: it can fail)
#
#   cmake -DMODE=... -DWORK=<dir> -DFIRMWARE_DIR=<firmware> -DEXAMPLE_DIR=<examples/main_loop>
#         [-DBUILD_DIR=<configured tree>] [-DTVO_DOUBLE=ON] [-DLIMITS=NAME=VALUE,...]
#         [-DTOOLCHAIN_FILE=<file>] [-DQEMU=<qemu-system-arm>] [-DGENERATOR=<gen>]
#         [-DC_COMPILER=<cc> -DPKG_CONFIG=<pkg-config>] -P package_check.cmake   (the last two: install)
cmake_minimum_required(VERSION 3.16)
include(${CMAKE_CURRENT_LIST_DIR}/../firmware_checks/check_no_allocator.cmake)
set(consumer_dir ${CMAKE_CURRENT_LIST_DIR}/consumer)
if(NOT GENERATOR)
  set(GENERATOR "Unix Makefiles")
endif()
if(TVO_DOUBLE)
  set(TVO_DOUBLE ON)
  set(expect_double 1)
else()
  set(TVO_DOUBLE OFF)
  set(expect_double 0)
endif()
# The consumer checks at compile time that it sees the scalar type and output limit the core has.
set(expect_args -DEXPECT_DOUBLE=${expect_double})
if(LIMITS MATCHES "TVO_MAX_OUTPUT_DIM=([0-9]+)")
  list(APPEND expect_args -DEXPECT_MAX_OUTPUT_DIM=${CMAKE_MATCH_1})
endif()
include(${FIRMWARE_DIR}/cmake/tvo_version.cmake)   # tvo_version: what every consumer must see
set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})   # every run starts from nothing: a stale prefix would hide a broken install

include("${CMAKE_CURRENT_LIST_DIR}/../cmake/run_command.cmake")

# Configures, builds and installs the standalone core from FIRMWARE_DIR into the prefix.
function(install_standalone_core)
  set(build_args -DCMAKE_BUILD_TYPE=Release)
  if(TOOLCHAIN_FILE)
    set(build_args -DCMAKE_BUILD_TYPE=MinSizeRel -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN_FILE})   # as the presets
  endif()
  tvo_run("configure the core" ${CMAKE_COMMAND} -S ${FIRMWARE_DIR} -B ${WORK}/core -G ${GENERATOR}
      ${build_args} -DTVO_DOUBLE=${TVO_DOUBLE} "-DTVO_LIMITS=${LIMITS}")
  tvo_run("build the core" ${CMAKE_COMMAND} --build ${WORK}/core --target tvo_core --parallel 2)
  tvo_run("install the core" ${CMAKE_COMMAND} --install ${WORK}/core --prefix ${prefix})
endfunction()

function(build_and_run_consumer)
  tvo_run("configure the consumer" ${CMAKE_COMMAND} -S ${consumer_dir} -B ${WORK}/consumer -G ${GENERATOR}
      -DCMAKE_BUILD_TYPE=Release -DEXAMPLE_DIR=${EXAMPLE_DIR} ${expect_args} -DEXPECT_VERSION=${tvo_version} ${ARGN})
  tvo_run("build the consumer" ${CMAKE_COMMAND} --build ${WORK}/consumer --target app version_check --parallel 2)
  tvo_run("run the consumer" ${WORK}/consumer/app)
  tvo_run("run the consumer's version check" ${WORK}/consumer/version_check)
endfunction()

# The installed tvo.pc: a plain compiler command with `pkg-config --cflags --libs tvo` builds the main
# loop (its layout checks need the Cflags' definitions) and version_check.c, and both run.
function(build_and_run_pkg_config_consumer)
  foreach(var C_COMPILER PKG_CONFIG)
    if(NOT ${var})
      message(FATAL_ERROR "package_check.cmake: MODE=install needs -D${var}=...")
    endif()
  endforeach()
  set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
  execute_process(COMMAND ${PKG_CONFIG} --modversion tvo RESULT_VARIABLE rc OUTPUT_VARIABLE pc_version
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0 OR NOT pc_version STREQUAL tvo_version)
    message(FATAL_ERROR "pkg-config --modversion tvo: '${pc_version}' (exit ${rc}), the sources say ${tvo_version}")
  endif()
  execute_process(COMMAND ${PKG_CONFIG} --cflags --libs tvo RESULT_VARIABLE rc OUTPUT_VARIABLE pc_flags
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config --cflags --libs tvo FAILED (exit ${rc})")
  endif()
  message(STATUS "pkg-config --cflags --libs tvo: ${pc_flags}")
  separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
  set(out ${WORK}/pkg_config)
  file(MAKE_DIRECTORY ${out})
  set(warnings -std=c11 -Wall -Wextra -Wpedantic -Wconversion -Wmissing-prototypes -Werror)
  tvo_run("build the main loop through pkg-config" ${C_COMPILER} ${warnings} ${expect_args} -I${EXAMPLE_DIR}
      ${EXAMPLE_DIR}/main_loop.c ${CMAKE_CURRENT_LIST_DIR}/plant.c ${pc_flags} -o ${out}/app)
  tvo_run("run the main loop built through pkg-config" ${out}/app)
  tvo_run("build the version check through pkg-config" ${C_COMPILER} ${warnings} "-DEXPECT_VERSION=\"${tvo_version}\""
      ${CMAKE_CURRENT_LIST_DIR}/version_check.c ${pc_flags} -o ${out}/version_check)
  tvo_run("run the version check built through pkg-config" ${out}/version_check)
endfunction()

if(MODE STREQUAL "install")
  if(BUILD_DIR)
    tvo_run("install the core" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
  else()
    install_standalone_core()
  endif()
  foreach(file include/tvo/controller.h include/tvo/config.h include/tvo/version.h lib/libtvo_core.a
               lib/cmake/tvo/tvoConfig.cmake lib/cmake/tvo/tvoConfigVersion.cmake lib/cmake/tvo/tvoTargets.cmake
               lib/pkgconfig/tvo.pc)
    if(NOT EXISTS ${prefix}/${file})
      message(FATAL_ERROR "the install lacks ${prefix}/${file}")
    endif()
  endforeach()
  build_and_run_consumer(-DCMAKE_PREFIX_PATH=${prefix})
  build_and_run_pkg_config_consumer()
elseif(MODE STREQUAL "subdirectory")
  build_and_run_consumer(-DTVO_FIRMWARE_DIR=${FIRMWARE_DIR} -DTVO_DOUBLE=${TVO_DOUBLE} "-DTVO_LIMITS=${LIMITS}")
elseif(MODE STREQUAL "cross")
  install_standalone_core()
  foreach(file include/tvo/version.h lib/pkgconfig/tvo.pc)
    if(NOT EXISTS ${prefix}/${file})
      message(FATAL_ERROR "the cross install lacks ${prefix}/${file}")
    endif()
  endforeach()
  load_cache(${WORK}/core READ_WITH_PREFIX core_ CMAKE_NM)
  set(board_dir ${FIRMWARE_DIR}/board/mps2_an386)
  set(variants stubs "" plant ${CMAKE_CURRENT_LIST_DIR}/plant.c malloc ${CMAKE_CURRENT_LIST_DIR}/malloc_board.c)
  while(variants)
    list(POP_FRONT variants name extra_source)
    set(bin ${WORK}/main_loop_${name})
    # A list in an initial cache file: tvo_run()'s arguments would split it.
    file(WRITE ${WORK}/main_loop_${name}.cmake "set(BOARD_SOURCES \"${board_dir}/startup.c;${board_dir}/board.c;${board_dir}/../common/semihosting_console.c;${extra_source}\" CACHE STRING \"\")\n")
    tvo_run("configure the main loop (${name})" ${CMAKE_COMMAND} -C ${WORK}/main_loop_${name}.cmake
        -S ${EXAMPLE_DIR} -B ${bin} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=MinSizeRel
        -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN_FILE} -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_COMPILE_WARNING_AS_ERROR=ON)
    tvo_run("build the main loop (${name})" ${CMAKE_COMMAND} --build ${bin} --parallel 2)
    tvo_find_allocator_symbols(found ${core_CMAKE_NM} ${bin}/main_loop.elf)
    string(REPLACE ";" ", " found_text "${found}")
    if(name STREQUAL "malloc")
      if(NOT found)
        message(FATAL_ERROR "self-test FAILED: no allocator found in ${bin}/main_loop.elf, whose board calls malloc")
      endif()
      message(STATUS "self-test passed: the image whose board calls malloc is caught: ${found_text}")
    elseif(found)
      message(FATAL_ERROR "allocator symbols in ${bin}/main_loop.elf: ${found_text}")
    else()
      message(STATUS "no allocator symbols in ${bin}/main_loop.elf")
    endif()
  endwhile()
  if(QEMU)
    tvo_run("run the main loop with the simulated robot" ${QEMU} -M mps2-an386 -cpu cortex-m4 -nographic
        -monitor none -semihosting-config enable=on,target=native -kernel ${WORK}/main_loop_plant/main_loop.elf)
  endif()
else()
  message(FATAL_ERROR "package_check.cmake: MODE must be install, subdirectory or cross (got '${MODE}')")
endif()
message(STATUS "package check (${MODE}) passed")
