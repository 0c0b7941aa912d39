#ifndef ASBUILT_UTIL_STATS_H_
#define ASBUILT_UTIL_STATS_H_

// Small robust statistics every layer uses.

#include <vector>

namespace asbuilt {

// The median (the mean of the two middle values of an even count); NaN
// for none.
double Median(std::vector<double> values);

// The upper median: the middle value, and of an even count the upper of the
// two middle ones (a value of the set, never a mean). The tilt fit of a
// panorama and the stereo calibration's outlier limit were tuned with it;
// their outputs depend on which of the two they get.
double UpperMedian(std::vector<double> values);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_STATS_H_
