// mbk bag end to end (offline/bag_command.h) on bags written here: every sample computed and
// written at its own stamp, poses as the core computes them, derivatives close to the exact
// ones, a CSV input giving the same output, and each kind of bad input a clear error or a
// counted drop.
#include <gtest/gtest.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/String.h>
#include <sys/stat.h>
#include <tf2_msgs/TFMessage.h>
#include <topic_tools/shape_shifter.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "mb_kinematics/analysis/demo_trajectory.h"
#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/tidy_csv.h"
#include "mb_kinematics/offline/bag_command.h"
#include "mb_kinematics/tools/bag_cli.h"
#include "test/support/renamed_bvh.h"

namespace {

const std::string kModel = MBK_SOURCE_DIR "/config/human_body.yaml";

std::string temp(const std::string& name) { return ::testing::TempDir() + name; }

sensor_msgs::JointState sample(const mbk::Model& model, const std::vector<mbk::Wave>& waves,
                               double t) {
  sensor_msgs::JointState js;
  js.header.stamp = ros::Time(t);
  for (int i = 0; i < model.nq; ++i) {
    js.name.push_back(model.coordinate_names[i]);
    js.position.push_back(waves[i].at(t, 0));
  }
  return js;
}

// A bag of the demo trajectory at `rate` Hz over `seconds`; `edit(i, msg)` may spoil samples.
std::string write_bag(const std::string& name, double rate, double seconds,
                      const std::function<void(int, sensor_msgs::JointState&)>& edit = {}) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  rosbag::Bag bag(temp(name), rosbag::bagmode::Write);
  for (int i = 0; i < static_cast<int>(rate * seconds); ++i) {
    sensor_msgs::JointState js = sample(model, waves, 1.0 + i / rate);
    if (edit) edit(i, js);
    bag.write("/joint_states", ros::Time(1.0 + i / rate), js);
  }
  bag.close();
  return temp(name);
}

mbk_offline::BagOptions options(const std::string& in, const std::string& out) {
  mbk_offline::BagOptions o;
  o.input = in;
  o.model = kModel;
  o.out_bag = out;
  return o;
}

std::map<std::string, int> count_topics(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::map<std::string, int> counts;
  for (const rosbag::MessageInstance& m : view) ++counts[m.getTopic()];
  return counts;
}

// system.missing_segments of every /body_kinematics message of the bag at `path`, in order.
std::vector<std::vector<std::string>> missing_segments_in(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/body_kinematics"));
  std::vector<std::vector<std::string>> lists;
  for (const rosbag::MessageInstance& m : view)
    lists.push_back(
        m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>()->system.missing_segments);
  return lists;
}

std::string error_of(const mbk_offline::BagOptions& o) {
  try {
    mbk_offline::run_bag(o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// The demo trajectory's exact kinematics at t.
mbk::Data<double> exact_kinematics(const mbk::Model& model, const std::vector<mbk::Wave>& waves,
                                   double t) {
  mbk::JointState<double> exact(model);
  for (int c = 0; c < model.nq; ++c) {
    exact.position[c] = waves[c].at(t, 0);
    exact.velocity[c] = waves[c].at(t, 1);
    exact.acceleration[c] = waves[c].at(t, 2);
  }
  mbk::Data<double> d(model);
  mbk::forward_kinematics(model, exact, d, mbk::Level::kAcceleration);
  return d;
}

TEST(BagTest, EverySampleAtItsStampWithPosesAndDerivatives) {
  const std::string in = write_bag("demo.bag", 100, 3.0);
  mbk_offline::BagOptions o = options(in, temp("demo_out.bag"));
  o.frame_prefix = "p/";
  const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
  EXPECT_EQ(s.read, 300);
  EXPECT_EQ(s.written, 300);
  EXPECT_EQ(s.log.dropped(), 0);
  const std::map<std::string, int> counts = count_topics(o.out_bag);
  EXPECT_EQ(counts.at("/body_kinematics"), 300);
  EXPECT_EQ(counts.at("/tf"), 300);
  EXPECT_EQ(counts.count("/tf_static"), 0u);  // the human scene has no fixed joints

  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/body_kinematics"));
  int i = 0;
  double worst_alpha = 0, scale_alpha = 0;
  for (const rosbag::MessageInstance& m : view) {
    const auto msg = m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>();
    const double t = 1.0 + i++ / 100.0;
    ASSERT_EQ(msg->header.stamp, ros::Time(t));
    ASSERT_EQ(m.getTime(), ros::Time(t));
    ASSERT_EQ(msg->header.frame_id, "p/" + model.frame);
    const mbk::Data<double> d = exact_kinematics(model, waves, t);
    ASSERT_EQ(msg->bodies.size(), 16u);
    for (int k = 1; k <= 16; ++k) {
      const auto& b = msg->bodies[k - 1];
      EXPECT_EQ(b.name, model.bodies[k].name);
      EXPECT_EQ(b.pose.position.x, d.origin[k].x());  // positions are as recorded: exact
      EXPECT_EQ(b.mass_center.z, d.mass_center[k].z());
      if (t < 1.2 || t > 3.78) continue;  // the ends: one-sided fits
      worst_alpha = std::max(
          worst_alpha,
          (mbk::Vec3<double>(b.accel.angular.x, b.accel.angular.y, b.accel.angular.z) - d.alpha[k])
              .norm());
      scale_alpha = std::max(scale_alpha, d.alpha[k].norm());
    }
  }
  EXPECT_EQ(i, 300);
  // The default estimator (auto) at 100 Hz on clean data, away from the ends: the joint
  // accelerations are within 4.2e-7 of their scale (doc/error_vs_runtime.md); alpha sums a few.
  EXPECT_LT(worst_alpha / scale_alpha, 2e-3);
  rosbag::View tf(bag, rosbag::TopicQuery("/tf"));
  const auto first = tf.begin()->instantiate<tf2_msgs::TFMessage>();
  EXPECT_EQ(first->transforms.size(), 16u);
  EXPECT_EQ(first->transforms[0].header.frame_id, "p/world");  // the scene's frame
  EXPECT_EQ(first->transforms[0].child_frame_id, "p/pelvis");
  EXPECT_EQ(first->transforms[0].header.stamp, ros::Time(1.0));
}

// A 1 kHz grid written as rospy.Time.from_sec writes it (nanoseconds truncated, up to 1 ns
// early): the summary says the derivatives are taken on the grid, and every output keeps its
// sample's stamp as recorded.
TEST(BagTest, StampsOnAGridAreDifferentiatedThereAndKept) {
  std::vector<ros::Time> stamps;
  for (int i = 0; i < 1000; ++i) {
    const double t = 2.0 + i * 1e-3, secs = std::trunc(t);
    stamps.emplace_back(static_cast<uint32_t>(secs), static_cast<uint32_t>((t - secs) * 1e9));
  }
  const std::string in = write_bag("grid.bag", 1000, 1.0, [&](int i, sensor_msgs::JointState& js) {
    js.header.stamp = stamps[i];
  });
  mbk_offline::BagOptions o = options(in, temp("grid_out.bag"));
  o.out_csv = temp("grid_out.csv");
  const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
  EXPECT_EQ(s.written, 1000);
  EXPECT_TRUE(s.grid.moves);
  EXPECT_NE(mbk_offline::format_summary(s).find("  stamps on a uniform grid of 0.001 s: "),
            std::string::npos)
      << mbk_offline::format_summary(s);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  int i = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/body_kinematics")))
    ASSERT_EQ(m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>()->header.stamp, stamps[i++])
        << i;
  EXPECT_EQ(i, 1000);
}

TEST(BagTest, CsvInputGivesTheSameKinematics) {
  const std::string in = write_bag("csv_src.bag", 50, 1.0);
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  std::ofstream csv(temp("traj_in.csv"));
  csv.precision(17);
  csv << "time";
  for (const std::string& n : model.coordinate_names) csv << "," << n;
  for (int i = 0; i < 50; ++i) {
    const double t = 1.0 + i / 50.0;
    csv << "\n" << ros::Time(t).toSec();  // the bag's stamp
    for (int c = 0; c < model.nq; ++c) csv << "," << waves[c].at(t, 0);
  }
  csv.close();
  mbk_offline::BagOptions a = options(in, "");
  a.out_csv = temp("from_bag.csv");
  mbk_offline::BagOptions b = options(temp("traj_in.csv"), "");
  b.out_csv = temp("from_csv.csv");
  a.estimator = b.estimator = "auto";
  const mbk_offline::BagSummary summary = mbk_offline::run_bag(a);
  EXPECT_EQ(summary.written, 50);
  EXPECT_EQ(mbk_offline::run_bag(b).written, 50);
  // The auto estimator's error bars: in the summary and in OUT.errors.csv, a row each.
  ASSERT_FALSE(summary.errors.empty());
  // The short summary: the noise level and the worst error bar in one line; --verbose: a line
  // per coordinate under its heading, and the times.
  const std::string brief = mbk_offline::format_summary(summary);
  const std::string verbose = mbk_offline::format_summary(summary, true);
  EXPECT_NE(brief.find("  noise level "), std::string::npos) << brief;
  EXPECT_NE(brief.find("; worst error bar: "), std::string::npos) << brief;
  EXPECT_EQ(brief.find("error bars (noise level"), std::string::npos) << brief;
  EXPECT_EQ(brief.find("wall "), std::string::npos) << brief;
  EXPECT_EQ(std::count(brief.begin(), brief.end(), '\n'), 2) << brief;
  EXPECT_NE(verbose.find("error bars (noise level"), std::string::npos) << verbose;
  EXPECT_NE(verbose.find("wall "), std::string::npos) << verbose;
  for (const mbk::CoordinateError& e : summary.errors)
    EXPECT_NE(verbose.find("    " + e.name + ": noise "), std::string::npos) << e.name;
  std::ifstream fe(temp("from_bag.errors.csv"));
  std::stringstream se;
  se << fe.rdbuf();
  const std::string errors = se.str();
  EXPECT_EQ(errors.rfind("coordinate,noise,velocity_se,acceleration_se\n", 0), 0u);
  EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1 + summary.errors.size());
  std::ifstream fa(a.out_csv), fb(b.out_csv);
  std::stringstream sa, sb;
  sa << fa.rdbuf();
  sb << fb.rdbuf();
  const std::string from_bag = sa.str(), from_csv = sb.str();
  EXPECT_EQ(std::count(from_bag.begin(), from_bag.end(), '\n'), 1 + 50 * 17);  // 16 bodies, system
  EXPECT_EQ(from_bag, from_csv);
}

// A trajectory CSV starting at time 0 (as mocap exports do): a bag cannot hold a zero stamp
// (ros::TIME_MIN is 1 ns), so --out stops with one line naming the input, the time and
// --start-time, leaving no bag; with --start-time 1 the bag's and the CSV's stamps start at 1 s.
TEST(BagTest, ATrajectoryFromTimeZeroNeedsAStartTimeForABag) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  std::ofstream csv(temp("from_zero.csv"));
  csv << "time";
  for (const std::string& n : model.coordinate_names) csv << "," << n;
  for (int i = 0; i < 20; ++i) {
    csv << "\n" << i / 50.0;
    for (int c = 0; c < model.nq; ++c) csv << "," << waves[c].at(i / 50.0, 0);
  }
  csv.close();
  mbk_offline::BagOptions o = options(temp("from_zero.csv"), temp("from_zero.bag"));
  o.out_csv = temp("from_zero_out.csv");
  std::remove(o.out_bag.c_str()), std::remove(o.out_csv.c_str());
  EXPECT_EQ(error_of(o), temp("from_zero.csv") +
                             ": time 0 s cannot be a bag's stamp (--out holds 1 ns, "
                             "ros::TIME_MIN, to ros::TIME_MAX): give --start-time S to add S "
                             "seconds to every time (e.g. --start-time 1); nothing written");
  EXPECT_FALSE(std::ifstream(o.out_bag).good());
  EXPECT_FALSE(std::ifstream(o.out_csv).good());
  o.start_time = 1;
  EXPECT_EQ(mbk_offline::run_bag(o).written, 20);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/body_kinematics"));
  ASSERT_EQ(view.size(), 20u);
  EXPECT_EQ(view.begin()->getTime(), ros::Time(1.0));
  EXPECT_EQ(view.begin()->instantiate<mb_kinematics_msgs::BodyKinematicsArray>()->header.stamp,
            ros::Time(1.0));
  std::ifstream out(o.out_csv);
  std::string line;
  std::getline(out, line);
  std::getline(out, line);
  EXPECT_EQ(line.rfind("1.000000000,", 0), 0u) << line;
  // The option: seconds, for a .csv or .bvh input only.
  std::vector<std::string> args = {"mbk",     "bag",          write_bag("keep.bag", 10, 0.5),
                                   "--model", kModel,         "--csv",
                                   "x.csv",   "--start-time", "1"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  EXPECT_THROW(mbk_offline::parse_bag_options(static_cast<int>(argv.size()), argv.data()),
               std::invalid_argument);
  args[2] = o.input, args.back() = "soon";
  argv.clear();
  for (std::string& a : args) argv.push_back(a.data());
  EXPECT_THROW(mbk_offline::parse_bag_options(static_cast<int>(argv.size()), argv.data()),
               std::invalid_argument);
  args.back() = "2.5";
  argv.clear();
  for (std::string& a : args) argv.push_back(a.data());
  EXPECT_EQ(mbk_offline::parse_bag_options(static_cast<int>(argv.size()), argv.data()).start_time,
            2.5);
}

// With auto (the default) the tidy CSV carries each body's propagated error bars: six columns
// more, finite and non-negative on every body row, positive on noisy data, empty on the system
// row; OUT.sample_errors.csv each sample's coordinates'; a fixed estimator's CSV has none.
TEST(BagTest, CsvCarriesTheBodiesErrorBars) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1e-3);
  const std::string in = write_bag("noisy.bag", 100, 2.0, [&](int, sensor_msgs::JointState& js) {
    for (double& q : js.position) q += noise(rng);
  });
  mbk_offline::BagOptions o = options(in, "");
  o.out_csv = temp("errors_out.csv");
  mbk_offline::run_bag(o);
  std::ifstream f(o.out_csv);
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line, std::string(mbk::TidyCsvWriter::header()) + mbk::TidyCsvWriter::errors_header());
  int rows = 0;
  double largest = 0;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::stringstream cs(line);
    for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
    if (line.back() == ',') cells.push_back("");
    ASSERT_EQ(cells.size(), 32u) << line;
    for (int i = 26; i < 32; ++i) {
      if (cells[1] == "system") {
        EXPECT_EQ(cells[i], "") << line;
        continue;
      }
      const double se = std::stod(cells[i]);
      EXPECT_TRUE(std::isfinite(se) && se >= 0) << line;
      largest = std::max(largest, se);
    }
    ++rows;
  }
  EXPECT_EQ(rows, 200 * 17);
  EXPECT_GT(largest, 0);
  // Each sample's coordinates' error bars beside it: OUT.sample_errors.csv, a row per sample.
  const mbk::Model model = mbk::load_model_file(kModel);
  std::ifstream se(temp("errors_out.sample_errors.csv"));
  std::getline(se, line);
  EXPECT_EQ(line.rfind("stamp," + model.coordinate_names[0] + "_velocity_se,", 0), 0u) << line;
  int samples = 0;
  while (std::getline(se, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 2 * model.nq) << line;
    const size_t a = line.find(',') + 1, b = line.find(',', a);
    EXPECT_GT(std::stod(line.substr(a, b - a)), 0) << line;  // noise 1e-3: a velocity se
    ++samples;
  }
  EXPECT_EQ(samples, 200);
  o.estimator = "centered_0.4s_4";
  mbk_offline::run_bag(o);
  std::ifstream g(o.out_csv);
  std::getline(g, line);
  EXPECT_EQ(line, mbk::TidyCsvWriter::header());
}

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

// The rows are computed by several threads, block by block, while the caller writes: the output
// must be the same, byte for byte, whatever the number of threads. 1201 samples: three blocks
// of 512 rows; every third message names half the joints (their own sample series); the last,
// after a long gap, is too lonely for derivatives (dropped and counted).
// A CSV that is not a regular file (here a pipe, like /dev/null or /dev/stdout) gets no error-bar
// side files beside it: they would land in /dev for --csv /dev/null.
TEST(BagTest, NoSideFilesBesideACsvThatIsNotARegularFile) {
  const std::string in = write_bag("pipe_in.bag", 50, 1.0);
  mbk_offline::BagOptions o = options(in, "");
  o.out_csv = temp("pipe_out.csv");
  for (const char* name : {"pipe_out.csv", "pipe_out.errors.csv", "pipe_out.sample_errors.csv"})
    std::remove(temp(name).c_str());
  ASSERT_EQ(mkfifo(o.out_csv.c_str(), 0600), 0);
  long drained = 0;
  std::thread reader([&] {
    std::ifstream f(o.out_csv);
    for (std::string line; std::getline(f, line);) ++drained;
  });
  mbk_offline::run_bag(o);
  reader.join();
  EXPECT_GT(drained, 50);
  EXPECT_FALSE(std::ifstream(temp("pipe_out.errors.csv")).good());
  EXPECT_FALSE(std::ifstream(temp("pipe_out.sample_errors.csv")).good());
  std::remove(o.out_csv.c_str());
}

TEST(BagTest, AnyNumberOfThreadsWritesTheSameOutput) {
  const std::string in =
      write_bag("threads.bag", 100, 12.01, [](int i, sensor_msgs::JointState& js) {
        if (i % 3 == 1) js.name.resize(js.name.size() / 2), js.position.resize(js.name.size());
        if (i == 1200) js.header.stamp = ros::Time(100.0);
      });
  std::string first;
  for (int threads : {1, 2, 5}) {
    mbk_offline::BagOptions o = options(in, "");
    o.out_csv = temp("threads_" + std::to_string(threads) + ".csv");
    o.threads = threads;
    const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
    EXPECT_EQ(s.threads, threads);
    EXPECT_EQ(s.read, 1201);
    EXPECT_EQ(s.written, 1200) << threads;
    EXPECT_EQ(s.log.drops.at("too few samples for derivatives"), 1) << threads;
    const std::string csv = read_file(o.out_csv);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 1200 * 17) << threads;
    if (first.empty()) first = csv;
    EXPECT_TRUE(csv == first) << threads << " threads: the CSV differs from one thread's";
  }
}

TEST(BagTest, MissingTopicNamesTheTopicsTheBagHas) {
  const std::string in = write_bag("topics.bag", 10, 1.0);
  mbk_offline::BagOptions o = options(in, temp("x.bag"));
  o.joint_states = "/robot/joint_states";
  const std::string e = error_of(o);
  EXPECT_NE(e.find("no topic '/robot/joint_states'; the bag has /joint_states "
                   "(sensor_msgs/JointState)"),
            std::string::npos)
      << e;
  o.joint_states = "/joint_states";
  o.joint_accelerations = "/joint_accelerations";
  EXPECT_NE(error_of(o).find("no topic '/joint_accelerations'"), std::string::npos);
}

TEST(BagTest, CorruptAndTruncatedBagsAreClearErrors) {
  const std::string in = write_bag("whole.bag", 100, 2.0);
  std::ifstream whole(in, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(whole)),
                          std::istreambuf_iterator<char>());
  std::ofstream(temp("truncated.bag"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::string garbage(4096, 'x');
  std::ofstream(temp("corrupt.bag"), std::ios::binary) << garbage;
  const std::string t = error_of(options(temp("truncated.bag"), temp("y.bag")));
  EXPECT_NE(t.find("truncated.bag: "), std::string::npos) << t;
  EXPECT_NE(t.find("rosbag reindex"), std::string::npos) << t;
  const std::string c = error_of(options(temp("corrupt.bag"), temp("y.bag")));
  EXPECT_NE(c.find("corrupt.bag: not a readable bag"), std::string::npos) << c;
  EXPECT_NE(error_of(options(temp("absent.bag"), temp("y.bag"))).find("absent.bag"),
            std::string::npos);
}

TEST(BagTest, UnknownMissingNanAndBackwardsAreCountedAndTheRestWritten) {
  const std::string in = write_bag("bad.bag", 100, 2.0, [](int i, sensor_msgs::JointState& js) {
    if (i < 3) {  // the first three lack the head: dropped until it is named
      js.name.erase(js.name.begin() + 5);
      js.position.erase(js.position.begin() + 5);
    }
    if (i % 10 == 0) js.name.push_back("tail"), js.position.push_back(1.0);  // unknown: noted
    if (i == 50 || i == 51) js.position[7] = std::nan("");
    if (i == 120) js.header.stamp = ros::Time(1.0);  // backwards
  });
  const mbk_offline::BagSummary s = mbk_offline::run_bag(options(in, temp("bad_out.bag")));
  EXPECT_EQ(s.read, 200);
  EXPECT_EQ(s.log.drops.at("missing joints (not named yet)"), 3);
  EXPECT_EQ(s.log.drops.at("bad sample (lengths, duplicates, NaN/Inf)"), 2);
  EXPECT_EQ(s.log.drops.at("stamp goes backwards"), 1);
  // every 10th names "tail", but samples 50 and 120 were dropped before being looked at
  EXPECT_EQ(s.log.notes.at("names not in the model ignored"), 18);
  EXPECT_EQ(s.written, 194);
  EXPECT_EQ(s.written + s.log.dropped(), s.read);
  EXPECT_EQ(count_topics(temp("bad_out.bag")).at("/body_kinematics"), 194);
  const std::string summary = mbk_offline::format_summary(s);
  EXPECT_NE(summary.find("200 samples read, 194 written, 6 dropped"), std::string::npos) << summary;
  EXPECT_NE(summary.find("position is NaN"), std::string::npos) << summary;
}

TEST(BagTest, AJointNeverNamedIsAnError) {
  const std::string in = write_bag("nohead.bag", 10, 1.0, [](int, sensor_msgs::JointState& js) {
    js.name.erase(js.name.begin() + 5);
    js.position.erase(js.position.begin() + 5);
  });
  EXPECT_NE(error_of(options(in, temp("z.bag"))).find("no sample names the joints"),
            std::string::npos);
}

// The model's root on a base that runs round a circle of radius 1 turning with it (yaw = w t;
// its velocity is w along its own y), the joints still: every body is carried rigidly.
TEST(BagTest, BaseOdometryCarriesTheModel) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const double w = 1.3;
  const auto base_at = [&](double t) {
    mbk::BaseMotion m;
    m.rotation = Eigen::AngleAxisd(w * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    m.position << std::cos(w * t), std::sin(w * t), 0.5;
    m.velocity << -w * std::sin(w * t), w * std::cos(w * t), 0;
    m.acceleration = -w * w * mbk::Vec3<double>(std::cos(w * t), std::sin(w * t), 0);
    m.omega << 0, 0, w;
    return m;
  };
  {
    rosbag::Bag bag(temp("odom.bag"), rosbag::bagmode::Write);
    for (int i = 0; i < 300; ++i) {  // odometry over [1, 3.99] s
      const double t = 1.0 + i / 100.0;
      const mbk::BaseMotion m = base_at(t);
      nav_msgs::Odometry o;
      o.header.stamp = ros::Time(t);
      o.header.frame_id = "odom";
      o.child_frame_id = "world";
      o.pose.pose.position.x = m.position.x();
      o.pose.pose.position.y = m.position.y();
      o.pose.pose.position.z = m.position.z();
      const Eigen::Quaterniond q(m.rotation);
      o.pose.pose.orientation.x = q.x(), o.pose.pose.orientation.y = q.y();
      o.pose.pose.orientation.z = q.z(), o.pose.pose.orientation.w = q.w();
      o.twist.twist.linear.y = w;  // in the child frame
      o.twist.twist.angular.z = w;
      bag.write("/odom", o.header.stamp, o);
    }
    for (int i = 0; i < 305; ++i) {  // joints at 100 Hz, 5 ms after the odometry, 5 beyond it
      sensor_msgs::JointState js;
      js.header.stamp = ros::Time(1.005 + i / 100.0);
      js.name = model.coordinate_names;
      js.position.assign(model.nq, 0.1);
      bag.write("/joint_states", js.header.stamp, js);
    }
  }
  mbk_offline::BagOptions o = options(temp("odom.bag"), temp("odom_out.bag"));
  o.base_odometry = "/odom";
  o.out_csv = temp("odom_out.csv");
  const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
  EXPECT_EQ(s.written, 299);
  std::ifstream csv(o.out_csv);
  std::string line;
  std::getline(csv, line);
  std::getline(csv, line);  // the first sample's first row: the base, body 1 on R
  EXPECT_NE(line.find("," + model.frame + ",1,0,"), std::string::npos) << line;
  EXPECT_EQ(s.log.drops.at("outside the base odometry's time span"), 6);
  mbk::JointState<double> still(model);
  still.position.setConstant(0.1);
  mbk::Data<double> relative(model);
  mbk::forward_kinematics(model, still, relative, mbk::Level::kAcceleration);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/body_kinematics"));
  double worst_p = 0, worst_v = 0, worst_a = 0;
  for (const rosbag::MessageInstance& m : view) {
    const auto msg = m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>();
    ASSERT_EQ(msg->header.frame_id, "odom");
    const double t = msg->header.stamp.toSec();
    mbk::Data<double> expected = relative;
    mbk::apply_floating_base(base_at(t), expected);
    // The node's layout: body 1 is the base (the root link on its free joint), then the model.
    ASSERT_EQ(msg->bodies.size(), model.bodies.size()) << "at " << t;
    const auto& base = msg->bodies[0];
    EXPECT_EQ(base.name, model.frame);
    EXPECT_EQ(base.index, 1u);
    EXPECT_LT((mbk::Vec3<double>(base.pose.position.x, base.pose.position.y, base.pose.position.z) -
               base_at(t).position)
                  .norm(),
              1e-4);
    for (int k = 1; k <= model.body_count(); ++k) {
      const auto& b = msg->bodies[k];
      EXPECT_EQ(b.name, model.bodies[k].name);
      const auto v3 = [](const auto& x) { return mbk::Vec3<double>(x.x, x.y, x.z); };
      worst_p = std::max(worst_p, (v3(b.mass_center) - expected.mass_center[k]).norm());
      worst_v = std::max(worst_v, (v3(b.twist.linear) - expected.mass_center_velocity[k]).norm());
      if (t > 1.4 && t < 3.6)  // the base's acceleration is estimated: away from the ends
        worst_a =
            std::max(worst_a, (v3(b.accel.linear) - expected.mass_center_acceleration[k]).norm());
    }
  }
  // Linear interpolation half way between odometry samples: chord errors of (w h)^2 / 8 times
  // the radius (about 2e-5 m), the speed scale w (1e-4 m/s with the arms' reach).
  EXPECT_LT(worst_p, 1e-4);
  EXPECT_LT(worst_v, 1e-4);
  EXPECT_LT(worst_a, 1e-3);  // of accelerations of about w^2 = 1.7 m/s^2
  rosbag::View tf(bag, rosbag::TopicQuery("/tf"));
  const auto first = tf.begin()->instantiate<tf2_msgs::TFMessage>();
  EXPECT_EQ(first->transforms.back().header.frame_id, "odom");
  EXPECT_EQ(first->transforms.back().child_frame_id, "world");
  o.base_odometry = "/nothing";
  EXPECT_NE(error_of(o).find("no topic '/nothing'"), std::string::npos);
}

// Fixed joints go to /tf_static once, at the first sample's stamp, with the prefix.
TEST(BagTest, FixedJointsOnTfStaticOnce) {
  const std::string urdf = MBK_SOURCE_DIR "/test/ros/test_robot.urdf";
  const mbk::Model model = mbk::load_model_file(urdf);
  {
    rosbag::Bag bag(temp("fixed.bag"), rosbag::bagmode::Write);
    for (int i = 0; i < 20; ++i) {
      sensor_msgs::JointState js;
      js.header.stamp = ros::Time(2.0 + i / 100.0);
      js.name = model.coordinate_names;
      js.position.assign(model.nq, 0.01 * i);
      bag.write("/joint_states", js.header.stamp, js);
    }
  }
  mbk_offline::BagOptions o = options(temp("fixed.bag"), temp("fixed_out.bag"));
  o.model = urdf;
  o.frame_prefix = "r1/";
  EXPECT_EQ(mbk_offline::run_bag(o).written, 20);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/tf_static"));
  ASSERT_EQ(view.size(), 1u);
  const auto fixed = view.begin()->instantiate<tf2_msgs::TFMessage>();
  EXPECT_EQ(view.begin()->getTime(), ros::Time(2.0));
  ASSERT_EQ(fixed->transforms.size(), 2u);  // camera_joint, tool_joint
  for (const auto& t : fixed->transforms) {
    EXPECT_EQ(t.child_frame_id.rfind("r1/", 0), 0u) << t.child_frame_id;
    EXPECT_EQ(t.header.frame_id.rfind("r1/", 0), 0u) << t.header.frame_id;
  }
  EXPECT_EQ(count_topics(o.out_bag).at("/tf"), 20);
}

// body_kinematics' system field as the node fills it (doc/method.md 9), every sample: the whole
// model's mass, its mass center from the recorded positions (as the core's), and its velocity
// from the estimated one close to the exact.
TEST(BagTest, SystemFieldFilledAsTheNodeFillsIt) {
  const std::string in = write_bag("system.bag", 100, 1.0);
  const mbk_offline::BagOptions o = options(in, temp("system_out.bag"));
  EXPECT_EQ(mbk_offline::run_bag(o).written, 100);
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/body_kinematics"));
  int i = 0;
  for (const rosbag::MessageInstance& m : view) {
    const auto msg = m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>();
    const double t = 1.0 + i++ / 100.0;
    const mbk::Data<double> d = exact_kinematics(model, waves, t);
    mbk::SystemKinematics<double> s;
    mbk::system_kinematics(model, d, s);
    const auto v3 = [](const auto& x) { return mbk::Vec3<double>(x.x, x.y, x.z); };
    ASSERT_TRUE(msg->system.filled) << "at " << t;
    EXPECT_EQ(msg->system.mass, s.mass);
    EXPECT_LT((v3(msg->system.mass_center) - s.mass_center).norm(), 1e-12);
    if (t > 1.2 && t < 1.78) {  // the ends: one-sided fits
      EXPECT_LT((v3(msg->system.velocity) - s.velocity).norm(), 2e-3 * s.velocity.norm() + 1e-6);
    }
  }
  EXPECT_EQ(i, 100);
}

TEST(BagTest, TheMbkCommandRunsIt) {
  const std::string in = write_bag("cli.bag", 10, 1.0);
  const std::string mbk = MBK_MBK_PATH;
  const std::string ok = mbk + " bag " + in + " --model " + kModel + " --csv " + temp("cli.csv") +
                         " 2>" + temp("cli.err");
  EXPECT_EQ(std::system(ok.c_str()), 0);
  std::ifstream err(temp("cli.err"));
  std::string line;
  std::getline(err, line);
  EXPECT_EQ(line.rfind("mbk bag: 10 samples read, 10 written, 0 dropped", 0), 0u) << line;
  const std::string bad = mbk + " bag " + in + " --model " + kModel + " --joint-states /js --out " +
                          temp("cli.bag.out") + " 2>" + temp("cli2.err");
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 1);
  std::ifstream err2(temp("cli2.err"));
  std::getline(err2, line);
  EXPECT_EQ(line.rfind("mbk: error: ", 0), 0u) << line;
  EXPECT_NE(line.find("the bag has /joint_states"), std::string::npos) << line;
}

// Each option that takes a value is given once at most (a second would silently win), and
// --summary-json's file is among the files the run refuses to overwrite with another.
TEST(BagTest, EveryValueOptionOnce) {
  const auto parse = [](std::vector<const char*> args) {
    args.insert(args.begin(), {"mbk", "bag", "in.bag", "--model", "m.yaml"});
    return mbk_offline::parse_bag_options(static_cast<int>(args.size()),
                                          const_cast<char**>(args.data()));
  };
  for (const char* option : {"--out", "--max-gap", "--threads", "--start-time", "--max-memory"}) {
    try {
      parse({"--csv", "o.csv", option, "1", option, "2"});
      ADD_FAILURE() << option << " twice accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(e.what(), std::string(option) + " is given twice");
    }
  }
  const mbk_offline::BagCommandLine line = parse({"--csv", "o.csv", "--summary-json", "s.json"});
  ASSERT_EQ(line.other_outputs.size(), 1u);
  EXPECT_EQ(line.other_outputs[0].name, "--summary-json");
  EXPECT_EQ(line.other_outputs[0].path, "s.json");
}

// An option that adds columns to an output is refused without one it adds to: mbk bag's message
// names the outputs with their values, mbk batch's (check_column_options without them) does not.
TEST(BagTest, ColumnOptionsNeedTheirOutput) {
  const auto error = [](std::vector<const char*> args) -> std::string {
    args.insert(args.begin(), {"mbk", "bag", "in.bag", "--model", "m.yaml"});
    try {
      mbk_offline::parse_bag_options(static_cast<int>(args.size()),
                                     const_cast<char**>(args.data()));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error({"--h5", "o.h5", "--body-axes"}),
            "--body-axes adds columns to the CSV: give --csv OUT.csv");
  EXPECT_EQ(error({"--csv", "o.csv", "--mot-coordinates"}),
            "--mot-coordinates adds columns to the OpenSim file: give --mot OUT.mot");
  EXPECT_EQ(error({"--out", "o.bag", "--angles", "XYZ"}),
            "--angles sets the joint angles of the CSV and the OpenSim file: give --csv OUT.csv "
            "or --mot OUT.mot");
  EXPECT_EQ(error({"--mot", "o.mot", "--angles", "XYZ", "--mot-coordinates"}), "");
  EXPECT_EQ(error({"--csv", "o.csv", "--angles", "XYZ", "--body-axes"}), "");
  try {
    mbk_offline::check_column_options({"--angles", "--scale"}, {"--h5"}, false);
    ADD_FAILURE() << "--angles without --csv or --mot accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "--angles sets the joint angles of the CSV and the OpenSim file: give --csv or --mot");
  }
  EXPECT_NO_THROW(mbk_offline::check_column_options({"--body-axes"}, {"--h5", "--csv"}, false));
}

TEST(BagTest, ThreadsOptionIsACountFromOne) {
  const auto parse = [](std::vector<const char*> args) {
    args.insert(args.begin(), {"mbk", "bag", "in.bag", "--model", "m.yaml", "--out", "o.bag"});
    return mbk_offline::parse_bag_options(static_cast<int>(args.size()),
                                          const_cast<char**>(args.data()));
  };
  EXPECT_EQ(parse({}).threads, 0);  // one per CPU
  EXPECT_EQ(parse({"--threads", "3"}).threads, 3);
  for (const char* bad : {"0", "-2", "two", "3.5", "5000"}) {
    try {
      parse({"--threads", bad});
      ADD_FAILURE() << "--threads " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--threads needs a count from 1 to 1024"),
                std::string::npos)
          << e.what();
    }
  }
}

// A bag of the demo trajectory (100 samples at 100 Hz on `topic`) with, where `extra(i, t, bag)`
// writes something, other messages among them.
std::string write_mixed(const std::string& name, const std::string& topic,
                        const std::function<void(int, double, rosbag::Bag&)>& extra) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  rosbag::Bag bag(temp(name), rosbag::bagmode::Write);
  for (int i = 0; i < 100; ++i) {
    const double t = 1.0 + i / 100.0;
    extra(i, t, bag);
    bag.write(topic, ros::Time(t), sample(model, waves, t));
  }
  bag.close();
  return temp(name);
}

// A std_msgs/String on /joint_states from a publisher of its own: a connection of its own.
void write_string(rosbag::Bag& bag, double t) {
  std_msgs::String text;
  text.data = "not a joint state";
  auto header = boost::make_shared<ros::M_string>();
  (*header)["topic"] = "/joint_states";
  (*header)["type"] = ros::message_traits::datatype(text);
  (*header)["md5sum"] = ros::message_traits::md5sum(text);
  (*header)["message_definition"] = ros::message_traits::definition(text);
  (*header)["callerid"] = "/talker";
  bag.write("/joint_states", ros::Time(t), text, header);
}

// An output that is an input (also through a symlink), the model, or the other
// output is refused before anything is written; the inputs are left as they were.
TEST(BagTest, AnOutputThatIsAnInputIsRefusedBeforeWriting) {
  const std::string in = write_bag("same.bag", 10, 1.0);
  const std::string model = temp("same_model.yaml");
  std::ofstream(model) << read_file(kModel);
  const std::string bag_bytes = read_file(in), model_text = read_file(model);
  const std::string link = temp("same_link.bag");
  std::remove(link.c_str());
  ASSERT_EQ(symlink(in.c_str(), link.c_str()), 0);
  std::remove(temp("same_both.out").c_str());
  const auto refused = [&](mbk_offline::BagOptions o, const std::string& what) {
    o.model = model;
    const std::string e = error_of(o);
    EXPECT_NE(e.find(what), std::string::npos) << e;
    EXPECT_NE(e.find("nothing written"), std::string::npos) << e;
  };
  refused(options(in, in), "--out " + in + " is the same file as the input");
  refused(options(in, link), "is the same file as the input");
  mbk_offline::BagOptions csv_is_model = options(in, "");
  csv_is_model.out_csv = model;
  refused(csv_is_model, "is the same file as --model");
  mbk_offline::BagOptions both = options(in, temp("same_both.out"));
  both.out_csv = temp("./same_both.out");
  refused(both, "are the same file");
  EXPECT_EQ(read_file(in), bag_bytes);
  EXPECT_EQ(read_file(model), model_text);
  std::ifstream absent(temp("same_both.out"));
  EXPECT_FALSE(absent.good());
}

// With "auto", --csv OUT.csv also writes OUT.errors.csv and OUT.sample_errors.csv;
// an input or another output that is one of them is refused before anything is written.
TEST(BagTest, AnInputOrOutputThatIsACsvSideFileIsRefused) {
  const std::string in = temp("side.errors.csv");  // a trajectory CSV with a side file's name
  std::ofstream(in) << "time,j1\n0,0.5\n";
  const std::string in_text = read_file(in);
  mbk_offline::BagOptions input_is_side = options(in, "");
  input_is_side.out_csv = temp("side.csv");
  std::string e = error_of(input_is_side);
  EXPECT_NE(e.find("side file " + in + " is the same file as the input"), std::string::npos) << e;
  EXPECT_NE(e.find("nothing written"), std::string::npos) << e;
  EXPECT_EQ(read_file(in), in_text);
  const std::string bag = temp("side_out.sample_errors.csv");
  std::remove(bag.c_str());
  std::remove(temp("side_out.csv").c_str());
  mbk_offline::BagOptions out_is_side = options(write_bag("side.bag", 10, 1.0), bag);
  out_is_side.out_csv = temp("side_out.csv");
  e = error_of(out_is_side);
  EXPECT_NE(e.find("--out " + bag + " and --csv's side file " + bag + " are the same file"),
            std::string::npos)
      << e;
  EXPECT_FALSE(std::ifstream(bag).good());
  EXPECT_FALSE(std::ifstream(temp("side_out.csv")).good());
}

// `mbk bag IN --model kModel ARGS`: its exit status, stderr into `err`.
int run_mbk_bag(const std::string& in, const std::string& args, std::string& err) {
  const std::string command = std::string(MBK_MBK_PATH) + " bag " + in + " --model " + kModel +
                              " " + args + " 2>" + temp("run.err");
  const int status = std::system(command.c_str());
  err = read_file(temp("run.err"));
  return WEXITSTATUS(status);
}

// `mbk bag --help` prints the usage on stdout and exits 0, whatever else is given; every row of
// its table of options is in it.
TEST(BagTest, HelpPrintsTheUsage) {
  const std::string command =
      std::string(MBK_MBK_PATH) + " bag --help > " + temp("help.out") + " 2>" + temp("help.err");
  EXPECT_EQ(WEXITSTATUS(std::system(command.c_str())), 0);
  EXPECT_EQ(read_file(temp("help.out")).rfind("usage: mbk bag IN.bag|IN.csv --model FILE", 0), 0u)
      << read_file(temp("help.out"));
  EXPECT_EQ(read_file(temp("help.err")), "");
  for (const mbk_offline::BagOptionRow& row : mbk_offline::bag_option_rows()) {
    const std::string item = "[" + row.name + (row.value.empty() ? "" : " " + row.value) + "]";
    EXPECT_NE(read_file(temp("help.out")).find(item), std::string::npos) << item;
  }
}

// A full disk (/dev/full) is one `mbk: error:` line naming the file, exit 1.
TEST(BagTest, AFullDiskIsOneErrorLine) {
  const std::string in = write_bag("full.bag", 100, 2.0);
  for (const std::string option : {"--out", "--csv"}) {
    std::string err;
    EXPECT_EQ(run_mbk_bag(in, option + " /dev/full", err), 1) << option << ": " << err;
    EXPECT_EQ(err.rfind("mbk: error: /dev/full: ", 0), 0u) << err;
    EXPECT_NE(err.find("writ"), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  }
}

// Outputs are written under a temporary name and renamed once whole: a run that
// fails (here: an unwritable --csv) leaves no new bag and the old one as it was; a run that
// succeeds leaves no temporary file.
TEST(BagTest, AFailedRunLeavesNoPartialOutput) {
  const std::string in = write_bag("whole_run.bag", 10, 1.0);
  const std::string out = temp("kept.bag"), fresh = temp("never.bag");
  std::ofstream(out) << "the previous output";
  std::remove(fresh.c_str());
  std::string err;
  EXPECT_EQ(run_mbk_bag(in, "--out " + out + " --csv /nonexistent/dir/x.csv", err), 1) << err;
  EXPECT_EQ(read_file(out), "the previous output");
  EXPECT_EQ(run_mbk_bag(in, "--out " + fresh + " --csv /nonexistent/dir/x.csv", err), 1) << err;
  EXPECT_FALSE(std::ifstream(fresh).good());
  EXPECT_EQ(run_mbk_bag(in, "--out " + out + " --csv " + temp("whole_run.csv"), err), 0) << err;
  EXPECT_EQ(count_topics(out).at("/body_kinematics"), 10);
  for (const std::string& path : {out, temp("whole_run.csv"), fresh}) {
    const std::string pattern = path + ".mbk-tmp-*";
    const std::string ls = "ls " + pattern + " >/dev/null 2>&1";
    EXPECT_NE(std::system(ls.c_str()), 0) << "left: " << pattern;
  }
}

// Odometry whose quaternion components are finite but huge (1e200 times a unit
// one) is the same rotation, not ignored.
TEST(BagTest, HugeOdometryQuaternionsAreTheirRotation) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  {
    rosbag::Bag bag(temp("huge_q.bag"), rosbag::bagmode::Write);
    for (int i = 0; i < 50; ++i) {
      const double t = 1.0 + i / 100.0;
      nav_msgs::Odometry o;
      o.header.stamp = ros::Time(t);
      o.header.frame_id = "odom";
      o.pose.pose.orientation.z = 1e200 * q.z(), o.pose.pose.orientation.w = 1e200 * q.w();
      bag.write("/odom", o.header.stamp, o);
      sensor_msgs::JointState js;
      js.header.stamp = ros::Time(t);
      js.name = model.coordinate_names;
      js.position.assign(model.nq, 0.1);
      bag.write("/joint_states", js.header.stamp, js);
    }
  }
  mbk_offline::BagOptions o = options(temp("huge_q.bag"), "");
  o.out_csv = temp("huge_q.csv");
  o.base_odometry = "/odom";
  const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
  EXPECT_EQ(s.written, 50);
  EXPECT_EQ(s.log.notes.count("base odometry ignored"), 0u);
}

// Two flipped bits that crashed librosbag itself (a segfault in its copy of a message, found by
// flipping random bits of this bag): each a message record's data length inside the chunk, now
// refused by name before librosbag reads the bag. Any other crash of librosbag's reading is
// refused as "damaged bag: reading it crashes librosbag" (survive_or_refuse, bag_input.cc).
TEST(BagTest, FlipsThatCrashedLibrosbagAreErrorsNamingTheRecord) {
  const std::string in = write_bag("flip_src.bag", 100, 2.0);
  std::string bytes = read_file(in);
  ASSERT_EQ(bytes.size(), 204133u) << "the bag's layout changed: find another crashing flip";
  for (const auto& flip : {std::make_pair(194964, 64), std::make_pair(149421, 8)}) {
    std::string damaged = bytes;
    damaged[flip.first] = static_cast<char>(damaged[flip.first] ^ flip.second);
    std::ofstream(temp("flip.bag"), std::ios::binary) << damaged;
    const std::string e = error_of(options(temp("flip.bag"), temp("flip_out.bag")));
    EXPECT_NE(e.find("flip.bag: damaged bag: the record at byte "), std::string::npos) << e;
    EXPECT_NE(e.find(" goes beyond the chunk's 195598 bytes"), std::string::npos) << e;
  }
}

// The complaints of librosbag itself about a damaged connection header stay off stderr;
// only mbk's summary (or its one error line) is printed.
TEST(BagTest, DamagedHeadersPrintOnlyMbksOwnLines) {
  const std::string in = write_bag("flip_src.bag", 100, 2.0);
  std::string damaged = read_file(in);
  ASSERT_EQ(damaged.size(), 204133u) << "the bag's layout changed: find another flip";
  damaged[16635] = static_cast<char>(damaged[16635] ^ 128);  // in a connection header
  std::ofstream(temp("header_flip.bag"), std::ios::binary) << damaged;
  std::string err;
  run_mbk_bag(temp("header_flip.bag"), "--csv " + temp("header_flip.csv"), err);
  std::istringstream lines(err);
  for (std::string line; std::getline(lines, line);)
    EXPECT_TRUE(line.rfind("mbk", 0) == 0 || line.rfind("  ", 0) == 0) << line;
}

// librosbag's error for a chunk's damaged compression field quotes the field's bytes: the
// summary's example of an unreadable message is printable (a byte that is not UTF-8 escaped;
// found by flipping bits of a bag).
TEST(BagTest, AnUnreadableMessagesExampleIsPrintable) {
  std::string damaged = read_file(write_bag("compression_src.bag", 100, 1.0));
  const std::size_t at = damaged.find("compression=none");
  ASSERT_NE(at, std::string::npos);
  damaged[at + 12] = static_cast<char>(damaged[at + 12] ^ 128);  // "none" -> "\xeeone"
  std::ofstream(temp("compression.bag"), std::ios::binary) << damaged;
  mbk_offline::BagOptions o = options(temp("compression.bag"), "");
  o.out_csv = temp("compression.csv");
  std::string example;
  try {
    example = mbk_offline::run_bag(o).unreadable_example;
  } catch (const std::invalid_argument& e) {  // nothing readable: an error, its example in it
    example = e.what();
  }
  EXPECT_NE(example.find("\\xeeone"), std::string::npos) << example;
  EXPECT_EQ(mbk::printable(example), example);
}

// A std_msgs/String connection on /joint_states, before or after the
// JointState one: those messages are skipped and counted, every joint sample is written.
TEST(BagTest, MessagesOfAnotherTypeAreSkippedAndCounted) {
  for (const bool string_first : {true, false}) {
    const std::string in =
        write_mixed("mixed.bag", "/joint_states", [&](int i, double t, auto& bag) {
          if (i == (string_first ? 0 : 50) || i == 70) write_string(bag, t);
        });
    const mbk_offline::BagSummary s = mbk_offline::run_bag(options(in, temp("mixed_out.bag")));
    EXPECT_EQ(s.written, 100) << string_first;
    EXPECT_EQ(s.unreadable, 2) << string_first;
    EXPECT_NE(s.unreadable_example.find("a std_msgs/String message"), std::string::npos)
        << s.unreadable_example;
    EXPECT_EQ(mbk_offline::exit_status(s), 2);  // partial: said so
    EXPECT_NE(mbk_offline::format_summary(s).find("unreadable 2 messages"), std::string::npos);
  }
}

TEST(BagTest, ATopicOfOnlyAnotherTypeNamesItsType) {
  const std::string in =
      write_mixed("strings.bag", "/other", [](int, double t, auto& bag) { write_string(bag, t); });
  const std::string e = error_of(options(in, temp("strings_out.bag")));
  EXPECT_NE(e.find("topic '/joint_states' is std_msgs/String, not sensor_msgs/JointState"),
            std::string::npos)
      << e;
}

// `rosbag record joint_states` stores the relative name; either form finds it.
TEST(BagTest, RelativeAndAbsoluteTopicNamesMatch) {
  const std::string relative =
      write_mixed("relative.bag", "joint_states", [](int, double, auto&) {});
  EXPECT_EQ(mbk_offline::run_bag(options(relative, temp("relative_out.bag"))).written, 100);
  const std::string absolute =
      write_mixed("absolute.bag", "/joint_states", [](int, double, auto&) {});
  mbk_offline::BagOptions o = options(absolute, temp("absolute_out.bag"));
  o.joint_states = "joint_states";
  const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
  EXPECT_EQ(s.written, 100);
  EXPECT_EQ(mbk_offline::exit_status(s), 0);
}

// A JointState whose name count says 2^32 - 1 (one damaged field) is refused from
// its bytes, without allocating, and the reading goes on.
TEST(BagTest, AnArrayCountBeyondTheMessageIsSkipped) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  const std::string in = write_mixed("huge.bag", "/joint_states", [&](int i, double t, auto& bag) {
    if (i != 10 && i != 20) return;
    sensor_msgs::JointState js = sample(model, waves, t - 0.005);
    js.header.frame_id = "f";
    std::vector<uint8_t> bytes(ros::serialization::serializationLength(js));
    ros::serialization::OStream out(bytes.data(), bytes.size());
    ros::serialization::serialize(out, js);
    const size_t count_at = 12 + 4 + 1;  // seq, stamp, frame_id; then name[]'s count
    const size_t at = i == 10 ? count_at : bytes.size() - 4 - 4 - 8 * model.nq - 4;  // position[]'s
    for (size_t b = at; b < at + 4; ++b) bytes[b] = 0xff;
    topic_tools::ShapeShifter shifter;
    shifter.morph(ros::message_traits::md5sum(js), ros::message_traits::datatype(js),
                  ros::message_traits::definition(js), "");
    ros::serialization::IStream in_bytes(bytes.data(), bytes.size());
    shifter.read(in_bytes);
    bag.write("/joint_states", ros::Time(t - 0.005), shifter);
  });
  const mbk_offline::BagSummary s = mbk_offline::run_bag(options(in, temp("huge_out.bag")));
  EXPECT_EQ(s.written, 100);
  EXPECT_EQ(s.unreadable, 2);
  EXPECT_NE(s.unreadable_example.find("/joint_states message 11: field 2 counts 4294967295"),
            std::string::npos)
      << s.unreadable_example;
}

// The command's exit status says a partial run (2), with the summary.
TEST(BagTest, APartialRunExitsTwoWithTheCounts) {
  const std::string in =
      write_mixed("cli_mixed.bag", "/joint_states", [](int i, double t, auto& bag) {
        if (i == 30) write_string(bag, t);
      });
  const std::string mbk = MBK_MBK_PATH;
  const std::string run = mbk + " bag " + in + " --model " + kModel + " --csv " +
                          temp("cli_mixed.csv") + " 2>" + temp("cli_mixed.err");
  EXPECT_EQ(WEXITSTATUS(std::system(run.c_str())), 2);
  std::ifstream err(temp("cli_mixed.err"));
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("100 samples read, 100 written"), std::string::npos) << text;
  EXPECT_NE(text.find("unreadable 1 messages"), std::string::npos) << text;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The demo trajectory at 100 Hz for 4 s in a bag of bz2 chunks of about 2 KB; messages
// skip_from..skip_to (1-based, inclusive) left out.
std::string write_bz2_bag(const std::string& name, int skip_from = 0, int skip_to = -1) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  rosbag::Bag bag(temp(name), rosbag::bagmode::Write);
  bag.setCompression(rosbag::compression::BZ2);
  bag.setChunkThreshold(2048);
  for (int i = 0; i < 400; ++i)
    if (i + 1 < skip_from || i + 1 > skip_to)
      bag.write("/joint_states", ros::Time(1.0 + i / 100.0), sample(model, waves, 1.0 + i / 100.0));
  bag.close();
  return temp(name);
}

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

void set_u32_at(std::string& bytes, std::size_t at, std::uint32_t v) {
  std::memcpy(&bytes[at], &v, 4);
}

// Where the data of each top-level record of kind `op` (0x05: a chunk, 0x04: an index) lies in a
// bag file's bytes: offset and length.
std::vector<std::pair<std::size_t, std::size_t>> record_data(const std::string& bytes, char op) {
  std::vector<std::pair<std::size_t, std::size_t>> records;
  for (std::size_t at = 13; at + 8 <= bytes.size();) {
    const std::size_t header = u32_at(bytes, at), data_at = at + 8 + header,
                      length = u32_at(bytes, at + 4 + header);
    if (bytes.substr(at + 4, header).find(std::string("op=") + op) != std::string::npos)
      records.emplace_back(data_at, length);
    at = data_at + length;
  }
  return records;
}

// write_bz2_bag's bag with 16 bytes of its middle chunk's data inverted, as `name`: its path.
std::string write_damaged_chunk_bag(const std::string& name) {
  std::string bytes = file_bytes(write_bz2_bag("undamaged_" + name));
  const auto chunks = record_data(bytes, 0x05);
  EXPECT_GE(chunks.size(), 20u);
  if (chunks.empty()) return temp(name);
  const auto [at, length] = chunks[chunks.size() / 2];
  for (std::size_t i = length / 4; i < length / 4 + 16; ++i) bytes[at + i] ^= '\xff';
  std::ofstream(temp(name), std::ios::binary) << bytes;
  return temp(name);
}

// A compressed chunk damaged in the middle of the bag (the joint states are read ahead on a
// second thread): librosbag throws for each of its messages, which are counted unreadable and
// skipped; the rest are read in order, and the output is the bag's without them, byte for byte.
TEST(BagTest, ADamagedChunkLosesItsMessagesAlone) {
  mbk_offline::BagOptions damaged = options(write_damaged_chunk_bag("damaged_chunk.bag"), "");
  damaged.out_csv = temp("damaged_chunk.csv");
  const mbk_offline::BagSummary s = mbk_offline::run_bag(damaged);
  ASSERT_GT(s.unreadable, 0);
  EXPECT_LT(s.unreadable, 20);
  EXPECT_EQ(s.read + s.unreadable, 400);
  const std::string where = "/joint_states message ";
  const std::size_t n = s.unreadable_example.find(where);
  ASSERT_NE(n, std::string::npos) << s.unreadable_example;
  const int first = std::stoi(s.unreadable_example.substr(n + where.size()));
  EXPECT_GT(first, 100) << s.unreadable_example;  // the middle of the bag
  EXPECT_LT(first, 300) << s.unreadable_example;
  mbk_offline::BagOptions without =
      options(write_bz2_bag("without.bag", first, first + static_cast<int>(s.unreadable) - 1), "");
  without.out_csv = temp("without.csv");
  EXPECT_EQ(mbk_offline::run_bag(without).read, s.read);
  EXPECT_EQ(file_bytes(damaged.out_csv), file_bytes(without.out_csv));
}

// Where each record inside an uncompressed chunk's data (at, length) starts in the file.
std::vector<std::size_t> records_in_chunk(const std::string& bytes, std::size_t at,
                                          std::size_t length) {
  std::vector<std::size_t> records;
  for (std::size_t r = at; r < at + length;) {
    records.push_back(r);
    const std::size_t header = u32_at(bytes, r);
    r += 8 + header + u32_at(bytes, r + 4 + header);
  }
  return records;
}

// A message record inside a chunk whose data length reaches past the chunk (librosbag copies
// what it says out of its buffer: a crash, or other bytes taken for the message's; found by
// flipping bits of a bag), and an index entry pointing inside a record: each an error naming
// the bag and the byte, before librosbag reads the bag.
TEST(BagTest, ARecordBeyondItsChunkOrAnIndexInsideARecordIsAnError) {
  const std::string bytes = file_bytes(write_bag("records_src.bag", 100, 2.0));
  const auto chunks = record_data(bytes, 0x05);
  ASSERT_FALSE(chunks.empty());
  const auto [at, length] = chunks[0];
  const std::vector<std::size_t> records = records_in_chunk(bytes, at, length);
  ASSERT_GE(records.size(), 3u);
  ASSERT_EQ(records.back() + 8 + u32_at(bytes, records.back()) +
                u32_at(bytes, records.back() + 4 + u32_at(bytes, records.back())),
            at + length);

  std::string beyond = bytes;
  const std::size_t data_length_at = records[1] + 4 + u32_at(bytes, records[1]);
  set_u32_at(beyond, data_length_at,
             u32_at(bytes, data_length_at) + static_cast<std::uint32_t>(length));
  std::ofstream(temp("beyond.bag"), std::ios::binary) << beyond;
  std::string e = error_of(options(temp("beyond.bag"), temp("beyond_out.bag")));
  EXPECT_NE(e.find("beyond.bag: damaged bag: the record at byte " +
                   std::to_string(records[1] - at) + " of the chunk at byte "),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("goes beyond the chunk's " + std::to_string(length) + " bytes"),
            std::string::npos)
      << e;

  std::string inside = bytes;
  const auto indexes = record_data(bytes, 0x04);
  ASSERT_FALSE(indexes.empty());
  const std::size_t index = indexes[0].first;
  const std::uint32_t first = u32_at(bytes, index + 8);  // the first entry's offset
  ASSERT_EQ(first, records[1] - at) << "the first message follows the connection record";
  set_u32_at(inside, index + 8, first + 4);
  std::ofstream(temp("inside.bag"), std::ios::binary) << inside;
  e = error_of(options(temp("inside.bag"), temp("inside_out.bag")));
  EXPECT_NE(e.find("inside.bag: damaged bag: the index at byte "), std::string::npos) << e;
  EXPECT_NE(e.find("points at byte " + std::to_string(first + 4) + " of the chunk at byte "),
            std::string::npos)
      << e;
  EXPECT_FALSE(std::ifstream(temp("beyond_out.bag")) || std::ifstream(temp("inside_out.bag")));
}

// Chunks compressed with LZ4 and bz2 are decompressed for the check as librosbag does: every
// message read, the same output as the uncompressed bag's.
TEST(BagTest, CompressedChunksAreCheckedAndRead) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  std::vector<std::string> outputs;
  for (const auto compression :
       {rosbag::compression::Uncompressed, rosbag::compression::LZ4, rosbag::compression::BZ2}) {
    const std::string name = "compressed_" + std::to_string(static_cast<int>(compression));
    {
      rosbag::Bag bag(temp(name + ".bag"), rosbag::bagmode::Write);
      bag.setCompression(compression);
      bag.setChunkThreshold(4096);
      for (int i = 0; i < 300; ++i)
        bag.write("/joint_states", ros::Time(1.0 + i / 100.0),
                  sample(model, waves, 1.0 + i / 100.0));
    }
    mbk_offline::BagOptions o = options(temp(name + ".bag"), "");
    o.out_csv = temp(name + ".csv");
    EXPECT_EQ(mbk_offline::run_bag(o).read, 300) << name;
    outputs.push_back(file_bytes(o.out_csv));
  }
  EXPECT_EQ(outputs[1], outputs[0]);
  EXPECT_EQ(outputs[2], outputs[0]);
}

// Stamps jittered so that every interval differs, more of them than the survey's
// 16,384 bins: the bounded-memory path surveys the stamps a second time and takes the whole
// recording's max_gap (5 x the median interval) bit for bit, and writes every sample.
TEST(BagTest, JitteredStampsGiveTheWholeRecordingsMaxGap) {
  const mbk::Model model = mbk::load_model_file(kModel);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  const int rows = 20000;
  std::vector<double> t;
  std::ofstream csv(temp("jittered.csv"));
  csv.precision(17);
  csv << "time";
  for (const std::string& n : model.coordinate_names) csv << "," << n;
  for (int i = 0; i < rows; ++i) {
    t.push_back(1 + 1e-3 * i + 3e-4 * std::sin(0.7 * i));
    csv << "\n" << t.back();
    for (int c = 0; c < model.nq; ++c) csv << "," << waves[c].at(t.back(), 0);
  }
  csv.close();
  std::set<double> intervals;
  for (int i = 1; i < rows; ++i) intervals.insert(t[i] - t[i - 1]);
  ASSERT_GT(intervals.size(), 1u << 14);
  mbk_offline::BagOptions o = options(temp("jittered.csv"), "");
  o.out_csv = "/dev/null";
  o.estimator = "centered_0.4s_4";
  const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
  EXPECT_EQ(s.max_gap, mbk::default_max_gap(t));
  EXPECT_EQ(s.read, rows);
  EXPECT_EQ(s.written, rows);
}

}  // namespace

// A published mimic value wins over the mimic rule, as in the node and
// robot_state_publisher; the finger (2 q_arm2 + 0.1) is recorded 0.3 off its rule.
TEST(BagTest, APublishedMimicValueWinsOverItsRule) {
  const std::string urdf = MBK_SOURCE_DIR "/test/ros/test_robot.urdf";
  const mbk::Model model = mbk::load_model_file(urdf);
  auto state_at = [&](double t) {
    mbk::JointState<double> s(model);
    for (int i = 0; i < model.nq; ++i)
      if (model.coordinate_names[i] == "arm2_joint") s.position[i] = 0.3 * std::sin(t);
    for (int i = 0; i < model.nq; ++i)
      if (model.coordinate_names[i] == "finger_joint") s.position[i] = 0.6 * std::sin(t) + 0.4;
    return s;
  };
  rosbag::Bag out(temp("mimic.bag"), rosbag::bagmode::Write);
  for (int i = 0; i < 50; ++i) {
    const double t = 1.0 + i / 100.0;
    const mbk::JointState<double> s = state_at(t);
    sensor_msgs::JointState js;
    js.header.stamp = ros::Time(t);
    js.name = model.coordinate_names;
    js.position.assign(s.position.data(), s.position.data() + model.nq);
    out.write("/joint_states", ros::Time(t), js);
  }
  out.close();
  mbk_offline::BagOptions o = options(temp("mimic.bag"), temp("mimic_out.bag"));
  o.model = urdf;
  EXPECT_EQ(mbk_offline::run_bag(o).written, 50);
  rosbag::Bag bag(o.out_bag, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/body_kinematics"));
  int i = 0;
  for (const rosbag::MessageInstance& m : view) {
    const auto msg = m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>();
    mbk::Data<double> d(model);
    mbk::forward_kinematics(model, state_at(1.0 + i++ / 100.0), d, mbk::Level::kPose);
    for (int k = 1; k <= model.body_count(); ++k) {
      const auto& b = msg->bodies[k - 1];
      const Eigen::Quaterniond q(d.rotation[k]);
      const Eigen::Quaterniond got(b.pose.orientation.w, b.pose.orientation.x, b.pose.orientation.y,
                                   b.pose.orientation.z);
      EXPECT_LT(q.angularDistance(got), 1e-12) << b.name << " at sample " << i;
      EXPECT_LT(
          (mbk::Vec3<double>(b.pose.position.x, b.pose.position.y, b.pose.position.z) - d.origin[k])
              .norm(),
          1e-12)
          << b.name;
    }
  }
  EXPECT_EQ(i, 50);
}

// The whole-body quantities of a skeleton lacking segments of the anthropometric table are
// marked in the CSV (its system rows are system_incomplete) and in every message of the bag
// (system.missing_segments names them).
TEST(BagTest, ASkeletonWithoutHandsMarksEveryWholeBodyOutputIncomplete) {
  std::ofstream(temp("paws.bvh")) << mbk_test::renamed(
      MBK_SOURCE_DIR "/test/io/data/cmu_walk.bvh",
      {{"LeftHand", "LeftPaw"}, {"RightHand", "RightPaw"}});
  const std::string run = std::string(MBK_MBK_PATH) + " bag " + temp("paws.bvh") +
                          " --scale 0.01 --body-mass 70 --csv " + temp("paws.csv") + " --out " +
                          temp("paws.bag") + " 2>" + temp("paws.err");
  ASSERT_EQ(std::system(run.c_str()), 0);
  const std::vector<std::string> hands = {"left hand", "right hand"};
  EXPECT_EQ(missing_segments_in(temp("paws.bag")),
            std::vector<std::vector<std::string>>(40, hands));
  std::ifstream csv(temp("paws.csv"));
  std::string line;
  int incomplete = 0;
  while (std::getline(csv, line)) {
    EXPECT_EQ(line.find(",system,"), std::string::npos) << line;
    incomplete += line.find(",system_incomplete,") != std::string::npos;
  }
  EXPECT_EQ(incomplete, 40);
}

// A BVH file is its own model and recording: every frame written at its time, with the segment
// parameters of --body-mass in the CSV's system rows; --scale etc. refused for other models.
TEST(BagTest, ABvhFileIsItsOwnRecording) {
  const std::string walk = MBK_SOURCE_DIR "/test/io/data/cmu_walk.bvh";
  const std::string run = std::string(MBK_MBK_PATH) + " bag " + walk +
                          " --scale 0.01 --body-mass 70 --csv " + temp("walk.csv") + " --out " +
                          temp("walk.bag") + " 2>" + temp("walk.err");
  ASSERT_EQ(std::system(run.c_str()), 0);
  std::ifstream err(temp("walk.err"));
  std::string line;
  std::getline(err, line);
  EXPECT_EQ(line.rfind("mbk bag: 40 samples read, 40 written, 0 dropped", 0), 0u) << line;
  std::ifstream csv(temp("walk.csv"));
  std::getline(csv, line);  // header
  int rows = 0, system_rows = 0;
  for (; std::getline(csv, line); ++rows) {
    if (line.find(",system,") == std::string::npos) continue;
    ++system_rows;
    EXPECT_EQ(line.rfind(std::to_string(system_rows / 60.0).substr(0, 6), 0), 0u) << line;
  }
  EXPECT_EQ(rows, 40 * 30);  // 29 bodies and the system per frame
  EXPECT_EQ(system_rows, 40);
  EXPECT_EQ(count_topics(temp("walk.bag")).at("/body_kinematics"), 40);
  EXPECT_EQ(missing_segments_in(temp("walk.bag")),
            std::vector<std::vector<std::string>>(40));  // every segment found
  std::vector<std::string> args = {"mbk",     "bag",  walk,    "--model", kModel,
                                   "--scale", "0.01", "--csv", "x.csv"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  try {
    mbk_offline::parse_bag_options(static_cast<int>(argv.size()), argv.data());
    ADD_FAILURE() << "--scale with a .yaml model accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--scale, --body-mass, --sex, --segments and --anthropometry apply to a .bvh "
                 "model only");
  }
}
