# What `cmake --install build --prefix P` installs, so that nothing needs the checkout afterwards:
#   P/bin/gpilot-*                       every binary (gpilot_add_executable)
#   P/share/gesture-pilot/               the data the binaries load (pose models included), in the checkout's layout, so that the
#                                        relative paths of config files resolve the same (common/paths.cpp
#                                        finds it from the executable: <exe dir>/../share/gesture-pilot)
#   P/lib/systemd/system/gpilot-*.service  the companion-computer units (deploy/systemd/generate, prefix P)
#   P/include/gpilot/*.hpp, P/lib/cmake/gesture_pilot/   the message types for other projects
#   P/lib/python3/dist-packages/gpilot/, gpilot_lcmlog.py  Python types and a log reader
#   P/share/java/gpilot_lcmtypes.jar     for lcm-spy
set(_share ${GPILOT_INSTALL_DATADIR})

# Data: the skin model (hands.skin.model), the synthetic world's skin tones, face and backdrops (scenarios),
# with their attribution. The rest of data/ (test and evaluation sets) stays in the checkout.
install(FILES data/README.md DESTINATION ${_share}/data)
install(FILES data/skin/skin_model.yaml data/skin/synthetic_skin_tones.csv data/skin/README.md
        DESTINATION ${_share}/data/skin)
install(FILES data/people/astronaut.png DESTINATION ${_share}/data/people)
install(DIRECTORY data/backgrounds DESTINATION ${_share}/data)
# The pose models (hands.pose), converted by deploy/models (git-ignored, made by deploy/setup), with the
# Apache-2.0 licence and the NOTICE of what was changed, which travel with them.
set(_pose_models models/pose/pose_detection.onnx models/pose/pose_landmark_lite.onnx
                 models/pose/pose_landmark_full.onnx)
install(CODE "
  foreach(_m ${_pose_models})
    if(NOT EXISTS \"${CMAKE_SOURCE_DIR}/\${_m}\")
      message(FATAL_ERROR \"\${_m} missing: run deploy/setup (deploy/models converts the pose models)\")
    endif()
  endforeach()
")
install(FILES ${_pose_models} models/pose/LICENSE models/pose/NOTICE DESTINATION ${_share}/models/pose)
# Configs, scenarios and the process list (gpilot-launch's default --services).
install(DIRECTORY deploy/config deploy/scenarios DESTINATION ${_share}/deploy FILES_MATCHING PATTERN "*.yaml")
install(FILES deploy/services.yaml DESTINATION ${_share}/deploy)

# systemd units for the installed binaries: written at install time with the prefix then in effect
# (`--prefix` or CPack's /usr), by the same generator as the committed deploy/systemd/*.service.
install(CODE "
  set(_units \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/lib/systemd/system\")
  message(STATUS \"Installing: \${_units}/gpilot-*.service\")
  execute_process(COMMAND \${CMAKE_COMMAND} -E env PREFIX=\${CMAKE_INSTALL_PREFIX}
                          GPILOT_LAUNCH=$<TARGET_FILE:gpilot-launch>
                          ${CMAKE_SOURCE_DIR}/deploy/systemd/generate \${_units}
                  RESULT_VARIABLE _rc OUTPUT_QUIET)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR \"deploy/systemd/generate failed (\${_rc})\")
  endif()
")

# The exported CMake package: find_package(gesture_pilot) gives gesture_pilot::lcmtypes (the lcm-gen C++
# headers under include/gpilot/, linking LCM through pkg-config as this project does).
include(CMakePackageConfigHelpers)
set(_cmakedir ${CMAKE_INSTALL_LIBDIR}/cmake/gesture_pilot)
install(EXPORT gesture_pilot_targets NAMESPACE gesture_pilot:: FILE gesture_pilot_targets.cmake
        DESTINATION ${_cmakedir})
configure_package_config_file(cmake/gesture_pilotConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/gesture_pilotConfig.cmake INSTALL_DESTINATION ${_cmakedir})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/gesture_pilotConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/gesture_pilotConfig.cmake
              ${CMAKE_BINARY_DIR}/package/gesture_pilotConfigVersion.cmake DESTINATION ${_cmakedir})

# The .deb: `cpack -G DEB` in build/ makes gesture-pilot_<version>_<arch>.deb, installed under /usr.
# Depends: the shared libraries the binaries link (dpkg-shlibdeps, so they cannot drift from the build) and
# deploy/runtime-packages (data and programs used at run time; deploy/setup installs the same list).
set(GPILOT_DEB_PREFIX /usr)
set(GPILOT_DEB_BINDIR ${GPILOT_DEB_PREFIX}/${CMAKE_INSTALL_BINDIR})
set(GPILOT_DEB_DATADIR ${GPILOT_DEB_PREFIX}/${GPILOT_INSTALL_DATADIR})
configure_file(cmake/deb/postinst.in ${CMAKE_BINARY_DIR}/deb/postinst @ONLY
               FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
file(STRINGS deploy/runtime-packages _runtime REGEX "^[a-z0-9]")
set(_depends)
foreach(_line IN LISTS _runtime)
  string(REGEX MATCH "^[^ \t#]+" _pkg "${_line}")
  list(APPEND _depends ${_pkg})
endforeach()
list(JOIN _depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/deploy/runtime-packages)

# cpack and `make install` pack what is built and build nothing themselves (build first: cmake --build): a
# package made while others build in the same tree must not start a second compile beside theirs.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME gesture-pilot)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "gesture-pilot maintainers <gesture-pilot@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "fly a drone by arm gestures (LCM stages, systemd units, message types)")
set(CPACK_PACKAGING_INSTALL_PREFIX ${GPILOT_DEB_PREFIX})
set(CPACK_STRIP_FILES ON)  # the build keeps -g1; the drone needs no debug info
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # gesture-pilot_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3")  # reading logs with the installed Python types
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "liblcm-java, default-jre, libjchart2d-java")  # lcm-spy with the types' jar
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_BINARY_DIR}/deb/postinst ${CMAKE_SOURCE_DIR}/cmake/deb/prerm
    ${CMAKE_SOURCE_DIR}/cmake/deb/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
