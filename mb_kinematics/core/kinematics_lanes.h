// forward_kinematics and system_kinematics of several samples at once (double_lanes.h: a lane
// each), for the batch (offline/batch_kinematics.cc): the same templates as in double, compiled
// for AVX-512F (eight samples) and for AVX2 (four), each lane its sample's double result bit for
// bit. On CPUs with neither (where the lanes take two SSE2 operations each for four, slower than
// one sample at a time) and for models with a joint of the generic kernel, samples_at_once is 1
// and callers go one sample at a time.
#pragma once

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/double_lanes.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

// The most samples the overloads below compute at once for `model` on this CPU: 8 (AVX-512F),
// 4 (AVX2) or 1 (neither, or a build without the dispatch: a sanitizer's).
int samples_at_once(const Model& model);

// As forward_kinematics (kinematics.h) for each lane; throws std::logic_error unless
// samples_at_once(model) is at least the lanes' count.
void forward_kinematics(const Model& model, const JointState<Double4>& state, Data<Double4>& data,
                        Level level);
void forward_kinematics(const Model& model, const JointState<Double8>& state, Data<Double8>& data,
                        Level level);

// As system_kinematics (system_kinematics.h) for each lane; the same precondition.
void system_kinematics(const Model& model, const Data<Double4>& data,
                       SystemKinematics<Double4>& out, Level level);
void system_kinematics(const Model& model, const Data<Double8>& data,
                       SystemKinematics<Double8>& out, Level level);

}  // namespace mbk
