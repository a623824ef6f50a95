// The kinematics of N joint states at once, into arrays the caller owns (the Python module's
// `Model.kinematics`, doc/python.md): row-major C arrays, one row per sample, only the fields
// asked for written, the level (pose, velocity, acceleration) the highest a field needs, the
// samples split over threads. Each sample is what `mbk eval` computes for that state, bit for
// bit, whatever the number of threads. ROS-free.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

// The arrays a batch can write, under the names of `mbk eval`'s JSON (the system's with a
// `system_` prefix where a body's field has the same name). Shapes, with N samples and B bodies
// chosen: rotation (N, B, 3, 3) S0K row by row; the other per-body fields (N, B, 3);
// system_mass (N); the other system fields (N, 3); the partial velocities and their time
// derivatives (N, B, nv, 3), zero in the columns of speeds outside a body's chain and of mimic
// coordinates (whose columns count, times the multiplier, in their sources', as in `mbk eval`).
// The segment frames and joint motion (core/segment_frames.h, opt-in): omega, alpha, velocity and
// acceleration of G_k in Bk's own axes (`*_body`, as `mbk eval --body-axes`); each body relative
// to its lower body Bj: relative_rotation SJK (N, B, 3, 3), relative_omega and relative_alpha in
// Bj's axes (as `mbk eval --relative`).
enum class BatchField {
  kRotation,
  kOrigin,
  kMassCenter,
  kOmega,
  kAlpha,
  kVelocity,      // of the mass center G_k
  kAcceleration,  // of the mass center G_k
  kSystemMass,
  kSystemMassCenter,
  kSystemVelocity,
  kSystemAcceleration,
  kLinearMomentum,
  kAngularMomentum,  // NaN where `mbk eval` writes null (a body with mass but no inertia)
  kPartialOmega,
  kPartialVelocity,
  kPartialOmegaDot,
  kPartialVelocityDot,
  kOmegaBody,
  kAlphaBody,
  kVelocityBody,
  kAccelerationBody,
  kRelativeRotation,
  kRelativeOmega,
  kRelativeAlpha,
  kCount,
};
constexpr int kBatchFieldCount = static_cast<int>(BatchField::kCount);

struct BatchFieldTraits {
  const char* name;
  Level level;              // the least level that computes it
  bool needs_velocity;      // depends on the joint speeds
  bool needs_acceleration;  // depends on their derivatives
  bool per_body;            // one block per chosen body
  int width;                // numbers per block (per sample for system fields); 0: nv * 3
  bool opt_in = false;      // written only when asked for by name (not in Python's default)
};
const BatchFieldTraits& batch_field_traits(BatchField field);
// The field of that name; throws std::invalid_argument naming it and the known names.
BatchField batch_field_from_name(const std::string& name);
// The shape of `field`'s numbers per sample for `bodies` chosen bodies of `model`: (bodies,) for
// a field per body, then (3, 3) for a rotation, (nv, 3) for partial velocities, (3,) for a
// vector, () for a number; batch_field_size, their count.
std::vector<std::size_t> batch_field_shape(const Model& model, BatchField field,
                                           std::size_t bodies);
std::size_t batch_field_size(const Model& model, BatchField field, std::size_t bodies);

// Row-major inputs: position (N, nq); velocity and acceleration (N, nv) or null (zero). Mimic
// coordinates are set from their sources (apply_mimics), whatever the rows hold there.
struct BatchInput {
  std::size_t samples = 0;
  const double* position = nullptr;
  const double* velocity = nullptr;
  const double* acceleration = nullptr;
};

// Where each field goes (null: not asked for), and the bodies (1..N, any order, repeats allowed).
template <typename T>
struct BatchOutput {
  std::array<T*, kBatchFieldCount> field{};
  std::vector<int> bodies;
  T*& operator[](BatchField f) { return field[static_cast<int>(f)]; }
  T* operator[](BatchField f) const { return field[static_cast<int>(f)]; }
};

// Sample s of `out`'s per-body and system fields (the partial velocities aside) from `data`,
// computed at `level` (at least batch_level(out)); `system`: scratch. What batch_kinematics
// writes for a sample, for writers of other formats (offline/h5_output.h).
template <typename T>
void write_batch_fields(const Model& model, const Data<double>& data, std::size_t s, Level level,
                        const BatchOutput<T>& out, SystemKinematics<double>& system);

// The level the fields asked for need.
template <typename T>
Level batch_level(const BatchOutput<T>& out);

// A call whose outputs take more than this many bytes streams them to memory
// (offline/stream_copy.h): each sample computed into a one-sample buffer and copied to its rows
// with streaming stores, which write each line once instead of reading it first. Smaller outputs
// are written in place with ordinary stores, which leave them in the caches for the caller's next
// read: faster up to about half of a 32 MiB L3 cache, slower above it (doc/speed.md#python).
constexpr std::size_t kBatchStreamBytes = std::size_t{16} << 20;

// Computes every sample into `out` (T = double or float) on `threads` threads (0: the machine's
// cores; never more than the samples). First checks everything and throws std::invalid_argument
// with a one-line message, writing nothing: a body index out of range, a field that needs
// velocities or accelerations the input lacks, or a sample check_state rejects ("sample 12: body 3
// 'arm', coordinate 'elbow': not finite (nan)").
// In double without partial velocities, the samples go up to samples_at_once(model)
// (core/kinematics_lanes.h) at once, at most `most_lanes` (a benchmark's or test's choice: 4 on a
// CPU that has 8, 1 for one at a time); the numbers are the same.
template <typename T>
void batch_kinematics(const Model& model, const BatchInput& in, const BatchOutput<T>& out,
                      int threads = 0, int most_lanes = 8);

}  // namespace mbk
