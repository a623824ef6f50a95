#include "mb_kinematics/offline/recording_input.h"

#include <stdexcept>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/recording_states.h"

namespace mbk_offline {

RecordingInput read_recording_input(const mbk::Model& model, const std::string& path,
                                    double bvh_scale, const BagTopics& topics, mbk::DropLog& log) {
  const std::string tail = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  if (tail != ".bag" && tail != ".csv" && !mbk::is_bvh_file(path))
    throw std::invalid_argument(path + ": not a recording (.bag, .csv or .bvh)");
  RecordingInput out;
  if (tail != ".bag") {
    if (!topics.joint_accelerations.empty() || !topics.base_odometry.empty())
      throw std::invalid_argument(path + ": joint accelerations and base odometry need a bag");
    out.recording = mbk::read_recording_file(model, path, bvh_scale, log);
    return out;
  }
  mbk::RecordingBuilder builder(model);
  Unreadable unreadable;
  read_bag(path, topics, builder, out.base, unreadable, [](long, long) {});
  out.recording = builder.finish();
  log = builder.log();
  if (unreadable.count) {
    log.drops["unreadable message"] = unreadable.count;
    log.example["unreadable message"] = unreadable.first;
  }
  if (!topics.base_odometry.empty() && out.base.samples.empty())
    throw std::invalid_argument(path + ": no usable message on '" + topics.base_odometry + "'");
  return out;
}

}  // namespace mbk_offline
