# Run at build time (cmake -P, target gpilot_version): writes OUT, a header with GPILOT_VERSION from
# `git describe --always --dirty` of SRC, or FALLBACK (the project version) where there is no git checkout.
# configure_file rewrites OUT only when the text changes, so an unchanged version rebuilds nothing.
execute_process(COMMAND git -C "${SRC}" describe --always --dirty
                OUTPUT_VARIABLE GPILOT_VERSION RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT rc EQUAL 0 OR GPILOT_VERSION STREQUAL "")
  set(GPILOT_VERSION "${FALLBACK}")
endif()
configure_file("${CMAKE_CURRENT_LIST_DIR}/gpilot_version.hpp.in" "${OUT}" @ONLY)
