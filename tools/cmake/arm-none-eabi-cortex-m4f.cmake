# CMake toolchain file: bare-metal ARM Cortex-M4F (single-precision FPU, hard-float ABI) with
# Debian's gcc-arm-none-eabi and newlib-nano (libnewlib-arm-none-eabi).
#   cmake -S firmware -B build/cross/cortex-m4f \
#         -DCMAKE_TOOLCHAIN_FILE=tools/cmake/arm-none-eabi-cortex-m4f.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(TVO_CROSS_PREFIX arm-none-eabi-)
find_program(CMAKE_C_COMPILER ${TVO_CROSS_PREFIX}gcc)
find_program(CMAKE_CXX_COMPILER ${TVO_CROSS_PREFIX}g++)
if(NOT CMAKE_C_COMPILER)
  message(FATAL_ERROR "arm-none-eabi-gcc not found: install gcc-arm-none-eabi libnewlib-arm-none-eabi "
                      "binutils-arm-none-eabi (tools/setup does)")
endif()
find_program(CMAKE_AR ${TVO_CROSS_PREFIX}ar)
find_program(CMAKE_RANLIB ${TVO_CROSS_PREFIX}ranlib)
find_program(CMAKE_NM ${TVO_CROSS_PREFIX}nm)
find_program(CMAKE_OBJCOPY ${TVO_CROSS_PREFIX}objcopy)
find_program(CMAKE_SIZE ${TVO_CROSS_PREFIX}size)

# No startup code or linker script here: compiler checks build a static library instead of linking.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(TVO_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
# newlib-nano: --specs=nano.specs in the compile flags (it selects nano's newlib.h) also reaches
# every link, since CMake passes the compile flags to the linker driver; do not repeat it there.
set(CMAKE_C_FLAGS_INIT "${TVO_CPU_FLAGS} --specs=nano.specs -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${CMAKE_C_FLAGS_INIT}")
set(CMAKE_ASM_FLAGS_INIT "${TVO_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

# Search headers/libraries only in the target environment, programs only on the host.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
