# Compiler warnings and sanitizers as INTERFACE targets (never global flags).
add_library(occlude_warnings INTERFACE)
add_library(occlude::warnings ALIAS occlude_warnings)
target_compile_options(occlude_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
  -Woverloaded-virtual -Wdouble-promotion -Wformat=2
  $<$<BOOL:${OCCLUDE_WERROR}>:-Werror>)

add_library(occlude_sanitize INTERFACE)
add_library(occlude::sanitize ALIAS occlude_sanitize)
if(OCCLUDE_SANITIZE)
  # -Wno-maybe-uninitialized: with the sanitizers' instrumentation GCC 12 reports false
  # positives inside libstdc++ (std::regex, std::optional of Eigen types) at -O1 and above.
  target_compile_options(occlude_sanitize INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
    $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  target_link_options(occlude_sanitize INTERFACE -fsanitize=address,undefined)
endif()

# Fuzzing (tests/fuzz): coverage for libFuzzer plus ASan and UBSan on every project
# target; the fuzz executables add -fsanitize=fuzzer (libFuzzer's main) themselves.
if(OCCLUDE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "occlude: OCCLUDE_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++ (Debian: apt-get install clang libclang-rt-14-dev)")
  endif()
  target_compile_options(occlude_sanitize INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -g)
  target_link_options(occlude_sanitize INTERFACE -fsanitize=address,undefined)
endif()

# Every project target links this: warnings + sanitizers + internal asserts.
add_library(occlude_defaults INTERFACE)
add_library(occlude::defaults ALIAS occlude_defaults)
target_link_libraries(occlude_defaults INTERFACE occlude_warnings occlude_sanitize)
