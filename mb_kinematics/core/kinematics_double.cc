#include "mb_kinematics/core/kinematics_double.h"

namespace mbk {

template void forward_kinematics<double>(const Model&, const JointState<double>&, Data<double>&,
                                         Level);

}  // namespace mbk
