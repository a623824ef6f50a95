// The 12 orders of three successive rotations about body-fixed (intrinsic) axes, for the angles of
// ball and free joints: SJK = C_k R_a1(alpha) R_a2(beta) R_a3(gamma), a1 != a2 != a3. Six are
// Tait-Bryan (three different axes, the chapter's 1-2-3 = XYZ among them) and six proper Euler
// (first axis repeated: XYX, ...). A BVH channel line "Zrotation Xrotation Yrotation" is ZXY.
#pragma once

#include <array>
#include <string>

namespace mbk {

enum class EulerOrder {
  kXYZ,  // 1-2-3, the chapter's (eq. 4.4.9-4.4.12)
  kXZY,
  kYXZ,
  kYZX,
  kZXY,
  kZYX,
  kXYX,
  kXZX,
  kYXY,
  kYZY,
  kZXZ,
  kZYZ,
  kLast = kZYZ,  // keep equal to the last order
};

// The axes of the three rotations in order, 0 = x, 1 = y, 2 = z.
std::array<int, 3> euler_axes(EulerOrder order);
// True for the six Tait-Bryan orders (three different axes).
bool is_tait_bryan(EulerOrder order);
// "XYZ", "ZXY", ... (upper case).
std::string to_string(EulerOrder order);
// Reads "XYZ"/"xyz" or the digits "123", "313", ... (1 = x, 2 = y, 3 = z). Throws
// std::invalid_argument naming the text for anything else (two equal successive axes, other
// letters, other lengths).
EulerOrder euler_order_from_string(const std::string& text);
// The order whose axes are `axes` (0 = x, 1 = y, 2 = z); std::invalid_argument if two successive
// axes are equal or an axis is out of range.
EulerOrder euler_order_from_axes(const std::array<int, 3>& axes);

}  // namespace mbk
