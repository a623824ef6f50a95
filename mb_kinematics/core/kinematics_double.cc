#include "mb_kinematics/core/kinematics_double.h"

namespace mbk {

template void forward_kinematics<double>(const Model&, const JointState<double>&, Data<double>&,
                                         Level);

namespace detail {

template void forward_kinematics_at<Level::kPose, double, false>(const Model&,
                                                                 const JointState<double>&,
                                                                 Data<double>&);
template void forward_kinematics_at<Level::kVelocity, double, false>(const Model&,
                                                                     const JointState<double>&,
                                                                     Data<double>&);
template void forward_kinematics_at<Level::kAcceleration, double, false>(const Model&,
                                                                         const JointState<double>&,
                                                                         Data<double>&);

}  // namespace detail

}  // namespace mbk
