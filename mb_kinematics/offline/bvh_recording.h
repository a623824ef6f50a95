// A BVH file's MOTION as a recording (doc/recorded_data.md#bvh-motion-capture-files): frame f
// (from 0) at t = (f + 1) * Frame Time (not f: ROS reads a zero stamp as none, and a bag refuses
// it), its values as the model's coordinates (io/bvh_model.h), rotations unwrapped
// at +-180 degrees first so that they can be differentiated. ROS-free.
#pragma once

#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk {

// Adds every frame of `bvh` to `builder` (made for `model`, model_from_bvh of `bvh` with the
// same `scale`).
void add_bvh_frames(const BvhFile& bvh, const Model& model, double scale,
                    RecordingBuilder& builder);

// Frame `frame`'s state: its coordinates, with velocities and accelerations from the offline
// zero-phase estimator `estimator` (estimation/offline_estimator.h) over the whole recording,
// as `mbk bag` computes them for that frame. Throws std::invalid_argument for a frame the file
// does not have or that has too few frames around it.
JointState<double> bvh_frame_state(const BvhFile& bvh, const Model& model, double scale, int frame,
                                   const std::string& estimator);

}  // namespace mbk
