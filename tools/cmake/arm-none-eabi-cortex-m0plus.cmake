# Toolchain: bare-metal Cortex-M0+ (ARMv6-M, no FPU: float32 in software), newlib-nano.
#   cmake -S firmware -B build/cross/cortex-m0plus -DCMAKE_TOOLCHAIN_FILE=tools/cmake/arm-none-eabi-cortex-m0plus.cmake
set(TVO_CROSS_PREFIX arm-none-eabi-)
set(TVO_SYSTEM_PROCESSOR arm)
set(TVO_CPU_FLAGS "-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft")
set(TVO_LIBC_FLAGS "--specs=nano.specs")
set(TVO_PACKAGES "gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi")
include(${CMAKE_CURRENT_LIST_DIR}/bare-metal.cmake)
