#include "mb_kinematics/offline/batch_kinematics.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <thread>
#include <type_traits>
#ifdef __x86_64__
#include <immintrin.h>
#endif

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/kinematics_lanes.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/segment_frames.h"
#include "mb_kinematics/core/split_runs.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/offline/stream_copy.h"

namespace mbk {
namespace {

constexpr Level kP = Level::kPose, kV = Level::kVelocity, kA = Level::kAcceleration;

// In BatchField order.
const BatchFieldTraits kTraits[kBatchFieldCount] = {
    {"rotation", kP, false, false, true, 9},
    {"origin", kP, false, false, true, 3},
    {"mass_center", kP, false, false, true, 3},
    {"omega", kV, true, false, true, 3},
    {"alpha", kA, true, true, true, 3},
    {"velocity", kV, true, false, true, 3},
    {"acceleration", kA, true, true, true, 3},
    {"system_mass", kP, false, false, false, 1},
    {"system_mass_center", kP, false, false, false, 3},
    {"system_velocity", kV, true, false, false, 3},
    {"system_acceleration", kA, true, true, false, 3},
    {"linear_momentum", kV, true, false, false, 3},
    {"angular_momentum", kV, true, false, false, 3},
    {"partial_omega", kV, false, false, true, 0, true},
    {"partial_velocity", kV, false, false, true, 0, true},
    {"partial_omega_dot", kA, true, false, true, 0, true},
    {"partial_velocity_dot", kA, true, false, true, 0, true},
    {"omega_body", kV, true, false, true, 3, true},
    {"alpha_body", kA, true, true, true, 3, true},
    {"velocity_body", kV, true, false, true, 3, true},
    {"acceleration_body", kA, true, true, true, 3, true},
    {"relative_rotation", kP, false, false, true, 9, true},
    {"relative_omega", kV, true, false, true, 3, true},
    {"relative_alpha", kA, true, true, true, 3, true},
};

template <typename T>
bool any_partials(const BatchOutput<T>& out) {
  return out[BatchField::kPartialOmega] || out[BatchField::kPartialVelocity] ||
         out[BatchField::kPartialOmegaDot] || out[BatchField::kPartialVelocityDot];
}

// One thread's workspace, made once for its run of samples.
struct Workspace {
  explicit Workspace(const Model& model) : state(model), data(model) {}
  JointState<double> state;
  Data<double> data;
  std::unique_ptr<PartialVelocities<double>> pv;  // O(N * depth): only for partials
  std::unique_ptr<Data<double>> scratch;          // partial_velocity_kinematics' own Data
  SystemKinematics<double> system;
};

// Row s of the inputs into `state`, mimic coordinates from their sources (as `mbk eval`).
void load_sample(const Model& model, const BatchInput& in, std::size_t s,
                 JointState<double>& state) {
  const auto row = [s](const double* rows, int width, VecX<double>& to) {  // `to`: width numbers
    std::memcpy(to.data(), rows + s * width, static_cast<std::size_t>(width) * sizeof(double));
  };
  row(in.position, model.nq, state.position);
  if (in.velocity) row(in.velocity, model.nv, state.velocity);
  if (in.acceleration) row(in.acceleration, model.nv, state.acceleration);
  apply_mimics(model, state);
}

// The writers below take the workspace's scalar S: double, or DoubleLanes (several samples, a lane
// each, written to a row of DoubleLanes that to_rows then turns into the samples' rows).
template <typename T, typename S>
void put(T* out, const Vec3<S>& v) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<T>(v[i]);
}

template <typename T, typename S>
void put(T* out, const Mat3<S>& m) {  // row by row
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out[a * 3 + b] = static_cast<T>(m(a, b));
}

template <typename T, typename S>
void put_or_nan(T* out, const Vec3<S>& v, bool known) {
  for (int i = 0; i < 3; ++i)
    out[i] = known ? static_cast<T>(v[i]) : T(std::numeric_limits<double>::quiet_NaN());
}

// Whether `bodies` is 1..N, every body in order (Model.kinematics' default).
bool every_body_in_order(const std::vector<int>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i] != static_cast<int>(i) + 1) return false;
  return true;
}

// The rows of `values` of the chosen bodies into v, 3 numbers a row: in S itself for every body
// in order, one copy of Data's run of rows 1..N.
template <typename T, typename S>
void put_rows(T* v, const std::vector<Vec3<S>>& values, const std::vector<int>& bodies,
              bool every_body) {
  static_assert(sizeof(Vec3<S>) == 3 * sizeof(S), "Vec3<S>: three packed numbers");
  if constexpr (std::is_same_v<T, S>)
    if (every_body) {
      std::memcpy(v, values[1].data(), bodies.size() * sizeof(Vec3<S>));
      return;
    }
  for (std::size_t i = 0; i < bodies.size(); ++i) put(v + i * 3, values[bodies[i]]);
}

// The per-body fields that are one vector of Data per body, with that vector: for every body in
// order, rows 1..N of it are one run of the field's row in the caller's array.
template <typename S>
using DataVector = std::vector<Vec3<S>> Data<S>::*;
template <typename S>
constexpr std::pair<BatchField, DataVector<S>> kDataVectors[] = {
    {BatchField::kOrigin, &Data<S>::origin},
    {BatchField::kMassCenter, &Data<S>::mass_center},
    {BatchField::kOmega, &Data<S>::omega},
    {BatchField::kAlpha, &Data<S>::alpha},
    {BatchField::kVelocity, &Data<S>::mass_center_velocity},
    {BatchField::kAcceleration, &Data<S>::mass_center_acceleration}};

// The vectors of Data the segment-frame fields read in Bk's axes (core/segment_frames.h).
template <typename S>
constexpr std::pair<BatchField, DataVector<S>> kInBodyVectors[] = {
    {BatchField::kOmegaBody, &Data<S>::omega},
    {BatchField::kAlphaBody, &Data<S>::alpha},
    {BatchField::kVelocityBody, &Data<S>::mass_center_velocity},
    {BatchField::kAccelerationBody, &Data<S>::mass_center_acceleration}};

// Field's vector in `table`; null if it has none.
template <typename S, std::size_t kSize>
DataVector<S> vector_of(const std::pair<BatchField, DataVector<S>> (&table)[kSize],
                        BatchField field) {
  for (const auto& [f, vector] : table)
    if (f == field) return vector;
  return nullptr;
}

// One sample's row of a per-body field (the partial velocities aside) into v: the chosen bodies'
// blocks from `data`, or computed from it (the segment frames and joint motion,
// core/segment_frames.h).
template <typename T, typename S>
void write_body_field(const Model& model, const Data<S>& data, BatchField field,
                      const std::vector<int>& bodies, bool every_body, T* v) {
  const std::size_t nb = bodies.size();
  if (const DataVector<S> vector = vector_of(kDataVectors<S>, field))
    return put_rows(v, data.*vector, bodies, every_body);
  if (const DataVector<S> vector = vector_of(kInBodyVectors<S>, field)) {
    for (std::size_t i = 0; i < nb; ++i)
      put(v + i * 3, in_body_axes(data, bodies[i], (data.*vector)[bodies[i]]));
  } else if (field == BatchField::kRotation) {
    for (std::size_t i = 0; i < nb; ++i) put(v + i * 9, data.rotation[bodies[i]]);
  } else if (field == BatchField::kRelativeRotation) {
    for (std::size_t i = 0; i < nb; ++i) put(v + i * 9, relative_rotation(model, data, bodies[i]));
  } else if (field == BatchField::kRelativeOmega) {
    for (std::size_t i = 0; i < nb; ++i) put(v + i * 3, relative_omega(model, data, bodies[i]));
  } else if (field == BatchField::kRelativeAlpha) {
    for (std::size_t i = 0; i < nb; ++i) put(v + i * 3, relative_alpha(model, data, bodies[i]));
  }
}

// Whether `field` is written by write_body_field.
bool is_body_field(BatchField field) {
  const BatchFieldTraits& t = kTraits[static_cast<int>(field)];
  return t.per_body && t.width > 0;
}

// Sample s's rows of the per-body outputs, a field at a time (each field's rows of a sample are
// one run of the caller's array). Writing in place instead would need every kernel to treat the
// ground, which has no row in the caller's arrays, apart.
template <typename T, typename S>
void write_bodies(const Model& model, const Data<S>& data, std::size_t s,
                  const BatchOutput<T>& out) {
  const std::size_t nb = out.bodies.size();
  const bool every_body = nb > 0 && every_body_in_order(out.bodies);
  for (int f = 0; f < kBatchFieldCount; ++f) {
    const BatchField field = static_cast<BatchField>(f);
    if (T* v = out[field]; v && is_body_field(field))
      write_body_field(model, data, field, out.bodies, every_body, v + s * nb * kTraits[f].width);
  }
}

// As `mbk eval`'s JSON: the vectors are NaN where it writes null (no mass: no mass center; a body
// with mass but no inertia: no angular momentum).
template <typename T, typename S>
void write_system(const SystemKinematics<S>& sys, std::size_t s, const BatchOutput<T>& out) {
  const bool g = sys.has_mass;
  if (T* m = out[BatchField::kSystemMass]) m[s] = static_cast<T>(sys.mass);
  const std::pair<BatchField, const Vec3<S>*> vectors[] = {
      {BatchField::kSystemMassCenter, &sys.mass_center},
      {BatchField::kSystemVelocity, &sys.velocity},
      {BatchField::kSystemAcceleration, &sys.acceleration},
      {BatchField::kLinearMomentum, &sys.linear_momentum}};
  for (const auto& [field, value] : vectors)
    if (T* v = out[field]) put_or_nan(v + s * 3, *value, g);
  if (T* h = out[BatchField::kAngularMomentum])
    put_or_nan(h + s * 3, sys.angular_momentum, g && sys.angular_momentum_known);
}

template <typename T>
void write_partials(const Model& model, const PartialVelocities<double>& pv, std::size_t s,
                    const BatchOutput<T>& out) {
  const std::size_t nb = out.bodies.size(), width = static_cast<std::size_t>(model.nv) * 3;
  const BatchField fields[] = {BatchField::kPartialOmega, BatchField::kPartialVelocity,
                               BatchField::kPartialOmegaDot, BatchField::kPartialVelocityDot};
  const Vec3<double> SpeedColumn::*members[] = {&SpeedColumn::omega, &SpeedColumn::velocity,
                                                &SpeedColumn::omega_dot,
                                                &SpeedColumn::velocity_dot};
  for (std::size_t i = 0; i < nb; ++i) {
    const std::vector<SpeedColumn> columns = independent_columns(model, pv, out.bodies[i]);
    for (int f = 0; f < 4; ++f) {
      T* block = out[fields[f]];
      if (!block) continue;
      block += (s * nb + i) * width;
      std::fill(block, block + width, T(0));
      for (const SpeedColumn& c : columns) put(block + c.speed * 3, c.*members[f]);
    }
  }
}

template <typename T>
bool any_system(const BatchOutput<T>& out) {
  return out[BatchField::kSystemMass] || out[BatchField::kSystemMassCenter] ||
         out[BatchField::kSystemVelocity] || out[BatchField::kSystemAcceleration] ||
         out[BatchField::kLinearMomentum] || out[BatchField::kAngularMomentum];
}

// write_batch_fields for the workspace's scalar S.
template <typename T, typename S>
void write_fields(const Model& model, const Data<S>& data, std::size_t s, Level level,
                  const BatchOutput<T>& out, SystemKinematics<S>& system) {
  write_bodies(model, data, s, out);
  if (any_system(out)) {
    system_kinematics(model, data, system, level);
    write_system(system, s, out);
  }
}

// Input row s into output row `row` of `out`.
template <typename T>
void compute_sample(const Model& model, const BatchInput& in, std::size_t s, std::size_t row,
                    Level level, const BatchOutput<T>& out, Workspace& w) {
  load_sample(model, in, s, w.state);
  if (w.pv) partial_velocity_kinematics(model, w.state, *w.pv, *w.scratch, level);
  forward_kinematics(model, w.state, w.data, level);
  write_fields(model, w.data, row, level, out, w.system);
  if (w.pv) write_partials(model, *w.pv, row, out);
}

// The numbers per sample of each field of `out` (0: not asked for).
template <typename T>
std::array<std::size_t, kBatchFieldCount> row_sizes(const Model& model, const BatchOutput<T>& out) {
  std::array<std::size_t, kBatchFieldCount> size{};
  for (int f = 0; f < kBatchFieldCount; ++f)
    if (out.field[f])
      size[f] = batch_field_size(model, static_cast<BatchField>(f), out.bodies.size());
  return size;
}

// One sample's outputs in a buffer that stays in the caches, streamed to the caller's rows once
// computed (stream_copy): each line of the arrays is written once, not read first, and the
// workspace is not evicted by the outputs (doc/speed.md#python). With every body in order, the
// vectors of Data (kDataVectors) of doubles are left out of the buffer and streamed straight
// from Data (`direct`).
template <typename T>
struct StagedRow {
  StagedRow(const Model& model, const BatchOutput<T>& out) : size(row_sizes(model, out)) {
    if (std::is_same_v<T, double> && !out.bodies.empty() && every_body_in_order(out.bodies))
      for (const auto& [field, vector] : kDataVectors<double>)
        if (out[field]) direct[static_cast<int>(field)] = vector;
    std::size_t total = 0;
    for (int f = 0; f < kBatchFieldCount; ++f)
      if (!direct[f]) total += size[f];
    buffer.resize(total);
    row.bodies = out.bodies;
    total = 0;
    for (int f = 0; f < kBatchFieldCount; ++f)
      if (size[f] > 0 && !direct[f]) {
        row.field[f] = buffer.data() + total;
        total += size[f];
      }
  }
  // Sample s's rows.
  void stream_to(const BatchOutput<T>& out, std::size_t s, const Data<double>& data) const {
    for (int f = 0; f < kBatchFieldCount; ++f) {
      const std::size_t n = size[f];
      if (n == 0) continue;
      const void* from = row.field[f];
      if (direct[f]) from = (data.*direct[f])[1].data();
      stream_copy(out.field[f] + s * n, from, n * sizeof(T));
    }
  }
  std::array<std::size_t, kBatchFieldCount> size;  // numbers per sample of each field
  std::array<DataVector<double>, kBatchFieldCount> direct{};
  std::vector<T> buffer;
  BatchOutput<T> row;  // row 0 of each other field of `out`, in `buffer`
};

#ifdef MBK_AVX2_DISPATCH
// N samples at once (core/kinematics_lanes.h), a lane each: their states in one JointState, each
// field's row written by the same writers as one row of DoubleLanes<N> (each number's N samples
// together), then turned into the N samples' rows, which follow each other in the caller's array,
// and copied there, a field at a time: the row and the rows stay in L1; eight lanes of a field of
// eight numbers or more, streamed, go from the row to the caller's array in registers
// (stream_transpose8). With every body in order, the vectors of Data (kDataVectors) are turned
// straight from Data.
template <int N>
struct LaneSamples {
  using Lanes = DoubleLanes<N>;
  LaneSamples(const Model& model, const BatchOutput<double>& out)
      : state(model),
        data(model),
        size(row_sizes(model, out)),
        every_body(!out.bodies.empty() && every_body_in_order(out.bodies)) {
    const std::size_t most = *std::max_element(size.begin(), size.end());
    numbers.resize(most);
    rows.resize(N * most);
  }
  JointState<Lanes> state;
  Data<Lanes> data;
  SystemKinematics<Lanes> system;
  std::array<std::size_t, kBatchFieldCount> size;  // numbers per sample of each field
  bool every_body;
  std::vector<Lanes> numbers;                   // one field's row, N samples a number
  std::vector<double> rows;                     // the N samples' rows of that field
  std::array<HeldLine, kBatchFieldCount> held;  // each field's line that the next group completes
};

// Field's row of the N samples in w: from Data, or written into w.numbers.
template <int N>
const DoubleLanes<N>* lane_row(const Model& model, BatchField field, const std::vector<int>& bodies,
                               LaneSamples<N>& w) {
  using Lanes = DoubleLanes<N>;
  if (const DataVector<Lanes> vector = vector_of(kDataVectors<Lanes>, field);
      vector && w.every_body)
    return (w.data.*vector)[1].data();
  if (is_body_field(field)) {
    write_body_field(model, w.data, field, bodies, w.every_body, w.numbers.data());
  } else {
    BatchOutput<Lanes> one;
    one[field] = w.numbers.data();
    write_system(w.system, 0, one);
  }
  return w.numbers.data();
}

// The 4 x 4 block of doubles a[0..3][0..3] into b[j][i] = a[i][j] (a[i], b[j]: four doubles, at
// any alignment), in registers.
__attribute__((target("avx2"))) void transpose4(const double* a0, const double* a1,
                                                const double* a2, const double* a3, double* b0,
                                                double* b1, double* b2, double* b3) {
  const __m256d a = _mm256_loadu_pd(a0), b = _mm256_loadu_pd(a1), c = _mm256_loadu_pd(a2),
                d = _mm256_loadu_pd(a3);
  const __m256d ab0 = _mm256_unpacklo_pd(a, b), ab1 = _mm256_unpackhi_pd(a, b);
  const __m256d cd0 = _mm256_unpacklo_pd(c, d), cd1 = _mm256_unpackhi_pd(c, d);
  _mm256_storeu_pd(b0, _mm256_permute2f128_pd(ab0, cd0, 0x20));
  _mm256_storeu_pd(b1, _mm256_permute2f128_pd(ab1, cd1, 0x20));
  _mm256_storeu_pd(b2, _mm256_permute2f128_pd(ab0, cd0, 0x31));
  _mm256_storeu_pd(b3, _mm256_permute2f128_pd(ab1, cd1, 0x31));
}

// b[j][i] = a[i][j] for the rows x cols matrix a (row i from a + i a_stride) into b (row j from
// b + j b_stride): 4 x 4 blocks by transpose4, the numbers past the last whole block one by one.
void transpose(const double* a, std::size_t a_stride, std::size_t rows, std::size_t cols, double* b,
               std::size_t b_stride) {
  const auto one = [&](std::size_t i, std::size_t j) { b[j * b_stride + i] = a[i * a_stride + j]; };
  std::size_t i = 0;
  for (; i + 4 <= rows; i += 4) {
    std::size_t j = 0;
    for (; j + 4 <= cols; j += 4) {
      const double* x = a + i * a_stride + j;
      double* y = b + j * b_stride + i;
      transpose4(x, x + a_stride, x + 2 * a_stride, x + 3 * a_stride, y, y + b_stride,
                 y + 2 * b_stride, y + 3 * b_stride);
    }
    for (; j < cols; ++j)
      for (std::size_t r = i; r < i + 4; ++r) one(r, j);
  }
  for (; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) one(i, j);
}

// The n numbers of N samples' rows (rows[l n + e]: sample l's number e) into the lanes of x
// (x[e] lane l), or back (to_rows).
template <int N>
void to_lanes(const double* rows, std::size_t n, DoubleLanes<N>* x) {
  transpose(rows, n, N, n, &x[0].v[0], N);
}

template <int N>
void to_rows(const DoubleLanes<N>* x, std::size_t n, double* rows) {
  transpose(&x[0].v[0], N, n, N, rows, n);
}

// Input rows s..s+N-1 into the lanes of `state`, mimic coordinates from their sources.
template <int N>
void load_lanes(const Model& model, const BatchInput& in, std::size_t s,
                JointState<DoubleLanes<N>>& state) {
  to_lanes(in.position + s * model.nq, model.nq, state.position.data());
  if (in.velocity) to_lanes(in.velocity + s * model.nv, model.nv, state.velocity.data());
  if (in.acceleration)
    to_lanes(in.acceleration + s * model.nv, model.nv, state.acceleration.data());
  apply_mimics(model, state);
}

// Input rows s..s+N-1 into output rows s..s+N-1 of `out`: streamed, or copied with ordinary
// stores.
template <int N>
void compute_lanes(const Model& model, const BatchInput& in, std::size_t s, Level level,
                   const BatchOutput<double>& out, bool streamed, LaneSamples<N>& w) {
  load_lanes(model, in, s, w.state);
  forward_kinematics(model, w.state, w.data, level);
  if (any_system(out)) system_kinematics(model, w.data, w.system, level);
  for (int f = 0; f < kBatchFieldCount; ++f) {
    const std::size_t n = w.size[f];
    if (n == 0) continue;
    const DoubleLanes<N>* row = lane_row(model, static_cast<BatchField>(f), out.bodies, w);
    double* to = out.field[f] + s * n;
    if (N == 8 && streamed && n >= 8) {  // straight from the lanes to memory
      stream_transpose8(&row[0].v[0], n, to, w.held[f]);
      continue;
    }
    to_rows(row, n, w.rows.data());
    if (streamed)
      stream_copy(to, w.rows.data(), N * n * sizeof(double));
    else
      std::memcpy(to, w.rows.data(), N * n * sizeof(double));
  }
}

// compute_lanes compiled for the least instruction set that has the lanes' vectors, everything
// it calls inlined into it (the recursion and the system's sums are kinematics_lanes.cc's).
__attribute__((target("avx2"))) MBK_FLATTEN void compute_four(const Model& model,
                                                              const BatchInput& in, std::size_t s,
                                                              Level level,
                                                              const BatchOutput<double>& out,
                                                              bool streamed, LaneSamples<4>& w) {
  compute_lanes(model, in, s, level, out, streamed, w);
}

__attribute__((target("avx512f"))) MBK_FLATTEN void compute_eight(
    const Model& model, const BatchInput& in, std::size_t s, Level level,
    const BatchOutput<double>& out, bool streamed, LaneSamples<8>& w) {
  compute_lanes(model, in, s, level, out, streamed, w);
}

// Samples [begin, end) N at a time, as far as they go; returns the first left.
template <int N, typename Compute>
std::size_t compute_groups(const Model& model, const BatchInput& in, std::size_t begin,
                           std::size_t end, Level level, const BatchOutput<double>& out,
                           bool streamed, Compute compute) {
  LaneSamples<N> w(model, out);
  for (; begin + N <= end; begin += N) compute(model, in, begin, level, out, streamed, w);
  for (HeldLine& line : w.held) write_held(line);
  return begin;
}

// Samples [begin, end) in groups of `lanes` (8 or 4), then of four, as far as they go; returns
// the first left.
std::size_t compute_in_lanes(const Model& model, const BatchInput& in, std::size_t begin,
                             std::size_t end, Level level, const BatchOutput<double>& out,
                             bool streamed, int lanes) {
  if (lanes >= 8 && begin + 8 <= end)
    begin = compute_groups<8>(model, in, begin, end, level, out, streamed, compute_eight);
  if (lanes >= 4 && begin + 4 <= end)
    begin = compute_groups<4>(model, in, begin, end, level, out, streamed, compute_four);
  return begin;
}
#else
std::size_t compute_in_lanes(const Model&, const BatchInput&, std::size_t begin, std::size_t, Level,
                             const BatchOutput<double>&, bool, int) {
  return begin;  // samples_at_once is 1
}
#endif

// Samples [begin, end) into the caller's arrays (each thread its own rows, so fresh arrays are
// first touched by the threads that fill them): streamed from a staged row when `streamed`, else
// written in place with ordinary stores, which leave them in the caches for the caller. Up to
// `lanes` at a time (8 or 4) in double without partial velocities, the rest one at a time.
template <typename T>
void compute_range(const Model& model, const BatchInput& in, std::size_t begin, std::size_t end,
                   Level level, const BatchOutput<T>& out, bool streamed, int lanes) {
  std::size_t s = begin;
  if constexpr (std::is_same_v<T, double>)
    if (!any_partials(out) && lanes >= 4)
      s = compute_in_lanes(model, in, begin, end, level, out, streamed, lanes);
  Workspace w(model);
  if (any_partials(out)) {
    w.pv = std::make_unique<PartialVelocities<double>>(model);
    w.scratch = std::make_unique<Data<double>>(model);
  }
  if (!streamed) {
    for (; s < end; ++s) compute_sample(model, in, s, s, level, out, w);
    return;
  }
  const StagedRow<T> staged(model, out);
  for (; s < end; ++s) {
    compute_sample(model, in, s, 0, level, staged.row, w);
    staged.stream_to(out, s, w.data);
  }
  stream_fence();
}

// The first sample in [begin, end) that check_state rejects, with its message; `end` if none.
std::size_t first_bad_sample(const Model& model, const BatchInput& in, std::size_t begin,
                             std::size_t end, std::string& problem) {
  JointState<double> state(model);
  for (std::size_t s = begin; s < end; ++s) {
    load_sample(model, in, s, state);
    problem = check_state(model, state);
    if (!problem.empty()) return s;
  }
  return end;
}

template <typename T>
void check_request(const Model& model, const BatchInput& in, const BatchOutput<T>& out) {
  for (int k : out.bodies)
    if (k < 1 || k > model.body_count())
      throw std::invalid_argument("body index " + std::to_string(k) + " out of range 1.." +
                                  std::to_string(model.body_count()));
  for (int f = 0; f < kBatchFieldCount; ++f) {
    if (!out.field[f]) continue;
    const BatchFieldTraits& t = kTraits[f];
    if (t.needs_velocity && !in.velocity)
      throw std::invalid_argument(std::string("output '") + t.name + "' needs velocities");
    if (t.needs_acceleration && !in.acceleration)
      throw std::invalid_argument(std::string("output '") + t.name + "' needs accelerations");
  }
  if (!in.position && in.samples > 0) throw std::invalid_argument("no positions given");
}

}  // namespace

template <typename T>
void write_batch_fields(const Model& model, const Data<double>& data, std::size_t s, Level level,
                        const BatchOutput<T>& out, SystemKinematics<double>& system) {
  write_fields(model, data, s, level, out, system);
}

const BatchFieldTraits& batch_field_traits(BatchField field) {
  return kTraits[static_cast<int>(field)];
}

BatchField batch_field_from_name(const std::string& name) {
  std::string known;
  for (int f = 0; f < kBatchFieldCount; ++f) {
    if (name == kTraits[f].name) return static_cast<BatchField>(f);
    known += (f ? ", " : "") + std::string(kTraits[f].name);
  }
  throw std::invalid_argument("unknown output '" + name + "' (known: " + known + ")");
}

std::vector<std::size_t> batch_field_shape(const Model& model, BatchField field,
                                           std::size_t bodies) {
  const BatchFieldTraits& t = batch_field_traits(field);
  std::vector<std::size_t> shape;
  if (t.per_body) shape.push_back(bodies);
  if (t.width == 0) shape.insert(shape.end(), {static_cast<std::size_t>(model.nv), 3});
  if (t.width == 9) shape.insert(shape.end(), {3, 3});
  if (t.width != 0 && t.width != 1 && t.width != 9) shape.push_back(t.width);
  return shape;
}

std::size_t batch_field_size(const Model& model, BatchField field, std::size_t bodies) {
  std::size_t size = 1;
  for (const std::size_t n : batch_field_shape(model, field, bodies)) size *= n;
  return size;
}

template <typename T>
Level batch_level(const BatchOutput<T>& out) {
  Level level = Level::kPose;
  for (int f = 0; f < kBatchFieldCount; ++f)
    if (out.field[f]) level = std::max(level, kTraits[f].level);
  return level;
}

template <typename T>
void batch_kinematics(const Model& model, const BatchInput& in, const BatchOutput<T>& out,
                      int threads, int most_lanes) {
  check_request(model, in, out);
  if (in.samples == 0) return;
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<std::size_t>(threads, in.samples));
  std::vector<std::size_t> bad(threads);
  std::vector<std::string> problems(threads);
  split_runs(in.samples, threads, [&](std::size_t t, std::size_t begin, std::size_t end) {
    bad[t] = first_bad_sample(model, in, begin, end, problems[t]);
  });
  for (int t = 0; t < threads; ++t)  // runs in sample order: the first bad sample overall
    if (bad[t] < in.samples * (t + 1) / threads)
      throw std::invalid_argument("sample " + std::to_string(bad[t]) + ": " + problems[t]);
  const Level level = batch_level(out);
  std::size_t bytes = 0;
  for (const std::size_t n : row_sizes(model, out)) bytes += n * sizeof(T) * in.samples;
  const int lanes = std::min(most_lanes, samples_at_once(model));
  split_runs(in.samples, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
    compute_range(model, in, begin, end, level, out, bytes > kBatchStreamBytes, lanes);
  });
}

template void write_batch_fields(const Model&, const Data<double>&, std::size_t, Level,
                                 const BatchOutput<double>&, SystemKinematics<double>&);
template Level batch_level(const BatchOutput<double>&);
template Level batch_level(const BatchOutput<float>&);
template void batch_kinematics(const Model&, const BatchInput&, const BatchOutput<double>&, int,
                               int);
template void batch_kinematics(const Model&, const BatchInput&, const BatchOutput<float>&, int,
                               int);

}  // namespace mbk
