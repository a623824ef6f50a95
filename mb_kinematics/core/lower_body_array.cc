#include "mb_kinematics/core/lower_body_array.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace mbk {

void validate_lower_body_array(const std::vector<int>& lower) {
  if (lower.empty()) throw std::invalid_argument("lower body array is empty: it needs L(1) = 0");
  for (size_t i = 0; i < lower.size(); ++i) {
    const int k = static_cast<int>(i) + 1;
    if (lower[i] < 0 || lower[i] >= k) {
      std::ostringstream msg;
      msg << "lower body array: body " << k << " has L(" << k << ") = " << lower[i]
          << ", must satisfy 0 <= L(k) < k";
      throw std::invalid_argument(msg.str());
    }
  }
}

int lower_body_power(const std::vector<int>& lower, int k, int t) {
  for (; t > 0 && k > 0; --t) k = lower[k - 1];
  return k;
}

int lower_body_table_rows(const std::vector<int>& lower) {
  std::vector<int> depth(lower.size() + 1, 0);  // depth[0] = 0: R
  int deepest = 0;
  for (size_t i = 0; i < lower.size(); ++i) {
    depth[i + 1] = depth[lower[i]] + 1;
    deepest = std::max(deepest, depth[i + 1]);
  }
  return deepest + 1;
}

void for_each_lower_body_row(const std::vector<int>& lower,
                             const std::function<void(int, const std::vector<int>&)>& row) {
  std::vector<int> powers(lower.size());
  for (size_t i = 0; i < powers.size(); ++i) powers[i] = static_cast<int>(i) + 1;
  const int rows = lower_body_table_rows(lower);
  for (int t = 0; t < rows; ++t) {
    if (t > 0)
      for (int& v : powers) v = v > 0 ? lower[v - 1] : 0;  // eq. 4.2.1
    row(t, powers);
  }
}

std::vector<std::vector<int>> lower_body_table(const std::vector<int>& lower) {
  std::vector<std::vector<int>> table;
  for_each_lower_body_row(lower, [&](int, const std::vector<int>& row) { table.push_back(row); });
  return table;
}

bool is_ancestor_or_self(const std::vector<int>& lower, int j, int k) {
  for (; k > j; k = lower[k - 1]) {
  }
  return k == j;
}

}  // namespace mbk
