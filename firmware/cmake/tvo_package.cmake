# Install rules of the control core (included by firmware/CMakeLists.txt after tvo_core is defined):
#   cmake --install <build> --prefix <P>
# puts tvo/*.h in <P>/include, libtvo_core.a in <P>/lib and the package config in <P>/lib/cmake/tvo,
# so a consumer writes find_package(tvo REQUIRED) and target_link_libraries(app PRIVATE tvo::core).
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
  VERSION ${tvo_core_version} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/tvoConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/tvoConfigVersion.cmake
        DESTINATION ${tvo_config_dir})
