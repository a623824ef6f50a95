// The update in long double, compiled once (reference_kinematics.h); quad is in
// reference_kinematics_quad.cc.
#include "mb_kinematics/analysis/reference_kinematics.h"

namespace mbk {

template void forward_kinematics<long double>(const Model&, const JointState<long double>&,
                                              Data<long double>&, Level);

}  // namespace mbk
