// Every loader error path (YAML scenes, URDF, STATE.json, model files) ends in one
// std::invalid_argument whose one-line message says what is wrong and where (doc/method.md
// 8), never in a crash, another exception type or a silently accepted model.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <string>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/state_json.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/io/yaml_scene.h"
#include "test/support/test_models.h"

namespace {

// Runs `load` and checks that it throws std::invalid_argument with a one-line message that
// contains every fragment.
void expect_error(const std::function<void()>& load, std::initializer_list<std::string> fragments) {
  std::string message;
  try {
    load();
    ADD_FAILURE() << "no error";
    return;
  } catch (const std::invalid_argument& e) {
    message = e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not std::invalid_argument: " << e.what();
    return;
  }
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  for (const std::string& fragment : fragments)
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "'" << fragment << "' missing from: " << message;
}

void expect_yaml_error(const std::string& text, std::initializer_list<std::string> fragments) {
  SCOPED_TRACE(text);
  expect_error([&] { mbk::load_yaml_scene_string(text, "scene.yaml"); }, fragments);
}

void expect_urdf_error(const std::string& xml, std::initializer_list<std::string> fragments) {
  SCOPED_TRACE(xml);
  expect_error([&] { mbk::load_urdf_string(xml, "robot.urdf"); }, fragments);
}

// A one-body scene with the given extra fields on body 1 (on line 3).
std::string one_body(const std::string& fields) {
  return "frame: R\nbodies:\n  - {name: B1, lower: 0, " + fields + "}\n";
}

TEST(YamlSceneErrors, Valid) {  // the fragments below are what goes wrong, not the frame
  EXPECT_NO_THROW(mbk::load_yaml_scene_string(one_body("joint: {type: revolute}, mass: 1")));
}

TEST(YamlSceneErrors, MalformedYamlGivesFileAndLine) {
  expect_yaml_error(
      "frame: R\n"
      "bodies:\n"
      "  - name: B1\n"
      "    lower: 0\n"
      "    joint: {type: revolute\n",  // flow map never closed
      {"scene.yaml:6: malformed YAML"});
  expect_yaml_error(
      "frame: R\n"
      "bodies:\n"
      "  - name: B1\n"
      "   lower: 0\n",  // indentation
      {"scene.yaml:4: malformed YAML"});
}

TEST(YamlSceneErrors, NoBodies) {
  expect_yaml_error("frame: R\n", {"scene.yaml:1:", "no 'bodies' list"});
  expect_yaml_error("frame: R\nbodies: []\n", {"scene.yaml:1:", "no 'bodies' list"});
  expect_yaml_error("bodies: B1\n", {"no 'bodies' list"});
  expect_yaml_error("- B1\n- B2\n", {"scene.yaml:1:", "a scene is a map"});
  expect_yaml_error("", {"scene.yaml", "a scene is a map"});
  expect_yaml_error("bodies:\n  - B1\n", {"scene.yaml:2:", "body 1 must be a map"});
  expect_yaml_error("bodies:\n  - {lower: 0, joint: {type: fixed}}\n",
                    {"scene.yaml:2:", "body 1 has no name"});
}

TEST(YamlSceneErrors, UnknownJointTypeListsTheKnownOnes) {
  expect_yaml_error(
      "bodies:\n"
      "  - {name: B1, lower: 0, joint: {type: revolute}}\n"
      "  - {name: B2, lower: 1, joint: {type: hinge}}\n",
      {"scene.yaml:3:", "body 2 joint", "unknown joint type 'hinge'",
       "known: fixed, revolute, prismatic, ball_123, ball_euler, free_123, free_euler, planar"});
  expect_yaml_error(one_body("joint: {axis: [0, 0, 1]}"),
                    {"scene.yaml:3:", "body 1 joint has no type"});
  // A missing key has no line of its own: the body's line is given.
  expect_yaml_error("bodies:\n  - {name: B1, lower: 0}\n",
                    {"scene.yaml:2:", "body 1 joint must be a map"});
  expect_yaml_error(one_body("joint: revolute"), {"scene.yaml:3:", "body 1 joint must be a map"});
  expect_yaml_error("lower_body_array: [0, 1]\njoint_type: hinge\n",
                    {"scene.yaml:1:", "unknown joint type 'hinge'", "known: fixed"});
}

TEST(YamlSceneErrors, EulerOrders) {
  EXPECT_EQ(mbk::load_yaml_scene_string(one_body("joint: {type: ball_123, euler_order: zxy}"))
                .bodies[1]
                .joint.euler_order,
            mbk::EulerOrder::kZXY);
  expect_yaml_error(one_body("joint: {type: ball_123, euler_order: ZZY}"),
                    {"scene.yaml:3:", "body 1 joint", "unknown Euler order 'ZZY'", "ZXY"});
  expect_yaml_error(one_body("joint: {type: revolute, euler_order: ZXY}"),
                    {"scene.yaml:3:", "body 1 joint", "euler_order is for ball_123 and free_123",
                     "not revolute"});
}

TEST(YamlSceneErrors, LowerBodyMustBeAnEarlierBody) {
  const std::string head =
      "bodies:\n"
      "  - {name: B1, lower: 0, joint: {type: revolute}}\n"
      "  - {name: B2, joint: {type: revolute}, lower: ";
  // B2 on the later B3 (by name or number; with B3 on B2 a cycle), on itself, on nobody.
  const std::string tail = "}\n  - {name: B3, lower: B2, joint: {type: revolute}}\n";
  expect_yaml_error(head + "B3" + tail, {"scene.yaml:3:", "body 2 lower 'B3'", "earlier body"});
  expect_yaml_error(head + "3" + tail, {"scene.yaml:3:", "body 2 lower = 3", "0 <= L(k) < k"});
  expect_yaml_error(head + "2" + tail, {"scene.yaml:3:", "body 2 lower = 2"});
  expect_yaml_error(head + "B2" + tail, {"scene.yaml:3:", "body 2 lower 'B2'"});
  expect_yaml_error(head + "ghost" + tail, {"scene.yaml:3:", "body 2 lower 'ghost'"});
  expect_yaml_error(head + "-1" + tail, {"scene.yaml:3:", "body 2 lower = -1"});
  expect_yaml_error("bodies:\n  - {name: B1, joint: {type: fixed}}\n",
                    {"scene.yaml:2:", "body 1 lower is missing"});
  expect_yaml_error("lower_body_array: [0, 1, 3]\n", {"scene.yaml:1:", "body 3 has L(3) = 3"});
  expect_yaml_error("lower_body_array: [0, 1.5]\n",
                    {"scene.yaml:1:", "lower_body_array entry '1.5' is not an integer"});
  expect_yaml_error("lower_body_array: 0\n", {"scene.yaml:1:", "lower_body_array must be a list"});
}

TEST(YamlSceneErrors, DuplicateNames) {
  expect_yaml_error(
      "bodies:\n"
      "  - {name: B1, lower: 0, joint: {type: revolute}}\n"
      "  - {name: B1, lower: 1, joint: {type: revolute}}\n",
      {"scene.yaml:", "body 2 'B1'", "name is used twice"});
  expect_yaml_error("frame: B1\nbodies:\n  - {name: B1, lower: 0, joint: {type: fixed}}\n",
                    {"body 1 'B1'", "used twice (or is R's)"});
  expect_yaml_error(
      "bodies:\n"
      "  - {name: B1, lower: 0, joint: {name: J, type: revolute}}\n"
      "  - {name: B2, lower: 1, joint: {name: J, type: revolute}}\n",
      {"body 2 'B2'", "joint name 'J' is used twice"});
}

TEST(YamlSceneErrors, NonFiniteNumbers) {
  // .nan/.inf are YAML's spellings and read as numbers; nan/inf/1e999 do not read at all.
  expect_yaml_error(one_body("joint: {type: revolute}, mass: .nan"),
                    {"scene.yaml:3:", "B1 mass is not finite"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass: NaN"),
                    {"scene.yaml:3:", "B1 mass must be a number, not 'NaN'"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass: inf"),
                    {"scene.yaml:3:", "B1 mass must be a number, not 'inf'"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass: 1e999"),
                    {"scene.yaml:3:", "B1 mass must be a number"});
  expect_yaml_error(one_body("joint: {type: revolute, origin: [0, .inf, 0]}"),
                    {"scene.yaml:3:", "body 1 joint origin is not finite"});
  expect_yaml_error(one_body("joint: {type: revolute, axis: [-.inf, 0, 1]}"),
                    {"scene.yaml:3:", "body 1 joint axis is not finite"});
  expect_yaml_error(one_body("joint: {type: revolute, rpy: [0, .NaN, 0]}"),
                    {"scene.yaml:3:", "body 1 joint rpy is not finite"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass_center: [0, 0, .nan]"),
                    {"scene.yaml:3:", "B1 mass_center is not finite"});
}

TEST(YamlSceneErrors, NonNumericValues) {
  expect_yaml_error(one_body("joint: {type: revolute}, mass: heavy"),
                    {"scene.yaml:3:", "B1 mass must be a number, not 'heavy'"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass: [1]"),
                    {"scene.yaml:3:", "B1 mass must be a number"});
  expect_yaml_error(one_body("joint: {type: revolute, origin: [0, x, 0]}"),
                    {"scene.yaml:3:", "body 1 joint origin must be a number, not 'x'"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass: -1"),
                    {"body 1 'B1'", "mass must be finite and >= 0"});
  expect_yaml_error(one_body("joint: {type: revolute, axis: [0, 0, 0]}"),
                    {"scene.yaml:3:", "body 1 joint axis is zero"});
  expect_yaml_error("speeds: fast\n" + one_body("joint: {type: fixed}"),
                    {"scene.yaml:1:", "speeds must be coordinate_derivatives or angular_velocity"});
  expect_yaml_error("frame: {name: R}\nbodies:\n  - {name: B1, lower: 0, joint: {type: fixed}}\n",
                    {"scene.yaml:1:", "frame must be a name"});
}

TEST(YamlSceneErrors, WrongVectorLength) {
  expect_yaml_error(one_body("joint: {type: revolute, origin: [0, 0]}"),
                    {"scene.yaml:3:", "body 1 joint origin must be a list of 3 numbers"});
  expect_yaml_error(one_body("joint: {type: revolute, axis: [0, 0, 1, 0]}"),
                    {"scene.yaml:3:", "body 1 joint axis must be a list of 3 numbers"});
  expect_yaml_error(one_body("joint: {type: revolute, rpy: 0}"),
                    {"scene.yaml:3:", "body 1 joint rpy must be a list of 3 numbers"});
  expect_yaml_error(one_body("joint: {type: revolute}, mass_center: []"),
                    {"scene.yaml:3:", "B1 mass_center must be a list of 3 numbers"});
}

// A ball joint `s` (coordinates s/alpha, s/beta, s/gamma) beside a joint named `s/alpha`.
TEST(YamlSceneErrors, DuplicateCoordinateNamesNameBothJoints) {
  expect_yaml_error(
      "bodies:\n  - {name: a, lower: 0, joint: {name: s, type: ball_123}}\n"
      "  - {name: b, lower: a, joint: {name: s/alpha, type: revolute}}\n",
      {"scene.yaml:2:", "body 2 'b'", "coordinate name 's/alpha'", "joint 's' (body 1 'a')"});
}

// yaml-cpp stops at a nesting depth it cannot handle; the error must still say where.
TEST(YamlSceneErrors, DeepNestingGivesFileAndLine) {
  expect_yaml_error("bodies: " + std::string(100000, '['),
                    {"scene.yaml:1:", "malformed YAML", "too deep"});
  expect_yaml_error("bodies:\n  - " + std::string(100000, '{'),
                    {"scene.yaml:2:", "malformed YAML", "too deep"});
}

TEST(YamlSceneErrors, FileNameInTheMessage) {
  const std::string missing = mbk_test::source_path("test/io/data/no_such_scene.yaml");
  expect_error([&] { mbk::load_yaml_scene_file(missing); }, {missing, "cannot open scene file"});
}

// A two-link URDF with the given joint (parent a, child b) and link b contents.
std::string two_links(const std::string& joint, const std::string& link_b = "") {
  return "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\">" +
         link_b + "</link>\n  " + joint + "\n</robot>\n";
}

std::string continuous(const std::string& name, const std::string& parent, const std::string& child,
                       const std::string& extra = "") {
  return "<joint name=\"" + name + "\" type=\"continuous\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/>" + extra + "</joint>";
}

const char kInertia[] = "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>";

TEST(UrdfErrors, Valid) {  // the cases below differ from this one only in what goes wrong
  const mbk::Model m = mbk::load_urdf_string(
      two_links(continuous("j", "a", "b", "<origin xyz=\"1 0 0\"/><axis xyz=\"0 1 0\"/>"),
                std::string("<inertial><mass value=\"2\"/>") + kInertia + "</inertial>"));
  EXPECT_EQ(m.body_count(), 1);
  EXPECT_EQ(m.bodies[1].mass, 2.0);
}

TEST(UrdfErrors, MalformedXmlGivesFileAndLine) {
  // The line of the element left open.
  expect_urdf_error("<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n",
                    {"robot.urdf:3: URDF does not parse: malformed XML"});
  expect_urdf_error("", {"robot.urdf", "malformed XML"});
  expect_urdf_error("<model name=\"r\"/>", {"robot.urdf", "'robot' element"});
  expect_urdf_error("<robot name=\"r\"/>", {"robot.urdf", "No link elements"});
}

TEST(UrdfErrors, TreeStructure) {
  // A joint's parent link that does not exist (dangling).
  expect_urdf_error(two_links(continuous("j", "nowhere", "b")),
                    {"robot.urdf", "parent link [nowhere] of joint [j] not found"});
  // Links in a cycle: no root.
  expect_urdf_error(two_links(continuous("j1", "a", "b") + continuous("j2", "b", "a")),
                    {"robot.urdf", "No root link found"});
  // A cycle below a root (urdfdom accepts it; the breadth-first numbering must not loop).
  const std::string loop =
      "<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"base\"/>"
      "<link name=\"a\"/><link name=\"b\"/>" +
      continuous("j0", "base", "a") + continuous("j1", "a", "b") + continuous("j2", "b", "a") +
      "</robot>";
  expect_urdf_error(loop, {"robot.urdf", "link 'a'", "'j0' and 'j2'", "not a tree"});
  // A cycle beside the root, not reached from it.
  const std::string island =
      "<robot name=\"r\"><link name=\"base\"/><link name=\"a\"/>"
      "<link name=\"b\"/>" +
      continuous("j1", "a", "b") + continuous("j2", "b", "a") + "</robot>";
  expect_urdf_error(island, {"robot.urdf", "link 'a' is not connected to the root link 'base'"});
  // Two links without a parent.
  expect_urdf_error("<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/></robot>",
                    {"robot.urdf", "Two root links found: [a] and [b]"});
  expect_urdf_error("<robot name=\"r\"><link name=\"a\"/></robot>",
                    {"robot.urdf", "model has no bodies"});
}

TEST(UrdfErrors, NonFiniteNumbers) {
  expect_urdf_error(two_links(continuous("j", "a", "b", "<origin xyz=\"nan 0 0\"/>")),
                    {"robot.urdf", "[nan]", "origin element for joint [j]"});
  expect_urdf_error(two_links(continuous("j", "a", "b", "<origin rpy=\"0 inf 0\"/>")),
                    {"robot.urdf", "[inf]", "origin element for joint [j]"});
  expect_urdf_error(two_links(continuous("j", "a", "b", "<axis xyz=\"0 NaN 1\"/>")),
                    {"robot.urdf", "axis element for joint [j]", "[NaN]"});
  expect_urdf_error(two_links(continuous("j", "a", "b", "<axis xyz=\"0 0 0\"/>")),
                    {"robot.urdf", "body 1 'b'", "joint axis is zero"});
  // urdfdom logs a bad mass but still returns the model (with some mass): it must not load.
  expect_urdf_error(
      two_links(continuous("j", "a", "b"),
                std::string("<inertial><mass value=\"nan\"/>") + kInertia + "</inertial>"),
      {"robot.urdf", "mass [nan]", "Link [b]"});
  expect_urdf_error(
      two_links(continuous("j", "a", "b"),
                std::string("<inertial><origin xyz=\"0 0 1e999\"/><mass value=\"1\"/>") + kInertia +
                    "</inertial>"),
      {"robot.urdf", "[1e999]", "Link [b]"});
}

TEST(UrdfErrors, JointTypesAndMimics) {
  expect_urdf_error(two_links("<joint name=\"j\" type=\"hinge\"><parent link=\"a\"/>"
                              "<child link=\"b\"/></joint>"),
                    {"robot.urdf", "Joint [j] has no known type [hinge]"});
  expect_urdf_error(two_links(continuous("j", "a", "b", "<mimic joint=\"ghost\"/>")),
                    {"robot.urdf", "joint 'j' mimics unknown joint 'ghost'"});
  // A mimic of a joint without a coordinate.
  const std::string fixed_then_mimic =
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
      "<joint name=\"f\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>" +
      continuous("m", "b", "c", "<mimic joint=\"f\"/>") + "</robot>";
  expect_urdf_error(fixed_then_mimic, {"robot.urdf", "mimic joint 'm'", "one coordinate"});
}

// Three hinges in a chain, each joint a mimic of the one before: m_end of z_mid of a_src.
// By name, m_end comes before z_mid: it once read z_mid's stale value.
std::string mimic_chain(const std::string& a_src_mimic = "") {
  return "<robot name=\"r\"><link name=\"l0\"/><link name=\"l1\"/><link name=\"l2\"/>"
         "<link name=\"l3\"/>" +
         continuous("a_src", "l0", "l1", a_src_mimic) +
         continuous("z_mid", "l1", "l2", "<mimic joint=\"a_src\" multiplier=\"2\" offset=\"1\"/>") +
         continuous("m_end", "l2", "l3", "<mimic joint=\"z_mid\" multiplier=\"-3\"/>") + "</robot>";
}

TEST(UrdfMimics, AMimicOfAMimicFollowsTheUpdatedValue) {
  const mbk::Model model = mbk::load_urdf_string(mimic_chain(), "robot.urdf");
  const mbk::JointState<double> s =
      mbk::read_state_string(model, "{\"position\": {\"a_src\": 0.5}}", "state.json");
  const double z_mid = 2 * 0.5 + 1;
  EXPECT_EQ(s.position[model.coordinate_index("z_mid")], z_mid);
  EXPECT_EQ(s.position[model.coordinate_index("m_end")], -3 * z_mid);
}

TEST(UrdfMimics, ACycleIsRefusedNamingTheJoints) {
  expect_urdf_error(mimic_chain("<mimic joint=\"m_end\"/>"),
                    {"robot.urdf", "mimic joints form a cycle", "a_src", "z_mid", "m_end"});
}

// urdfdom's console_bridge output (its errors and warnings) stays off stderr: the errors are
// in the exception's one line; the warnings of a URDF that loads are of no use to a user.
TEST(UrdfErrors, UrdfdomPrintsNothing) {
  testing::internal::CaptureStderr();
  expect_urdf_error(
      two_links(continuous("j", "a", "b"),
                std::string("<inertial><mass value=\"nan\"/>") + kInertia + "</inertial>"),
      {"mass [nan]"});
  expect_urdf_error(two_links(continuous("j", "nowhere", "b")), {"[nowhere]"});
  EXPECT_NO_THROW(mbk::load_urdf_string(mimic_chain(), "robot.urdf"));  // mimics without offset
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(UrdfErrors, FileNameInTheMessage) {
  const std::string missing = mbk_test::source_path("test/io/data/no_such_robot.urdf");
  expect_error([&] { mbk::load_urdf_file(missing); }, {missing, "cannot open URDF file"});
}

class StateErrors : public ::testing::Test {
 protected:
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/human_body.yaml"));

  void expect_state_error(const std::string& json, std::initializer_list<std::string> fragments) {
    SCOPED_TRACE(json);
    expect_error([&] { mbk::read_state_string(model, json, "state.json"); }, fragments);
  }
};

TEST_F(StateErrors, Valid) {
  const mbk::JointState<double> s = mbk::read_state_string(
      model, R"({"position": {"head_nod": 0.5}, "velocity": {"root/x": -1e-3}})");
  EXPECT_EQ(s.position[model.coordinate_index("head_nod")], 0.5);
  EXPECT_EQ(s.velocity[model.speed_index("root/x")], -1e-3);
}

TEST_F(StateErrors, UnknownNames) {
  expect_state_error(R"({"position": {"ghost": 1}})",
                     {"state.json", "position: unknown coordinate 'ghost'"});
  expect_state_error(R"({"acceleration": {"root": 1}})",  // a joint, not one of its coordinates
                     {"state.json", "acceleration: unknown coordinate 'root'"});
  expect_state_error(R"({"positions": {"head_nod": 1}})",
                     {"state.json", "unknown key 'positions'", "position, velocity, acceleration"});
}

TEST_F(StateErrors, NonNumbers) {
  expect_state_error(R"({"velocity": {"head_nod": "fast"}})",
                     {"state.json", "velocity.head_nod is not a number"});
  expect_state_error(R"({"velocity": {"head_nod": null}})",
                     {"state.json", "velocity.head_nod is not a number"});
  expect_state_error(R"({"velocity": {"head_nod": [1]}})",
                     {"state.json", "velocity.head_nod is not a number"});
  expect_state_error(R"({"position": [1, 2]})", {"state.json", "position must be an object"});
  expect_state_error("[1, 2]", {"state.json", "must be a JSON object"});
  expect_state_error("", {"state.json", "must be a JSON object"});
}

TEST_F(StateErrors, NonFinite) {
  // JSON has no NaN; what other writers (Python's json) emit instead must not pass either.
  expect_state_error(R"({"position": {"head_nod": NaN}})",
                     {"state.json", "position.head_nod is not a number"});
  expect_state_error(R"({"position": {"head_nod": Infinity}})",
                     {"state.json", "position.head_nod is not a number"});
  expect_state_error(R"({"position": {"head_nod": 1e999}})",
                     {"state.json", "position.head_nod is not a number"});
  expect_state_error(R"({"acceleration": {"head_nod": .nan}})",
                     {"state.json", "acceleration.head_nod is not finite"});
  expect_state_error(R"({"acceleration": {"head_nod": -.inf}})",
                     {"state.json", "acceleration.head_nod is not finite"});
}

TEST_F(StateErrors, MalformedJsonGivesLine) {
  expect_state_error("{\n  \"position\": {\"head_nod\": 1}\n", {"state.json:3: malformed JSON"});
  expect_state_error("{\n  \"position\": {\"head_nod\": 1]\n}\n", {"state.json:2: malformed JSON"});
}

TEST_F(StateErrors, DeepNestingGivesLine) {  // yaml-cpp's own message was "bad file"
  expect_state_error("{\"position\": " + std::string(100000, '['),
                     {"state.json:1: malformed JSON", "too deep"});
}

TEST_F(StateErrors, FileNameInTheMessage) {
  const std::string missing = mbk_test::source_path("test/io/data/no_such_state.json");
  expect_error([&] { mbk::read_state_file(model, missing); }, {missing, "cannot open state file"});
}

TEST(LoadModelFileErrors, ExtensionAndMissingFile) {
  expect_error([] { mbk::load_model_file("model.txt"); },
               {"model.txt", "unknown model file type", ".urdf", ".yaml"});
  expect_error([] { mbk::load_model_file("config/human_body"); },
               {"config/human_body", "unknown model file type"});
  const std::string yaml = mbk_test::source_path("test/io/data/no_such_scene.yml");
  expect_error([&] { mbk::load_model_file(yaml); }, {yaml, "cannot open scene file"});
  const std::string urdf = mbk_test::source_path("test/io/data/no_such_robot.xml");
  expect_error([&] { mbk::load_model_file(urdf); }, {urdf, "cannot open URDF, MJCF or SDFormat file"});
}

// A model (or state) path that is not a regular file is refused, naming it: a link to
// /dev/zero would be read until memory runs out, a pipe waited on for a writer.
TEST(LoadModelFileErrors, ANonRegularFileIsRefused) {
  const std::string dir = ::testing::TempDir();
  const std::string folder = dir + "a_folder.yaml";
  mkdir(folder.c_str(), 0700);
  expect_error([&] { mbk::load_model_file(folder); }, {folder, "not a regular file"});
  for (const std::string name : {"zero.urdf", "zero.yaml", "zero.bvh"}) {
    const std::string link = dir + name;
    std::remove(link.c_str());
    ASSERT_EQ(symlink("/dev/zero", link.c_str()), 0);
    expect_error([&] { mbk::load_model_file(link); }, {link, "not a regular file"});
  }
  const std::string pipe = dir + "pipe.urdf";
  std::remove(pipe.c_str());
  ASSERT_EQ(mkfifo(pipe.c_str(), 0600), 0);
  expect_error([&] { mbk::load_model_file(pipe); }, {pipe, "not a regular file"});
  const mbk::Model model = mbk_test::revolute_chain(2);
  expect_error([&] { mbk::read_state_file(model, dir + "zero.yaml"); }, {"not a regular file"});
}

// An axis whose length overflows a double ([1e200, 1e200, 0]: its squared norm is inf) is
// normalized as any other, in a YAML scene and a URDF alike; `mbk urdf` writes it as a unit
// axis (before: a "rotation" of 0.54 I and axis="0 0 0").
TEST(HugeAxes, AreNormalizedWithoutOverflow) {
  const mbk::Model yaml = mbk::load_yaml_scene_string(
      one_body("joint: {type: revolute, axis: [1e200, 1e200, 0]}, mass: 1"));
  const mbk::Model urdf = mbk::load_urdf_string(
      two_links(continuous("j", "a", "b", "<axis xyz=\"1e200 1e200 0\"/>"),
                std::string("<inertial><mass value=\"2\"/>") + kInertia + "</inertial>"));
  for (const mbk::Model* model : {&yaml, &urdf}) {
    const mbk::Vec3<double> axis = model->bodies[1].joint.axis;
    EXPECT_NEAR(axis.x(), std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(axis.y(), std::sqrt(0.5), 1e-15);
    EXPECT_EQ(axis.z(), 0.0);
    const std::string text = mbk::write_urdf(*model, "r", mbk::UrdfStyle::kEquivalent);
    EXPECT_EQ(text.find("axis xyz=\"0 0 0\""), std::string::npos) << text;
    EXPECT_EQ(mbk::load_urdf_string(text).bodies[1].joint.axis, axis);
  }
}

// Masses whose sum overflows (two bodies of 1.7e308 kg) are refused by every loader alike: the
// URDF loader let them through and `mbk eval` printed "mass": inf, which is not JSON.
TEST(HugeMasses, WhoseSumOverflowsAreRefusedByEveryLoader) {
  expect_yaml_error(
      "frame: R\nbodies:\n  - {name: B1, lower: 0, joint: {type: revolute}, mass: 1.7e308}\n"
      "  - {name: B2, lower: B1, joint: {type: revolute}, mass: 1.7e308}\n",
      {"masses sum to more than a double holds"});
  const std::string heavy =
      std::string("<inertial><mass value=\"1.7e308\"/>") + kInertia + "</inertial>";
  expect_urdf_error("<robot name=\"r\"><link name=\"a\">" + heavy + "</link><link name=\"b\">" +
                        heavy + "</link>" + continuous("j", "a", "b") + "</robot>",
                    {"robot.urdf", "masses sum to more than a double holds"});
}

}  // namespace
