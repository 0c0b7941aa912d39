// Precompiled header of every asbuilt library (cmake/AsbuiltHelpers.cmake,
// asbuilt_precompile). Parsing these headers was most of the build: one test
// file preprocesses to ~230,000 lines (nlohmann-json, Eigen, GoogleTest, fmt),
// and -fsyntax-only took 7.5 of its 12.7 s. Only headers that do not change
// from one build to the next belong here; a project header would rebuild
// every target when it changes.
//
// __has_include keeps one header for every target: a target sees Eigen or
// OpenCV only when it links them (their include folders are on its path).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#if __has_include(<Eigen/Core>)
#include <Eigen/Core>
#include <Eigen/Geometry>
#endif
#if __has_include(<opencv2/core.hpp>)
#include <opencv2/core.hpp>
#endif
