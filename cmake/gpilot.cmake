# gpilot_add_test(NAME name SOURCES ... [LIBS ...] [LABELS ...] [NETNS] [TIMEOUT s] [CASES filter ...])
#   A GoogleTest executable registered with ctest. Unit tests are discovered case by case. NETNS tests
#   (real LCM traffic) run whole inside a private network namespace via tests/netns-run, which exits 77
#   (skipped, with a message) where no namespace can be made; with CASES, one ctest entry per gtest filter
#   (name:last part of the filter), each in its own namespace; a filter that selects no test fails.
#   Every test sees tests/support (helpers shared by tests, e.g. child_process.hpp).
#   The tests share one precompiled header (GoogleTest and OpenCV's core, which every test file parses: about 3 s
#   of a test file's compile), built once in gpilot_test_pch.
function(gpilot_add_test)
  cmake_parse_arguments(T "NETNS" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS;CASES" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 120)
  endif()
  if(NOT TARGET gpilot_test_pch)
    file(WRITE ${CMAKE_BINARY_DIR}/gpilot_test_pch.cpp "// the precompiled header's own translation unit\n")
    add_library(gpilot_test_pch STATIC ${CMAKE_BINARY_DIR}/gpilot_test_pch.cpp)
    target_link_libraries(gpilot_test_pch PRIVATE GTest::gtest GTest::gmock opencv_core)
    target_compile_options(gpilot_test_pch PRIVATE -pthread)  # as every test (_REENTRANT must match)
    target_compile_definitions(gpilot_test_pch PRIVATE GPILOT_SHARED_DIR="${GPILOT_SHARED_DIR}")
    target_precompile_headers(gpilot_test_pch PRIVATE <gtest/gtest.h> <opencv2/core.hpp>)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_definitions(${T_NAME} PRIVATE GPILOT_SHARED_DIR="${GPILOT_SHARED_DIR}")
  target_include_directories(${T_NAME} PRIVATE ${CMAKE_SOURCE_DIR}/tests/support)
  target_precompile_headers(${T_NAME} REUSE_FROM gpilot_test_pch)
  # A test built with other options than the header's parses the headers itself (a warning, never an error).
  target_compile_options(${T_NAME} PRIVATE -pthread -Wno-error=invalid-pch)
  if(T_NETNS AND T_CASES)
    foreach(_filter IN LISTS T_CASES)
      string(REGEX REPLACE ".*/" "" _case "${_filter}")
      add_test(NAME ${T_NAME}:${_case}
        COMMAND ${CMAKE_SOURCE_DIR}/tests/netns-run $<TARGET_FILE:${T_NAME}> --gtest_filter=${_filter})
      set_tests_properties(${T_NAME}:${_case} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT}
        SKIP_RETURN_CODE 77 SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]" FAIL_REGULAR_EXPRESSION "Running 0 tests")
    endforeach()
  elseif(T_NETNS)
    add_test(NAME ${T_NAME} COMMAND ${CMAKE_SOURCE_DIR}/tests/netns-run $<TARGET_FILE:${T_NAME}>)
    set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT} SKIP_RETURN_CODE 77
      SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]")
  else()
    gtest_discover_tests(${T_NAME} DISCOVERY_MODE PRE_TEST
      PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT} SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]")
  endif()
endfunction()

# gpilot_add_executable(name SOURCES ... LIBS ...): a service or tool in build/bin, installed into bin/.
function(gpilot_add_executable NAME)
  cmake_parse_arguments(E "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${NAME} ${E_SOURCES})
  target_link_libraries(${NAME} PRIVATE ${E_LIBS})
  install(TARGETS ${NAME} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# Adds every child folder of the current source folder that has a CMakeLists.txt, in name order.
function(gpilot_add_subdirectories)
  file(GLOB _dirs LIST_DIRECTORIES true CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*")
  list(SORT _dirs)
  foreach(_dir IN LISTS _dirs)
    if(IS_DIRECTORY "${_dir}" AND EXISTS "${_dir}/CMakeLists.txt")
      add_subdirectory("${_dir}")
    endif()
  endforeach()
endfunction()
