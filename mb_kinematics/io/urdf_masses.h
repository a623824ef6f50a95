// The mass of every link of a URDF, by name, for what only needs masses (the rviz display's
// mass filter): read with urdfdom, without the model's checks, so a description that the model
// loader refuses still gives its masses.
#pragma once

#include <map>
#include <string>

namespace mbk {

// Link name -> <inertial><mass> (kg); 0 for a link without <inertial>. Throws
// std::runtime_error naming the problem when `urdf_xml` is not a URDF.
std::map<std::string, double> urdf_link_masses(const std::string& urdf_xml);

}  // namespace mbk
