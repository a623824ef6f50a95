#include "mb_kinematics/ros/outputs/output_table.h"

#include "mb_kinematics/ros/outputs/body_kinematics_output.h"
#include "mb_kinematics/ros/outputs/body_motion_output.h"
#include "mb_kinematics/ros/outputs/diagnostics_output.h"
#include "mb_kinematics/ros/outputs/markers_output.h"
#include "mb_kinematics/ros/outputs/partial_velocities_service.h"
#include "mb_kinematics/ros/outputs/tf_output.h"

namespace mbk_ros {
namespace {

struct OutputKind {
  bool (*enabled)(const NodeParams&);  // its parameter flag
  bool in_r;                           // it needs R
  std::unique_ptr<Output> (*make)(const OutputSetup&);
};

template <typename T>
OutputKind kind(bool in_r = true) {
  return {&T::enabled, in_r,
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
    kind<DiagnosticsOutput>(/*in_r=*/false),  // made at start, before R may be known
};

}  // namespace

std::vector<std::unique_ptr<Output>> make_outputs(const OutputSetup& setup, bool in_r) {
  std::vector<std::unique_ptr<Output>> outputs;
  for (const OutputKind& k : kOutputs)
    if (k.in_r == in_r && k.enabled(setup.params)) outputs.push_back(k.make(setup));
  return outputs;
}

}  // namespace mbk_ros
