#include "mb_kinematics/tools/error_bar_summary.h"

#include <algorithm>
#include <cstdio>

#include "mb_kinematics/core/printable.h"

namespace mbk {

double median_noise(const std::vector<CoordinateError>& errors) {
  std::vector<double> noise;
  for (const CoordinateError& e : errors) noise.push_back(e.noise);
  const size_t middle = noise.size() / 2;
  std::nth_element(noise.begin(), noise.begin() + middle, noise.end());
  return noise[middle];
}

std::string error_bar_line(const std::vector<CoordinateError>& errors) {
  if (errors.empty()) return "";
  const CoordinateError* noisiest = &errors.front();
  const CoordinateError* worst = &errors.front();
  for (const CoordinateError& e : errors) {
    if (e.noise > noisiest->noise) noisiest = &e;
    if (e.acceleration_se > worst->acceleration_se) worst = &e;
  }
  char line[512];
  std::snprintf(line, sizeof line,
                "  noise level %.2e (median over %zu coordinates; largest %.2e, %s); worst error "
                "bar: %s, acceleration %.2e (velocity %.2e)\n",
                median_noise(errors), errors.size(), noisiest->noise, printable(noisiest->name).c_str(),
                printable(worst->name).c_str(), worst->acceleration_se, worst->velocity_se);
  return line;
}

}  // namespace mbk
