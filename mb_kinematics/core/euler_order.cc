#include "mb_kinematics/core/euler_order.h"

#include <cctype>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"

namespace mbk {

Mat3<double> SignedPermutation::matrix() const {
  Mat3<double> m = Mat3<double>::Zero();
  for (int j = 0; j < 3; ++j) m(index[j], j) = sign[j];
  return m;
}

std::array<int, 3> euler_axes(EulerOrder order) {
  const EulerTurns& o = kEulerOrders.at(static_cast<size_t>(order));
  return {o.a1, o.a2, o.a3};
}

bool is_tait_bryan(EulerOrder order) { return !kEulerOrders.at(static_cast<size_t>(order)).proper; }

std::string to_string(EulerOrder order) {
  std::string s;
  for (int axis : euler_axes(order)) s += static_cast<char>('X' + axis);
  return s;
}

EulerOrder euler_order_from_axes(const std::array<int, 3>& axes) {
  for (size_t i = 0; i < kEulerOrders.size(); ++i)
    if (euler_axes(static_cast<EulerOrder>(i)) == axes) return static_cast<EulerOrder>(i);
  throw std::invalid_argument("not an Euler order: axes " + std::to_string(axes[0]) + ", " +
                              std::to_string(axes[1]) + ", " + std::to_string(axes[2]));
}

EulerOrder euler_order_from_string(const std::string& text) {
  std::array<int, 3> axes{};
  bool ok = text.size() == 3;
  for (size_t i = 0; ok && i < 3; ++i) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    if (c >= 'X' && c <= 'Z')
      axes[i] = c - 'X';
    else if (c >= '1' && c <= '3')
      axes[i] = c - '1';
    else
      ok = false;
  }
  for (int i = 0; ok && i < static_cast<int>(kEulerOrders.size()); ++i)
    if (euler_axes(static_cast<EulerOrder>(i)) == axes) return static_cast<EulerOrder>(i);
  throw std::invalid_argument("unknown Euler order '" + printable(text) +
                              "' (one of XYZ, XZY, YXZ, YZX, ZXY, ZYX, XYX, XZX, YXY, YZY, ZXZ, "
                              "ZYZ, or the same as digits 123, 313, ...)");
}

}  // namespace mbk
