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

// A body's link (massless links: body = nullptr). URDF requires an <inertia>: without the
// scene's, a token one marked kTokenInertia, which our loader reads as none.
void write_link(std::ostream& out, const std::string& name, const Body* body,
                const std::string& visuals) {
  out << "  <link name=\"" << name << "\">\n";
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

// A ball or free joint on 1-2-3 angles as URDF joints: prismatic x, y, z (free joints), then
// continuous joints about x, the new y and the new z, through massless links <body>__<coord>.
void write_angle_chain(std::ostream& out, const Body& body, const std::string& parent) {
  const Vec3<double> ex = Vec3<double>::UnitX(), ey = Vec3<double>::UnitY(),
                     ez = Vec3<double>::UnitZ();
  struct Step {
    const char* coordinate;
    const char* type;
    const Vec3<double>* axis;
  };
  const Step steps[] = {{"x", "prismatic", &ex},     {"y", "prismatic", &ey},
                        {"z", "prismatic", &ez},     {"alpha", "continuous", &ex},
                        {"beta", "continuous", &ey}, {"gamma", "continuous", &ez}};
  const Joint& joint = body.joint;
  const int first = joint.type == JointType::kFree123 ? 0 : 3;
  std::string from = parent;
  for (int i = first; i < 6; ++i) {
    const bool last = i == 5;
    const std::string to = last ? body.name : body.name + "__" + steps[i].coordinate;
    write_joint(out, joint.name + "/" + steps[i].coordinate, steps[i].type, from, to,
                i == first ? origin(joint.offset, joint.rotation)
                           : origin(Vec3<double>::Zero(), Mat3<double>::Identity()),
                steps[i].axis);
    if (!last) write_link(out, to, nullptr, "");
    from = to;
  }
}

}  // namespace

std::string write_urdf(const Model& model, const std::string& robot_name, UrdfStyle style) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<!-- Generated by `mbk urdf` from a scene: do not edit. -->\n"
      << "<robot name=\"" << robot_name << "\">\n"
      << "  <material name=\"mbk_body\"><color rgba=\"0.6 0.65 0.75 1\"/></material>\n";
  write_link(out, model.frame, nullptr, "");
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const Joint& joint = body.joint;
    const std::string parent = model.bodies[body.lower].name;
    const std::string first = origin(joint.offset, joint.rotation);
    const bool multi_axis = joint.type == JointType::kBall123 ||
                            joint.type == JointType::kFree123 || uses_euler_parameters(joint.type);
    if (style == UrdfStyle::kDisplay && multi_axis) {
      write_joint(out, joint.name, "floating", parent, body.name, first, nullptr);
      write_link(out, body.name, &body, visuals(model, k));
      continue;
    }
    switch (joint.type) {
      case JointType::kFixed:
        write_joint(out, joint.name, "fixed", parent, body.name, first, nullptr);
        break;
      case JointType::kRevolute:
        write_joint(out, joint.name, "continuous", parent, body.name, first, &joint.axis);
        break;
      case JointType::kPrismatic:
        write_joint(out, joint.name, "prismatic", parent, body.name, first, &joint.axis);
        break;
      case JointType::kPlanar:
        write_joint(out, joint.name, "planar", parent, body.name, first, &joint.axis);
        break;
      case JointType::kBall123:
      case JointType::kFree123:
        write_angle_chain(out, body, parent);
        break;
      case JointType::kBallEuler:
      case JointType::kFreeEuler:
        throw std::invalid_argument("body '" + body.name + "': joint '" + joint.name + "' (" +
                                    to_string(joint.type) + ") has no URDF equivalent");
    }
    write_link(out, body.name, &body, visuals(model, k));
  }
  out << "</robot>\n";
  return out.str();
}

}  // namespace mbk
