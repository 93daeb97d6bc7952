# Toolchain: bare-metal Cortex-M4F (single-precision FPU fpv4-sp-d16, hard-float ABI), newlib-nano.
#   cmake -S firmware -B build/cross/cortex-m4f -DCMAKE_TOOLCHAIN_FILE=tools/cmake/arm-none-eabi-cortex-m4f.cmake
# (or: cmake --preset cortex-m4f, from firmware/)
set(TVO_CROSS_PREFIX arm-none-eabi-)
set(TVO_SYSTEM_PROCESSOR arm)
set(TVO_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
set(TVO_LIBC_FLAGS "--specs=nano.specs")
set(TVO_PACKAGES "gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi")
include(${CMAKE_CURRENT_LIST_DIR}/bare-metal.cmake)
