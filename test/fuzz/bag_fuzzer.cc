// libFuzzer harness: whole bag files (bytes of a recorded bag, mutated) through mbk bag's reader
// (mb_kinematics/offline/bag_input.h) for the human body scene. A bag it cannot read is one
// std::invalid_argument with a one-line message; whatever it reads is counted (read, dropped or
// unreadable); anything else (a crash, a sanitizer report, an allocation beyond libFuzzer's
// -rss_limit_mb) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/bag_input.h"
#include "test/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mbk::Model model = mbk::load_model_file(MBK_SOURCE_DIR "/config/human_body.yaml");
  static const std::string path = "/tmp/mbk_bag_fuzz_" + std::to_string(getpid()) + ".bag";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), size);
  mbk::RecordingBuilder builder(model);
  mbk_offline::BaseOdometry base;
  mbk_offline::Unreadable unreadable;
  try {
    mbk_offline::read_bag(path, {}, builder, base, unreadable, [](long, long) {});
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::expect_one_line(e.what());
  }
  std::remove(path.c_str());
  return 0;
}
