// One update of the kinematics, ours and Orocos KDL's, on the human body model and on revolute
// chains of 10, 100 and 1000 bodies.
//
//   ours/<model>/<recursive|pv>/<pose|velocity|full>
//       forward_kinematics (doc/method.md 4) or partial_velocity_kinematics (doc/method.md 5) at
//       Level::kPose, kVelocity, kAcceleration ("full": orientation, origin, mass center, omega,
//       alpha, velocity and acceleration of every body).
//   kdl/<model>/tree_pose_all_links   TreeFkSolverPos_recursive::JntToCart for every link
//                                     (what robot_state_publisher's users get: poses only)
//   kdl/<model>/chain_pose_longest    ChainFkSolverPos_recursive, all frames of the longest chain
//   kdl/<model>/chain_vel_longest     ChainFkSolverVel_recursive, tip twist of the longest chain
//   (KDL has no forward acceleration solver.)
//
// Models: human = config/human_body.yaml (16 bodies, ball joints as such); human_urdf =
// config/human_body.urdf loaded by our URDF loader (37 links: ball and free joints expanded into
// one-axis joints, the same links KDL computes); chainN = N revolute bodies, axes alternating z, y,
// links of 1 m along x (mbk::make_chain), given to KDL as URDF by write_urdf.
// Each iteration nudges one coordinate and speed so that nothing is computed once and reused.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainfksolvervel_recursive.hpp>
#include <kdl/frames.hpp>
#include <kdl/framevel.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntarrayvel.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_writer.h"

namespace {

std::string source_path(const std::string& relative) {
  return std::string(MBK_SOURCE_DIR) + "/" + relative;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "cannot open %s\n", path.c_str());
    std::exit(1);
  }
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

mbk::JointState<double> random_state(const mbk::Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  return mbk::random_state(model, rng);
}

// Nudges coordinate i % n by a tiny amount: the state differs every iteration at no real cost.
inline void nudge(double* q, double* v, int n, int64_t i) {
  const int c = static_cast<int>(i % n);
  q[c] += 1e-9;
  if (v) v[c] -= 1e-9;
}

void ours_recursive(benchmark::State& st, const mbk::Model* model, mbk::Level level) {
  mbk::JointState<double> state = random_state(*model, 1);
  mbk::Data<double> data(*model);
  int64_t i = 0;
  for (auto _ : st) {
    nudge(state.position.data(), state.velocity.data(), model->nq, i++);
    mbk::forward_kinematics(*model, state, data, level);
    benchmark::DoNotOptimize(data.origin.back().data());
    benchmark::DoNotOptimize(data.mass_center_acceleration.back().data());
    benchmark::ClobberMemory();
  }
  st.counters["bodies"] = model->body_count();
}

void ours_partial_velocity(benchmark::State& st, const mbk::Model* model, mbk::Level level) {
  mbk::JointState<double> state = random_state(*model, 1);
  mbk::Data<double> data(*model);
  mbk::PartialVelocities<double> pv(*model);
  int64_t i = 0;
  for (auto _ : st) {
    nudge(state.position.data(), state.velocity.data(), model->nq, i++);
    mbk::partial_velocity_kinematics(*model, state, pv, data, level);
    benchmark::DoNotOptimize(data.origin.back().data());
    benchmark::DoNotOptimize(data.mass_center_acceleration.back().data());
    benchmark::ClobberMemory();
  }
  st.counters["bodies"] = model->body_count();
}

// A KDL tree from URDF text with our state's values in KDL's joint order.
struct KdlScene {
  KDL::Tree tree;
  std::vector<std::string> links;  // every segment but the root
  KDL::Chain longest;              // root to the leaf farthest from it (ties: first by name)
  KDL::JntArray tree_q;
  KDL::JntArrayVel chain_q;
};

std::unique_ptr<KdlScene> make_kdl_scene(const std::string& xml, const mbk::Model& model) {
  auto s = std::make_unique<KdlScene>();
  if (!kdl_parser::treeFromString(xml, s->tree)) {
    std::fprintf(stderr, "kdl_parser cannot read the URDF\n");
    std::exit(1);
  }
  const mbk::JointState<double> state = random_state(model, 1);
  const std::string root = GetTreeElementSegment(s->tree.getRootSegment()->second).getName();
  s->tree_q.resize(s->tree.getNrOfJoints());
  for (const auto& [name, element] : s->tree.getSegments()) {
    if (name == root) continue;
    s->links.push_back(name);
    const KDL::Joint& joint = GetTreeElementSegment(element).getJoint();
    if (joint.getType() != KDL::Joint::None)
      s->tree_q(GetTreeElementQNr(element)) =
          state.position[model.coordinate_index(joint.getName())];
    if (!GetTreeElementChildren(element).empty()) continue;
    KDL::Chain chain;
    s->tree.getChain(root, name, chain);
    if (chain.getNrOfSegments() > s->longest.getNrOfSegments()) s->longest = chain;
  }
  s->chain_q = KDL::JntArrayVel(s->longest.getNrOfJoints());
  unsigned j = 0;
  for (const KDL::Segment& segment : s->longest.segments) {
    if (segment.getJoint().getType() == KDL::Joint::None) continue;
    const int c = model.coordinate_index(segment.getJoint().getName());
    s->chain_q.q(j) = state.position[c];
    s->chain_q.qdot(j) = state.velocity[c];
    ++j;
  }
  return s;
}

void kdl_tree_pose_all_links(benchmark::State& st, KdlScene* s) {
  KDL::TreeFkSolverPos_recursive fk(s->tree);
  std::vector<KDL::Frame> frames(s->links.size());
  const int n = s->tree_q.rows();
  int64_t i = 0;
  for (auto _ : st) {
    nudge(s->tree_q.data.data(), nullptr, n, i++);
    for (size_t l = 0; l < s->links.size(); ++l) fk.JntToCart(s->tree_q, frames[l], s->links[l]);
    benchmark::DoNotOptimize(frames.back().p.data);
    benchmark::ClobberMemory();
  }
  st.counters["bodies"] = s->links.size();
}

void kdl_chain_pose_longest(benchmark::State& st, KdlScene* s) {
  KDL::ChainFkSolverPos_recursive fk(s->longest);
  std::vector<KDL::Frame> frames(s->longest.getNrOfSegments());
  const int n = s->chain_q.q.rows();
  int64_t i = 0;
  for (auto _ : st) {
    nudge(s->chain_q.q.data.data(), nullptr, n, i++);
    fk.JntToCart(s->chain_q.q, frames);
    benchmark::DoNotOptimize(frames.back().p.data);
    benchmark::ClobberMemory();
  }
  st.counters["bodies"] = s->longest.getNrOfSegments();
}

void kdl_chain_vel_longest(benchmark::State& st, KdlScene* s) {
  KDL::ChainFkSolverVel_recursive fk(s->longest);
  KDL::FrameVel tip;
  const int n = s->chain_q.q.rows();
  int64_t i = 0;
  for (auto _ : st) {
    nudge(s->chain_q.q.data.data(), s->chain_q.qdot.data.data(), n, i++);
    fk.JntToCart(s->chain_q, tip);
    benchmark::DoNotOptimize(tip.p.v.data);
    benchmark::ClobberMemory();
  }
  st.counters["bodies"] = s->longest.getNrOfSegments();
}

// Before timing anything: KDL and we agree on the tip of the longest chain (pose and twist), so
// the two sides compute the same thing (test/peers/kdl_test.cc checks this thoroughly).
void check_agreement(const std::string& name, const mbk::Model& model, KdlScene& s) {
  mbk::JointState<double> state(model);  // KDL's values by joint name; others do not matter
  unsigned j = 0;
  for (const KDL::Segment& segment : s.longest.segments) {
    if (segment.getJoint().getType() == KDL::Joint::None) continue;
    const int c = model.coordinate_index(segment.getJoint().getName());
    if (c < 0) {
      std::fprintf(stderr, "%s: no coordinate %s\n", name.c_str(),
                   segment.getJoint().getName().c_str());
      std::exit(1);
    }
    state.position[c] = s.chain_q.q(j);
    state.velocity[c] = s.chain_q.qdot(j);
    ++j;
  }
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data, mbk::Level::kVelocity);
  KDL::ChainFkSolverVel_recursive fk(s.longest);
  KDL::FrameVel tip;
  fk.JntToCart(s.chain_q, tip);
  const std::string tip_name = s.longest.getSegment(s.longest.getNrOfSegments() - 1).getName();
  const int k = model.body_index(tip_name);
  double e = k < 1 ? 1.0 : 0.0;
  for (int m = 0; m < 3 && k >= 1; ++m) {
    e = std::max(e, std::abs(tip.p.p(m) - data.origin[k][m]));
    e = std::max(e, std::abs(tip.p.v(m) - data.origin_velocity[k][m]));
    e = std::max(e, std::abs(tip.M.w(m) - data.omega[k][m]));
  }
  if (!(e < 1e-9)) {
    std::fprintf(stderr, "%s: KDL and ours disagree at %s (%g)\n", name.c_str(), tip_name.c_str(),
                 e);
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  struct Scene {
    std::string name;
    mbk::Model model;
    std::string urdf;
  };
  std::vector<std::unique_ptr<Scene>> scenes;
  const std::string human_urdf = read_file(source_path("config/human_body.urdf"));
  scenes.push_back(std::make_unique<Scene>(
      Scene{"human", mbk::load_model_file(source_path("config/human_body.yaml")), human_urdf}));
  scenes.push_back(std::make_unique<Scene>(Scene{
      "human_urdf", mbk::load_model_file(source_path("config/human_body.urdf")), human_urdf}));
  for (int n : {10, 100, 1000}) {
    mbk::Model chain = mbk::make_chain(n, mbk::JointType::kRevolute);
    const std::string urdf = mbk::write_urdf(chain, "chain");
    scenes.push_back(
        std::make_unique<Scene>(Scene{"chain" + std::to_string(n), std::move(chain), urdf}));
  }

  std::vector<std::unique_ptr<KdlScene>> kdl;
  const std::pair<const char*, mbk::Level> levels[] = {{"pose", mbk::Level::kPose},
                                                       {"velocity", mbk::Level::kVelocity},
                                                       {"full", mbk::Level::kAcceleration}};
  for (const auto& scene : scenes) {
    const mbk::Model* model = &scene->model;
    for (const auto& [level_name, level] : levels) {
      benchmark::RegisterBenchmark(("ours/" + scene->name + "/recursive/" + level_name).c_str(),
                                   ours_recursive, model, level);
      benchmark::RegisterBenchmark(("ours/" + scene->name + "/pv/" + level_name).c_str(),
                                   ours_partial_velocity, model, level);
    }
    if (scene->name == "human") continue;  // KDL runs on the URDF: see human_urdf
    kdl.push_back(make_kdl_scene(scene->urdf, *model));
    check_agreement(scene->name, *model, *kdl.back());
    const std::string peer = (scene->name == "human_urdf" ? "human" : scene->name);
    KdlScene* s = kdl.back().get();
    benchmark::RegisterBenchmark(("kdl/" + peer + "/tree_pose_all_links").c_str(),
                                 kdl_tree_pose_all_links, s);
    benchmark::RegisterBenchmark(("kdl/" + peer + "/chain_pose_longest").c_str(),
                                 kdl_chain_pose_longest, s);
    benchmark::RegisterBenchmark(("kdl/" + peer + "/chain_vel_longest").c_str(),
                                 kdl_chain_vel_longest, s);
  }
  // Our 16-body human scene is checked against KDL too (same URDF, by link name).
  check_agreement("human", scenes[0]->model, *kdl[0]);

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
