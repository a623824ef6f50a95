#include "mb_kinematics/core/known_bodies.h"

#include <stdexcept>

#include "mb_kinematics/core/joint.h"

namespace mbk {

int known_bodies(const Model& model, std::vector<char>& coordinate_known,
                 std::vector<char>& body_known) {
  if (static_cast<int>(coordinate_known.size()) != model.nq)
    throw std::invalid_argument("known_bodies: " + std::to_string(coordinate_known.size()) +
                                " coordinate flags for " + std::to_string(model.nq) +
                                " coordinates");
  for (const Mimic& m : model.mimics) coordinate_known[m.coordinate] = coordinate_known[m.source];
  const int n = model.body_count();
  body_known.resize(n + 1);
  body_known[0] = 1;
  int count = 0;
  for (int k = 1; k <= n; ++k) {  // L(k) < k: the lower body is settled first
    const Body& body = model.bodies[k];
    bool known = body_known[body.lower];
    const int end = body.q_index + coordinate_count(body.joint.type);
    for (int i = body.q_index; known && i < end; ++i) known = coordinate_known[i];
    body_known[k] = known;
    count += known;
  }
  return count;
}

}  // namespace mbk
