#include "mb_kinematics/analysis/reference_kinematics.h"

namespace mbk {

template void forward_kinematics<Quad>(const Model&, const JointState<Quad>&, Data<Quad>&, Level);
template void forward_kinematics<long double>(const Model&, const JointState<long double>&,
                                              Data<long double>&, Level);

}  // namespace mbk
