// Loading a BVH recording (doc/speed.md#reading-bvh): reading the file, unwrapping its rotations
// and building the model with the segment parameters for 70 kg, as `mbk bag FILE.bvh` does before
// it computes. By default the two CMU recordings of test/mocap/ (CMU units); more files as
// arguments FILE.bvh:SCALE, e.g. `bvh_load_benchmark big.bvh:0.01` for a file in centimetres.
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"

namespace {

void load(benchmark::State& state, const std::string& path, double scale) {
  mbk::BvhModelOptions options;
  options.scale = scale;
  options.body_mass = 70;
  for (auto _ : state) {
    mbk::BvhFile bvh = mbk::read_bvh(path);
    mbk::unwrap_rotations(bvh);
    benchmark::DoNotOptimize(mbk::model_from_bvh(bvh, options));
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const std::string mocap = std::string(MBK_SOURCE_DIR) + "/test/mocap/";
  std::vector<std::pair<std::string, double>> files = {{mocap + "131_01.bvh", 0.0254 / 0.45},
                                                       {mocap + "131_03.bvh", 0.0254 / 0.45}};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const size_t colon = arg.rfind(':');
    files.emplace_back(arg.substr(0, colon),
                       colon == std::string::npos ? 1.0 : std::stod(arg.substr(colon + 1)));
  }
  for (const auto& [path, scale] : files)
    benchmark::RegisterBenchmark(("load/" + path.substr(path.rfind('/') + 1)).c_str(), load, path,
                                 scale)
        ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
