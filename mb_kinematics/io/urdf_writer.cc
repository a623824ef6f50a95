#include "mb_kinematics/io/urdf_writer.h"

#include <sstream>
#include <stdexcept>

#include "mb_kinematics/io/number_format.h"

namespace mbk {
namespace {

std::string num(double x) { return format_double(x); }

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

void write_link(std::ostream& out, const std::string& name, double mass, const Vec3<double>& com,
                const std::string& visuals) {
  out << "  <link name=\"" << name << "\">\n";
  if (mass > 0) {
    const std::string i = num(1e-3 * mass);  // a token inertia: kinematics does not use it
    out << "    <inertial>\n      " << origin(com, Mat3<double>::Identity())
        << "\n      <mass value=\"" << num(mass) << "\"/>\n      <inertia ixx=\"" << i
        << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << i << "\" iyz=\"0\" izz=\"" << i
        << "\"/>\n    </inertial>\n";
  }
  out << visuals << "  </link>\n";
}

void write_joint(std::ostream& out, const std::string& name, const std::string& type,
                 const std::string& parent, const std::string& child, const std::string& origin_tag,
                 const Vec3<double>* axis) {
  out << "  <joint name=\"" << name << "\" type=\"" << type << "\">\n    " << origin_tag
      << "\n    <parent link=\"" << parent << "\"/>\n    <child link=\"" << child << "\"/>\n";
  if (axis) out << "    <axis xyz=\"" << triple(*axis) << "\"/>\n";
  if (type == "prismatic")
    out << "    <limit lower=\"-1e6\" upper=\"1e6\" effort=\"1e6\" velocity=\"1e6\"/>\n";
  out << "  </joint>\n";
}

constexpr const char* kMaterial = "<material name=\"mbk_body\"/>";  // defined once, in the robot

std::string sphere(const Vec3<double>& at, double radius) {
  return "    <visual>" + origin(at, Mat3<double>::Identity()) + "<geometry><sphere radius=\"" +
         num(radius) + "\"/></geometry>" + kMaterial + "</visual>\n";
}

// A sphere at the mass center and a capsule (a cylinder with sphere caps) from O_k to each
// child's joint point.
std::string visuals(const Model& model, int k) {
  constexpr double kRadius = 0.02;
  std::ostringstream out;
  const Body& body = model.bodies[k];
  out << sphere(body.mass_center, 0.03);
  bool capped = false;
  for (int c = k + 1; c <= model.body_count(); ++c) {
    const Vec3<double> to = model.bodies[c].joint.offset;
    if (model.bodies[c].lower != k || to.norm() < 1e-9) continue;
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
// prismatic along x, y, z, then 1-2-3 angles continuous about x, the new y and the new z
// (doc/method.md 2), through massless links <body>__<coord>.
void write_axis_chain(std::ostream& out, const Body& body, const std::string& parent) {
  const Joint& joint = body.joint;
  const std::vector<Coordinate>& coordinates = joint_traits(joint.type).coordinates;
  std::string from = parent;
  int translations = 0, angles = 0;
  for (size_t i = 0; i < coordinates.size(); ++i) {
    const Coordinate& c = coordinates[i];
    const bool last = i + 1 == coordinates.size();
    const bool translation = c.kind == CoordinateKind::kTranslation;
    const Vec3<double> axis = Vec3<double>::Unit(translation ? translations++ : angles++);
    const std::string to = last ? body.name : body.name + "__" + c.suffix;
    write_joint(out, joint.name + "/" + c.suffix, translation ? "prismatic" : "continuous", from,
                to,
                i == 0 ? origin(joint.offset, joint.rotation)
                       : origin(Vec3<double>::Zero(), Mat3<double>::Identity()),
                &axis);
    if (!last) write_link(out, to, 0.0, Vec3<double>::Zero(), "");
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
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<!-- Generated by `mbk urdf` from a scene: do not edit. -->\n"
      << "<robot name=\"" << robot_name << "\">\n"
      << "  <material name=\"mbk_body\"><color rgba=\"0.6 0.65 0.75 1\"/></material>\n";
  write_link(out, model.frame, 0.0, Vec3<double>::Zero(), "");
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const Joint& joint = body.joint;
    const std::string parent = model.bodies[body.lower].name;
    const std::string first = origin(joint.offset, joint.rotation);
    const JointTraits& traits = joint_traits(joint.type);
    if (style == UrdfStyle::kDisplay && multi_axis(joint.type)) {
      write_joint(out, joint.name, "floating", parent, body.name, first, nullptr);
      write_link(out, body.name, body.mass, body.mass_center, visuals(model, k));
      continue;
    }
    switch (traits.urdf_form) {
      case UrdfForm::kJoint:
        write_joint(out, joint.name, traits.urdf_type, parent, body.name, first,
                    traits.uses_axis ? &joint.axis : nullptr);
        break;
      case UrdfForm::kAxisChain:
        write_axis_chain(out, body, parent);
        break;
      case UrdfForm::kNone:
        throw std::invalid_argument("body '" + body.name + "': joint '" + joint.name + "' (" +
                                    to_string(joint.type) + ") has no URDF equivalent");
    }
    write_link(out, body.name, body.mass, body.mass_center, visuals(model, k));
  }
  out << "</robot>\n";
  return out.str();
}

}  // namespace mbk
