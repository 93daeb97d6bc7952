# CMake toolchain file: bare-metal 32-bit RISC-V (RV32IMAC, soft-float ilp32 ABI) with Debian's
# gcc-riscv64-unknown-elf (multilib) and picolibc-riscv64-unknown-elf (C library headers, libm).
# Library builds only (no startup code or linker script):
#   cmake -S firmware -B build/cross/riscv32 -DCMAKE_TOOLCHAIN_FILE=tools/cmake/riscv32-imac.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR riscv32)

set(TVO_CROSS_PREFIX riscv64-unknown-elf-)
find_program(CMAKE_C_COMPILER ${TVO_CROSS_PREFIX}gcc)
find_program(CMAKE_CXX_COMPILER ${TVO_CROSS_PREFIX}g++)
if(NOT CMAKE_C_COMPILER)
  message(FATAL_ERROR "riscv64-unknown-elf-gcc not found: install gcc-riscv64-unknown-elf "
                      "picolibc-riscv64-unknown-elf (tools/setup does)")
endif()
find_program(CMAKE_AR ${TVO_CROSS_PREFIX}ar)
find_program(CMAKE_RANLIB ${TVO_CROSS_PREFIX}ranlib)
find_program(CMAKE_NM ${TVO_CROSS_PREFIX}nm)
find_program(CMAKE_OBJCOPY ${TVO_CROSS_PREFIX}objcopy)
find_program(CMAKE_SIZE ${TVO_CROSS_PREFIX}size)

# Freestanding library build: compiler checks build a static library, nothing is linked.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(TVO_CPU_FLAGS "-march=rv32imac -mabi=ilp32")
# picolibc.specs puts picolibc's headers (math.h, ...) on the include path; gcc has none of its own.
set(CMAKE_C_FLAGS_INIT "${TVO_CPU_FLAGS} --specs=picolibc.specs -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${CMAKE_C_FLAGS_INIT}")
set(CMAKE_ASM_FLAGS_INIT "${TVO_CPU_FLAGS}")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
