#ifndef ASBUILT_GEOMETRY_LABEL_CLASS_H_
#define ASBUILT_GEOMETRY_LABEL_CLASS_H_

// The classes of a label image (DESIGN.md), stated once for every layer: the
// enum for code that names a class, and its pixel values for code that
// compares a label image's bytes.

#include <cstdint>

namespace asbuilt {

enum class LabelClass : std::uint8_t { kBackground = 0, kWall = 1, kDoor = 2, kWindow = 3 };

// "background", "wall", "door", "window".
const char* LabelClassName(LabelClass c);

// A label image's pixel value for class c.
constexpr std::uint8_t LabelId(LabelClass c) { return static_cast<std::uint8_t>(c); }

inline constexpr std::uint8_t kLabelBackground = LabelId(LabelClass::kBackground);
inline constexpr std::uint8_t kLabelWall = LabelId(LabelClass::kWall);
inline constexpr std::uint8_t kLabelDoor = LabelId(LabelClass::kDoor);
inline constexpr std::uint8_t kLabelWindow = LabelId(LabelClass::kWindow);
// Pixels no class is scored or trained on.
inline constexpr std::uint8_t kLabelIgnore = 255;

}  // namespace asbuilt

#endif  // ASBUILT_GEOMETRY_LABEL_CLASS_H_
