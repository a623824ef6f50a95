// ~publish_frequency (doc/node.md): the outputs at most this often, by the samples'
// stamps; every sample still goes through the input (its estimators take it in).
#pragma once

namespace mbk_ros {

class PublishRate {
 public:
  explicit PublishRate(double frequency = 0) : frequency_(frequency) {}  // 0: every sample

  // True for a sample less than a period (by stamp t, seconds) after the last one that went
  // out; a stamp going backwards starts again.
  bool skip(double t);

 private:
  double frequency_;
  double last_output_ = -1e300;  // stamp of the last sample that went out
};

}  // namespace mbk_ros
