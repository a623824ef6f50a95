#include "mb_kinematics/io/urdf_model.h"

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/inertia.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/io/xacro_markup.h"

namespace mbk {
namespace {

// urdfdom reports what is wrong only through console_bridge. While it parses, this handler
// collects the error messages (one line, for the exception) and keeps everything else (its
// warnings and notes, also on success) off stderr.
class UrdfdomErrors : public console_bridge::OutputHandler {
 public:
  UrdfdomErrors() : previous_(console_bridge::getOutputHandler()) {
    console_bridge::useOutputHandler(this);
  }
  ~UrdfdomErrors() override {
    console_bridge::restorePreviousOutputHandler();
    console_bridge::useOutputHandler(previous_);  // leaves no pointer to this behind
  }
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*file*/,
           int /*line*/) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_ERROR) return;
    std::string one_line = text;
    std::replace(one_line.begin(), one_line.end(), '\n', ' ');
    messages_ += (messages_.empty() ? "" : "; ") + one_line;
  }
  const std::string& messages() const { return messages_; }

 private:
  console_bridge::OutputHandler* previous_;
  std::string messages_;
};

// urdfdom's joint type as the file spells it.
const char* urdf_type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FIXED:
      return "fixed";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    default:  // urdf::Joint::UNKNOWN
      return "";
  }
}

// Our type for it, from the joint traits table (JointTraits::urdf_type).
JointType joint_type(const urdf::Joint& joint) {
  const std::string name = urdf_type_name(joint.type);
  if (name.empty()) throw std::invalid_argument("joint '" + joint.name + "' has an unknown type");
  return joint_type_from_urdf_type(name);
}

// Joint names in the order the file lists them (urdfdom keeps them in a name-sorted map).
std::map<std::string, int> joint_file_order(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  std::map<std::string, int> order;
  if (doc.Parse(xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.FirstChildElement("robot"))
    return order;
  int i = 0;
  for (auto* e = doc.FirstChildElement("robot")->FirstChildElement("joint"); e;
       e = e->NextSiblingElement("joint"))
    if (e->Attribute("name")) order[e->Attribute("name")] = i++;
  return order;
}

// Links whose <inertial> `mbk urdf` wrote with a token inertia (the scene gave none): marked by
// a comment starting with kTokenInertia (urdf_writer.h), as URDF requires an <inertia>.
std::set<std::string> links_with_token_inertia(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  std::set<std::string> links;
  if (doc.Parse(xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.FirstChildElement("robot"))
    return links;
  for (auto* e = doc.FirstChildElement("robot")->FirstChildElement("link"); e;
       e = e->NextSiblingElement("link")) {
    const auto* inertial = e->FirstChildElement("inertial");
    for (auto* c = inertial ? inertial->FirstChild() : nullptr; c; c = c->NextSibling())
      if (c->ToComment() && std::string(c->Value()).find(kTokenInertia) != std::string::npos)
        links.insert(e->Attribute("name") ? e->Attribute("name") : "");
  }
  return links;
}

// I_k in Bk's axes from URDF's inertia in the <inertial> origin's axes: R I R^T.
void set_inertia(const urdf::Inertial& inertial, Body& body) {
  const urdf::Rotation& r = inertial.origin.rotation;
  const Mat3<double> rotation =
      Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  const Mat3<double> i = inertia_matrix(inertial.ixx, inertial.iyy, inertial.izz, inertial.ixy,
                                        inertial.ixz, inertial.iyz);
  body.inertia = rotation * i * rotation.transpose();
  body.has_inertia = true;
}

// A URDF is what the vendor ships: an inertia that is not physical leaves its body without one
// (H_G is then left out, as for a missing inertia) and one warning names every such link.
void drop_unphysical_inertias(Model& model, const std::string& source) {
  std::string links;
  for (Body& body : model.bodies) {
    const std::string problem = body.has_inertia ? inertia_problem(body.inertia) : "";
    if (problem.empty()) continue;
    links += (links.empty() ? "link '" : "; link '") + body.name + "' inertia " + problem;
    body.has_inertia = false;
  }
  if (!links.empty())
    model.warnings.push_back(source +
                             ": inertia not physical, so the system's angular "
                             "momentum is left out: " +
                             links);
}

// m_k, r_k and I_k from the link's <inertial>, if it has one.
void set_mass_properties(const urdf::Link& link, Body& body) {
  if (!link.inertial) return;
  const urdf::Vector3& c = link.inertial->origin.position;
  body.mass_center = Vec3<double>(c.x, c.y, c.z);
  body.mass = link.inertial->mass;
  set_inertia(*link.inertial, body);
}

Body make_body(const urdf::Link& link, const urdf::Joint& joint, int lower) {
  Body body;
  body.name = link.name;
  body.lower = lower;
  body.joint.name = joint.name;
  body.joint.type = joint_type(joint);
  const urdf::Pose& origin = joint.parent_to_joint_origin_transform;
  body.joint.offset = Vec3<double>(origin.position.x, origin.position.y, origin.position.z);
  const urdf::Rotation& r = origin.rotation;
  body.joint.rotation = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  if (joint_traits(body.joint.type).uses_axis)
    body.joint.axis = Vec3<double>(joint.axis.x, joint.axis.y, joint.axis.z);
  set_mass_properties(link, body);
  return body;
}

Model build_model(const urdf::ModelInterface& urdf, const std::string& xml,
                  const std::string& source) {
  const std::map<std::string, int> order = joint_file_order(xml);
  auto file_position = [&](const urdf::JointSharedPtr& j) {
    auto it = order.find(j->name);
    return it == order.end() ? -1 : it->second;
  };
  Model model;
  const urdf::LinkConstSharedPtr root = urdf.getRoot();
  model.frame = root->name;
  model.bodies.resize(1);
  model.bodies[0].name = root->name;
  set_mass_properties(*root, model.bodies[0]);  // the root link, fixed in R: its mass counts
  std::vector<std::pair<urdf::LinkConstSharedPtr, int>> queue = {{root, 0}};  // link, its k
  std::map<std::string, int> index_of_joint;
  std::map<std::string, std::string> parent_joint = {{root->name, ""}};  // of each link reached
  for (size_t head = 0; head < queue.size(); ++head) {
    std::vector<urdf::JointSharedPtr> joints = queue[head].first->child_joints;
    std::stable_sort(joints.begin(), joints.end(), [&](const auto& a, const auto& b) {
      return file_position(a) < file_position(b);
    });
    for (const urdf::JointSharedPtr& joint : joints) {
      // urdfdom accepts a link that is the child of two joints (a closed loop).
      const auto [seen, first] = parent_joint.insert({joint->child_link_name, joint->name});
      if (!first)
        throw std::invalid_argument("link '" + joint->child_link_name +
                                    "' is reached through two joints ('" + seen->second +
                                    "' and '" + joint->name + "'): a closed loop, not a tree");
      const urdf::LinkConstSharedPtr child = urdf.getLink(joint->child_link_name);
      model.bodies.push_back(make_body(*child, *joint, queue[head].second));
      index_of_joint[joint->name] = static_cast<int>(model.bodies.size()) - 1;
      queue.push_back({child, static_cast<int>(model.bodies.size()) - 1});
    }
  }
  for (const auto& [name, link] : urdf.links_)
    if (!parent_joint.count(name))
      throw std::invalid_argument("link '" + name + "' is not connected to the root link '" +
                                  root->name + "' (its joints form a loop)");
  for (const std::string& link : links_with_token_inertia(xml)) {
    const int k = model.body_index(link);
    if (k > 0) model.bodies[k].has_inertia = false;
  }
  drop_unphysical_inertias(model, source);
  finalize_model(model);
  for (const auto& [name, k] : index_of_joint) {
    const urdf::Joint& joint = *urdf.getJoint(name);
    if (!joint.mimic) continue;
    auto source = index_of_joint.find(joint.mimic->joint_name);
    const Body& body = model.bodies[k];
    if (source == index_of_joint.end())
      throw std::invalid_argument("joint '" + name + "' mimics unknown joint '" +
                                  joint.mimic->joint_name + "'");
    const Body& source_body = model.bodies[source->second];
    if (coordinate_count(body.joint.type) != 1 || coordinate_count(source_body.joint.type) != 1)
      throw std::invalid_argument("mimic joint '" + name + "': both joints need one coordinate");
    model.mimics.push_back(
        {body.q_index, source_body.q_index, joint.mimic->multiplier, joint.mimic->offset});
  }
  finalize_model(model);  // validates the mimics
  return model;
}

Model parse_urdf(const std::string& xml, const std::string& source) {
  tinyxml2::XMLDocument doc;  // for the line of a syntax error, which urdfdom does not give
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw std::invalid_argument(source + ":" + std::to_string(doc.ErrorLineNum()) +
                                ": URDF does not parse: malformed XML: " + doc.ErrorStr());
  const std::string xacro = xacro_markup(doc);
  if (!xacro.empty()) throw std::invalid_argument(xacro_refusal(source, xacro));
  urdf::ModelInterfaceSharedPtr urdf;
  std::string errors;
  {
    static std::mutex console_bridge_handler;  // one collector installed at a time
    std::lock_guard<std::mutex> lock(console_bridge_handler);
    UrdfdomErrors collector;
    try {
      urdf = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      throw std::invalid_argument(source + ": URDF does not parse: " + e.what());
    }
    errors = collector.messages();
  }
  // urdfdom returns a model despite some errors (e.g. a mass that is not a number): reject it.
  if (!urdf || !errors.empty())
    throw std::invalid_argument(
        source + ": URDF does not parse: " + (errors.empty() ? "urdfdom gave no reason" : errors));
  try {
    return build_model(*urdf, xml, source);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
}

}  // namespace

// Messages hold names and urdfdom's text: control characters escaped to keep them one line.
Model load_urdf_string(const std::string& xml, const std::string& source) {
  try {
    Model model = parse_urdf(xml, source);
    for (std::string& warning : model.warnings) warning = printable(warning);
    return model;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(printable(e.what()));
  }
}

Model load_urdf_file(const std::string& path) {
  return load_urdf_string(read_text_file(path, "URDF file"), path);
}

}  // namespace mbk
