# Toolchain: bare-metal Cortex-M7 with the double-precision FPU (fpv5-d16, hard-float ABI),
# newlib-nano. The core is built in double (TVO_DOUBLE), which this FPU executes in hardware.
#   cmake -S firmware -B build/cross/cortex-m7 -DCMAKE_TOOLCHAIN_FILE=tools/cmake/arm-none-eabi-cortex-m7.cmake
set(TVO_CROSS_PREFIX arm-none-eabi-)
set(TVO_SYSTEM_PROCESSOR arm)
set(TVO_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-d16")
set(TVO_LIBC_FLAGS "--specs=nano.specs")
set(TVO_PACKAGES "gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi")
set(TVO_DOUBLE ON CACHE BOOL "Build the control core in double precision (default float32)")
include(${CMAKE_CURRENT_LIST_DIR}/bare-metal.cmake)
