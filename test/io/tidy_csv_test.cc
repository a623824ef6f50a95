// The tidy CSV writer (io/tidy_csv.h): the same text, byte for byte, as printing each cell on its
// own (the documented form: stamp with 9 decimals, numbers in their shortest round-trip form,
// -0 as 0), across many buffer flushes, whether written at once or formatted apart (format,
// write_text) and interleaved; known values byte for byte; and write_shortest
// (io/number_format.h): the bytes of std::to_chars.
#include "mb_kinematics/io/tidy_csv.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
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
    for (int r = 0; r < 600; ++r) {  // about 1.5 MB: more than one block (io/block_file.h)
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

// Awkward doubles read back bit for bit from write_shortest's and format_double's text: the
// smallest and largest subnormals, the smallest normal, 1e-300, 0.1 + 0.2, the largest finite
// (both signs), a value needing 17 digits; -0 reads back as +0 (written "0").
TEST(NumberFormatTest, AwkwardDoublesReadBackBitForBit) {
  using limits = std::numeric_limits<double>;
  const auto bits = [](double x) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  for (double x : {limits::denorm_min(), -limits::denorm_min(), 3 * limits::denorm_min(),
                   std::nextafter(limits::min(), 0.0), limits::min(), 1e-300, -1e-300, 0.1 + 0.2,
                   limits::max(), limits::lowest(), std::nextafter(1.0, 2.0), 2.0 / 3.0, -0.0}) {
    char buf[mbk::kMaxDoubleChars];
    const std::string written(buf, mbk::write_shortest(buf, x)), formatted = mbk::format_double(x);
    EXPECT_EQ(formatted, written);
    EXPECT_EQ(bits(std::strtod(written.c_str(), nullptr)), bits(x + 0.0)) << written;
  }
  EXPECT_EQ(mbk::format_double(-0.0), "0");
}

std::string shortest(double x) {
  char buf[mbk::kMaxDoubleChars];
  return std::string(buf, mbk::write_shortest(buf, x));
}

// The bytes of std::to_chars(first, last, x): fixed or scientific, whichever is shorter (fixed
// on a tie); subnormals; whole numbers printed exactly; 17 digits where 16 do not read back.
TEST(NumberFormatTest, WriteShortestKnownBytes) {
  const std::pair<double, const char*> known[] = {
      {0.1, "0.1"},
      {-0.0, "0"},
      {0.0, "0"},
      {1.0, "1"},
      {-17.0, "-17"},
      {1e308, "1e+308"},
      {-1e308, "-1e+308"},
      {std::numeric_limits<double>::max(), "1.7976931348623157e+308"},
      {std::numeric_limits<double>::denorm_min(), "5e-324"},
      {3 * std::numeric_limits<double>::denorm_min(), "1.5e-323"},
      {std::nextafter(std::numeric_limits<double>::min(), 0.0), "2.225073858507201e-308"},
      {std::numeric_limits<double>::min(), "2.2250738585072014e-308"},
      {0.1 + 0.2, "0.30000000000000004"},
      {2.0 / 3.0, "0.6666666666666666"},
      {-0.00012345678901234567, "-0.00012345678901234567"},
      {1e-4, "1e-04"},
      {1.5e-4, "0.00015"},
      {1e-3, "0.001"},
      {1e4, "10000"},
      {1e5, "1e+05"},
      {1.5e5, "150000"},
      {1.5e6, "1500000"},  // a tie: fixed
      {1.5e7, "1.5e+07"},
      {1.5e-5, "1.5e-05"},
      {1.2345678901234567e-3, "0.0012345678901234567"},
      {1.2345678901234567e-5, "1.2345678901234568e-05"},
      {123456.789, "123456.789"},
      {1e15, "1e+15"},
      {9007199254740992.0, "9007199254740992"},
      {123456789012345680000.0, "123456789012345683968"},  // exact: more digits than shortest
      {1e23, "1e+23"},
  };
  for (const auto& [x, text] : known) {
    EXPECT_EQ(shortest(x), text);
    EXPECT_EQ(std::strtod(text, nullptr), x + 0.0) << text;
  }
  EXPECT_EQ(shortest(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(shortest(std::nan("")), "nan");
}

// Draw i of a mix: a random bit pattern (every exponent, subnormals, NaNs, -0), a short decimal
// around the fixed/scientific bounds, or a random value of any size.
double random_double(std::mt19937_64& rng, int i) {
  double x;
  if (i % 3 == 1) {
    const uint64_t bits = rng();
    std::memcpy(&x, &bits, sizeof x);
  } else if (i % 3 == 2) {
    x = std::strtod(
        (std::to_string(rng() % 100000) + "e" + std::to_string(int(rng() % 51) - 25)).c_str(),
        nullptr);
  } else {
    x = std::ldexp(std::uniform_real_distribution<double>(-10, 10)(rng),
                   static_cast<int>(rng() % 140) - 70);
  }
  return x;
}

// Random bit patterns (every exponent, subnormals, NaNs), random values of every size and short
// decimals around the fixed/scientific bounds: the same bytes as std::to_chars, and every finite
// one reads back exactly.
TEST(NumberFormatTest, WriteShortestSameAsToCharsOnRandomDoubles) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 400000; ++i) {
    const double x = random_double(rng, i);
    const std::string s = shortest(x);
    ASSERT_EQ(s, cell(x)) << i;
    if (std::isfinite(x)) {
      ASSERT_EQ(std::strtod(s.c_str(), nullptr), x + 0.0) << s;
    }
  }
}

// write_general: the bytes an std::ostream writes at that precision (OUT.sample_errors.csv was
// written so), on random doubles of every kind (random_double) and known ones, at 6 significant
// digits and at 1 and 17.
TEST(NumberFormatTest, WriteGeneralSameAsAnOstreamAtThatPrecision) {
  const auto general = [](double x, int precision) {
    char buf[mbk::kMaxDoubleChars];
    return std::string(buf, mbk::write_general(buf, x, precision));
  };
  const auto streamed = [](double x, int precision) {
    std::ostringstream s;
    s.precision(precision);
    s << x;
    return s.str();
  };
  std::mt19937_64 rng(12);
  for (int i = 0; i < 200000; ++i) {
    const double x = random_double(rng, i);
    for (int precision : {6, 1, 17}) ASSERT_EQ(general(x, precision), streamed(x, precision)) << i;
  }
  // Halves at the digit rounded away, and nines rounded up to the next power of ten: x's digits
  // one past the precision, ending in 5 (a tie in decimal, a little above or below it in binary).
  for (int i = 0; i < 200000; ++i) {
    const int precision = i % 2 == 0 ? 6 : 9;
    const uint64_t digits = i % 10 == 1 ? 9999995 : rng() % 1000000000;
    const double x = std::strtod((std::to_string(digits % (uint64_t{1} << 63)) + "5e" +
                                  std::to_string(int(rng() % 61) - 30))
                                     .c_str(),
                                 nullptr);
    ASSERT_EQ(general(x, precision), streamed(x, precision)) << i;
    ASSERT_EQ(general(-x, precision), streamed(-x, precision)) << i;
  }
  EXPECT_EQ(general(1e-5, 6), "1e-05");
  EXPECT_EQ(general(123456.7, 6), "123457");
  EXPECT_EQ(general(1234567.0, 6), "1.23457e+06");
  EXPECT_EQ(general(0.000123456789, 6), "0.000123457");
  EXPECT_EQ(general(-0.0, 6), "-0");
  EXPECT_EQ(general(std::numeric_limits<double>::lowest(), 17), "-1.7976931348623157e+308");
}

// Known values in a row: the exact bytes of the line and every cell read back exactly.
TEST(TidyCsvWriterTest, KnownValuesWrittenExactly) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  // origin; qx, qy, qz, qw of the identity; mass center, omega, alpha, velocity, acceleration
  const double v[] = {-0.0,
                      1e308,
                      tiny,
                      0,
                      0,
                      0,
                      1,
                      0.1 + 0.2,
                      2.0 / 3.0,
                      -1e-4,
                      1.5e5,
                      123456.789,
                      std::numeric_limits<double>::min(),
                      1e5,
                      -1.7976931348623157e+308,
                      1e-3,
                      9007199254740992.0,
                      123456789012345680000.0,
                      -17,
                      0,
                      1,
                      -0.00012345678901234567};
  const mbk::Model model = mbk::make_random_tree(1, 3);
  mbk::Data<double> d(model);
  d.origin[1] = {v[0], v[1], v[2]};
  d.rotation[1].setIdentity();
  int i = 7;
  for (auto* x :
       {&d.mass_center, &d.omega, &d.alpha, &d.mass_center_velocity, &d.mass_center_acceleration})
    (*x)[1] = {v[i], v[i + 1], v[i + 2]}, i += 3;
  const std::string path = ::testing::TempDir() + "tidy_known.csv";
  mbk::TidyCsvWriter w(path, model);
  w.write(2.5, d);
  w.close();
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  const std::string body = "2.500000000," + model.bodies[1].name + ",1,0,";
  EXPECT_EQ(line, body +
                      "0,1e+308,5e-324,0,0,0,1,0.30000000000000004,0.6666666666666666,-1e-04,"
                      "150000,123456.789,2.2250738585072014e-308,1e+05,-1.7976931348623157e+308,"
                      "0.001,9007199254740992,123456789012345683968,-17,0,1,"
                      "-0.00012345678901234567");
  std::istringstream cells(line.substr(body.size()));
  std::string c;
  for (double x : v) {
    ASSERT_TRUE(std::getline(cells, c, ','));
    EXPECT_EQ(std::strtod(c.c_str(), nullptr), x) << c;
  }
  EXPECT_FALSE(std::getline(cells, c, ','));
}

}  // namespace
