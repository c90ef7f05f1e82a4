# What `cmake --install` puts where (GNUInstallDirs), in two components:
#   runtime      bin/camgen, share/camgen/machines/*.json, share/camgen/schema/*.json,
#                share/man/man1/camgen.1, the bash and zsh completions
#   development  the static library, include/camgen/ and the CMake package (find_package(camgen))
# and the Debian packages made from them by `cpack -G DEB` (camgen and camgen-dev).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The installed camgen finds its machine files relative to itself (src/post/machine.cpp).
file(RELATIVE_PATH CAMGEN_MACHINES_FROM_BIN ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_DATADIR}/camgen/machines)
target_compile_definitions(camgen_core PRIVATE CAMGEN_MACHINES_FROM_BIN="${CAMGEN_MACHINES_FROM_BIN}")

# The man page, written by the built camgen from its own option table (camgen --man), each
# time camgen is linked: `cmake --build build --target camgen` makes everything the install
# needs, and the install does not build the tests first (CMAKE_SKIP_INSTALL_ALL_DEPENDENCY).
add_custom_command(TARGET camgen POST_BUILD
  COMMAND ${CMAKE_COMMAND} -DCAMGEN=$<TARGET_FILE:camgen> -DOUT=${CMAKE_BINARY_DIR}/camgen.1
          -P ${CMAKE_SOURCE_DIR}/cmake/write_man.cmake
  COMMENT "Writing the man page camgen.1" VERBATIM)
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

set(CAMGEN_BASH_COMPLETION_DIR ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
    CACHE STRING "Where the bash completion goes (bash-completion's completionsdir)")
# Debian's zsh reads packages' completions from vendor-completions (in its default fpath).
set(CAMGEN_ZSH_COMPLETION_DIR ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions
    CACHE STRING "Where the zsh completion goes (a folder of zsh's fpath)")

install(TARGETS camgen RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(FILES ${CAMGEN_MACHINE_FILES} DESTINATION ${CMAKE_INSTALL_DATADIR}/camgen/machines COMPONENT runtime)
# The committed schemas equal `camgen schema job|machine|tools` (a unit test keeps them so).
install(FILES schema/job.schema.json schema/machine.schema.json schema/tools.schema.json
        DESTINATION ${CMAKE_INSTALL_DATADIR}/camgen/schema COMPONENT runtime)
install(FILES ${CMAKE_BINARY_DIR}/camgen.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
install(FILES completions/camgen.bash DESTINATION ${CAMGEN_BASH_COMPLETION_DIR} RENAME camgen COMPONENT runtime)
install(FILES completions/_camgen DESTINATION ${CAMGEN_ZSH_COMPLETION_DIR} COMPONENT runtime)

# The library: camgen::camgen. Only include/camgen/ is its API; src/ and machines/ headers stay
# inside (tests/install/check_install.sh proves that every installed header's includes resolve).
set_target_properties(camgen_core PROPERTIES OUTPUT_NAME camgen EXPORT_NAME camgen)
install(TARGETS camgen_core EXPORT camgenTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/camgen DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT development
        FILES_MATCHING PATTERN "*.hpp")
set(CAMGEN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/camgen)
install(EXPORT camgenTargets NAMESPACE camgen:: DESTINATION ${CAMGEN_CMAKE_DIR} COMPONENT development)
configure_package_config_file(cmake/camgenConfig.cmake.in ${CMAKE_BINARY_DIR}/camgenConfig.cmake
                              INSTALL_DESTINATION ${CAMGEN_CMAKE_DIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/camgenConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/camgenConfig.cmake ${CMAKE_BINARY_DIR}/camgenConfigVersion.cmake
        DESTINATION ${CAMGEN_CMAKE_DIR} COMPONENT development)

# Debian packages: cpack -G DEB --config build/CPackConfig.cmake (scripts/test-install).
set(CPACK_PACKAGE_NAME camgen)
set(CPACK_PACKAGE_VENDOR "camgen")
set(CPACK_PACKAGE_CONTACT "camgen developers <camgen@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME camgen)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION misc)
# libfmt, libcairo2, libstdc++ and libc as dpkg-shlibdeps finds them in the executable.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
# The engrave operation's single-stroke fonts, read at run time from /usr/share/hershey-fonts.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "hershey-fonts-data")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "bash-completion")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME camgen-dev)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS "libfmt-dev, nlohmann-json3-dev (>= 3.10), libeigen3-dev (>= 3.3), libboost-dev (>= 1.74), libcairo2-dev, pkgconf")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SUGGESTS "camgen")
# A Debian description: its summary line, then the long description.
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "CAM for CNC mills and lathes: JSON job in, NC program out
camgen turns a JSON job (drilling, contours, bores, tool paths, turning) into the NC program of a control: Fanuc, LinuxCNC, GRBL, Sinumerik, Heidenhain, nccad. This package holds the command, its machine files, the JSON Schemas of job and machine files, the man page and the bash and zsh completions.")
set(CPACK_DEBIAN_DEVELOPMENT_DESCRIPTION "camgen CAM as a C++ library
The static library, the headers of its API (include/camgen) and the CMake package of camgen: find_package(camgen) and the target camgen::camgen.")
include(CPack)
cpack_add_component(runtime DISPLAY_NAME "camgen")
cpack_add_component(development DISPLAY_NAME "camgen-dev")
