# Install rules of the control core (included by firmware/CMakeLists.txt after tvo_core is defined):
#   cmake --install <build> --prefix <P>
# puts tvo/*.h (the generated tvo/version.h too) in <P>/include, libtvo_core.a in <P>/lib, the package
# config in <P>/lib/cmake/tvo and the pkg-config file in <P>/lib/pkgconfig/tvo.pc, so a consumer writes
# find_package(tvo 1.0 REQUIRED) and target_link_libraries(app PRIVATE tvo::core), or compiles with
# `pkg-config --cflags --libs tvo`.
include(CMakePackageConfigHelpers)

# The scalar type and the size limits set the struct layouts, so tvo::core carries them as compile
# definitions (PUBLIC on tvo_core). A TVO_* definition that reaches the core another way (compiler
# flags, a parent directory) would change the library's layouts without reaching a consumer: refused.
set(tvo_abi_flags "${CMAKE_C_FLAGS}")
if(CMAKE_BUILD_TYPE)
  string(TOUPPER "${CMAKE_BUILD_TYPE}" tvo_build_type)
  string(APPEND tvo_abi_flags " ${CMAKE_C_FLAGS_${tvo_build_type}}")
endif()
get_directory_property(tvo_abi_definitions COMPILE_DEFINITIONS)
get_directory_property(tvo_abi_options COMPILE_OPTIONS)
list(FILTER tvo_abi_definitions INCLUDE REGEX "^TVO_")
if(tvo_abi_definitions OR "${tvo_abi_flags};${tvo_abi_options}" MATCHES "-D[ ]*TVO_")
  message(FATAL_ERROR "a TVO_* definition is set through compiler flags or directory definitions, where "
                      "the installed tvo::core cannot pass it on to its users: use -DTVO_DOUBLE=ON for the "
                      "scalar type and -DTVO_LIMITS=NAME=VALUE,... for the size limits")
endif()

set(tvo_config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/tvo)
install(TARGETS tvo_core EXPORT tvoTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/tvo DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(FILES ${tvo_generated_include_dir}/tvo/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tvo)
install(EXPORT tvoTargets NAMESPACE tvo:: DESTINATION ${tvo_config_dir})

# What tvoConfig.cmake reports and checks (the definitions themselves travel with tvo::core).
if(TVO_DOUBLE)
  set(tvo_package_double ON)
else()
  set(tvo_package_double OFF)
endif()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/tvoConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/tvoConfig.cmake INSTALL_DESTINATION ${tvo_config_dir})
# Same major version; the pointer-size check of this file also tells a 32-bit microcontroller build
# from a 64-bit host one.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/tvoConfigVersion.cmake
  VERSION ${tvo_version} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/tvoConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/tvoConfigVersion.cmake
        DESTINATION ${tvo_config_dir})

# pkg-config (tvo.pc beside the CMake package, in <libdir>/pkgconfig): the same include folder, scalar
# type and size limits as tvo::core (its interface definitions, not a second list) and its libraries.
# Relocatable: the prefix is found from the file's own folder, so `cmake --install --prefix P` works.
get_target_property(tvo_pc_definitions_list tvo_core INTERFACE_COMPILE_DEFINITIONS)
get_target_property(tvo_pc_link_list tvo_core INTERFACE_LINK_LIBRARIES)
set(tvo_pc_cflags "")
foreach(definition IN LISTS tvo_pc_definitions_list)
  if(definition MATCHES "[$<>]")
    message(FATAL_ERROR "tvo.pc: tvo_core's definition '${definition}' is a generator expression")
  endif()
  string(APPEND tvo_pc_cflags " -D${definition}")
endforeach()
set(tvo_pc_libs "")
foreach(library IN LISTS tvo_pc_link_list)
  # Plain system libraries (m on the host); the build-only warning target is a generator expression.
  if(library MATCHES "^[A-Za-z0-9_]+$" AND NOT TARGET ${library})
    string(APPEND tvo_pc_libs " -l${library}")
  endif()
endforeach()
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    message(FATAL_ERROR "tvo.pc is relocatable: CMAKE_INSTALL_${dir} must be relative to the prefix")
  endif()
endforeach()
file(RELATIVE_PATH tvo_pc_up "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
string(REGEX REPLACE "/$" "" tvo_pc_up "${tvo_pc_up}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/tvo.pc.in ${CMAKE_CURRENT_BINARY_DIR}/tvo.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/tvo.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
