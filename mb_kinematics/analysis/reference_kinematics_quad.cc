// The update in quad precision, compiled once (reference_kinematics.h). A file of its own, apart
// from the long double one, so that a 2-core build compiles the two at the same time.
#include "mb_kinematics/analysis/reference_kinematics.h"

namespace mbk {

template void forward_kinematics<Quad>(const Model&, const JointState<Quad>&, Data<Quad>&, Level);

}  // namespace mbk
