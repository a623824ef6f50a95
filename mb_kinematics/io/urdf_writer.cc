#include "mb_kinematics/io/urdf_writer.h"

#include <array>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/utf8.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {
namespace {

std::string num(double x) { return format_double(x); }

// A name as an XML attribute value (between double quotes).
std::string xml(const std::string& name) {
  std::string out;
  for (const char c : name) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// XML 1.0 has no control characters but tab, newline and carriage return, and parsers turn
// those into spaces in attributes; its text is Unicode. A name with a control character or
// bytes that are not UTF-8 cannot be written.
void check_name(const std::string& name, const std::string& what) {
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw std::invalid_argument(what + " '" + printable(name) +
                                  "' has a control character, which URDF (XML) cannot hold");
  if (!is_utf8(name))
    throw std::invalid_argument(what + " '" + printable(name) +
                                "' is not UTF-8 text, which URDF (XML) needs");
}

// The URDF being written. Every link name and every joint name must be used once: expanded
// joints' names (`<joint>/alpha`, `<body>__alpha`) may meet names of the scene.
struct UrdfOut {
  std::ostream& out;
  std::string owner;  // the body (or R) being written, for errors
  std::unordered_map<std::string, std::string> links, joints;  // name -> owner

  void add(std::unordered_map<std::string, std::string>& names, const std::string& name,
           const char* kind) {
    check_name(name, std::string(kind) + " of " + owner);
    const auto [it, inserted] = names.emplace(name, owner);
    if (!inserted)
      throw std::invalid_argument(std::string("URDF ") + kind + " name '" + printable(name) +
                                  "' is made by " + it->second + " and by " + owner);
  }
};

std::string triple(const Vec3<double>& v) {
  return num(v.x()) + " " + num(v.y()) + " " + num(v.z());
}

// URDF rpy of a rotation matrix: R = Rz(yaw) Ry(pitch) Rx(roll).
Vec3<double> rpy_of(const Mat3<double>& r) {
  const Vec3<double> ypr = r.eulerAngles(2, 1, 0);
  return Vec3<double>(ypr[2], ypr[1], ypr[0]);
}

std::string origin(const Vec3<double>& xyz, const Mat3<double>& rotation) {
  return "<origin xyz=\"" + triple(xyz) + "\" rpy=\"" + triple(rpy_of(rotation)) + "\"/>";
}

// A body's link (massless links: body = nullptr). URDF requires an <inertia>: without the
// scene's, a token one marked kTokenInertia, which our loader reads as none.
void write_link(UrdfOut& urdf, const std::string& name, const Body* body,
                const std::string& visuals) {
  urdf.add(urdf.links, name, "link");
  std::ostream& out = urdf.out;
  out << "  <link name=\"" << xml(name) << "\">\n";
  if (body && (body->mass > 0 || body->has_inertia)) {
    const Mat3<double> i = body->has_inertia
                               ? body->inertia
                               : Mat3<double>(1e-3 * body->mass * Mat3<double>::Identity());
    out << "    <inertial>\n      " << origin(body->mass_center, Mat3<double>::Identity())
        << "\n      <mass value=\"" << num(body->mass) << "\"/>\n      <inertia ixx=\""
        << num(i(0, 0)) << "\" ixy=\"" << num(i(0, 1)) << "\" ixz=\"" << num(i(0, 2)) << "\" iyy=\""
        << num(i(1, 1)) << "\" iyz=\"" << num(i(1, 2)) << "\" izz=\"" << num(i(2, 2)) << "\"/>\n";
    if (!body->has_inertia) out << "      <!-- " << kTokenInertia << " -->\n";
    out << "    </inertial>\n";
  }
  out << visuals << "  </link>\n";
}

void write_joint(UrdfOut& urdf, const std::string& name, const std::string& type,
                 const std::string& parent, const std::string& child, const std::string& origin_tag,
                 const Vec3<double>* axis, const std::string& mimic = "") {
  urdf.add(urdf.joints, name, "joint");
  std::ostream& out = urdf.out;
  out << "  <joint name=\"" << xml(name) << "\" type=\"" << type << "\">\n    " << origin_tag
      << "\n    <parent link=\"" << xml(parent) << "\"/>\n    <child link=\"" << xml(child)
      << "\"/>\n";
  if (axis) out << "    <axis xyz=\"" << triple(*axis) << "\"/>\n";
  if (type == "prismatic")
    out << "    <limit lower=\"-1e6\" upper=\"1e6\" effort=\"1e6\" velocity=\"1e6\"/>\n";
  out << mimic << "  </joint>\n";
}

constexpr const char* kMaterial = "<material name=\"mbk_body\"/>";  // defined once, in the robot

std::string sphere(const Vec3<double>& at, double radius) {
  return "    <visual>" + origin(at, Mat3<double>::Identity()) + "<geometry><sphere radius=\"" +
         num(radius) + "\"/></geometry>" + kMaterial + "</visual>\n";
}

// A sphere at the mass center and a capsule (a cylinder with sphere caps) from O_k to each
// child's joint point.
std::string visuals(const Model& model, int k, const std::vector<int>& children) {
  constexpr double kRadius = 0.02;
  std::ostringstream out;
  const Body& body = model.bodies[k];
  out << sphere(body.mass_center, 0.03);
  bool capped = false;
  for (const int c : children) {
    const Vec3<double> to = model.bodies[c].joint.offset;
    if (to.norm() < 1e-9) continue;
    const Mat3<double> along =
        Eigen::Quaterniond::FromTwoVectors(Vec3<double>::UnitZ(), to).toRotationMatrix();
    if (!capped) out << sphere(Vec3<double>::Zero(), kRadius);
    capped = true;
    out << "    <visual>" << origin(to / 2, along) << "<geometry><cylinder radius=\""
        << num(kRadius) << "\" length=\"" << num(to.norm()) << "\"/></geometry>" << kMaterial
        << "</visual>\n"
        << sphere(to, kRadius);
  }
  return out.str();
}

// A joint as a one-axis URDF joint per coordinate (UrdfForm::kAxisChain): translations
// prismatic along x, y, z, then the angles continuous about the joint's Euler order's axes, each
// the new one (1-2-3: x, the new y, the new z; doc/method.md 2), through massless links
// <body>__<coord>.
void write_axis_chain(UrdfOut& out, const Body& body, const std::string& parent) {
  const Joint& joint = body.joint;
  const std::vector<Coordinate>& coordinates = joint_traits(joint.type).coordinates;
  const std::array<int, 3> angle_axes =
      takes_euler_order(joint.type) ? euler_axes(joint.euler_order) : std::array<int, 3>{0, 1, 2};
  std::string from = parent;
  int translations = 0, angles = 0;
  for (size_t i = 0; i < coordinates.size(); ++i) {
    const Coordinate& c = coordinates[i];
    const bool last = i + 1 == coordinates.size();
    const bool translation = c.kind == CoordinateKind::kTranslation;
    const Vec3<double> axis =
        Vec3<double>::Unit(translation ? translations++ : angle_axes[angles++]);
    const std::string to = last ? body.name : body.name + "__" + c.suffix;
    write_joint(out, joint.name + "/" + c.suffix, translation ? "prismatic" : "continuous", from,
                to,
                i == 0 ? origin(joint.offset, joint.rotation)
                       : origin(Vec3<double>::Zero(), Mat3<double>::Identity()),
                &axis);
    if (!last) write_link(out, to, nullptr, "");
    from = to;
  }
}

// More than one rotation coordinate: drawn as one URDF floating joint by UrdfStyle::kDisplay.
bool multi_axis(JointType type) {
  int rotations = 0;
  for (const Coordinate& c : joint_traits(type).coordinates)
    rotations += c.kind != CoordinateKind::kTranslation;
  return rotations > 1;
}

}  // namespace

std::string write_urdf(const Model& model, const std::string& robot_name, UrdfStyle style) {
  check_name(robot_name, "robot name");
  std::vector<std::vector<int>> children(model.bodies.size());  // for the visuals, in O(N)
  for (int k = 1; k <= model.body_count(); ++k) children[model.bodies[k].lower].push_back(k);
  std::vector<std::string> mimics(model.nq);  // the <mimic> tag of each coordinate that has one
  for (const Mimic& m : model.mimics)
    mimics[m.coordinate] = "    <mimic joint=\"" + xml(model.coordinate_names[m.source]) +
                           "\" multiplier=\"" + num(m.multiplier) + "\" offset=\"" + num(m.offset) +
                           "\"/>\n";
  std::ostringstream text;
  UrdfOut out{text, "R '" + printable(model.frame) + "'", {}, {}};
  text << "<?xml version=\"1.0\"?>\n<!-- Generated by `mbk urdf` from a scene: do not edit. -->\n"
       << "<robot name=\"" << xml(robot_name) << "\">\n"
       << "  <material name=\"mbk_body\"><color rgba=\"0.6 0.65 0.75 1\"/></material>\n";
  write_link(out, model.frame, nullptr, "");
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    out.owner = "body " + std::to_string(k) + " '" + printable(body.name) + "'";
    const Joint& joint = body.joint;
    const std::string parent = model.bodies[body.lower].name;
    const std::string first = origin(joint.offset, joint.rotation);
    const JointTraits& traits = joint_traits(joint.type);
    if (style == UrdfStyle::kDisplay && multi_axis(joint.type)) {
      write_joint(out, joint.name, "floating", parent, body.name, first, nullptr);
      write_link(out, body.name, &body, visuals(model, k, children[k]));
      continue;
    }
    switch (traits.urdf_form) {
      case UrdfForm::kJoint:
        write_joint(out, joint.name, traits.urdf_type, parent, body.name, first,
                    traits.uses_axis ? &joint.axis : nullptr,
                    traits.coordinates.size() == 1 ? mimics[body.q_index] : "");
        break;
      case UrdfForm::kAxisChain:
        write_axis_chain(out, body, parent);
        break;
      case UrdfForm::kNone:
        throw std::invalid_argument(printable("body '" + body.name + "': joint '" + joint.name +
                                              "' (" + to_string(joint.type) +
                                              ") has no URDF equivalent"));
    }
    write_link(out, body.name, &body, visuals(model, k, children[k]));
  }
  text << "</robot>\n";
  return text.str();
}

}  // namespace mbk
