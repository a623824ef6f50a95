// A sample of joint states (names, positions and optionally velocities, as a
// sensor_msgs/JointState carries them) onto a model's coordinates, for the node
// (ros/joint_state_input.h) and recordings (offline/recording.h) alike: each name looked up
// (again only when a sample's names differ from the previous one's: a publisher sends one list),
// the sample checked whole, and the signs of Euler parameters kept continuous (e and -e are one
// rotation, doc/method.md 2). No allocation per sample while the names stay the same.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "mb_kinematics/core/model.h"

namespace mbk {

// Names onto a model's coordinates, looked up again only when they differ from the last names
// (a publisher sends one list): no allocation while they stay the same.
class CoordinateLookup {
 public:
  explicit CoordinateLookup(const Model& model);
  // Each name's coordinate, -1 for a name that is none of the model's; `changed`: the names
  // differ from the last ones.
  const std::vector<int>& look_up(const std::vector<std::string>& names, bool* changed = nullptr);
  const std::vector<int>& coordinates() const { return coordinate_of_; }  // of the last names

 private:
  std::unordered_map<std::string, int> index_;  // coordinate by name
  std::vector<std::string> names_;
  std::vector<int> coordinate_of_;
};

// The class of a sample's problem (JointStateIntake::check).
enum class SampleProblem { kNone, kUnequalLengths, kDuplicateName, kNonFinite };

class JointStateIntake {
 public:
  explicit JointStateIntake(const Model& model);  // `model` outlives this object

  // "" for a sound sample, else its first problem, in the sample's order: "3 names but 2
  // positions" (or velocities; no velocities at all is sound), "joint 'x' is named twice",
  // "joint 'x': position is NaN" (or velocity, Inf). Names not in the model are ignored
  // (unknown()). problem() classifies the answer.
  std::string check(const std::vector<std::string>& names, const std::vector<double>& position,
                    const std::vector<double>& velocity);
  SampleProblem problem() const { return problem_; }
  // The last sample checked had the names of the one checked before it (in the same order).
  bool same_names() const { return same_names_; }
  // Of the last sample checked with equal lengths: each name's coordinate (-1: none of the
  // model's), and the names that are none of the model's, in the sample's order.
  const std::vector<int>& coordinates() const { return lookup_.coordinates(); }
  const std::vector<std::string>& unknown() const { return unknown_; }

  // Takes the last sample checked sound: each coordinate it names gets its position times
  // sign(coordinate) as its last(). sign is -1 on the four Euler parameters of a joint that the
  // sample gives whole with a negative dot product against their last values (all four taken
  // before), else 1: a publisher may flip between e and -e (to keep e4 >= 0, say), and e (and
  // the derivatives estimated from it) stays continuous. Returns the joints negated.
  int take(const std::vector<double>& position);
  double sign(int coordinate) const { return sign_[coordinate]; }
  // Each coordinate's last position taken (0 before any), and whether it was ever taken.
  const std::vector<double>& last() const { return last_; }
  bool taken(int coordinate) const { return taken_[coordinate] != 0; }
  // A coordinate's last position replaced (a recording's outlier by its window's median).
  void replace_last(int coordinate, double value) { last_[coordinate] = value; }

 private:
  void map_names(const std::vector<std::string>& names);

  const Model& model_;
  std::vector<int> euler_;  // the first coordinate of each joint with Euler parameters
  // Of the names looked up last: each name's coordinate, the names not in the model, each
  // coordinate's place in the sample (-1: not named), the first name given twice (or their
  // count).
  CoordinateLookup lookup_;
  std::vector<std::string> unknown_;
  std::vector<int> place_;
  size_t duplicate_at_ = 0;
  SampleProblem problem_ = SampleProblem::kNone;
  bool same_names_ = false;
  std::vector<double> sign_, last_;
  std::vector<char> taken_;
};

}  // namespace mbk
