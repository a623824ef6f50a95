// The BVH reader (mb_kinematics/io/bvh.h): a hand-written file with mixed channel orders read
// exactly, every error naming its line, a generated 1 MB file, and the +-180 degree unwrapping.
#include "mb_kinematics/io/bvh.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using mbk::BvhChannel;

// Line numbers are those of this text (line 1 is HIERARCHY).
const char kWalk[] =
    "HIERARCHY\n"                                                                 // 1
    "ROOT Hips\n"                                                                 // 2
    "{\n"                                                                         // 3
    "  OFFSET 0.5 1.0 -0.25\n"                                                    // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"  // 5
    "  JOINT LeftUpLeg\n"                                                         // 6
    "  {\n"                                                                       // 7
    "    OFFSET 3.5 0 0\n"                                                        // 8
    "    CHANNELS 3 Zrotation Yrotation Xrotation\n"                              // 9
    "    JOINT LeftLeg\n"                                                         // 10
    "    {\n"                                                                     // 11
    "      OFFSET 0 -17.25 1e-1\n"                                                // 12
    "      CHANNELS 3 Zrotation Xrotation Yrotation\n"                            // 13
    "      End Site\n"                                                            // 14
    "      {\n"                                                                   // 15
    "        OFFSET 0 -16 0\n"                                                    // 16
    "      }\n"                                                                   // 17
    "    }\n"                                                                     // 18
    "  }\n"                                                                       // 19
    "  JOINT Chest\n"                                                             // 20
    "  {\n"                                                                       // 21
    "\tOFFSET 0 5 0\n"                                                            // 22
    "\tCHANNELS 3 Zrotation Xrotation Yrotation\n"                                // 23
    "  }\n"                                                                       // 24
    "}\n"                                                                         // 25
    "MOTION\n"                                                                    // 26
    "Frames: 3\n"                                                                 // 27
    "Frame Time: 0.0083333\n"                                                     // 28
    "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15\n"                                       // 29
    "-1.5 2.5e1 0 179 -179 90 0 0 0 -0 0.25 -0.5 1 2 3\r\n"                       // 30
    "\t0 0 0 0 0 0 0 0 0 0 0 0 0 0 180   \n";                                     // 31

// The message of the std::invalid_argument that parsing `text` throws ("" and a failure if none).
std::string error_of(const std::string& text) {
  try {
    mbk::parse_bvh(text, "walk.bvh");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

// kWalk with its line `number` (from 1) replaced by `line` ("" removes it, keeping later
// numbers one lower).
std::string with_line(int number, const std::string& line) {
  std::istringstream in(kWalk);
  std::string out, current;
  for (int n = 1; std::getline(in, current); ++n) {
    if (n != number)
      out += current + "\n";
    else if (!line.empty())
      out += line + "\n";
  }
  return out;
}

TEST(Bvh, ReadsTheHierarchyWithMixedChannelOrders) {
  const mbk::BvhFile bvh = mbk::parse_bvh(kWalk, "walk.bvh");
  ASSERT_EQ(bvh.segments.size(), 4u);
  const std::vector<std::string> names = {"Hips", "LeftUpLeg", "LeftLeg", "Chest"};
  const std::vector<int> parents = {-1, 0, 1, 0};
  const std::vector<int> first_columns = {0, 6, 9, 12};
  for (size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(bvh.segments[i].name, names[i]);
    EXPECT_EQ(bvh.segments[i].parent, parents[i]);
    EXPECT_EQ(bvh.segments[i].first_column, first_columns[i]);
  }
  using C = BvhChannel;
  EXPECT_EQ(bvh.segments[0].channels,
            (std::vector<C>{C::kXposition, C::kYposition, C::kZposition, C::kZrotation,
                            C::kYrotation, C::kXrotation}));
  EXPECT_EQ(bvh.segments[1].channels,
            (std::vector<C>{C::kZrotation, C::kYrotation, C::kXrotation}));
  EXPECT_EQ(bvh.segments[2].channels,
            (std::vector<C>{C::kZrotation, C::kXrotation, C::kYrotation}));
  EXPECT_EQ(bvh.segments[3].channels,
            (std::vector<C>{C::kZrotation, C::kXrotation, C::kYrotation}));
  EXPECT_EQ(bvh.segments[0].offset, Eigen::Vector3d(0.5, 1.0, -0.25));
  EXPECT_EQ(bvh.segments[2].offset, Eigen::Vector3d(0, -17.25, 0.1));
  EXPECT_EQ(bvh.segments[3].offset, Eigen::Vector3d(0, 5, 0));
  EXPECT_TRUE(bvh.segments[2].has_end_site);
  EXPECT_EQ(bvh.segments[2].end_site, Eigen::Vector3d(0, -16, 0));
  EXPECT_FALSE(bvh.segments[0].has_end_site);
  EXPECT_FALSE(bvh.segments[3].has_end_site);
}

TEST(Bvh, ReadsTheMotionRowMajor) {
  const mbk::BvhFile bvh = mbk::parse_bvh(kWalk, "walk.bvh");
  EXPECT_EQ(bvh.channel_count, 15);
  EXPECT_EQ(bvh.frame_count, 3);
  EXPECT_EQ(bvh.frame_time, 0.0083333);
  ASSERT_EQ(bvh.frames.size(), 45u);
  for (int c = 0; c < 15; ++c) EXPECT_EQ(bvh.value(0, c), c + 1.0);
  EXPECT_EQ(bvh.value(1, 0), -1.5);
  EXPECT_EQ(bvh.value(1, 1), 25.0);
  EXPECT_EQ(bvh.value(1, 3), 179.0);
  EXPECT_EQ(bvh.value(1, 4), -179.0);
  EXPECT_EQ(bvh.value(1, 10), 0.25);
  EXPECT_EQ(bvh.value(1, 14), 3.0);
  EXPECT_EQ(bvh.value(2, 14), 180.0);
  EXPECT_EQ(bvh.frames[2 * 15 + 14], 180.0);
}

// `text` with every line ended by `end` ("\r\n" or a lone "\r").
std::string with_line_ends(const std::string& text, const std::string& end) {
  std::string out;
  for (char c : text) out += c == '\n' ? end : std::string(1, c);
  return out;
}

void expect_same_bvh(const mbk::BvhFile& read, const mbk::BvhFile& plain) {
  ASSERT_EQ(read.segments.size(), plain.segments.size());
  for (size_t i = 0; i < plain.segments.size(); ++i) {
    const mbk::BvhSegment& a = read.segments[i];
    const mbk::BvhSegment& b = plain.segments[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.parent, b.parent);
    EXPECT_EQ(a.offset, b.offset);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_EQ(a.first_column, b.first_column);
    EXPECT_EQ(a.has_end_site, b.has_end_site);
    EXPECT_EQ(a.end_site, b.end_site);
    EXPECT_EQ(a.line, b.line);
  }
  EXPECT_EQ(read.channel_count, plain.channel_count);
  EXPECT_EQ(read.frame_count, plain.frame_count);
  EXPECT_EQ(read.frame_time, plain.frame_time);
  EXPECT_EQ(read.frames, plain.frames);
}

TEST(Bvh, ReadsAByteOrderMarkAndEveryLineEnd) {
  // kWalk with its one CRLF made an LF.
  const std::string plain_text = with_line(30, "-1.5 2.5e1 0 179 -179 90 0 0 0 -0 0.25 -0.5 1 2 3");
  const mbk::BvhFile plain = mbk::parse_bvh(plain_text, "walk.bvh");
  ASSERT_EQ(plain.frame_count, 3);
  const std::string bom = "\xEF\xBB\xBF";
  // Each variant: its byte-order mark and line end.
  const std::vector<std::pair<std::string, std::string>> variants = {
      {bom, "\n"}, {"", "\r"}, {"", "\r\n"}, {bom, "\r"}, {bom, "\r\n"}};
  for (const auto& [mark, end] : variants) {
    SCOPED_TRACE(testing::PrintToString(mark + end));
    expect_same_bvh(mbk::parse_bvh(mark + with_line_ends(plain_text, end), "walk.bvh"), plain);
    // A damaged frame is named by the same line as in the plain file.
    const std::string bad = mark + with_line_ends(with_line(29, "1 2 x"), end);
    EXPECT_NE(error_of(bad).find("walk.bvh:29: frame 0, value 3"), std::string::npos)
        << error_of(bad);
  }
}

TEST(Bvh, ErrorsNameTheFileAndLine) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {with_line(31, ""), {"walk.bvh:31:", "truncated MOTION", "2 of the 3 frames", "line 27"}},
      {with_line(30, "1 2 3"), {"walk.bvh:30:", "frame 1 has 3 values", "need 15"}},
      {with_line(29, "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16"), {"walk.bvh:29:", "16 values"}},
      {with_line(13, "CHANNELS 3 Zrotation Xrotation Wrotation"),
       {"walk.bvh:13:", "unknown channel 'Wrotation'"}},
      {with_line(13, "CHANNELS 3 Zrotation Xrotation " + std::string(1000, 'W')),
       {"walk.bvh:13:", "unknown channel '" + std::string(40, 'W') + "...'"}},
      {with_line(12, "OFFSET 0 -17.25 x1"), {"walk.bvh:12:", "OFFSET", "'x1' is not a number"}},
      {with_line(30, "-1.5 2.5e1 0 179 -179 90 0 0 0 -0 0.25 -0.5 1 2 3z"),
       {"walk.bvh:30:", "frame 1, value 15", "'3z' is not a number"}},
      {with_line(29, "1 2 3 4 5 6 7 8 9 10 11 12 13 nan 15"), {"walk.bvh:29:", "'nan'"}},
      {with_line(28, "Frame Time: -1"), {"walk.bvh:28:", "Frame Time: must be positive"}},
      {with_line(28, "Frame Time: 1e300"),
       {"walk.bvh:28:", "Frame Time: 1e+300 s is not between", "the longest ROS duration"}},
      {with_line(28, "Frame Time: 1e-12"), {"walk.bvh:28:", "Frame Time: 1e-12 s", "nanosecond"}},
      {with_line(27, "Frames: 2.5"), {"walk.bvh:27:", "Frames:", "not a count"}},
      {with_line(9, "    CHANNELS 7 Zrotation Yrotation Xrotation"),
       {"walk.bvh:9:", "CHANNELS of LeftUpLeg", "not a count from 0 to 6"}},
      {"HIERARCHY\nMOTION\nFrames: 0\nFrame Time: 1\n", {"walk.bvh:2:", "empty hierarchy"}},
      {"", {"walk.bvh:1:", "expected 'HIERARCHY'"}},
      {with_line(7, "  OFFSET 3.5 0 0"), {"walk.bvh:7:", "expected '{' after JOINT LeftUpLeg"}},
      {with_line(19, ""), {"walk.bvh:25:", "missing '}' of Hips (opened at line 2)"}},
      {with_line(25, "}\n}"), {"walk.bvh:26:", "unexpected '}' outside every ROOT"}},
      {with_line(25, "}\nROOT Other\n{\n}"), {"walk.bvh:26:", "a second ROOT"}},
      {with_line(16, "        OFFSET 0 -16 0 0"),
       {"walk.bvh:16:", "expected '}' after End Site of LeftLeg's OFFSET, got '0'"}},
      {with_line(26, ""), {"walk.bvh:26:", "unexpected 'Frames:' outside every ROOT"}},
      {with_line(31, "0 0 0 0 0 0 0 0 0 0 0 0 0 0 180\n1"),
       {"walk.bvh:32:", "more lines than the 3 frames declared at line 27"}},
      {with_line(8, "    OFFSET 3.5 0"), {"walk.bvh:9:", "'CHANNELS' is not a number"}},
      {with_line(6, "  JOINT {"), {"walk.bvh:6:", "JOINT without a name"}},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(c.first);
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& fragment : c.second)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
  }
}

TEST(Bvh, ReadsAFileFromDisk) {
  const std::string path = ::testing::TempDir() + "bvh_test_walk.bvh";
  std::ofstream(path) << kWalk;
  const mbk::BvhFile bvh = mbk::read_bvh(path);
  EXPECT_EQ(bvh.segments.size(), 4u);
  EXPECT_EQ(bvh.value(1, 10), 0.25);
  std::remove(path.c_str());
  try {
    mbk::read_bvh(path);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open BVH file");
  }
}

// A chain of 20 joints and as many frames as make 1 MB, every value distinct and read back.
TEST(Bvh, ReadsAOneMegabyteFile) {
  const int joints = 20;
  std::string text = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\n";
  text += "CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n";
  for (int j = 1; j < joints; ++j)
    text += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation " +
            "Yrotation\n";
  text += "End Site\n{\nOFFSET 0 1 0\n}\n" + std::string(joints, '}') + "\n";
  const int columns = 6 + 3 * (joints - 1);
  std::string motion;
  int frames = 0;
  for (; motion.size() < 1000000; ++frames) {
    for (int c = 0; c < columns; ++c)
      motion += std::to_string(frames * columns + c) + ".25" + (c + 1 < columns ? " " : "\n");
  }
  text += "MOTION\nFrames: " + std::to_string(frames) + "\nFrame Time: 0.01\n" + motion;
  ASSERT_GT(text.size(), 1000000u);
  const mbk::BvhFile bvh = mbk::parse_bvh(text, "big.bvh");
  ASSERT_EQ(bvh.segments.size(), static_cast<size_t>(joints));
  EXPECT_EQ(bvh.segments.back().parent, joints - 2);
  EXPECT_TRUE(bvh.segments.back().has_end_site);
  ASSERT_EQ(bvh.channel_count, columns);
  ASSERT_EQ(bvh.frame_count, frames);
  for (int f = 0; f < frames; ++f)
    for (int c = 0; c < columns; ++c) ASSERT_EQ(bvh.value(f, c), f * columns + c + 0.25);
}

// A hierarchy nested deeper than any call stack allows for recursion is read; braces need no
// space around them.
TEST(Bvh, ReadsADeepHierarchy) {
  const int depth = 100000;
  std::string text = "HIERARCHY\nROOT r{CHANNELS 1 Xposition\n";
  for (int j = 0; j < depth; ++j) text += "JOINT j{\n";
  text += std::string(depth + 1, '}') + "\nMOTION\nFrames: 1\nFrame Time: 1\n7\n";
  const mbk::BvhFile bvh = mbk::parse_bvh(text, "deep.bvh");
  EXPECT_EQ(bvh.segments.size(), static_cast<size_t>(depth + 1));
  EXPECT_EQ(bvh.value(0, 0), 7.0);
}

TEST(Bvh, UnwrapsRotationsNotPositions) {
  std::string text =
      "HIERARCHY\nROOT r\n{\nCHANNELS 2 Xposition Zrotation\nJOINT j\n{\nCHANNELS 1 "
      "Yrotation\n}\n}\nMOTION\nFrames: 7\nFrame Time: 0.1\n";
  const std::vector<double> x = {170, -170, 350, -150, -10, 700, -179};
  for (double v : x)
    text += std::to_string(v) + " " + std::to_string(v) + " " + std::to_string(-v) + "\n";
  mbk::BvhFile bvh = mbk::parse_bvh(text, "wrap.bvh");
  mbk::unwrap_rotations(bvh);
  // Each angle moved by a multiple of 360 to within 180 of the previous unwrapped one.
  const std::vector<double> z = {170, 190, 350, 210, 350, 340, 181};
  for (int f = 0; f < 7; ++f) {
    EXPECT_EQ(bvh.value(f, 0), x[f]) << f;
    EXPECT_EQ(bvh.value(f, 1), z[f]) << f;
    EXPECT_EQ(bvh.value(f, 2), -z[f]) << f;
  }
}

}  // namespace
