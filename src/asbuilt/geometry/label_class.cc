#include "asbuilt/geometry/label_class.h"

namespace asbuilt {

const char* LabelClassName(LabelClass c) {
  switch (c) {
    case LabelClass::kBackground:
      return "background";
    case LabelClass::kWall:
      return "wall";
    case LabelClass::kDoor:
      return "door";
    case LabelClass::kWindow:
      return "window";
  }
  return "unknown";
}

}  // namespace asbuilt
