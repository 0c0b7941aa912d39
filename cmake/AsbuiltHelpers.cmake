# One helper call per library and per test binary (STYLE.md 11).

set(ASBUILT_WARNINGS -Wall -Wextra -Wpedantic -Wno-unused-parameter -Wno-missing-field-initializers)

# Code that runs once per command or per test case (argument parsing, test
# bodies) is compiled at -O1 in Release: its cost is template code generation
# (CLI11, nlohmann-json, GoogleTest), and -O3 took 25–50 % longer per file for
# no run-time gain (the work happens in the libraries, which stay at -O3).
# Measured on 2 cores: bad_input_test.cc 24.0 -> 12.5 s, plan_command.cc 21.2 -> 15.4 s.
function(asbuilt_light_optimization target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-O1>)
endfunction()

function(asbuilt_apply_common target)
  target_compile_options(${target} PRIVATE ${ASBUILT_WARNINGS})
  if(ASBUILT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(ASBUILT_FUZZ)
    # Coverage feedback from the libraries too, not only the harness file:
    # without it libFuzzer is blind inside the parsers it is meant to explore.
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
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
  asbuilt_apply_common(${target})
  asbuilt_light_optimization(${target})
  gtest_discover_tests(${target} TEST_PREFIX "${ARG_NAME}/"
    DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${ARG_TIMEOUT})
endfunction()
