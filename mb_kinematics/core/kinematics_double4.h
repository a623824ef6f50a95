// forward_kinematics and system_kinematics of four samples at once (double4.h: a lane each), for
// the batch (offline/batch_kinematics.cc): the same templates as in double, compiled for AVX2,
// each lane its sample's double result bit for bit. On CPUs without AVX2 (where the four lanes
// take two SSE2 operations each, slower than one sample at a time) and for models with a joint
// of the generic kernel, four_samples_at_once is false and callers go one sample at a time.
#pragma once

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/double4.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

// Whether the overloads below run for `model` on this CPU.
bool four_samples_at_once(const Model& model);

// As forward_kinematics (kinematics.h) for each lane; throws std::logic_error unless
// four_samples_at_once(model).
void forward_kinematics(const Model& model, const JointState<Double4>& state, Data<Double4>& data,
                        Level level);

// As system_kinematics (system_kinematics.h) for each lane; the same precondition.
void system_kinematics(const Model& model, const Data<Double4>& data,
                       SystemKinematics<Double4>& out, Level level);

}  // namespace mbk
