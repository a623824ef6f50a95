// The `mbk` command line as users run it (doc/method.md 8): the built executable, from
// the source directory, its stdout, stderr and exit code.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/state_json.h"
#include "mb_kinematics/io/urdf_model.h"
#include "test/support/test_models.h"

namespace {

using mbk_test::source_path;

// mbk is built into the same catkin devel lib directory as this test.
std::string mbk_path() {
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return "mbk";
  const std::string exe(self, n);
  return exe.substr(0, exe.rfind('/')) + "/mbk";
}

struct Output {
  int status = -1;  // exit code
  std::string out, err;
};

// Runs `mbk <args>` in the source directory (args are shell words, as a user types them).
Output mbk(const std::string& args) {
  char err_path[] = "/tmp/mbk_cli_test_XXXXXX";
  const int fd = mkstemp(err_path);
  if (fd < 0) throw std::runtime_error("mkstemp failed");
  close(fd);
  const std::string command =
      "cd '" + source_path("") + "' && '" + mbk_path() + "' " + args + " 2>'" + err_path + "'";
  Output run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed: " + command);
  char buffer[4096];
  size_t got;
  while ((got = fread(buffer, 1, sizeof buffer, pipe)) > 0) run.out.append(buffer, got);
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_path);
  std::stringstream err;
  err << in.rdbuf();
  run.err = err.str();
  std::remove(err_path);
  return run;
}

TEST(MbkCli, ExecutableIsThere) {
  ASSERT_EQ(access(mbk_path().c_str(), X_OK), 0) << mbk_path() << " missing: build target mbk";
  const Output help = mbk("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out.rfind("usage: mbk tables", 0), 0u) << help.out;
  const Output bare = mbk("");
  EXPECT_NE(bare.status, 0);
  EXPECT_EQ(bare.out, "");
  EXPECT_EQ(bare.err.rfind("usage: mbk", 0), 0u) << bare.err;
}

TEST(MbkCli, TablesCsvIsTable421) {
  const Output run = mbk("tables --lower 0,1,2,1,1,5,2,7,8,9 --csv");
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.err, "");
  // Table 4.2.1, its blanks (chain already at R) written as 0; the last row is all zeros.
  EXPECT_EQ(run.out,
            "1,2,3,4,5,6,7,8,9,10\n"
            "0,1,2,1,1,5,2,7,8,9\n"
            "0,0,1,0,0,1,1,2,7,8\n"
            "0,0,0,0,0,0,0,1,2,7\n"
            "0,0,0,0,0,0,0,0,1,2\n"
            "0,0,0,0,0,0,0,0,0,1\n"
            "0,0,0,0,0,0,0,0,0,0\n");
}

TEST(MbkCli, TablesTextIsTable421) {
  const Output run = mbk("tables --lower '0, 1, 2, 1, 1, 5, 2, 7, 8, 9'");
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.err, "");
  // As printed in the chapter: an entry is blank once its chain has reached 0.
  EXPECT_EQ(run.out,
            "Lower body arrays, N = 10 (method.md 1)\n"
            "L^0(k)     1   2   3   4   5   6   7   8   9  10\n"
            "L^1(k)     0   1   2   1   1   5   2   7   8   9\n"
            "L^2(k)         0   1   0   0   1   1   2   7   8\n"
            "L^3(k)             0           0   0   1   2   7\n"
            "L^4(k)                                 0   1   2\n"
            "L^5(k)                                     0   1\n"
            "L^6(k)                                         0\n");
}

// Whitespace-separated words of a line.
std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

TEST(MbkCli, TablesOfTheHumanBodyModel) {
  const Output run = mbk("tables --model config/human_body.yaml");
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.err, "");
  std::istringstream out(run.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(out, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 9u) << run.out;  // header, t = 0..6 (Table 4.2.2), legend
  EXPECT_EQ(lines[0], "Lower body arrays, N = 16 (method.md 1)");
  std::vector<std::string> k, lower;
  for (int i = 1; i <= 16; ++i) k.push_back(std::to_string(i));
  for (int l : {0, 1, 2, 3, 4, 5, 4, 7, 4, 9, 2, 11, 12, 2, 14, 15})
    lower.push_back(std::to_string(l));
  k.insert(k.begin(), "L^0(k)");
  lower.insert(lower.begin(), "L^1(k)");
  EXPECT_EQ(words(lines[1]), k);
  EXPECT_EQ(words(lines[2]), lower);
  EXPECT_EQ(words(lines[7]), (std::vector<std::string>{"L^6(k)", "0", "0", "0"}));  // 6, 8, 10
  EXPECT_EQ(lines[8].rfind("bodies: 1=pelvis 2=lower_torso ", 0), 0u) << lines[8];
  EXPECT_NE(lines[8].find(" 16=left_foot"), std::string::npos) << lines[8];
}

// A minimal strict JSON reader, enough for `mbk eval`'s output.
struct Json {
  enum Type { kNull, kBool, kNumber, kString, kArray, kObject } type = kNull;
  double number = 0;
  std::string string;
  std::vector<Json> array;
  std::vector<std::pair<std::string, Json>> object;  // in order

  const Json& at(const std::string& key) const {
    for (const auto& [k, v] : object)
      if (k == key) return v;
    throw std::runtime_error("no key '" + key + "'");
  }
  std::vector<std::string> keys() const {
    std::vector<std::string> k;
    for (const auto& entry : object) k.push_back(entry.first);
    return k;
  }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : s_(text) {}

  Json document() {
    Json v = value();
    skip();
    if (i_ != s_.size()) fail("trailing text");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(i_));
  }
  void skip() {
    while (i_ < s_.size() && std::string(" \t\r\n").find(s_[i_]) != std::string::npos) ++i_;
  }
  bool take(char c) {
    skip();
    if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
    return false;
  }
  void expect(char c) {
    if (!take(c)) fail(std::string("expected '") + c + "'");
  }
  std::string string_literal() {
    expect('"');
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') {
        if (++i_ >= s_.size()) fail("unfinished escape");
        const char* simple = std::strchr("\"\\/bfnrt", s_[i_]);
        if (s_[i_] == 'u') {  // \uXXXX below U+0800 (what names here need), as UTF-8
          const unsigned long u = std::strtoul(s_.substr(i_ + 1, 4).c_str(), nullptr, 16);
          if (i_ + 4 >= s_.size()) fail("short \\u escape");
          out += u < 0x80    ? std::string(1, static_cast<char>(u))
                 : u < 0x800 ? std::string{static_cast<char>(0xc0 | u >> 6),
                                           static_cast<char>(0x80 | (u & 0x3f))}
                             : "\xef\xbf\xbd";  // U+FFFD stands for the rest
          i_ += 5;
          continue;
        }
        if (!simple || !*simple) fail("unsupported escape");
        out += "\"\\/\b\f\n\r\t"[simple - "\"\\/bfnrt"];
        ++i_;
        continue;
      } else if (static_cast<unsigned char>(s_[i_]) < 0x20) {
        fail("control character in string");
      }
      out += s_[i_++];
    }
    expect('"');
    return out;
  }
  Json value() {
    skip();
    Json v;
    if (i_ >= s_.size()) fail("unexpected end");
    const char c = s_[i_];
    if (c == '{') {
      v.type = Json::kObject;
      ++i_;
      if (take('}')) return v;
      do {
        skip();
        std::string key = string_literal();
        expect(':');
        v.object.emplace_back(key, value());
      } while (take(','));
      expect('}');
    } else if (c == '[') {
      v.type = Json::kArray;
      ++i_;
      if (take(']')) return v;
      do v.array.push_back(value());
      while (take(','));
      expect(']');
    } else if (c == '"') {
      v.type = Json::kString;
      v.string = string_literal();
    } else if (c == '-' || (c >= '0' && c <= '9')) {  // JSON's grammar: no nan, inf, +, .5
      const size_t start = i_;
      if (s_[i_] == '-') ++i_;
      auto digits = [&] {
        const size_t from = i_;
        while (i_ < s_.size() && s_[i_] >= '0' && s_[i_] <= '9') ++i_;
        if (i_ == from) fail("digit expected");
      };
      digits();
      if (i_ < s_.size() && s_[i_] == '.') ++i_, digits();
      if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
        ++i_;
        if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
        digits();
      }
      v.type = Json::kNumber;
      v.number = std::strtod(s_.substr(start, i_ - start).c_str(), nullptr);
    } else {
      for (const char* word : {"null", "true", "false"})
        if (s_.compare(i_, std::string(word).size(), word) == 0) {
          i_ += std::string(word).size();
          v.type = word[0] == 'n' ? Json::kNull : Json::kBool;
          return v;
        }
      fail("unexpected character");
    }
    return v;
  }

  const std::string& s_;
  size_t i_ = 0;
};

const std::vector<std::string> kBodyFields = {"index",    "name",        "lower", "origin",
                                              "rotation", "mass_center", "omega", "alpha",
                                              "velocity", "acceleration"};
// A body's keys in order: kBodyFields with the body's mass, local mass center and inertia
// after its mass center.
const std::vector<std::string> kBodyKeys = {
    "index",       "name",        "lower", "origin",
    "rotation",    "mass_center", "mass",  "local_mass_center",
    "inertia",     "omega",       "alpha", "velocity",
    "acceleration"};

// Numbers of one array field, checked to be `size` numbers.
std::vector<double> numbers(const Json& body, const std::string& field, size_t size) {
  const Json& a = body.at(field);
  EXPECT_EQ(a.type, Json::kArray) << field;
  EXPECT_EQ(a.array.size(), size) << field;
  std::vector<double> out;
  for (const Json& x : a.array) {
    EXPECT_EQ(x.type, Json::kNumber) << field;
    out.push_back(x.number);
  }
  return out;
}

template <typename M>
std::vector<double> row_major(const M& m) {
  std::vector<double> out;
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) out.push_back(m(r, c));
  return out;
}

// The per-field scale of the bodies' values: max |component| over all bodies (1 if all zero).
std::map<std::string, double> field_scales(const Json& bodies) {
  std::map<std::string, double> scale;
  for (const Json& body : bodies.array)
    for (const auto& [field, value] : body.object)
      for (const Json& x : value.array) scale[field] = std::max(scale[field], std::abs(x.number));
  for (auto& entry : scale)
    if (entry.second == 0) entry.second = 1;
  return scale;
}

// Both are the same double computations printed with round-trip precision, in two binaries;
// 1e-12 of the field's scale allows for a compiler contracting or reordering differently.
void expect_near_all(const std::vector<double>& a, const std::vector<double>& b, double scale,
                     const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_LE(std::abs(a[i] - b[i]), 1e-12 * scale)
        << what << "[" << i << "]: " << a[i] << " vs " << b[i];
}

class MbkEval : public ::testing::Test {
 protected:
  const std::string args =
      "eval --model config/human_body.yaml --state config/human_body_state.json";

  static Json parse(const Output& run) {
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    try {
      return JsonReader(run.out).document();
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what() << " in:\n" << run.out;
      return Json();
    }
  }
};

TEST_F(MbkEval, JsonHasTheContractFieldsAndTheKinematics) {
  const Json doc = parse(mbk(args));
  ASSERT_EQ(doc.type, Json::kObject);
  EXPECT_EQ(doc.keys(), (std::vector<std::string>{"frame", "bodies", "system"}));
  EXPECT_EQ(doc.at("frame").string, "world");
  const Json& bodies = doc.at("bodies");
  ASSERT_EQ(bodies.array.size(), 16u);

  const mbk::Model model = mbk::load_model_file(source_path("config/human_body.yaml"));
  const mbk::JointState<double> state =
      mbk::read_state_file(model, source_path("config/human_body_state.json"));
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  const std::map<std::string, double> scale = field_scales(bodies);
  for (int k = 1; k <= 16; ++k) {
    const Json& body = bodies.array[k - 1];
    SCOPED_TRACE("body " + std::to_string(k));
    ASSERT_EQ(body.type, Json::kObject);
    EXPECT_EQ(body.keys(), kBodyKeys);
    EXPECT_EQ(body.at("index").number, k);
    EXPECT_EQ(body.at("name").string, model.bodies[k].name);
    EXPECT_EQ(body.at("lower").number, model.bodies[k].lower);
    auto check = [&](const std::string& field, const std::vector<double>& expected) {
      expect_near_all(numbers(body, field, expected.size()), expected, scale.at(field), field);
    };
    check("origin", row_major(data.origin[k]));
    check("rotation", row_major(data.rotation[k]));  // S0K row by row
    check("mass_center", row_major(data.mass_center[k]));
    check("omega", row_major(data.omega[k]));
    check("alpha", row_major(data.alpha[k]));
    check("velocity", row_major(data.mass_center_velocity[k]));
    check("acceleration", row_major(data.mass_center_acceleration[k]));
  }
  // Not a trivial state: the bodies move and accelerate.
  EXPECT_GT(scale.at("velocity"), 0.5);
  EXPECT_GT(scale.at("acceleration"), 1.0);
  EXPECT_EQ(bodies.array[15].at("name").string, "left_foot");
  EXPECT_EQ(bodies.array[15].at("lower").number, 15);
}

// "--state -" is standard input: the same JSON as from the file, and errors name the input.
TEST_F(MbkEval, StateDashReadsStandardInput) {
  const Output from_file = mbk(args);
  const Output from_stdin =
      mbk("eval --model config/human_body.yaml --state - < config/human_body_state.json");
  parse(from_stdin);
  EXPECT_EQ(from_stdin.out, from_file.out);

  const Output bad = mbk(
      "eval --model config/human_body.yaml --state - < test/io/data/unknown_coordinate_state.json");
  EXPECT_NE(bad.status, 0);
  EXPECT_EQ(bad.err.rfind("mbk: error: standard input", 0), 0u) << bad.err;
  EXPECT_NE(bad.err.find("unknown coordinate 'ghost'"), std::string::npos) << bad.err;
  const Output zero = mbk(
      "eval --model test/io/data/ball_euler.yaml --state - < test/io/data/zero_euler_state.json");
  EXPECT_NE(zero.status, 0);
  EXPECT_EQ(zero.err.rfind("mbk: error: standard input: body 2 'arm'", 0), 0u) << zero.err;
}

TEST_F(MbkEval, PartialVelocityMethodGivesTheSameNumbers) {
  const Json a = parse(mbk(args));
  const Json b = parse(mbk(args + " --method partial_velocity"));
  ASSERT_EQ(a.at("bodies").array.size(), 16u);
  ASSERT_EQ(b.at("bodies").array.size(), 16u);
  const std::map<std::string, double> scale = field_scales(a.at("bodies"));
  for (size_t k = 0; k < 16; ++k) {
    const Json& ba = a.at("bodies").array[k];
    const Json& bb = b.at("bodies").array[k];
    EXPECT_EQ(ba.at("name").string, bb.at("name").string);
    for (const std::string& field : kBodyFields) {
      if (ba.at(field).type != Json::kArray) continue;
      const size_t n = field == "rotation" ? 9 : 3;
      expect_near_all(numbers(bb, field, n), numbers(ba, field, n), scale.at(field),
                      ba.at("name").string + " " + field);
    }
  }
  EXPECT_EQ(mbk(args + " --method recursive").out, mbk(args).out);  // the default
}

// "system": M, p_G, v_G, a_G, M v_G as the core computes them; the angular momentum
// null with the bodies that lack an inertia named, or a vector when all have one.
void expect_system(const Json& system, const mbk::Model& model, const mbk::Data<double>& data) {
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model, data, s);
  const bool known = s.angular_momentum_known;
  std::vector<std::string> keys = {"mass",         "mass_center",     "velocity",
                                   "acceleration", "linear_momentum", "angular_momentum"};
  if (!known) keys.push_back("missing_inertia");
  ASSERT_EQ(system.keys(), keys);
  EXPECT_EQ(system.at("mass").number, s.mass);
  const double scale = std::max(1.0, s.acceleration.norm());
  expect_near_all(numbers(system, "mass_center", 3), row_major(s.mass_center), scale, "p_G");
  expect_near_all(numbers(system, "velocity", 3), row_major(s.velocity), scale, "v_G");
  expect_near_all(numbers(system, "acceleration", 3), row_major(s.acceleration), scale, "a_G");
  expect_near_all(numbers(system, "linear_momentum", 3), row_major(s.linear_momentum),
                  s.mass * scale, "M v_G");
  if (known) {
    expect_near_all(numbers(system, "angular_momentum", 3), row_major(s.angular_momentum),
                    s.mass * scale, "H_G");
    return;
  }
  EXPECT_EQ(system.at("angular_momentum").type, Json::kNull);
  std::vector<std::string> missing;
  for (const Json& name : system.at("missing_inertia").array) missing.push_back(name.string);
  EXPECT_EQ(missing, mbk::bodies_without_inertia(model));
  EXPECT_FALSE(missing.empty());
}

TEST_F(MbkEval, SystemQuantities) {
  const mbk::Model model = mbk::load_model_file(source_path("config/human_body.yaml"));
  const mbk::JointState<double> state =
      mbk::read_state_file(model, source_path("config/human_body_state.json"));
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  expect_system(parse(mbk(args)).at("system"), model, data);
  EXPECT_GT(parse(mbk(args)).at("system").at("mass").number, 70.0);  // about 79 kg
  // With inertias: a scene that gives every body one, written to a temporary file.
  const std::string path = "/tmp/mbk_cli_test_inertia.yaml";
  {
    std::ofstream out(path);
    out << "bodies:\n"
           "  - {name: a, lower: 0, joint: {type: ball_123}, mass_center: [0, 0, 0.3], mass: 2,"
           " inertia: [0.1, 0.2, 0.25, 0.01, 0, 0]}\n"
           "  - {name: b, lower: a, joint: {type: revolute, origin: [0, 0, 0.6], axis: [0, 1, 0]},"
           " mass_center: [0.2, 0, 0], mass: 1, inertia: [0.01, 0.05, 0.05, 0, 0, 0]}\n";
  }
  const mbk::Model with = mbk::load_model_file(path);
  {
    std::ofstream out("/tmp/mbk_cli_test_inertia_state.json");
    out << "{\"position\": {\"a_joint/alpha\": 0.3, \"a_joint/beta\": 0.4, "
           "\"a_joint/gamma\": 0.5, \"b_joint\": 0.6}, \"velocity\": {\"a_joint/alpha\": 1, "
           "\"a_joint/beta\": 0.6, \"a_joint/gamma\": 0.2, \"b_joint\": -0.2}, "
           "\"acceleration\": {\"a_joint/alpha\": 0, \"a_joint/beta\": 0.5, \"a_joint/gamma\": 1, "
           "\"b_joint\": 1.5}}\n";
  }
  const mbk::JointState<double> read =
      mbk::read_state_file(with, "/tmp/mbk_cli_test_inertia_state.json");
  mbk::Data<double> with_data(with);
  mbk::forward_kinematics(with, read, with_data);
  const Json doc =
      parse(mbk("eval --model " + path + " --state /tmp/mbk_cli_test_inertia_state.json"));
  expect_system(doc.at("system"), with, with_data);
  EXPECT_EQ(doc.at("system").at("angular_momentum").type, Json::kArray);
  std::remove(path.c_str());
  std::remove("/tmp/mbk_cli_test_inertia_state.json");
}

// --partial-velocities: per body the columns of the speeds of its own chain, keyed by speed
// name, and v_k = sum_r v_kr y_r, alpha_k = sum_r (omega_kr y_r' + omega_kr' y_r) hold with the
// printed numbers (1e-12 of the field's scale, as above).
TEST_F(MbkEval, PartialVelocitiesAreTheColumnsOfTheChain) {
  const mbk::Model model = mbk::load_model_file(source_path("config/human_body.yaml"));
  const mbk::JointState<double> state =
      mbk::read_state_file(model, source_path("config/human_body_state.json"));
  const Json doc = parse(mbk(args + " --partial-velocities"));
  const Json plain = parse(mbk(args));
  const Json& bodies = doc.at("bodies");
  ASSERT_EQ(bodies.array.size(), 16u);
  const std::map<std::string, double> scale = field_scales(plain.at("bodies"));
  mbk::PartialVelocities<double> pv(model);
  for (int k = 1; k <= 16; ++k) {
    const Json& body = bodies.array[k - 1];
    SCOPED_TRACE(model.bodies[k].name);
    std::vector<std::string> keys = kBodyKeys;
    for (const char* f :
         {"partial_omega", "partial_velocity", "partial_omega_dot", "partial_velocity_dot"})
      keys.push_back(f);
    ASSERT_EQ(body.keys(), keys);
    std::vector<std::string> chain;  // the speeds of Bk's chain, from R outward
    for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i)
      chain.push_back(model.speed_names[pv.speed[i]]);
    EXPECT_EQ(body.at("partial_omega").keys(), chain);
    EXPECT_EQ(body.at("partial_velocity_dot").keys(), chain);
    std::vector<double> v(3, 0.0), alpha(3, 0.0);
    for (const std::string& speed : chain) {
      const int r = model.speed_index(speed);
      const std::vector<double> vr = numbers(body.at("partial_velocity"), speed, 3);
      const std::vector<double> wr = numbers(body.at("partial_omega"), speed, 3);
      const std::vector<double> wdr = numbers(body.at("partial_omega_dot"), speed, 3);
      for (int i = 0; i < 3; ++i) {
        v[i] += vr[i] * state.velocity[r];
        alpha[i] += wr[i] * state.acceleration[r] + wdr[i] * state.velocity[r];
      }
    }
    expect_near_all(v, numbers(body, "velocity", 3), scale.at("velocity"), "v_k");
    expect_near_all(alpha, numbers(body, "alpha", 3), scale.at("alpha"), "alpha_k");
  }
  EXPECT_EQ(doc.at("system").keys(), plain.at("system").keys());
}

struct BadInput {
  const char* args;
  std::vector<std::string> fragments;  // in the error line
  bool usage;                          // a command-line mistake: the usage follows
};

TEST(MbkCli, BadInputIsAOneLineErrorAndNonZeroExit) {
  const BadInput cases[] = {
      {"tables --lower 0,1,3", {"body 3 has L(3) = 3"}, false},
      {"tables --lower 0,x,1", {"entry 2 ('x') is not an integer"}, false},
      {"tables --lower 1 --csv", {"body 1 has L(1) = 1"}, false},
      {"tables --lower ''", {"lower body array is empty"}, false},
      {"eval --model config/no_such_scene.yaml",
       {"config/no_such_scene.yaml", "cannot open"},
       false},
      {"tables --model config/no_such_robot.urdf",
       {"config/no_such_robot.urdf", "cannot open"},
       false},
      {"eval --model config/human_body.json",
       {"config/human_body.json", "unknown model file type"},
       false},
      {"eval --model test/io/data/bad_scene.yaml",
       {"test/io/data/bad_scene.yaml:6: malformed YAML"},
       false},
      {"eval --model config/human_body.yaml --state test/io/data/unknown_coordinate_state.json",
       {"test/io/data/unknown_coordinate_state.json", "unknown coordinate 'ghost'"},
       false},
      {"eval --model config/human_body.yaml --state test/io/data/no_such_state.json",
       {"test/io/data/no_such_state.json", "cannot open state file"},
       false},
      {"eval --model test/io/data/ball_euler.yaml --state test/io/data/zero_euler_state.json",
       {"zero_euler_state.json", "body 2 'arm'", "shoulder/e1..e4", "Euler parameters",
        "below 1e-12"},
       false},
      {"eval --model test/io/data/ball_euler.yaml --state test/io/data/zero_euler_state.json "
       "--method partial_velocity",
       {"body 2 'arm'", "Euler parameters", "below 1e-12"},
       false},
      {"urdf --model test/io/data/ball_euler.yaml", {"'shoulder'", "no URDF equivalent"}, false},
      {"tables --lower 0,1 --colour", {"unknown or incomplete option '--colour'"}, true},
      {"tables --lower", {"unknown or incomplete option '--lower'"}, true},
      {"tables", {"exactly one of --lower and --model"}, true},
      {"tables --lower 0 --model config/human_body.yaml", {"exactly one of"}, true},
      {"eval --state config/human_body_state.json", {"eval needs --model"}, true},
      {"eval --model config/human_body.yaml --method magic", {"unknown --method 'magic'"}, true},
      {"draw --model config/human_body.yaml", {"unknown command 'draw'"}, true},
  };
  for (const BadInput& c : cases) {
    SCOPED_TRACE(std::string("mbk ") + c.args);
    const Output run = mbk(c.args);
    EXPECT_NE(run.status, 0);
    EXPECT_EQ(run.out, "") << "stdout must stay empty";
    const size_t eol = run.err.find('\n');
    ASSERT_NE(eol, std::string::npos) << run.err;
    const std::string line = run.err.substr(0, eol);
    EXPECT_EQ(line.rfind("mbk: error: ", 0), 0u) << line;
    for (const std::string& fragment : c.fragments)
      EXPECT_NE(line.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << line;
    const std::string rest = run.err.substr(eol + 1);
    if (c.usage)
      EXPECT_EQ(rest.rfind("usage: mbk", 0), 0u) << rest;
    else
      EXPECT_EQ(rest, "") << "more than one line";
  }
}

// Writes `text` to a temporary file with the given suffix; removed with the object.
struct TempFile {
  std::string path;
  TempFile(const std::string& text, const std::string& suffix) {
    char name[] = "/tmp/mbk_cli_test_XXXXXX";
    const int fd = mkstemp(name);
    if (fd < 0) throw std::runtime_error("mkstemp failed");
    close(fd);
    std::remove(name);
    path = std::string(name) + suffix;
    std::ofstream(path) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

// Body names with a quote, a backslash and control characters: valid JSON, the same names.
TEST(MbkCli, EvalEscapesNamesInJson) {
  const TempFile scene(
      "frame: \"R\\\"0\"\nbodies:\n"
      "  - {name: \"a\\\"b\", lower: 0, joint: {type: revolute}}\n"
      "  - {name: \"c\\\\d\", lower: 1, joint: {type: revolute}}\n"
      "  - {name: \"e\\nf\\tg\\x01h\", lower: 2, joint: {type: revolute}}\n",
      ".yaml");
  const Output run = mbk("eval --model " + scene.path);
  ASSERT_EQ(run.status, 0) << run.err;
  Json doc;
  ASSERT_NO_THROW(doc = JsonReader(run.out).document()) << run.out;
  EXPECT_EQ(doc.at("frame").string, "R\"0");
  const std::vector<Json>& bodies = doc.at("bodies").array;
  ASSERT_EQ(bodies.size(), 3u);
  EXPECT_EQ(bodies[0].at("name").string, "a\"b");
  EXPECT_EQ(bodies[1].at("name").string, "c\\d");
  EXPECT_EQ(bodies[2].at("name").string, "e\nf\tg\x01h");
}

// Names with XML's special characters: a URDF that loads, with the same names.
TEST(MbkCli, UrdfEscapesNames) {
  const TempFile scene(
      "bodies:\n  - {name: 'a\"b', lower: 0, joint: {name: 'j<1>', type: ball_123}}\n"
      "  - {name: 'c&d', lower: 1, joint: {name: \"j'2\", type: revolute}}\n",
      ".yaml");
  const Output run = mbk("urdf --model " + scene.path + " --name 'r&\"'");
  ASSERT_EQ(run.status, 0) << run.err;
  const mbk::Model back = mbk::load_urdf_string(run.out, "out.urdf");
  EXPECT_GE(back.body_index("a\"b"), 1);
  EXPECT_GE(back.body_index("c&d"), 1);
  EXPECT_GE(back.coordinate_index("j<1>/gamma"), 0);
  EXPECT_GE(back.coordinate_index("j'2"), 0);
}

// A chain deeper than 1000 (the table's label column once underflowed: "basic_string::
// _M_create") and with more than 999 bodies (entries of four digits).
TEST(MbkCli, TablesOfADeepChain) {
  std::string lower = "0";
  for (int k = 2; k <= 1100; ++k) lower += "," + std::to_string(k - 1);
  for (const char* csv : {"", " --csv"}) {
    const Output run = mbk("tables --lower " + lower + csv);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    std::istringstream out(run.out);
    std::vector<std::string> lines;
    for (std::string line; std::getline(out, line);) lines.push_back(line);
    ASSERT_EQ(lines.size(), *csv ? 1101u : 1102u);  // t = 0..1100 (and the header)
    std::string zeros = "0";
    for (int k = 2; k <= 1100; ++k) zeros += ",0";
    if (*csv)
      EXPECT_EQ(lines.back(), zeros);
    else
      EXPECT_EQ(words(lines.back()), (std::vector<std::string>{"L^1100(k)", "0"}));
  }
}

// The one-line error holds user text with newlines escaped.
TEST(MbkCli, ErrorsWithNewlinesInTheInputStayOneLine) {
  const Output run = mbk("tables --lower \"$(printf '0,1,x\\ny')\"");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(run.err, "mbk: error: lower body array: entry 3 ('x\\ny') is not an integer\n");
}

// urdfdom's own output (console_bridge) once added four lines to the error.
TEST(MbkCli, BadUrdfIsOneLine) {
  const TempFile robot(
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"><inertial><mass value=\"x\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>"
      "<joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>"
      "</robot>",
      ".urdf");
  const Output run = mbk("eval --model " + robot.path);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
  EXPECT_NE(run.err.find("mass [x]"), std::string::npos) << run.err;
}

// A URDF with an inertia that is not physical loads: mbk prints the warning once on stderr, exits
// 0, and leaves the angular momentum out.
TEST(MbkCli, UnphysicalUrdfInertiaIsOneWarningAndExitZero) {
  const TempFile robot(
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"><inertial><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"5\"/></inertial></link>"
      "<joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>"
      "</robot>",
      ".urdf");
  for (const char* command : {"eval", "tables"}) {
    const Output run = mbk(std::string(command) + " --model " + robot.path);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;  // one line
    EXPECT_EQ(run.err.rfind("mbk: warning: " + robot.path + ": inertia not physical", 0), 0u)
        << run.err;
    EXPECT_NE(run.err.find("'b' inertia violates the triangle inequality"), std::string::npos);
  }
  EXPECT_NE(mbk("eval --model " + robot.path).out.find("\"missing_inertia\""), std::string::npos);
}

// A xacro model (what most robots ship) is refused with the command that expands it, one line.
TEST(MbkCli, XacroModelSaysHowToExpandIt) {
  const TempFile robot("<robot name=\"r\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\"/>",
                       ".urdf.xacro");
  const Output run = mbk("eval --model " + robot.path);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
  EXPECT_NE(run.err.find("a xacro file: expand it first (xacro " + robot.path + " > robot.urdf"),
            std::string::npos)
      << run.err;
}

TEST(MbkCli, EulerSceneWithAValidStateWorks) {  // the zero-norm failure above is the state's
  const Output run = mbk("eval --model test/io/data/ball_euler.yaml");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(JsonReader(run.out).document().at("bodies").array.size(), 2u);
}

// A BVH recording as the model: its skeleton's tables, a frame's kinematics (the segment
// parameters for --body-mass in the system), the options refused for other models.
// `mbk COMMAND --help` prints that command's usage on stdout and exits 0; `mbk --help` all.
TEST(MbkCli, HelpPrintsTheUsage) {
  for (const std::string command : {"tables", "eval", "urdf"}) {
    const Output help = mbk(command + " --help");
    EXPECT_EQ(help.status, 0) << command << ": " << help.err;
    EXPECT_EQ(help.err, "") << command;
    EXPECT_EQ(help.out.rfind("usage: mbk " + command + " ", 0), 0u) << help.out;
  }
  EXPECT_NE(mbk("eval --model x.bvh -h").out.find("--segments MAP.yaml"), std::string::npos);
  const Output all = mbk("--help");
  EXPECT_EQ(all.status, 0);
  EXPECT_NE(all.out.find("mbk COMMAND --help"), std::string::npos) << all.out;
  EXPECT_EQ(mbk("nosuch --help").status, 1);
}

TEST(MbkCli, ABvhFileIsAModel) {
  const std::string walk = "--model test/io/data/cmu_walk.bvh";
  const Output tables = mbk("tables --csv " + walk + " --scale 0.01");
  EXPECT_EQ(tables.status, 0) << tables.err;
  EXPECT_EQ(tables.err, "");
  EXPECT_EQ(tables.out.substr(0, tables.out.find('\n', tables.out.find('\n') + 1)),
            "1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,26,27,28,29\n"
            "0,1,2,3,4,5,1,7,8,9,10,1,12,13,14,15,16,14,18,19,20,21,21,14,24,25,26,27,27");
  const Output eval =
      mbk("eval " + walk + " --scale 0.01 --body-mass 61.5 --sex female --frame 15");
  EXPECT_EQ(eval.status, 0) << eval.err;
  EXPECT_EQ(eval.err, "");
  const Json doc = JsonReader(eval.out).document();
  EXPECT_NEAR(doc.at("system").at("mass").number, 61.5, 1e-12 * 61.5);
  EXPECT_EQ(doc.at("system").at("angular_momentum").type, Json::kArray);
  const mbk::BvhFile bvh = mbk::read_bvh(source_path("test/io/data/cmu_walk.bvh"));
  const mbk::Model model = mbk::model_from_bvh(bvh, {0.01, 61.5, "female"});
  mbk::JointState<double> state(model);
  const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, model, 15, 0.01);
  state.position = Eigen::Map<const Eigen::VectorXd>(q.data(), q.size());
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  const Json& bodies = doc.at("bodies");
  ASSERT_EQ(static_cast<int>(bodies.array.size()), model.body_count());
  for (int k = 1; k <= model.body_count(); ++k)
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(bodies.array[k - 1].at("origin").array[i].number, data.origin[k][i], 1e-12);
  // Each body's mass, local mass center r_k and inertia, to inspect the segments' mapping.
  for (int k = 1; k <= model.body_count(); ++k) {
    const Json& b = bodies.array[k - 1];
    const mbk::Body& body = model.bodies[k];
    EXPECT_EQ(b.at("mass").number, body.mass) << body.name;
    for (int i = 0; i < 3; ++i)
      EXPECT_EQ(b.at("local_mass_center").array[i].number, body.mass_center[i]) << body.name;
    if (!body.has_inertia) {
      EXPECT_EQ(b.at("inertia").type, Json::kNull) << body.name;
      continue;
    }
    ASSERT_EQ(b.at("inertia").array.size(), 9u) << body.name;
    for (int i = 0; i < 9; ++i)
      EXPECT_EQ(b.at("inertia").array[i].number, body.inertia(i / 3, i % 3)) << body.name;
  }
  EXPECT_GT(bodies.array[model.body_index("LeftUpLeg") - 1].at("mass").number, 5.0);
  // mbk urdf of the skeleton: the same bodies at the same places, the same masses.
  const Output urdf_run = mbk("urdf " + walk + " --scale 0.01 --body-mass 61.5 --sex female");
  ASSERT_EQ(urdf_run.status, 0) << urdf_run.err;
  const mbk::Model urdf = mbk::load_urdf_string(urdf_run.out, "walk.urdf");
  mbk::JointState<double> urdf_state(urdf);
  for (int i = 0; i < model.nq; ++i)
    urdf_state.position[urdf.coordinate_index(model.coordinate_names[i])] = q[i];
  mbk::Data<double> urdf_data(urdf);
  mbk::forward_kinematics(urdf, urdf_state, urdf_data);
  double urdf_mass = 0;
  for (const mbk::Body& b : urdf.bodies) urdf_mass += b.mass;
  EXPECT_NEAR(urdf_mass, 61.5, 1e-9);
  for (int k = 1; k <= model.body_count(); ++k) {
    const int u = urdf.body_index(model.bodies[k].name);
    ASSERT_GE(u, 0) << model.bodies[k].name;
    EXPECT_LT((urdf_data.origin[u] - data.origin[k]).norm(), 1e-12) << model.bodies[k].name;
    EXPECT_LT((urdf_data.mass_center[u] - data.mass_center[k]).norm(), 1e-9)
        << model.bodies[k].name;
  }
  const Output unscaled = mbk("urdf " + walk);
  EXPECT_EQ(unscaled.status, 0);
  EXPECT_NE(unscaled.err.find("mbk: warning: test/io/data/cmu_walk.bvh: the skeleton's standing "
                              "height is 172 m"),
            std::string::npos)
      << unscaled.err;
  const Output late = mbk("eval " + walk + " --frame 40");
  EXPECT_EQ(late.status, 1);
  EXPECT_NE(late.err.find("mbk: error: test/io/data/cmu_walk.bvh: frame 40 does not exist (the "
                          "file has frames 0 to 39)\n"),
            std::string::npos)
      << late.err;
  const Output yaml = mbk("eval --model config/human_body.yaml --body-mass 70");
  EXPECT_EQ(yaml.status, 1);
  EXPECT_EQ(yaml.err.rfind("mbk: error: --scale, --body-mass, --sex, --segments, --anthropometry "
                           "and --frame apply to a .bvh model only\nusage:",
                           0),
            0u)
      << yaml.err;
  EXPECT_EQ(mbk("eval " + walk + " --scale 0.01 --sex other").err,
            "mbk: error: sex: 'other' is neither male nor female (de Leva's columns)\n");
}

// Without --state, mbk eval evaluates the state an empty STATE.json gives: a mimic with
// multiplier 2 and offset 0.5 sits at 0.5, not at 0 (its rule applied on both paths).
TEST(MbkCli, EvalWithoutAStateAppliesTheMimicRules) {
  const std::string dir = ::testing::TempDir();
  const std::string urdf = dir + "mimic_offset.urdf", state = dir + "empty_state.json";
  std::ofstream(urdf) << "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
                         "<joint name=\"j\" type=\"continuous\"><parent link=\"a\"/>"
                         "<child link=\"b\"/></joint>"
                         "<joint name=\"m\" type=\"continuous\"><parent link=\"b\"/>"
                         "<child link=\"c\"/><origin xyz=\"1 0 0\"/>"
                         "<mimic joint=\"j\" multiplier=\"2\" offset=\"0.5\"/></joint></robot>";
  std::ofstream(state) << "{}";
  const Output bare = mbk("eval --model " + urdf);
  const Output empty = mbk("eval --model " + urdf + " --state " + state);
  ASSERT_EQ(bare.status, 0) << bare.err;
  ASSERT_EQ(empty.status, 0) << empty.err;
  EXPECT_EQ(bare.out, empty.out);
  const mbk::Model model = mbk::load_urdf_file(urdf);
  EXPECT_EQ(mbk::read_state_file(model, state).position[1], 0.5);
}

// mbk bag's error lines escape control bytes as mbk eval's do (core/printable.h): an ANSI escape in
// a CSV cell and a newline in a path are written as \x1b and \n, one line of text.
TEST(MbkCli, BagErrorLinesEscapeControlBytes) {
  const std::string dir = ::testing::TempDir();
  const std::string csv = dir + "ansi.csv";
  std::ofstream(csv) << "time,Hips/x\n0,\x1b[31mred\n";
  const Output cell = mbk("bag " + csv + " --model config/human_body.yaml --csv " + dir + "a.csv");
  const Output path =
      mbk("bag '" + dir + "new\nline.csv' --model config/human_body.yaml --csv " + dir + "b.csv");
  for (const Output* run : {&cell, &path}) {
    EXPECT_EQ(run->status, 1) << run->err;
    EXPECT_EQ(run->err.rfind("mbk: error: ", 0), 0u) << run->err;
    EXPECT_EQ(std::count(run->err.begin(), run->err.end(), '\n'), 1) << run->err;
    EXPECT_EQ(run->err.find('\x1b'), std::string::npos) << run->err;
  }
  EXPECT_NE(cell.err.find("'\\x1b[31mred' is not a number"), std::string::npos) << cell.err;
  EXPECT_NE(path.err.find("new\\nline.csv"), std::string::npos) << path.err;
}

// A NUL in a state's name, raw or as JSON's \u0000, is escaped: it would end the C string that
// the error is printed from.
TEST(MbkCli, EvalErrorsShowANulInANameWhole) {
  const std::string dir = ::testing::TempDir();
  const std::string raw = dir + "nul_raw_state.json", escaped = dir + "nul_escaped_state.json";
  const char raw_text[] = "{\"position\": {\"ab\0cd\": 1}}";
  std::ofstream(raw) << std::string(raw_text, sizeof raw_text - 1);
  std::ofstream(escaped) << "{\"velocity\": {\"ab\\u0000cd\": 1}}";
  const std::string model = " --model config/human_body.yaml --state ";
  const Output raw_run = mbk("eval" + model + raw);
  EXPECT_EQ(raw_run.status, 1);
  EXPECT_EQ(raw_run.err, "mbk: error: " + raw + ": position: unknown coordinate 'ab\\x00cd'\n");
  const Output escaped_run = mbk("eval" + model + escaped);
  EXPECT_EQ(escaped_run.status, 1);
  EXPECT_EQ(escaped_run.err,
            "mbk: error: " + escaped + ": velocity: unknown coordinate 'ab\\x00cd'\n");
}

// A NUL in a YAML scene's name (YAML's "\\0") is escaped the same way.
TEST(MbkCli, EvalErrorsShowANulInASceneNameWhole) {
  const std::string scene = ::testing::TempDir() + "nul_scene.yaml";
  std::ofstream(scene) << "frame: world\nbodies:\n"
                          "  - {name: a, lower: \"no\\0such\", joint: {name: j, type: revolute, "
                          "origin: [0, 0, 0], axis: [0, 0, 1]}, mass_center: [0, 0, 0], mass: 1}\n";
  const Output run = mbk("eval --model " + scene);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.err, "mbk: error: " + scene +
                         ":3: body 1 lower 'no\\x00such' is neither an earlier body's name nor a "
                         "number below 1\n");
}

// The text of a file, one string per line.
std::vector<std::string> file_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A CSV line's cells.
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

// A 1e300 and a -1e30 in a BVH's Hips/x and Hips/y: noted by coordinate and frame, excluded; no
// cell of any output is NaN or inf (before: the noise level was inf and the error bars -nan), and
// what the other coordinates give (every body's omega, alpha and their error bars) is as without.
TEST(MbkCli, BagExcludesAGrossOutlierAndWritesNoNan) {
  const std::string dir = ::testing::TempDir();
  std::vector<std::string> lines = file_lines(source_path("test/io/data/cmu_walk.bvh"));
  const size_t first =
      std::find_if(lines.begin(), lines.end(),
                   [](const std::string& l) { return l.rfind("Frame Time", 0) == 0; }) -
      lines.begin() + 1;
  auto replace_cell = [&](int frame, int column, const std::string& value) {
    std::vector<std::string> words;
    std::istringstream in(lines[first + frame]);
    for (std::string w; in >> w;) words.push_back(w);
    words[column] = value;
    std::string line;
    for (const std::string& w : words) line += (line.empty() ? "" : " ") + w;
    lines[first + frame] = line;
  };
  replace_cell(15, 0, "1e300");
  replace_cell(28, 1, "-1e30");
  const std::string spiky = dir + "spiky_walk.bvh";
  std::ofstream out(spiky);
  for (const std::string& line : lines) out << line << "\n";
  out.close();
  const std::string options = " --scale 0.01 --body-mass 61.5 --csv ";
  const Output clean = mbk("bag test/io/data/cmu_walk.bvh" + options + dir + "clean_walk.csv");
  const Output run = mbk("bag " + spiky + options + dir + "spiky_walk.csv");
  ASSERT_EQ(clean.status, 0) << clean.err;
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("note 2 samples: outliers excluded"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("frame 15 (t = 0.266667): coordinate 'Hips/x' is 1e+298"),
            std::string::npos)
      << run.err;
  for (const char* file :
       {"spiky_walk.csv", "spiky_walk.errors.csv", "spiky_walk.sample_errors.csv"}) {
    const std::vector<std::string> written = file_lines(dir + file);
    EXPECT_GT(written.size(), 1u) << file;
    for (std::string line : written) {
      std::transform(line.begin(), line.end(), line.begin(), ::tolower);
      EXPECT_EQ(line.find("nan"), std::string::npos) << file << ": " << line;
      EXPECT_EQ(line.find("inf"), std::string::npos) << file << ": " << line;
    }
  }
  const std::vector<std::string> a = file_lines(dir + "clean_walk.csv"),
                                 b = file_lines(dir + "spiky_walk.csv");
  ASSERT_EQ(a.size(), b.size());
  const std::vector<std::string> header = cells(a[0]);
  for (size_t i = 1; i < a.size(); ++i) {
    const std::vector<std::string> x = cells(a[i]), y = cells(b[i]);
    ASSERT_EQ(x.size(), y.size());
    for (size_t c = 0; c < x.size(); ++c) {
      const std::string& name = header[c];
      const bool other =
          name.rfind("omega", 0) == 0 || name.rfind("alpha", 0) == 0 || name == "origin_z";
      EXPECT_TRUE(!other || x[c] == y[c]) << name << " line " << i << ": " << x[c] << " " << y[c];
    }
  }
}

// No raw control byte reaches the terminal: `run`'s stderr holds none (a NUL, \v, an ANSI
// escape) and each of `shown` as escaped text.
void expect_escaped(const Output& run, const std::vector<std::string>& shown) {
  for (char c : {'\0', '\v', '\x1b'})
    EXPECT_EQ(run.err.find(c), std::string::npos) << static_cast<int>(c) << ": " << run.err;
  for (const std::string& text : shown)
    EXPECT_NE(run.err.find(text), std::string::npos) << text << " in " << run.err;
}

// Names with a NUL, \v and an ANSI escape in a BVH joint and a URDF link and joint: every error,
// drop, note and summary line of mbk eval and mbk bag shows them escaped (core/printable.h), and
// whole (before: a NUL in a BVH name or a YAML body name cut the error there; mbk bag's summary
// wrote the bytes raw).
TEST(MbkCli, NamesWithControlBytesAreEscapedInEveryLine) {
  const std::string dir = ::testing::TempDir();
  std::string walk;
  for (const std::string& line : file_lines(source_path("test/io/data/cmu_walk.bvh")))
    walk += line + "\n";
  const char raw[] = "Le\0ft\v\x1b[31mUpLeg";
  const std::string bad_name(raw, sizeof raw - 1);
  for (const char* joint : {"JOINT LeftUpLeg", "JOINT LeftLeg"})
    walk.replace(walk.find(joint), std::strlen(joint), "JOINT " + bad_name);
  const std::string bvh = dir + "control_names.bvh";
  std::ofstream(bvh) << walk;
  const std::string shown = "JOINT Le\\x00ft\\x0b\\x1b[31mUpLeg: a second segment of this name";
  for (const std::string& command :
       {"eval --model " + bvh, "bag " + bvh + " --csv " + dir + "control_names.csv"}) {
    const Output run = mbk(command);
    EXPECT_EQ(run.status, 1) << command;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    expect_escaped(run, {shown});
  }
  const std::string link = "b\x1b[31mX\vY", joint = "j\x1b[31m\v";
  const std::string inertia =
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>";
  auto robot = [&](const std::string& mass) {
    return "<robot name=\"r\"><link name=\"base\"/><link name=\"b&#27;[31mX&#11;Y\"><inertial>"
           "<mass value=\"" +
           mass + "\"/>" + inertia +
           "</inertial></link>"
           "<joint name=\"j&#27;[31m&#11;\" type=\"continuous\"><parent link=\"base\"/>"
           "<child link=\"b&#27;[31mX&#11;Y\"/></joint></robot>";
  };
  const TempFile bad_mass(robot("-1"), ".urdf"), good(robot("1"), ".urdf");
  std::string csv = "time," + joint + ",extra\x1b[32m\vcolumn\n";
  for (int i = 0; i < 50; ++i) {  // x = A t^3: accelerations 6 A t above 1e50 from t = 0.31 on
    char row[64];
    const double t = 0.01 * i;
    std::snprintf(row, sizeof row, "%.2f,%.17g,1\n", t, 1e50 / (6 * 0.305) * t * t * t);
    csv += row;
  }
  const TempFile recording(csv, ".csv");
  const std::string mass_error = "body 1 'b\\x1b[31mX\\x0bY': mass must be finite and >= 0";
  for (const std::string& command :
       {"eval --model " + bad_mass.path,
        "bag " + recording.path + " --model " + bad_mass.path + " --csv " + dir + "c.csv"}) {
    const Output run = mbk(command);
    EXPECT_EQ(run.status, 1) << command;
    expect_escaped(run, {mass_error});
  }
  const Output bag =
      mbk("bag " + recording.path + " --model " + good.path + " --verbose --csv " + dir + "d.csv");
  expect_escaped(bag, {"body 1 'b\\x1b[31mX\\x0bY', acceleration of 'j\\x1b[31m\\x0b'",
                       ": extra\\x1b[32m\\x0bcolumn)", "    j\\x1b[31m\\x0b: noise"});
}

// A run that needs more than --max-memory ends with one line naming it, and writes nothing
// (the kernel's out-of-memory killer would end it mid-write); the option takes GiB > 0.
TEST(MbkCli, BagRefusesToGrowBeyondMaxMemory) {
  const std::string out = ::testing::TempDir() + "capped_walk.csv";
  std::remove(out.c_str());
  const Output capped = mbk("bag test/mocap/131_01.bvh --csv " + out + " --max-memory 0.05");
#if defined(__SANITIZE_ADDRESS__)  // AddressSanitizer's shadow rules out the cap (memory_cap.cc)
  EXPECT_EQ(capped.status, 0) << capped.err;
  std::remove(out.c_str());
#else
  EXPECT_EQ(capped.status, 1);
  EXPECT_EQ(capped.err.substr(capped.err.find("mbk: error: ")),
            "mbk: error: out of memory: the run needs more than --max-memory 0.05 GiB of address "
            "space (default: 90 % of this machine's memory); give a larger --max-memory or fewer "
            "--threads\n");
  EXPECT_FALSE(std::ifstream(out).good());
#endif
  const Output zero = mbk("bag test/mocap/131_01.bvh --csv " + out + " --max-memory 0");
  EXPECT_EQ(zero.status, 1);
  EXPECT_EQ(zero.err, "mbk: error: --max-memory needs GiB > 0, not '0'\n");
  const Output enough = mbk("bag test/mocap/131_01.bvh --csv " + out + " --max-memory 2");
  EXPECT_EQ(enough.status, 0) << enough.err;
}

// `--max-gap 0` is refused (it silently meant the default), and so is an option given twice
// (the last one silently won).
TEST(MbkCli, BagRefusesAZeroMaxGapAndAnOptionGivenTwice) {
  const std::string in = ::testing::TempDir() + "twice.csv";
  std::ofstream(in) << "time\n1\n";
  const std::string bag = "bag " + in + " --model config/human_body.yaml ";
  const Output zero = mbk(bag + "--csv /dev/null --max-gap 0");
  EXPECT_EQ(zero.status, 1);
  EXPECT_NE(zero.err.find("--max-gap needs seconds > 0, not '0'"), std::string::npos) << zero.err;
  const Output twice = mbk(bag + "--csv /dev/null --csv /dev/null");
  EXPECT_EQ(twice.status, 1);
  EXPECT_NE(twice.err.find("--csv is given twice"), std::string::npos) << twice.err;
}

}  // namespace
