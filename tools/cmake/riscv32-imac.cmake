# Toolchain: bare-metal 32-bit RISC-V RV32IMAC (no FPU, soft-float ilp32 ABI) with Debian's
# gcc-riscv64-unknown-elf (rv32 multilibs) and picolibc-riscv64-unknown-elf (math.h, libm).
# Freestanding library build (no startup code or linker script):
#   cmake -S firmware -B build/cross/riscv32 -DCMAKE_TOOLCHAIN_FILE=tools/cmake/riscv32-imac.cmake
set(TVO_CROSS_PREFIX riscv64-unknown-elf-)
set(TVO_SYSTEM_PROCESSOR riscv32)
set(TVO_CPU_FLAGS "-march=rv32imac -mabi=ilp32")
# picolibc.specs puts picolibc's headers (math.h, ...) on the include path; gcc has none of its own.
set(TVO_LIBC_FLAGS "--specs=picolibc.specs")
set(TVO_PACKAGES "gcc-riscv64-unknown-elf picolibc-riscv64-unknown-elf")
include(${CMAKE_CURRENT_LIST_DIR}/bare-metal.cmake)
