#include "mb_kinematics/io/urdf_masses.h"

#include <urdf_parser/urdf_parser.h>

#include <stdexcept>

namespace mbk {

std::map<std::string, double> urdf_link_masses(const std::string& urdf_xml) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw std::runtime_error("not a valid URDF (urdfdom could not parse it)");
  std::map<std::string, double> masses;
  for (const auto& [name, link] : model->links_)
    masses[name] = link->inertial ? link->inertial->mass : 0.0;
  return masses;
}

}  // namespace mbk
