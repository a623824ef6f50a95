// Recorded samples into a table (offline/recording.h), trajectory CSV input, tidy CSV output, and
// the offline states (offline/offline_kinematics.h): every bad sample is a counted drop or a clear
// error.
#include "mb_kinematics/offline/recording.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/io/tidy_csv.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/trajectory_csv.h"
#include "test/support/temp_file.h"

namespace {

mbk::Model two_joints() {  // coordinates "J1" and "J2"
  return mbk::make_bare_model({0, 1}, mbk::JointType::kRevolute);
}

TEST(RecordingTest, BadSamplesAreCountedDropsAndTheRestIsKept) {
  const mbk::Model model = two_joints();
  ASSERT_EQ(model.coordinate_names, (std::vector<std::string>{"J1", "J2"}));
  mbk::RecordingBuilder b(model);
  const double nan = std::nan("");
  b.add(0.0, {"J1"}, {0.1}, {}, "s0");  // J2 not named yet: dropped at finish
  b.add(0.1, {"J1", "J2", "extra"}, {0.1, 0.2, 9}, {}, "s1");  // unknown name: noted
  b.add(0.2, {"J1", "J2"}, {nan, 0.2}, {}, "s2");              // NaN
  b.add(0.05, {"J1", "J2"}, {0.1, 0.2}, {}, "s3");             // backwards
  b.add(0.1, {"J1", "J2"}, {0.1, 0.2}, {}, "s4");              // repeated stamp
  b.add(0.3, {"J1", "J1"}, {0.1, 0.2}, {}, "s5");              // named twice
  b.add(0.4, {"J1", "J2"}, {0.1}, {}, "s6");                   // unequal lengths
  b.add(0.5, {"J2"}, {0.7}, {}, "s7");                         // J1 keeps its value
  const mbk::Recording r = b.finish();
  EXPECT_EQ(b.samples_read(), 8);
  ASSERT_EQ(r.rows(), 2);
  EXPECT_EQ(r.stamp, (std::vector<double>{0.1, 0.5}));
  EXPECT_EQ(r.position, (std::vector<double>{0.1, 0.2, 0.1, 0.7}));
  EXPECT_EQ(r.given[2], 0);  // J1 not in the last sample
  const mbk::DropLog& log = b.log();
  EXPECT_EQ(log.dropped(), 6);
  EXPECT_EQ(log.drops.at("missing joints (not named yet)"), 1);
  EXPECT_EQ(log.drops.at("stamp goes backwards"), 1);
  EXPECT_EQ(log.drops.at("repeated stamp"), 1);
  EXPECT_EQ(log.drops.at("bad sample (lengths, duplicates, NaN/Inf)"), 3);
  EXPECT_NE(log.example.at("bad sample (lengths, duplicates, NaN/Inf)")
                .find("s2: joint 'J1': position is NaN"),
            std::string::npos);
  EXPECT_EQ(log.notes.at("names not in the model ignored"), 1);
  EXPECT_NE(log.example.at("missing joints (not named yet)").find("J2"), std::string::npos);
}

TEST(RecordingTest, AJointNeverNamedIsAnError) {
  const mbk::Model model = two_joints();
  mbk::RecordingBuilder b(model);
  b.add(0.0, {"J1"}, {0.1}, {}, "s0");
  try {
    b.finish();
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no sample names the joints J2"), std::string::npos);
  }
}

// When every sample was dropped, the error says why (NaN, a name given twice), not
// only that no sample names the joints.
TEST(RecordingTest, EveryDroppedSampleSaysWhy) {
  const mbk::Model model = two_joints();
  for (const auto& bad :
       {std::make_tuple(std::vector<std::string>{"J1", "J2"}, std::nan(""), "position is NaN"),
        std::make_tuple(std::vector<std::string>{"J1", "J2", "J1"}, 0.1, "'J1' is named twice")}) {
    const std::vector<std::string>& names = std::get<0>(bad);
    mbk::RecordingBuilder b(model);
    for (int i = 0; i < 3; ++i)
      b.add(i * 0.1, names, std::vector<double>(names.size(), std::get<1>(bad)), {},
            "s" + std::to_string(i));
    try {
      b.finish();
      FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("3 of 3 samples dropped"), std::string::npos) << what;
      EXPECT_NE(what.find(std::get<2>(bad)), std::string::npos) << what;
    }
  }
}

TEST(RecordingTest, EulerParametersStayContinuousAndAccelerationsPair) {
  const mbk::Model model = mbk::make_bare_model({0}, mbk::JointType::kBallEuler);
  mbk::RecordingBuilder b(model);
  const auto& n = model.coordinate_names;
  b.add(0.0, n, {0.1, 0, 0, 0.99}, {}, "s0");
  b.add(0.1, n, {-0.1, 0, 0, -0.99}, {1, 2, 3, 4}, "s1");  // -e: the same rotation
  b.add_accelerations(0.1, {n[0]}, {5.0}, "a1");
  b.add_accelerations(0.2, {"nope"}, {5.0}, "a2");  // unknown: ignored, noted
  const mbk::Recording r = b.finish();
  ASSERT_EQ(r.rows(), 2);
  EXPECT_EQ(r.position[4], 0.1);
  EXPECT_EQ(r.position[7], 0.99);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(r.velocity[4 + c], -(c + 1.0));  // negated with e
  EXPECT_EQ(r.acceleration[4], 5.0);
  EXPECT_TRUE(r.given[4] & mbk::Recording::kAcceleration);
  EXPECT_FALSE(r.given[5] & mbk::Recording::kAcceleration);
  EXPECT_EQ(b.log().notes.at("joint_accelerations ignored"), 1);
}

// A gross outlier (1e300 in J1, 1e30 in J2) is noted, naming the coordinate and the sample, and
// excluded: not given in its row (its derivatives come from the other samples), its value the
// median of its window; every other cell is as added. The same rows are streamed.
TEST(RecordingTest, AGrossOutlierIsNotedAndExcluded) {
  const mbk::Model model = two_joints();
  std::vector<double> j1(40), j2(40);
  for (int i = 0; i < 40; ++i) j1[i] = std::sin(0.1 * i), j2[i] = 0.5 * std::cos(0.07 * i);
  std::vector<double> spiky1 = j1, spiky2 = j2;
  spiky1[12] = 1e300, spiky2[37] = -1e30;
  mbk::RecordingBuilder table(model), streamed(model);
  mbk::Recording rows;
  rows.nq = 2;
  streamed.stream_to([&](double t, const double* q, const double*, const std::uint8_t* given) {
    rows.stamp.push_back(t);
    rows.position.insert(rows.position.end(), q, q + 2);
    rows.given.insert(rows.given.end(), given, given + 2);
  });
  for (mbk::RecordingBuilder* b : {&table, &streamed})
    for (int i = 0; i < 40; ++i)
      b->add(0.01 * i, {"J1", "J2"}, {spiky1[i], spiky2[i]}, {}, "s" + std::to_string(i));
  const mbk::Recording r = table.finish();
  streamed.finish();
  const mbk::Recording& sent = rows;
  for (const mbk::Recording* out : {&r, &sent}) {
    ASSERT_EQ(out->rows(), 40);
    for (int i = 0; i < 40; ++i) {
      const bool out1 = i == 12, out2 = i == 37;
      EXPECT_EQ(out->given[2 * i], out1 ? 0 : mbk::Recording::kPosition) << i;
      EXPECT_EQ(out->given[2 * i + 1], out2 ? 0 : mbk::Recording::kPosition) << i;
      if (!out1) {
        EXPECT_EQ(out->position[2 * i], j1[i]) << i;
      }
      if (!out2) {
        EXPECT_EQ(out->position[2 * i + 1], j2[i]) << i;
      }
    }
    EXPECT_NEAR(out->position[2 * 12], j1[12], 0.1);  // the median of its window
    EXPECT_NEAR(out->position[2 * 37 + 1], j2[37], 0.1);
  }
  for (mbk::RecordingBuilder* b : {&table, &streamed}) {
    const mbk::DropLog& log = b->log();
    EXPECT_EQ(log.dropped(), 0);
    ASSERT_EQ(log.notes.size(), 1u);
    EXPECT_EQ(log.notes.begin()->second, 2);
    const std::string example = log.example.at(log.notes.begin()->first);
    EXPECT_EQ(example.rfind("s12 (t = 0.120000): coordinate 'J1' is 1e+300", 0), 0u) << example;
  }
}

TEST(TrajectoryCsvTest, ReadsSamplesAndCountsBadLines) {
  const mbk::Model model = two_joints();
  const std::string path = mbk_test::write_temp(
      "time,J2,J1\n0.0,0.2,0.1\n0.01,0.3,\n0.02,nan,0.1\n0.03,0.4,0.5\n0.04,0.1", "traj.csv");
  mbk::RecordingBuilder b(model);
  mbk::read_trajectory_csv(path, b);
  const mbk::Recording r = b.finish();
  ASSERT_EQ(r.rows(), 3);
  EXPECT_EQ(r.position, (std::vector<double>{0.1, 0.2, 0.1, 0.3, 0.5, 0.4}));
  EXPECT_EQ(b.log().drops.at("wrong number of cells"), 1);  // the truncated last line
  EXPECT_EQ(b.log().drops.at("bad sample (lengths, duplicates, NaN/Inf)"), 1);
}

TEST(TrajectoryCsvTest, ClearErrors) {
  const mbk::Model model = two_joints();
  mbk::RecordingBuilder b(model);
  for (const auto& bad :
       {std::make_pair("t,J1\n0,1\n", "traj_bad1.csv:1: the first column must be 'time'"),
        std::make_pair("time,J1\n0,x1\n", "traj_bad2.csv:2: column 'J1': 'x1' is not a number")}) {
    const std::string name = std::string(bad.second).substr(0, 13);
    const std::string path = mbk_test::write_temp(bad.first, name);
    try {
      mbk::read_trajectory_csv(path, b);
      FAIL() << "no error for " << bad.first;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad.second), std::string::npos) << e.what();
    }
  }
}

// CR-only and CRLF line ends and a byte-order mark read as LF; a NUL inside a
// cell and a column given twice are clear errors.
TEST(TrajectoryCsvTest, LineEndsAndByteOrderMark) {
  const mbk::Model model = two_joints();
  for (const std::string end : {"\n", "\r\n", "\r"}) {
    for (const std::string bom : {"", "\xEF\xBB\xBF"}) {
      const std::string path = mbk_test::write_temp(
          bom + "time,J1,J2" + end + "0,0.1,0.2" + end + "0.01,0.3,0.4" + end, "traj_ends.csv");
      mbk::RecordingBuilder b(model);
      mbk::read_trajectory_csv(path, b);
      const mbk::Recording r = b.finish();
      ASSERT_EQ(r.rows(), 2) << bom.size() << " " << end.size();
      EXPECT_EQ(r.position, (std::vector<double>{0.1, 0.2, 0.3, 0.4}));
    }
  }
}

// A header of many columns is checked for a name given twice in time linear in its length: here
// 300,000 columns (2.4 MB; a pairwise check makes 4.5e10 comparisons, minutes beyond the test's
// timeout), the last naming the first again.
TEST(TrajectoryCsvTest, ATwiceNamedColumnAmongManyIsFoundInLinearTime) {
  constexpr int kColumns = 300000;
  std::string header = "time";
  for (int i = 0; i < kColumns; ++i) header += ",c" + std::to_string(i);
  const std::string path = mbk_test::write_temp(
      header + ",c0\n0" + std::string(kColumns + 1, ',') + "\n", "traj_wide.csv");
  mbk::RecordingBuilder b(two_joints());
  try {
    mbk::read_trajectory_csv(path, b);
    FAIL() << "no error for a column given twice";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("column 'c0' is given twice (2 and " +
                                         std::to_string(kColumns + 2) + ")"),
              std::string::npos)
        << std::string(e.what()).substr(0, 200);
  }
}

TEST(TrajectoryCsvTest, NulInACellAndATwiceNamedColumnAreErrors) {
  const mbk::Model model = two_joints();
  for (const auto& bad :
       {std::make_pair(std::string("time,J1,J2\n0,0.5\0abc,0.1\n", 25),
                       "traj_nul.csv:2: column 'J1': '0.5\\x00abc' is not a number"),
        std::make_pair(std::string("time,J1,J1\n0,0.5,0.1\n"),
                       "traj_two.csv:1: column 'J1' is given twice (2 and 3)")}) {
    const std::string path = mbk_test::write_temp(bad.first, std::string(bad.second).substr(0, 12));
    mbk::RecordingBuilder b(model);
    try {
      mbk::read_trajectory_csv(path, b);
      FAIL() << "no error for " << path;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad.second), std::string::npos) << e.what();
    }
  }
}

TEST(TidyCsvTest, OneRowPerSampleAndBodyWithEveryColumn) {
  const mbk::Model model = two_joints();
  mbk::JointState<double> state(model);
  state.position << 0.3, -0.2;
  state.velocity << 1.0, 0.5;
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
  const std::string path = ::testing::TempDir() + "tidy.csv";
  {
    mbk::TidyCsvWriter w(path, model);
    w.write(1.5, data);
    w.close();
  }
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);  // header, 2 bodies, system
  const auto columns = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  for (const std::string& l : lines) EXPECT_EQ(columns(l), 26) << l;
  EXPECT_EQ(lines[0].substr(0, 20), "stamp,body,index,low");
  EXPECT_EQ(lines[1].substr(0, 19), "1.500000000,B1,1,0,");
  EXPECT_EQ(lines[3].substr(0, 21), "1.500000000,system,0,");
  // The last value of body 2's row reads back as its acceleration z, exactly.
  EXPECT_EQ(std::stod(lines[2].substr(lines[2].rfind(',') + 1)),
            data.mass_center_acceleration[2].z());
}

TEST(OfflineStatesTest, EstimatesFromOwnSamplesAndDropsLoneSamples) {
  const mbk::Model model = two_joints();
  mbk::RecordingBuilder b(model);
  // J1 at 100 Hz, J2 at 50 Hz (every other message), then a lone sample after a long gap.
  for (int i = 0; i < 40; ++i) {
    const double t = 0.01 * i;
    if (i % 2 == 0)
      b.add(t, {"J1", "J2"}, {t * t, 2 * t * t * t}, {}, "s");
    else
      b.add(t, {"J1"}, {t * t}, {}, "s");
  }
  b.add(10.0, {"J1", "J2"}, {1, 1}, {}, "lone");
  const mbk::Recording r = b.finish();
  mbk::OfflineStates states(model, r, mbk::make_offline_estimator("centered_9_4"), 0);
  EXPECT_NEAR(states.max_gap(), 0.05, 1e-12);
  mbk::JointState<double> s(model);
  for (int row = 0; row < 40; ++row) {
    ASSERT_EQ(states.state_at(row, s), "") << row;
    const double t = 0.01 * row, t2 = 0.02 * (row / 2);  // J2 holds its last own sample
    EXPECT_NEAR(s.velocity[0], 2 * t, 1e-9);
    EXPECT_NEAR(s.acceleration[0], 2, 1e-6);
    EXPECT_NEAR(s.velocity[1], 6 * t2 * t2, 1e-9) << row;
    EXPECT_NEAR(s.acceleration[1], 12 * t2, 1e-6) << row;
  }
  EXPECT_NE(states.state_at(40, s).find("too few samples"), std::string::npos);
}

// A worker of OfflineBatch starts mid-recording: skipping rows gives the same states, bit for
// bit, as visiting every row (J2's held values come from its last own sample before the start).
TEST(OfflineStatesTest, SkippingRowsGivesTheSameStates) {
  const mbk::Model model = two_joints();
  mbk::RecordingBuilder b(model);
  for (int i = 0; i < 40; ++i) {
    const double t = 0.01 * i;
    if (i % 3 == 0)
      b.add(t, {"J1", "J2"}, {std::sin(t), std::cos(3 * t)}, {}, "s");
    else
      b.add(t, {"J1"}, {std::sin(t)}, {}, "s");
  }
  const mbk::Recording r = b.finish();
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_9_4");
  mbk::OfflineStates every(model, r, e, 0);
  std::vector<mbk::JointState<double>> expected(40, mbk::JointState<double>(model));
  for (int row = 0; row < 40; ++row) ASSERT_EQ(every.state_at(row, expected[row]), "");
  for (int start : {1, 2, 4, 17, 39}) {
    mbk::OfflineStates skipping(model, r, e, 0);
    mbk::JointState<double> s(model);
    for (int row = start; row < 40; row += 1 + row % 4) {  // irregular jumps forward
      ASSERT_EQ(skipping.state_at(row, s), "");
      EXPECT_EQ(s.position, expected[row].position) << start << " " << row;
      EXPECT_EQ(s.velocity, expected[row].velocity) << start << " " << row;
      EXPECT_EQ(s.acceleration, expected[row].acceleration) << start << " " << row;
    }
  }
}

}  // namespace
