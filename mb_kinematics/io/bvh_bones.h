// Bone lengths of a BVH skeleton over its MOTION: a JOINT whose position channels give its local
// translation (doc/conventions.md#bvh-files) has a bone that may change length from frame to
// frame, which in a human skeleton usually means a file read the wrong way. ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/io/bvh.h"

namespace mbk {

// The length range, in metres, of the bone from a JOINT's parent to it over every frame.
struct BoneLength {
  std::string name;  // the JOINT's
  double min = 0, max = 0;
};

// Per segment: whether it stays where it is in R through the motion, its channels and all its
// ancestors' constant (a ROOT whose channels are all 0, as Bandai Namco's joint_Root).
std::vector<bool> fixed_in_space(const BvhFile& bvh);

// The bones whose length changes during the motion by more than 1e-3 of their longest (and
// 1e-6 m): JOINTs with position channels whose translation (OFFSET with the channels' axes
// replaced by their values, times `scale`) changes length. A JOINT whose parent is fixed in
// space carries the skeleton's motion, no bone: it is left out. In segment order.
std::vector<BoneLength> changing_bones(const BvhFile& bvh, double scale);

// "" or one warning naming each changing bone with its min-max length in metres.
std::string changing_bones_warning(const BvhFile& bvh, double scale);

}  // namespace mbk
