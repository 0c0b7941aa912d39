#ifndef ASBUILT_FORMATS_POINTS_PLY_H_
#define ASBUILT_FORMATS_POINTS_PLY_H_

// points.ply: labelled points for viewers (MeshLab, CloudCompare).

#include <filesystem>
#include <vector>

#include "asbuilt/formats/points_file.h"

namespace asbuilt {

// Coloured PLY (ASCII), world metres to 0.1 mm: wall grey-blue, door brown,
// window cyan, and the label id as a `label` property. Written atomically.
void WritePointsPly(const std::vector<ClassPoint>& points, const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_POINTS_PLY_H_
