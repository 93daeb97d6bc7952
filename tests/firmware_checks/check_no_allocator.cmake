# Fails if any of the given object files, archives or ELFs defines or references a heap allocator.
#
#   cmake -DNM=<nm> -DFILES="<file>;<file>" [-DEXPECT_ALLOCATOR=ON] -P check_no_allocator.cmake
#
# EXPECT_ALLOCATOR=ON inverts the verdict: the run passes only if an allocator symbol IS found
# (negative self-test on a program that calls malloc, proving the check can fail).
# Also usable with include(): defines tvo_find_allocator_symbols(<out-var> <nm> <file>).

if(CMAKE_SCRIPT_MODE_FILE)
  cmake_minimum_required(VERSION 3.16)   # policies (IN_LIST) when run with -P
endif()

set(TVO_ALLOCATOR_SYMBOLS
  malloc calloc realloc free
  _malloc_r _free_r _calloc_r _realloc_r
  aligned_alloc posix_memalign memalign valloc pvalloc reallocarray
  _sbrk _sbrk_r sbrk)

# Sets <out-var> to "<symbol> (<nm type>)" entries for every allocator symbol in <file>.
function(tvo_find_allocator_symbols out_var nm file)
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "allocator check: '${file}' does not exist (was it built?)")
  endif()
  # POSIX format: one "name type [value size]" line per symbol; archive members get a header line.
  execute_process(COMMAND "${nm}" --format=posix "${file}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "allocator check: '${nm} ${file}' failed (${rc}): ${err}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  set(found "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^([^ \t]+) ([A-Za-z])( |$)")
      set(name "${CMAKE_MATCH_1}")
      set(type "${CMAKE_MATCH_2}")
      string(REGEX REPLACE "@.*$" "" name "${name}")   # strip symbol versions (malloc@GLIBC_2.2.5)
      if(name IN_LIST TVO_ALLOCATOR_SYMBOLS)
        list(APPEND found "${name} (${type})")
      endif()
    endif()
  endforeach()
  list(REMOVE_DUPLICATES found)
  set(${out_var} "${found}" PARENT_SCOPE)
endfunction()

# Script mode: check FILES, report, and fail (or, with EXPECT_ALLOCATOR, fail if nothing found).
if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT NM OR NOT FILES)
    message(FATAL_ERROR "usage: cmake -DNM=<nm> -DFILES=<files> [-DEXPECT_ALLOCATOR=ON] -P ${CMAKE_CURRENT_LIST_FILE}")
  endif()
  set(any_found FALSE)
  foreach(file IN LISTS FILES)
    tvo_find_allocator_symbols(found "${NM}" "${file}")
    if(found)
      set(any_found TRUE)
      string(REPLACE ";" ", " found_text "${found}")
      message(STATUS "allocator symbols in ${file}: ${found_text}")
    else()
      message(STATUS "no allocator symbols in ${file}")
    endif()
  endforeach()
  if(EXPECT_ALLOCATOR)
    if(NOT any_found)
      message(FATAL_ERROR "self-test FAILED: the check found no allocator in a program that calls malloc")
    endif()
    message(STATUS "self-test passed: the check detects allocator use")
  elseif(any_found)
    message(FATAL_ERROR "allocator use found (the control core must not allocate): see above")
  endif()
endif()
