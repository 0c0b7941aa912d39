# One helper call per library and per test binary (STYLE.md 11).

set(ASBUILT_WARNINGS -Wall -Wextra -Wpedantic -Wno-unused-parameter -Wno-missing-field-initializers)

# asbuilt_apply_common(<target> [LIGHT])
# Warnings and, when asked, sanitizers and fuzzing coverage.
#
# LIGHT: code that runs once per command or per test case (argument parsing,
# test bodies). Its compile time is template code generation (CLI11,
# nlohmann-json, GoogleTest) for no run-time gain, so it is compiled at -O1 in
# Release (the libraries, where the work happens, stay at -O3), and in the
# sanitizer build without libFuzzer's coverage (a test is not a fuzz target;
# the libraries it links keep theirs). Measured alone on 2 cores:
# bad_input_test.cc 24.0 -> 12.5 s, plan_command.cc 21.2 -> 15.4 s in
# Release. Not -O0 under the sanitizers: it compiled tools_test.cc in 14.8 s
# instead of 37.0, but test bodies inline Eigen and the planners' headers,
# and the sanitized tests took 223 s instead of 87 (one 75 s instead of 15).
function(asbuilt_apply_common target)
  cmake_parse_arguments(ARG "LIGHT" "" "" ${ARGN})
  target_compile_options(${target} PRIVATE ${ASBUILT_WARNINGS})
  if(ARG_LIGHT)
    target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-O1>)
  endif()
  if(ASBUILT_SANITIZE OR ASBUILT_FUZZ)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(ASBUILT_FUZZ AND NOT ARG_LIGHT)
    # Coverage feedback from the libraries too, not only the harness file:
    # without it libFuzzer is blind inside the parsers it is meant to explore.
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

# asbuilt_precompile(<target> <library|test|cli>)
# The target's translation units start from a precompiled header
# (cmake/pch/<kind>_pch.h): the third-party headers that every file parses
# (one test file preprocessed to 228,000 lines; parsing was 7.5 of its 12.7 s).
# One per target, built with that target's own flags, so it is valid for every
# compiler and flag set (Release, the sanitizer build); GCC rejects a shared
# one across targets whose -D, -O or -fPIC/-fPIE differ, and ours do.
# ASBUILT_PCH=OFF builds without them, which also shows a file that forgot an
# include. Test binaries and the program use unity batches instead (asbuilt_unity).
function(asbuilt_precompile target kind)
  if(ASBUILT_PCH)
    target_precompile_headers(${target} PRIVATE ${PROJECT_SOURCE_DIR}/cmake/pch/${kind}_pch.h)
  endif()
endfunction()

# asbuilt_unity(<target> <pch kind>)
# Unity build: up to ASBUILT_UNITY_BATCH files per translation unit, so
# GoogleTest's, CLI11's, nlohmann-json's and Eigen's headers are parsed and
# their templates instantiated once per batch, not once per file. For the
# test binaries and the `asbuilt` program (code that runs once per command,
# at -O1); the libraries stay one file per unit in Release. Building
# scene_test + plan_test and their libraries on 2 cores: 189 s one by one,
# 163 s with a precompiled header per target, 134 s with unity batches of 8
# (and the libraries' precompiled headers); a precompiled header on top of a
# unity batch costs more than it saves. A file's helpers in an anonymous
# namespace share the batch with its neighbours': give them distinct names.
# With ASBUILT_UNITY_BATCH=0 the target gets its precompiled header of
# `pch_kind` instead.
function(asbuilt_unity target pch_kind)
  if(ASBUILT_UNITY_BATCH)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${ASBUILT_UNITY_BATCH})
  else()
    asbuilt_precompile(${target} ${pch_kind})
  endif()
endfunction()

# asbuilt_library(NAME <module> SRCS <files> [DEPS <targets>] [PRIVATE_DEPS <targets>])
# Declares library `asbuilt_<module>` with alias `asbuilt::<module>`; headers
# are included as "asbuilt/<module>/x.h" from the src/ root.
function(asbuilt_library)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;DEPS;PRIVATE_DEPS" ${ARGN})
  set(target asbuilt_${ARG_NAME})
  add_library(${target} STATIC ${ARG_SRCS})
  add_library(asbuilt::${ARG_NAME} ALIAS ${target})
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${target} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  asbuilt_apply_common(${target})
  asbuilt_precompile(${target} library)
endfunction()

# asbuilt_test(NAME <module> SRCS <files> DEPS <targets>)
# One GoogleTest binary per module; ctest names are "<module>/<Suite>.<Test>",
# so `ctest -R render/` runs one module's tests.
function(asbuilt_test)
  cmake_parse_arguments(ARG "" "NAME;TIMEOUT" "SRCS;DEPS" ${ARGN})
  if(NOT ASBUILT_BUILD_TESTS)
    return()
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  set(target ${ARG_NAME}_test)
  add_executable(${target} ${ARG_SRCS})
  target_link_libraries(${target} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main GTest::gmock)
  target_compile_definitions(${target} PRIVATE
    ASBUILT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    ASBUILT_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data"
    ASBUILT_BINARY_DIR="${PROJECT_BINARY_DIR}")
  asbuilt_apply_common(${target} LIGHT)
  asbuilt_unity(${target} test)
  gtest_discover_tests(${target} TEST_PREFIX "${ARG_NAME}/"
    DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${ARG_TIMEOUT})
endfunction()
