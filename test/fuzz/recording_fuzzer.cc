// libFuzzer harness: a trajectory CSV (`time,<coordinate>,...`) of the ten-body scene read as
// `mbk bag` and the Python module's read_recording read it (offline/trajectory_csv.h, the
// RecordingBuilder), then every row's joint state as Model.states() computes it
// (offline/recording_states.h) with the input's first byte choosing the estimator. Refused with
// one std::invalid_argument line, or: stamps increasing, and a row given as valid (no drop
// reason) has a finite position, velocity and acceleration.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "mb_kinematics/io/yaml_scene.h"
#include "mb_kinematics/offline/recording.h"
#include "mb_kinematics/offline/recording_states.h"
#include "mb_kinematics/offline/trajectory_csv.h"
#include "test/fuzz/fuzz_support.h"

namespace {

// The scene with coordinate-derivative speeds, as mbk bag and read_recording take it.
const mbk::Model& scene() {
  static const mbk::Model model = [] {
    mbk::Model m = mbk::load_yaml_scene_file(mbk_fuzz::source_path("config/ten_body.yaml"));
    m.speeds = mbk::SpeedKind::kCoordinateDerivatives;
    mbk::finalize_model(m);
    return m;
  }();
  return model;
}

// The input as a CSV file of this process's own (read_trajectory_csv reads a path).
std::string write_csv(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/mbk_recording_fuzz_" + std::to_string(getpid()) + ".csv";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) mbk_fuzz::finding("cannot write " + path);
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

void expect_finite_rows(const mbk::Recording& recording, const mbk::RecordingStates& states) {
  for (int r = 1; r < recording.rows(); ++r)
    if (!(recording.stamp[r] > recording.stamp[r - 1])) mbk_fuzz::finding("stamps not increasing");
  const std::size_t nq = static_cast<std::size_t>(recording.nq);
  for (std::size_t r = 0; r < states.drop_reason.size(); ++r) {
    if (!states.drop_reason[r].empty()) continue;
    for (std::size_t i = r * nq; i < (r + 1) * nq; ++i)
      if (!std::isfinite(states.position[i]) || !std::isfinite(states.velocity[i]) ||
          !std::isfinite(states.acceleration[i]))
        mbk_fuzz::finding("row " + std::to_string(r) + " valid but not finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kEstimators[] = {"auto", "centered_5_2", "centered_0.1s_4"};
  if (size == 0) return 0;
  const char* estimator = kEstimators[data[0] % 3];
  const std::string path = write_csv(data + 1, size - 1);
  mbk::RecordingBuilder builder(scene());
  try {
    mbk::read_trajectory_csv(path, builder);
    const mbk::Recording recording = builder.finish();
    expect_finite_rows(recording, mbk::recording_states(scene(), recording, estimator, 0));
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::expect_one_line(e.what());
  }
  return 0;
}
