# Fails unless every file in FILES exists. Used after code generators that can exit 0 without
# writing anything (lcm-gen does when an output folder is missing).
#   cmake -DWHAT=<label> -DFILES="<f1>;<f2>" -P require_files.cmake
set(missing "")
foreach(f IN LISTS FILES)
  if(NOT EXISTS "${f}")
    list(APPEND missing "${f}")
  endif()
endforeach()
if(missing)
  string(REPLACE ";" "\n  " missing "${missing}")
  message(FATAL_ERROR "${WHAT}: expected outputs were not written:\n  ${missing}")
endif()
