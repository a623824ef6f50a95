// batch_kinematics (offline/batch_kinematics.h): every sample of a batch is, bit for bit, what
// `mbk eval` computes for that state (forward_kinematics, system_kinematics and the independent
// partial velocities), on any number of threads; only the fields asked for are written; float
// output is the double result rounded; a bad sample or request throws and writes nothing.
#include "mb_kinematics/offline/batch_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/kinematics_lanes.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/load_model.h"
#include "test/support/test_models.h"

namespace {

using mbk::BatchField;

// The same random tree as models()[1] with coordinate-derivative speeds.
mbk::Model coordinate_twin() { return mbk_test::random_tree(17, 9); }

// N samples of a smooth trajectory, row-major. A model with angular-velocity speeds takes its
// trajectory from `coordinate_model`, its twin with coordinate-derivative speeds.
struct Inputs {
  Inputs(const mbk::Model& model, int samples) {
    const bool angular = model.speeds == mbk::SpeedKind::kAngularVelocity;
    const mbk::Model twin = angular ? coordinate_twin() : model;
    const mbk_test::Trajectory trajectory(twin, 7);
    for (int s = 0; s < samples; ++s) {
      const double t = 0.013 * s;
      const mbk::JointState<double> state =
          angular ? mbk_test::state_with_angular_speeds(model, twin, trajectory, t)
                  : trajectory.at<double>(t);
      position.insert(position.end(), state.position.data(), state.position.data() + model.nq);
      velocity.insert(velocity.end(), state.velocity.data(), state.velocity.data() + model.nv);
      acceleration.insert(acceleration.end(), state.acceleration.data(),
                          state.acceleration.data() + model.nv);
    }
    in.samples = samples;
    in.position = position.data();
    in.velocity = velocity.data();
    in.acceleration = acceleration.data();
  }
  std::vector<double> position, velocity, acceleration;
  mbk::BatchInput in;
};

// Arrays for every field (or those of `fields`), filled with a sentinel.
template <typename T>
struct Outputs {
  Outputs(const mbk::Model& model, std::size_t samples, const std::vector<int>& bodies,
          std::vector<BatchField> fields = {}) {
    if (fields.empty())
      for (int f = 0; f < mbk::kBatchFieldCount; ++f) fields.push_back(static_cast<BatchField>(f));
    out.bodies = bodies;
    for (BatchField f : fields) {
      auto& a = arrays[static_cast<int>(f)];
      a.assign(samples * mbk::batch_field_size(model, f, bodies.size()), T(-7));
      out[f] = a.data();
    }
  }
  std::array<std::vector<T>, mbk::kBatchFieldCount> arrays;
  mbk::BatchOutput<T> out;
  const std::vector<T>& operator[](BatchField f) const { return arrays[static_cast<int>(f)]; }
};

std::vector<int> all_bodies(const mbk::Model& model) {
  std::vector<int> bodies;
  for (int k = 1; k <= model.body_count(); ++k) bodies.push_back(k);
  return bodies;
}

// Bitwise: -0.0 and NaN patterns count.
void expect_bits(double expected, double actual, const std::string& where) {
  EXPECT_EQ(0, std::memcmp(&expected, &actual, sizeof(double)))
      << where << ": " << expected << " vs " << actual;
}

void expect_vector(const mbk::Vec3<double>& expected, const double* actual,
                   const std::string& where) {
  for (int i = 0; i < 3; ++i) expect_bits(expected[i], actual[i], where);
}

// Sample s of `o` against `mbk eval`'s computation of that state.
void expect_eval(const mbk::Model& model, const Inputs& inputs, std::size_t s,
                 const Outputs<double>& o) {
  mbk::JointState<double> state(model);
  state.position = Eigen::Map<const Eigen::VectorXd>(&inputs.position[s * model.nq], model.nq);
  state.velocity = Eigen::Map<const Eigen::VectorXd>(&inputs.velocity[s * model.nv], model.nv);
  state.acceleration =
      Eigen::Map<const Eigen::VectorXd>(&inputs.acceleration[s * model.nv], model.nv);
  mbk::apply_mimics(model, state);
  mbk::Data<double> data(model), scratch(model);
  mbk::PartialVelocities<double> pv(model);
  mbk::partial_velocity_kinematics(model, state, pv, scratch);
  mbk::forward_kinematics(model, state, data);
  mbk::SystemKinematics<double> system;
  mbk::system_kinematics(model, data, system);
  const std::size_t nb = o.out.bodies.size(), nv = model.nv;
  for (std::size_t i = 0; i < nb; ++i) {
    const int k = o.out.bodies[i];
    const std::string where = "sample " + std::to_string(s) + " body " + std::to_string(k);
    const std::size_t row = s * nb + i;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        expect_bits(data.rotation[k](a, b), o[BatchField::kRotation][row * 9 + a * 3 + b], where);
    expect_vector(data.origin[k], &o[BatchField::kOrigin][row * 3], where + " origin");
    expect_vector(data.mass_center[k], &o[BatchField::kMassCenter][row * 3], where);
    expect_vector(data.omega[k], &o[BatchField::kOmega][row * 3], where + " omega");
    expect_vector(data.alpha[k], &o[BatchField::kAlpha][row * 3], where + " alpha");
    expect_vector(data.mass_center_velocity[k], &o[BatchField::kVelocity][row * 3], where);
    expect_vector(data.mass_center_acceleration[k], &o[BatchField::kAcceleration][row * 3], where);
    std::vector<char> seen(nv, 0);
    for (const mbk::SpeedColumn& c : mbk::independent_columns(model, pv, k)) {
      seen[c.speed] = 1;
      const std::size_t at = (row * nv + c.speed) * 3;
      expect_vector(c.omega, &o[BatchField::kPartialOmega][at], where + " partial_omega");
      expect_vector(c.velocity, &o[BatchField::kPartialVelocity][at], where);
      expect_vector(c.omega_dot, &o[BatchField::kPartialOmegaDot][at], where);
      expect_vector(c.velocity_dot, &o[BatchField::kPartialVelocityDot][at], where);
    }
    for (std::size_t r = 0; r < nv; ++r)
      if (!seen[r])
        expect_vector(mbk::Vec3<double>::Zero(), &o[BatchField::kPartialOmega][(row * nv + r) * 3],
                      where + " column outside the chain");
  }
  expect_bits(system.mass, o[BatchField::kSystemMass][s], "system mass");
  expect_vector(system.mass_center, &o[BatchField::kSystemMassCenter][s * 3], "system");
  expect_vector(system.velocity, &o[BatchField::kSystemVelocity][s * 3], "system velocity");
  expect_vector(system.acceleration, &o[BatchField::kSystemAcceleration][s * 3], "system");
  expect_vector(system.linear_momentum, &o[BatchField::kLinearMomentum][s * 3], "momentum");
  if (system.angular_momentum_known)
    expect_vector(system.angular_momentum, &o[BatchField::kAngularMomentum][s * 3], "H_G");
  else
    EXPECT_TRUE(std::isnan(o[BatchField::kAngularMomentum][s * 3]));
}

std::vector<mbk::Model> models() {
  std::vector<mbk::Model> out = {
      mbk_test::random_tree(23, 5), mbk_test::random_tree(17, 9, mbk::SpeedKind::kAngularVelocity),

      mbk::load_model_file(mbk_test::source_path("config/human_body.urdf")),
      mbk::load_model_file(mbk_test::source_path("test/robots/pr2.urdf"))};
  EXPECT_FALSE(out.back().mimics.empty()) << "pr2.urdf: the mimic joints this test needs";
  return out;
}

TEST(BatchKinematics, EverySampleIsEvalsBitForBit) {
  for (const mbk::Model& model : models()) {
    const Inputs inputs(model, 9);
    Outputs<double> o(model, 9, all_bodies(model));
    mbk::batch_kinematics(model, inputs.in, o.out, 1);
    for (std::size_t s = 0; s < 9; ++s) expect_eval(model, inputs, s, o);
  }
}

TEST(BatchKinematics, ChosenBodiesInTheirOrder) {
  const mbk::Model model = models()[2];
  const Inputs inputs(model, 4);
  const std::vector<int> chosen = {5, 2, 5, model.body_count()};
  Outputs<double> o(model, 4, chosen);
  mbk::batch_kinematics(model, inputs.in, o.out, 2);
  for (std::size_t s = 0; s < 4; ++s) expect_eval(model, inputs, s, o);
}

TEST(BatchKinematics, ThreadsGiveTheSameBits) {
  const mbk::Model model = models()[3];
  const Inputs inputs(model, 37);
  Outputs<double> one(model, 37, all_bodies(model));
  mbk::batch_kinematics(model, inputs.in, one.out, 1);
  for (int threads : {2, 3, 8, 0}) {
    Outputs<double> many(model, 37, all_bodies(model));
    mbk::batch_kinematics(model, inputs.in, many.out, threads);
    for (int f = 0; f < mbk::kBatchFieldCount; ++f)
      EXPECT_EQ(0, std::memcmp(one.arrays[f].data(), many.arrays[f].data(),
                               one.arrays[f].size() * sizeof(double)))
          << mbk::batch_field_traits(static_cast<BatchField>(f)).name << ", threads " << threads;
  }
}

TEST(BatchKinematics, OnlyTheFieldsAskedForAndTheirLevel) {
  const mbk::Model model = models()[2];
  Inputs inputs(model, 5);
  Outputs<double> all(model, 5, all_bodies(model));
  mbk::batch_kinematics(model, inputs.in, all.out, 1);
  inputs.in.velocity = inputs.in.acceleration = nullptr;  // a pose-only call needs neither
  Outputs<double> pose(model, 5, all_bodies(model), {BatchField::kRotation, BatchField::kOrigin});
  EXPECT_EQ(mbk::Level::kPose, mbk::batch_level(pose.out));
  mbk::batch_kinematics(model, inputs.in, pose.out, 1);
  EXPECT_EQ(all[BatchField::kRotation], pose[BatchField::kRotation]);
  EXPECT_EQ(all[BatchField::kOrigin], pose[BatchField::kOrigin]);
  EXPECT_TRUE(pose[BatchField::kOmega].empty());
  Outputs<double> omega(model, 5, all_bodies(model), {BatchField::kOmega});
  EXPECT_THROW(mbk::batch_kinematics(model, inputs.in, omega.out, 1), std::invalid_argument);
}

bool is_partial(BatchField f) {
  return f == BatchField::kPartialOmega || f == BatchField::kPartialVelocity ||
         f == BatchField::kPartialOmegaDot || f == BatchField::kPartialVelocityDot;
}

// How a batch is asked for in expect_rows_of_samples_alone.
struct Request {
  bool streamed = true;  // outputs above kBatchStreamBytes, or 23 samples written in place
  bool partials = true;  // with the partial velocities (every sample alone), or without (samples
                         // in lanes where the model and CPU allow it)
  int most_lanes = 8;    // batch_kinematics' most_lanes
};

// Every field of every sample (the partial velocities only with r.partials), one number past the
// start of each array (4 or 8 bytes off a 16-byte boundary), on `threads` threads, against each
// sample computed alone (in place, one at a time).
template <typename T>
void expect_rows_of_samples_alone(const mbk::Model& model, const std::vector<int>& bodies,
                                  int threads, Request r = {}) {
  std::array<std::size_t, mbk::kBatchFieldCount> size{};
  std::size_t bytes_per_sample = 0;
  for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
    if (!r.partials && is_partial(static_cast<BatchField>(f))) continue;
    size[f] = mbk::batch_field_size(model, static_cast<BatchField>(f), bodies.size());
    bytes_per_sample += size[f] * sizeof(T);
  }
  ASSERT_LT(bytes_per_sample, mbk::kBatchStreamBytes);
  const std::size_t samples = r.streamed ? mbk::kBatchStreamBytes / bytes_per_sample + 2 : 23;
  const Inputs inputs(model, static_cast<int>(samples));
  std::array<std::vector<T>, mbk::kBatchFieldCount> arrays;
  mbk::BatchOutput<T> out;
  out.bodies = bodies;
  for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
    arrays[f].assign(samples * size[f] + 2, T(-7));
    if (size[f] > 0) out.field[f] = arrays[f].data() + 1;
  }
  mbk::batch_kinematics(model, inputs.in, out, threads, r.most_lanes);
  for (std::size_t s = 0; s < samples; ++s) {
    mbk::BatchInput one = inputs.in;
    one.samples = 1;
    one.position += s * model.nq;
    one.velocity += s * model.nv;
    one.acceleration += s * model.nv;
    Outputs<T> alone(model, 1, bodies);
    mbk::batch_kinematics(model, one, alone.out, 1);
    for (int f = 0; f < mbk::kBatchFieldCount; ++f)
      ASSERT_EQ(
          0, std::memcmp(alone.arrays[f].data(), out.field[f] + s * size[f], size[f] * sizeof(T)))
          << mbk::batch_field_traits(static_cast<BatchField>(f)).name << ", sample " << s << " of "
          << samples << ", threads " << threads << ", most lanes " << r.most_lanes;
  }
  for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
    EXPECT_EQ(T(-7), arrays[f].front()) << "written before the array";
    EXPECT_EQ(T(-7), arrays[f].back()) << "written past the array";
  }
}

// Outputs above kBatchStreamBytes are computed into a staged row and streamed (stream_copy); with
// every body in order, doubles' vectors straight from Data.
TEST(BatchKinematics, StreamedOutputsAreTheSamplesAloneBitForBit) {
  for (const mbk::Model& model : {models()[2], models()[3]})
    for (const int threads : {1, 3}) {
      expect_rows_of_samples_alone<double>(model, all_bodies(model), threads);
      expect_rows_of_samples_alone<float>(model, all_bodies(model), threads);
      expect_rows_of_samples_alone<double>(model, {5, 2, 5, model.body_count()}, threads);
    }
}

// Without the partial velocities, a batch of doubles computes eight or four samples at once where
// the model and CPU allow it (core/kinematics_lanes.h; the human model and pr2 on AVX-512F and on
// AVX2 CPUs: eight, then four, then one at a time in each thread's run; four and one with
// most_lanes 4): still each sample alone bit for bit, the segment frames included, in place and
// streamed, for every body in order and chosen bodies.
TEST(BatchKinematics, SamplesInLanesAreTheSamplesAloneBitForBit) {
#ifdef MBK_AVX2_DISPATCH  // the lanes' build (not a sanitizer's)
  const int lanes = __builtin_cpu_supports("avx512f") ? 8 : __builtin_cpu_supports("avx2") ? 4 : 1;
  EXPECT_EQ(lanes, mbk::samples_at_once(models()[2])) << "the human model";
  EXPECT_EQ(lanes, mbk::samples_at_once(models()[3])) << "pr2";
#endif
  for (const mbk::Model& model : models())
    for (const int threads : {1, 3})
      for (const bool streamed : {false, true})
        for (const int most_lanes : {8, 4}) {
          const Request r{streamed, false, most_lanes};
          expect_rows_of_samples_alone<double>(model, all_bodies(model), threads, r);
          expect_rows_of_samples_alone<double>(model, {5, 2, 5, model.body_count()}, threads, r);
        }
}

TEST(BatchKinematics, FloatIsTheDoubleRounded) {
  const mbk::Model model = models()[0];
  const Inputs inputs(model, 6);
  Outputs<double> d(model, 6, all_bodies(model));
  Outputs<float> f(model, 6, all_bodies(model));
  mbk::batch_kinematics(model, inputs.in, d.out, 2);
  mbk::batch_kinematics(model, inputs.in, f.out, 2);
  for (int field = 0; field < mbk::kBatchFieldCount; ++field)
    for (std::size_t i = 0; i < d.arrays[field].size(); ++i) {
      const float expected = static_cast<float>(d.arrays[field][i]);
      if (std::isnan(expected))  // no inertia: no angular momentum in either
        ASSERT_TRUE(std::isnan(f.arrays[field][i])) << field << " " << i;
      else
        ASSERT_EQ(expected, f.arrays[field][i]) << field << " " << i;
    }
}

TEST(BatchKinematics, BadSampleThrowsNamingItAndWritesNothing) {
  const mbk::Model model = models()[2];
  Inputs inputs(model, 40);
  inputs.position[31 * model.nq + 4] = std::numeric_limits<double>::quiet_NaN();
  inputs.velocity[33 * model.nv + 2] = std::numeric_limits<double>::infinity();
  for (int threads : {1, 2, 4}) {
    Outputs<double> o(model, 40, all_bodies(model));
    try {
      mbk::batch_kinematics(model, inputs.in, o.out, threads);
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(0u, what.find("sample 31: ")) << what;
      EXPECT_NE(std::string::npos, what.find(model.coordinate_names[4])) << what;
    }
    for (const auto& a : o.arrays)
      for (double x : a) ASSERT_EQ(-7.0, x) << "written before the check";
  }
  Outputs<double> o(model, 40, {0});
  EXPECT_THROW(mbk::batch_kinematics(model, inputs.in, o.out, 1), std::invalid_argument);
}

TEST(BatchKinematics, FieldNames) {
  for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
    const auto field = static_cast<BatchField>(f);
    EXPECT_EQ(field, mbk::batch_field_from_name(mbk::batch_field_traits(field).name));
  }
  EXPECT_THROW(mbk::batch_field_from_name("rotations"), std::invalid_argument);
}

TEST(LoadModel, TextOrFileName) {
  const std::string urdf =
      "<robot name='r'><link name='a'/><link name='b'/>"
      "<joint name='j' type='continuous'><parent link='a'/><child link='b'/></joint></robot>";
  EXPECT_TRUE(mbk::is_model_text(urdf));
  EXPECT_EQ(1, mbk::load_model("  \n" + urdf).body_count());
  const mbk::Model scene = mbk::load_model(
      "bodies:\n  - {name: a, lower: 0, joint: {name: j, type: revolute}, mass: 1}\n", nullptr,
      "scene");
  EXPECT_EQ("a", scene.bodies[1].name);
  EXPECT_FALSE(mbk::is_model_text(mbk_test::source_path("config/ten_body.yaml")));
  EXPECT_EQ(10, mbk::load_model(mbk_test::source_path("config/ten_body.yaml")).body_count());
  const mbk::BvhModelOptions bvh;
  EXPECT_THROW(mbk::load_model(urdf, &bvh), std::invalid_argument);
  EXPECT_THROW(mbk::load_model(mbk_test::source_path("config/ten_body.yaml"), &bvh),
               std::invalid_argument);
  try {
    mbk::load_model("<robot name='r'><link name='a'/>", nullptr, "robot_description");
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(0u, std::string(e.what()).find("robot_description")) << e.what();
  }
}

}  // namespace
