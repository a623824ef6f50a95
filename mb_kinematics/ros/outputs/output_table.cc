#include "mb_kinematics/ros/outputs/output_table.h"

#include "mb_kinematics/ros/outputs/body_kinematics_output.h"
#include "mb_kinematics/ros/outputs/body_motion_output.h"
#include "mb_kinematics/ros/outputs/markers_output.h"
#include "mb_kinematics/ros/outputs/partial_velocities_service.h"
#include "mb_kinematics/ros/outputs/tf_output.h"

namespace mbk_ros {
namespace {

struct OutputKind {
  bool (*enabled)(const NodeParams&);  // its parameter flag
  std::unique_ptr<Output> (*make)(const OutputSetup&);
};

template <typename T>
OutputKind kind() {
  return {&T::enabled,
          [](const OutputSetup& s) -> std::unique_ptr<Output> { return std::make_unique<T>(s); }};
}

// Adding a topic: its Output class and one line here.
const OutputKind kOutputs[] = {
    kind<LowerBodyArrayOutput>(),
    kind<TfStaticOutput>(),
    kind<TfOutput>(),
    kind<BodyKinematicsOutput>(),
    kind<MarkersOutput>(),
    kind<BodyTwistOutput>(),
    kind<BodyAccelOutput>(),
    kind<PartialVelocitiesService>(),
};

}  // namespace

std::vector<std::unique_ptr<Output>> make_outputs(const OutputSetup& setup) {
  std::vector<std::unique_ptr<Output>> outputs;
  for (const OutputKind& k : kOutputs)
    if (k.enabled(setup.params)) outputs.push_back(k.make(setup));
  return outputs;
}

}  // namespace mbk_ros
