# occlude_code_hash(TARGET HEADER SYMBOL FILES...): generates HEADER (a name, found by TARGET's
# sources as #include "HEADER") declaring `inline constexpr char SYMBOL[]`, 16 hex digits of a
# hash of FILES, remade whenever one of them changes (cmake/HashSources.cmake). Cache entries of
# what that code computes are keyed by it, so an edited algorithm never reads an older build's.
# The header is also written when the build is configured, so that tools which only configure
# (clang-tidy on the compile commands, scripts/tidy) find it.
function(occlude_code_hash target header symbol)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/generated/${header})
  set(script ${PROJECT_SOURCE_DIR}/cmake/HashSources.cmake)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DNAME=${symbol} "-DFILES=${ARGN}" -P ${script}
    RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "occlude_code_hash: cannot write ${out}")
  endif()
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DNAME=${symbol} "-DFILES=${ARGN}" -P ${script}
    DEPENDS ${ARGN} ${script}
    COMMENT "Hashing the code of ${symbol}"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_BINARY_DIR}/generated)
endfunction()
