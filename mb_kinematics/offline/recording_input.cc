#include "mb_kinematics/offline/recording_input.h"

#include <stdexcept>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/bag_input.h"
#include "mb_kinematics/offline/recording_states.h"

namespace mbk_offline {

mbk::Recording read_recording_input(const mbk::Model& model, const std::string& path,
                                    double bvh_scale, const std::string& joint_states,
                                    mbk::DropLog& log) {
  const std::string tail = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  if (tail != ".bag" && tail != ".csv" && !mbk::is_bvh_file(path))
    throw std::invalid_argument(path + ": not a recording (.bag, .csv or .bvh)");
  if (tail != ".bag") return mbk::read_recording_file(model, path, bvh_scale, log);
  mbk::RecordingBuilder builder(model);
  BagTopics topics;
  topics.joint_states = joint_states;
  BaseOdometry base;
  Unreadable unreadable;
  read_bag(path, topics, builder, base, unreadable, [](long, long) {});
  mbk::Recording recording = builder.finish();
  log = builder.log();
  if (unreadable.count) {
    log.drops["unreadable message"] = unreadable.count;
    log.example["unreadable message"] = unreadable.first;
  }
  return recording;
}

}  // namespace mbk_offline
