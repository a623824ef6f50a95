// BVH (Biovision hierarchy) motion capture files read as they are: the skeleton's segments with
// their offsets and channels, and the frames' values in the file's own units (degrees for
// rotations). ROS-free; turning a BVH file into a Model is not done here.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace mbk {

enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

// True for Xrotation, Yrotation and Zrotation.
bool is_rotation(BvhChannel channel);

// One ROOT or JOINT of the hierarchy; segments come in file order, parents first.
struct BvhSegment {
  std::string name;
  int parent = -1;  // index in BvhFile::segments; -1 for the ROOT
  int line = 0;     // of its ROOT or JOINT keyword, for errors found later
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // from the parent's origin, parent axes
  std::vector<BvhChannel> channels;                  // in the file's order
  int first_column = 0;                              // of channels[0] in a frame row
  bool has_end_site = false;
  Eigen::Vector3d end_site = Eigen::Vector3d::Zero();  // the End Site's OFFSET, if any
};

// The frame times read (s): a ROS stamp counts nanoseconds, a ROS duration at most 2^31 - 1 s.
constexpr double kMinBvhFrameTime = 1e-9;
constexpr double kMaxBvhFrameTime = 2147483647.0;

struct BvhFile {
  std::string path;  // as given to parse_bvh, for errors found later
  std::vector<BvhSegment> segments;
  int channel_count = 0;  // values per frame: every segment's channels, in segment order
  int frame_count = 0;
  double frame_time = 0;       // seconds
  std::vector<double> frames;  // row-major, frame_count x channel_count
  double value(int frame, int column) const {
    return frames[static_cast<size_t>(frame) * channel_count + column];
  }
};

// Parses the text of a BVH file; `path` names it in errors. Throws std::invalid_argument (as the
// other model loaders do)
// "<path>:<line>: <what is wrong>" (missing braces, unknown channel, a bad number, an empty
// hierarchy, a frame with the wrong number of values, a truncated MOTION). Linear time.
BvhFile parse_bvh(const std::string& text, const std::string& path);

// parse_bvh of the file at `path`; std::invalid_argument "<path>: cannot open" if unreadable.
BvhFile read_bvh(const std::string& path);

// Unwraps every rotation column at +-180 degrees: each frame's angle moves by the multiple of
// 360 that brings it nearest the (unwrapped) previous frame's, so the angles can be
// differentiated. Position columns are left as they are.
void unwrap_rotations(BvhFile& bvh);

}  // namespace mbk
