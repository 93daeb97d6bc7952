# Shared part of the bare-metal toolchain files (included by them, never used alone).
# The including file sets:
#   TVO_CROSS_PREFIX    e.g. arm-none-eabi-
#   TVO_SYSTEM_PROCESSOR
#   TVO_CPU_FLAGS       architecture, ABI and FPU flags
#   TVO_LIBC_FLAGS      C library selection passed to compile and link (e.g. --specs=nano.specs)
#   TVO_PACKAGES        the Debian packages that provide the toolchain, for the error message
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR ${TVO_SYSTEM_PROCESSOR})

find_program(CMAKE_C_COMPILER ${TVO_CROSS_PREFIX}gcc)
if(NOT CMAKE_C_COMPILER)
  message(FATAL_ERROR "${TVO_CROSS_PREFIX}gcc not found: install ${TVO_PACKAGES} (tools/setup does)")
endif()
find_program(CMAKE_CXX_COMPILER ${TVO_CROSS_PREFIX}g++)
foreach(tool ar ranlib nm objcopy objdump size)
  string(TOUPPER ${tool} tool_var)
  find_program(CMAKE_${tool_var} ${TVO_CROSS_PREFIX}${tool})
endforeach()

# Compiler checks build a static library: linking needs a board's startup code and linker script.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# The C library flags sit in the compile flags too (a specs file selects the library's headers);
# CMake passes compile flags to the linker driver, so they reach every link without repeating.
set(CMAKE_C_FLAGS_INIT "${TVO_CPU_FLAGS} ${TVO_LIBC_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${CMAKE_C_FLAGS_INIT}")
set(CMAKE_ASM_FLAGS_INIT "${TVO_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

# Search headers/libraries only in the target environment, programs only on the host.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
