// ~missing_coordinates (doc/node.md): per sample, which coordinates come from
// the input, which bodies may be published (mbk::known_bodies: a body's whole chain to R), and
// the names of what is missing, for the node's warnings and /diagnostics.
//   skip: coordinates never received, or stale (no sample for ~max_sample_gap), are unknown;
//         the bodies they place are left out;
//   wait: nothing until every coordinate has come once; stale ones are held (and named);
//   zero: coordinates never received are taken as 0 (and named); stale ones are held.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/ros/joint_state_input.h"
#include "mb_kinematics/ros/node_params.h"

namespace mbk_ros {

class CoordinateCoverage {
 public:
  CoordinateCoverage(const mbk::Model& model, MissingCoordinates mode);

  // For a sample at time t: true if the names of what is missing changed since the last call.
  // skip: a coordinate that comes after the first sample, or comes back after being stale,
  // joins (its bodies are published) once JointStateInput::settled, so that its first samples
  // do not hold back the others' velocities and accelerations.
  bool update(const JointStateInput& input, double t);

  MissingCoordinates mode() const { return mode_; }
  // False: wait, and some coordinate was never received (nothing may be published).
  bool ready() const { return mode_ != MissingCoordinates::kWait || never_.empty(); }
  // For JointStateInput::fill: 1 where the coordinate is taken from the input.
  const std::vector<char>& from_input() const { return from_input_; }
  // Per body (index k; [0] is R): published with this sample.
  const std::vector<char>& published() const { return published_; }
  bool complete() const { return left_out_.empty(); }  // every body published

  const std::vector<std::string>& never() const { return never_; }  // never received
  const std::vector<std::string>& stale() const { return stale_; }  // older than the gap
  // Bodies whose chain needs one of those: left out (skip), or from invented or held values.
  const std::vector<std::string>& affected() const { return affected_; }
  const std::vector<std::string>& left_out() const { return left_out_; }  // skip: = affected
  // One line on what is missing and what is done about it; empty when nothing is.
  const std::string& describe() const { return description_; }

 private:
  const mbk::Model& model_;
  MissingCoordinates mode_;
  std::vector<char> is_mimic_, fresh_, from_input_, placed_, published_;
  std::vector<char> joined_;                           // skip: taken from the input (see update)
  std::vector<JointStateInput::Freshness> freshness_;  // at the last update
  std::string description_;
  std::string describe_missing() const;
  bool started_ = false;
  bool all_joined_ = false;  // at the last update: every coordinate fresh, joined, from the input
  std::vector<std::string> never_, stale_, affected_, left_out_;
};

// "a, b, c", at most `max` names, then how many in all.
std::string join_names(const std::vector<std::string>& names, size_t max = 8);

}  // namespace mbk_ros
