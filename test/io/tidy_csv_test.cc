// The tidy CSV writer (io/tidy_csv.h): the same text, byte for byte, as printing each cell on its
// own (the documented form: stamp with 9 decimals, numbers in their shortest round-trip form,
// -0 as 0), across many buffer flushes, whether written at once or formatted apart (format,
// write_text) and interleaved; and write_shortest (io/number_format.h).
#include "mb_kinematics/io/tidy_csv.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/number_format.h"

namespace {

// One cell as the documented form prints it, built the slow way.
std::string cell(double x) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, x == 0 ? 0.0 : x).ptr);
}

std::string reference_rows(const mbk::Model& model, double stamp, const mbk::Data<double>& d) {
  char t[400];
  std::snprintf(t, sizeof t, "%.9f", stamp);
  std::ostringstream out;
  for (int k = 1; k <= model.body_count(); ++k) {
    out << t << "," << model.bodies[k].name << "," << k << "," << model.bodies[k].lower;
    const Eigen::Quaterniond q(d.rotation[k]);
    for (double x : {d.origin[k].x(), d.origin[k].y(), d.origin[k].z(), q.x(), q.y(), q.z(), q.w()})
      out << "," << cell(x);
    for (const auto* v :
         {&d.mass_center, &d.omega, &d.alpha, &d.mass_center_velocity, &d.mass_center_acceleration})
      for (int i = 0; i < 3; ++i) out << "," << cell((*v)[k][i]);
    out << "\n";
  }
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model, d, s, mbk::Level::kAcceleration);
  out << t << ",system,0,0,,,,,,,";
  for (int i = 0; i < 3; ++i) out << "," << cell(s.mass_center[i]);
  out << ",,,,,,";
  for (const auto* v : {&s.velocity, &s.acceleration})
    for (int i = 0; i < 3; ++i) out << "," << cell((*v)[i]);
  out << "\n";
  return out.str();
}

TEST(TidyCsvWriterTest, SameTextAsEachCellPrintedAloneAcrossManyFlushes) {
  const mbk::Model model = mbk::make_random_tree(12, 3);  // joints of every type, with mass
  mbk::JointState<double> state(model);
  mbk::Data<double> data(model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  const std::string path = ::testing::TempDir() + "tidy_writer.csv";
  std::string expected = std::string(mbk::TidyCsvWriter::header()) + "\n";
  {
    mbk::TidyCsvWriter w(path, model);
    std::string text;
    for (int r = 0; r < 600; ++r) {  // about 1.5 MB: many 64 kB buffers
      for (int i = 0; i < model.nq; ++i)
        state.position[i] = u(rng), state.velocity[i] = u(rng), state.acceleration[i] = u(rng);
      mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
      if (r % 7 == 0) data.origin[1].x() = -0.0, data.omega[2].y() = 1e-300;
      if (r % 11 == 0) data.alpha[1].z() = -1.2345678901234567e+300, data.omega[1].x() = 1e7;
      const double stamp = 1.7e9 + r / 1000.0;
      if (r % 2) {  // as the computing threads format rows for mbk bag
        text.clear();
        w.format(stamp, data, text);
        w.write_text(text);
      } else {
        w.write(stamp, data);
      }
      expected += reference_rows(model, stamp, data);
    }
    w.close();
  }
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(text.size(), 1u << 20);
  ASSERT_EQ(text.size(), expected.size());
  EXPECT_TRUE(text == expected);
}

TEST(NumberFormatTest, WriteShortestReadsBackExactly) {
  const double lowest = std::numeric_limits<double>::denorm_min();
  for (double x : {0.1, -0.0, 1e7, 1e-5, 123456.789, -1.2345678901234567e+300, lowest,
                   std::numeric_limits<double>::max(), 2.0 / 3.0}) {
    char buf[mbk::kMaxDoubleChars];
    const std::string s(buf, mbk::write_shortest(buf, x));
    EXPECT_EQ(std::strtod(s.c_str(), nullptr), x) << s;
    EXPECT_EQ(s, cell(x));
  }
  char buf[mbk::kMaxDoubleChars];
  EXPECT_EQ(std::string(buf, mbk::write_shortest(buf, -0.0)), "0");
}

}  // namespace
