#include "mb_kinematics/analysis/kinematics_error.h"

namespace mbk {

const char* quantity_name(int q) {
  static const char* names[] = {"orientation", "omega",    "alpha",
                                "position",    "velocity", "acceleration"};
  return q >= 0 && q < ErrorQuantity::kCount ? names[q] : "?";
}

}  // namespace mbk
