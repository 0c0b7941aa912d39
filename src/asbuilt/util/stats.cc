#include "asbuilt/util/stats.h"

#include <algorithm>
#include <cmath>

namespace asbuilt {

double Median(std::vector<double> values) {
  if (values.empty()) return NAN;
  const auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  if (values.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(values.begin(), mid));
}

double UpperMedian(std::vector<double> values) {
  if (values.empty()) return NAN;
  const auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace asbuilt
