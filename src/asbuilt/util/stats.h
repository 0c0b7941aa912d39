#ifndef ASBUILT_UTIL_STATS_H_
#define ASBUILT_UTIL_STATS_H_

// Small robust statistics every layer uses.

#include <vector>

namespace asbuilt {

// The median (the mean of the two middle values of an even count); NaN
// for none.
double Median(std::vector<double> values);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_STATS_H_
