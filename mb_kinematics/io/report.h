// Text the `mbk` tool prints: the lower body arrays table and the kinematics as JSON.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

// Table 4.2.1 layout: a row per t with L^t(k), each entry shown until its chain has reached 0
// (the 0 itself shown once). `names` (optional, N entries) adds a legend. Columns widen for
// N >= 1000 and depths >= 1000. Written row by row as computed: O(N) memory for N x depth text.
void write_lower_body_table(std::ostream& out, const std::vector<int>& lower,
                            const std::vector<std::string>& names = {});
std::string format_lower_body_table(const std::vector<int>& lower,
                                    const std::vector<std::string>& names = {});

// One row per t = 0, 1, ... until a row is all zeros, N comma-separated values each; streamed
// like write_lower_body_table.
void write_lower_body_csv(std::ostream& out, const std::vector<int>& lower);
std::string format_lower_body_csv(const std::vector<int>& lower);

// A JSON string literal: quotes, backslashes and control characters escaped; bytes that are
// not UTF-8 become U+FFFD (JSON text is Unicode).
std::string json_string(const std::string& text);

// The `mbk eval` JSON (doc/mbk.md; doc/method.md 8). Throws std::runtime_error naming the body if a
// value is not finite (nothing is printed then). `system` adds "system" (doc/method.md 9: null
// vectors when M = 0, a null angular momentum and "missing_inertia" when bodies lack inertias);
// `pv` adds per body "partial_omega", "partial_velocity", "partial_omega_dot",
// "partial_velocity_dot", keyed by independent speed name (core/independent_speeds.h);
// `incomplete` (segments of the body the model lacks, e.g. a BVH skeleton's "left hand") adds
// "incomplete": [names] to "system": the whole-body quantities are not the whole body's.
// `extra.body_axes` adds per body "omega_body", "alpha_body", "velocity_body",
// "acceleration_body" (in Bk's axes), `extra.relative` "relative_rotation", "relative_omega",
// "relative_alpha" (relative to L(k), in its axes): core/segment_frames.h.
struct EvalExtras {
  bool body_axes = false;
  bool relative = false;
};
std::string format_eval_json(const Model& model, const Data<double>& data,
                             const SystemKinematics<double>* system = nullptr,
                             const PartialVelocities<double>* pv = nullptr,
                             const std::vector<std::string>& incomplete = {},
                             const EvalExtras& extra = {});

}  // namespace mbk
