// mb_kinematics._core: the compiled part of the Python module (doc/python.md). It converts
// arrays and exceptions and releases the GIL around the C++; the loaders are io/load_model.h,
// the batch is offline/batch_kinematics.h. The Python package beside it (__init__.py) checks
// the caller's arguments and names them; the checks here only keep a wrong call from writing
// out of bounds.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/core/euler_angles.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/offline/base_track.h"
#include "mb_kinematics/offline/batch_kinematics.h"
#include "mb_kinematics/offline/recording_input.h"
#include "mb_kinematics/offline/recording_states.h"
#include "mb_kinematics/offline/retained_blocks.h"
#include "mb_kinematics/tools/bag_cli.h"

namespace py = pybind11;

namespace {

using ModelPtr = std::shared_ptr<mbk::Model>;  // never changed after load
using InputArray = py::array_t<double, py::array::c_style>;

ModelPtr load(const std::string& path_or_text, py::object scale, py::object body_mass,
              py::object sex, py::object segments, const std::string& source,
              py::object anthropometry) {
  const bool bvh = !scale.is_none() || !body_mass.is_none() || !sex.is_none() ||
                   !segments.is_none() || !anthropometry.is_none();
  mbk::BvhModelOptions options;
  if (!scale.is_none()) options.scale = scale.cast<double>();
  if (!body_mass.is_none()) options.body_mass = body_mass.cast<double>();
  if (!sex.is_none()) options.sex = sex.cast<std::string>();
  if (!segments.is_none()) options.segments = segments.cast<std::string>();
  if (!options.segments.empty() && !(options.body_mass > 0))
    throw std::invalid_argument("segments maps joints to masses: it needs body_mass");
  if (!anthropometry.is_none()) options.anthropometry = anthropometry.cast<std::string>();
  py::gil_scoped_release release;
  return std::make_shared<mbk::Model>(
      mbk::load_model(path_or_text, bvh ? &options : nullptr, source));
}

// mbk bag's check of a BVH model's --scale, --body-mass and --sex texts ("" keeps the default):
// mbk batch refuses a bad subjects row before anything runs, with mbk bag's message.
void check_bvh_options(const std::string& scale, const std::string& body_mass,
                       const std::string& sex) {
  mbk::bvh_model_options(scale, body_mass, sex);
}

// mbk bag's rule for the options that add columns to an output (tools/bag_cli.h): mbk batch
// refuses, before any job runs, one given (`options`, by name) without an output it adds to
// (`outputs`: "--csv", "--mot", ...), with mbk bag's message less the outputs' values.
void check_column_options(const std::vector<std::string>& options,
                          const std::vector<std::string>& outputs) {
  mbk_offline::check_column_options(options, outputs, false);
}

// mbk bag's options (tools/bag_cli.h's table): (name, value, who takes it) per option, the value
// "" for a flag, who: "every job", "bvh jobs" (mbk batch's) or "bag alone".
py::list bag_options() {
  py::list out;
  for (const mbk_offline::BagOptionRow& row : mbk_offline::bag_option_rows()) {
    const char* use = row.use == mbk_offline::BagOptionUse::kEveryJob  ? "every job"
                      : row.use == mbk_offline::BagOptionUse::kBvhJobs ? "bvh jobs"
                                                                       : "bag alone";
    out.append(py::make_tuple(row.name, row.value, use));
  }
  return out;
}

py::dict joint(const mbk::Body& body) {
  py::dict d;
  d["name"] = body.joint.name;
  d["type"] = mbk::to_string(body.joint.type);
  d["axis"] = std::vector<double>(body.joint.axis.data(), body.joint.axis.data() + 3);
  d["offset"] = std::vector<double>(body.joint.offset.data(), body.joint.offset.data() + 3);
  return d;
}

py::list mimics(const mbk::Model& model) {
  py::list out;
  for (const mbk::Mimic& m : model.mimics) {
    py::dict d;
    d["coordinate"] = model.coordinate_names[m.coordinate];
    d["source"] = model.coordinate_names[m.source];
    d["multiplier"] = m.multiplier;
    d["offset"] = m.offset;
    out.append(d);
  }
  return out;
}

// The state JointState(model) starts from: zeros, Euler parameters the identity (e4 = 1).
std::vector<double> neutral_position(const mbk::Model& model) {
  const mbk::JointState<double> state(model);
  return std::vector<double>(state.position.data(), state.position.data() + model.nq);
}

const double* input(const py::object& array, std::size_t samples, int width, const char* name) {
  if (array.is_none()) return nullptr;
  const InputArray a = array.cast<InputArray>();
  if (a.ndim() != 2 || static_cast<std::size_t>(a.shape(0)) != samples || a.shape(1) != width)
    throw std::invalid_argument(std::string(name) + ": wrong shape");
  return a.data();
}

template <typename T>
void fill_output(const mbk::Model& model, const py::dict& arrays, std::size_t samples,
                 mbk::BatchOutput<T>& out) {
  for (const auto& item : arrays) {
    const std::string name = item.first.cast<std::string>();
    const mbk::BatchField field = mbk::batch_field_from_name(name);
    auto a = item.second.cast<py::array>();
    if (!py::isinstance<py::array_t<T>>(a) || !(a.flags() & py::array::c_style) || !a.writeable() ||
        static_cast<std::size_t>(a.size()) !=
            samples * mbk::batch_field_size(model, field, out.bodies.size()))
      throw std::invalid_argument("out['" + name + "']: not a writeable C-contiguous array of " +
                                  "the right dtype and size");
    out[field] = static_cast<T*>(a.mutable_data());
  }
}

template <typename T>
void run(const mbk::Model& model, const InputArray& position, const py::object& velocity,
         const py::object& acceleration, const py::dict& outputs, const std::vector<int>& bodies,
         int threads) {
  if (position.ndim() != 2 || position.shape(1) != model.nq)
    throw std::invalid_argument("position: wrong shape");
  mbk::BatchInput in;
  in.samples = static_cast<std::size_t>(position.shape(0));
  in.position = position.data();
  in.velocity = input(velocity, in.samples, model.nv, "velocity");
  in.acceleration = input(acceleration, in.samples, model.nv, "acceleration");
  mbk::BatchOutput<T> out;
  out.bodies = bodies;
  fill_output(model, outputs, in.samples, out);
  py::gil_scoped_release release;
  mbk::batch_kinematics(model, in, out, threads);
}

// Writes the fields named by `outputs` (name -> array, all float64 or all float32) for every row
// of `position` (N, nq) and the optional velocity and acceleration (N, nv).
void batch_kinematics(const ModelPtr& model, const InputArray& position, py::object velocity,
                      py::object acceleration, const py::dict& outputs,
                      const std::vector<int>& bodies, int threads, bool single) {
  if (single)
    run<float>(*model, position, velocity, acceleration, outputs, bodies, threads);
  else
    run<double>(*model, position, velocity, acceleration, outputs, bodies, threads);
}

// An uninitialized C-contiguous array of `shape`, float64 or float32 (`single`): above 1 MiB in a
// block of offline/retained_blocks.h, given back when the array is released.
py::array empty(const std::vector<py::ssize_t>& shape, bool single) {
  const py::dtype dtype = single ? py::dtype::of<float>() : py::dtype::of<double>();
  std::size_t bytes = static_cast<std::size_t>(dtype.itemsize());
  for (const py::ssize_t n : shape) bytes *= static_cast<std::size_t>(n);
  if (bytes <= (std::size_t{1} << 20)) return py::array(dtype, shape);
  struct Block {
    void* data;
    std::size_t bytes;
  };
  auto* block = new Block{mbk::RetainedBlocks::shared().take(bytes), bytes};
  const py::capsule owner(block, [](void* p) {
    auto* b = static_cast<Block*>(p);
    mbk::RetainedBlocks::shared().give(b->data, b->bytes);
    delete b;
  });
  return py::array(dtype, shape, block->data, owner);
}

// A recording read as mbk bag reads it (with a bag's base odometry), and what was dropped.
struct Recorded {
  mbk::Recording recording;
  mbk_offline::BaseOdometry base;
  mbk::DropLog log;
  std::vector<std::string> coordinates;  // of the model it was read for
};
using RecordedPtr = std::shared_ptr<Recorded>;

// A recording's columns are its model's coordinates: another model's would be read as its own.
void check_same_model(const mbk::Model& model, const Recorded& recorded) {
  if (recorded.coordinates != model.coordinate_names)
    throw std::invalid_argument(
        "recording: read for another model (its coordinates differ from this model's); read it "
        "with this model's read_recording or recording");
}

py::array_t<double> matrix(const std::vector<double>& values, std::size_t rows, std::size_t cols) {
  py::array_t<double> out({rows, cols});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// Recorded values where `flag` is set, NaN elsewhere.
py::array_t<double> where_given(const mbk::Recording& r, const std::vector<double>& values,
                                std::uint8_t flag) {
  py::array_t<double> out = matrix(values, r.rows(), r.nq);
  double* x = out.mutable_data();
  for (std::size_t i = 0; i < r.given.size(); ++i)
    if (!(r.given[i] & flag)) x[i] = std::numeric_limits<double>::quiet_NaN();
  return out;
}

RecordedPtr read_recording(const ModelPtr& model, const std::string& path, double scale,
                           const std::string& joint_states, const std::string& joint_accelerations,
                           const std::string& base_odometry) {
  auto out = std::make_shared<Recorded>();
  out->coordinates = model->coordinate_names;
  py::gil_scoped_release release;
  mbk_offline::RecordingInput in = mbk_offline::read_recording_input(
      *model, path, scale, {joint_states, joint_accelerations, base_odometry}, out->log);
  out->recording = std::move(in.recording);
  out->base = std::move(in.base);
  return out;
}

// The base odometry's samples as arrays (None without): times (n,), position, linear, angular
// (n, 3), orientation (n, 4: x, y, z, w), frame.
py::object base_arrays(const Recorded& r) {
  const std::vector<mbk::BaseSample>& b = r.base.samples;
  if (b.empty()) return py::none();
  const std::size_t n = b.size();
  py::array_t<double> t(n), position({n, std::size_t{3}}), orientation({n, std::size_t{4}}),
      linear({n, std::size_t{3}}), angular({n, std::size_t{3}});
  for (std::size_t i = 0; i < n; ++i) {
    t.mutable_data()[i] = b[i].t;
    std::copy(b[i].position.data(), b[i].position.data() + 3, position.mutable_data() + 3 * i);
    std::copy(b[i].orientation.coeffs().data(), b[i].orientation.coeffs().data() + 4,
              orientation.mutable_data() + 4 * i);
    std::copy(b[i].linear.data(), b[i].linear.data() + 3, linear.mutable_data() + 3 * i);
    std::copy(b[i].angular.data(), b[i].angular.data() + 3, angular.mutable_data() + 3 * i);
  }
  py::dict out;
  out["times"] = t;
  out["position"] = position;
  out["orientation"] = orientation;
  out["linear"] = linear;
  out["angular"] = angular;
  out["frame"] = r.base.frame;
  return out;
}

// (rows, bodies, 3) of one Data field, bodies 1..N of each row.
template <typename Field>
py::array_t<double> body_vectors(const std::vector<mbk::Data<double>>& data, Field field) {
  const std::size_t rows = data.size(), bodies = rows ? data[0].origin.size() - 1 : 0;
  py::array_t<double> out({rows, bodies, std::size_t{3}});
  double* x = out.mutable_data();
  for (const mbk::Data<double>& d : data)
    for (std::size_t k = 1; k <= bodies; ++k, x += 3) std::copy_n((d.*field)[k].data(), 3, x);
  return out;
}

// mbk bag's rows of a recording with its base odometry (offline/base_track.h), in the node's
// layout, under the names of Model.kinematics, with the body names and the drops.
py::dict floating_base_kinematics(const ModelPtr& model, const RecordedPtr& recorded,
                                  const std::string& estimator, double max_gap, int threads) {
  check_same_model(*model, *recorded);
  mbk::DropLog log = recorded->log;
  mbk::BaseRows rows;
  {
    py::gil_scoped_release release;
    rows = mbk::floating_base_rows(*model, recorded->recording, recorded->base.samples,
                                   recorded->base.frame, mbk::make_offline_estimator(estimator),
                                   max_gap, threads, log);
  }
  const std::size_t n = rows.stamp.size(), bodies = rows.layout.body_count();
  py::dict out;
  out["time"] = matrix(rows.stamp, n, 1).attr("ravel")();
  std::vector<std::string> names;
  for (std::size_t k = 1; k <= bodies; ++k) names.push_back(rows.layout.bodies[k].name);
  out["body_names"] = names;
  py::array_t<double> rotation({n, bodies, std::size_t{3}, std::size_t{3}});
  double* r = rotation.mutable_data();
  for (const mbk::Data<double>& d : rows.data)
    for (std::size_t k = 1; k <= bodies; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) *r++ = d.rotation[k](i, j);
  out["rotation"] = rotation;
  using D = mbk::Data<double>;
  out["origin"] = body_vectors(rows.data, &D::origin);
  out["omega"] = body_vectors(rows.data, &D::omega);
  out["alpha"] = body_vectors(rows.data, &D::alpha);
  out["mass_center"] = body_vectors(rows.data, &D::mass_center);
  out["velocity"] = body_vectors(rows.data, &D::mass_center_velocity);
  out["acceleration"] = body_vectors(rows.data, &D::mass_center_acceleration);
  py::array_t<double> g({n, std::size_t{3}}), v({n, std::size_t{3}}), a({n, std::size_t{3}});
  for (std::size_t i = 0; i < n; ++i) {
    const mbk::SystemKinematics<double>& system = rows.system[i];
    std::copy_n(system.mass_center.data(), 3, g.mutable_data() + 3 * i);
    std::copy_n(system.velocity.data(), 3, v.mutable_data() + 3 * i);
    std::copy_n(system.acceleration.data(), 3, a.mutable_data() + 3 * i);
  }
  out["system_mass_center"] = g;
  out["system_velocity"] = v;
  out["system_acceleration"] = a;
  out["drops"] = log.drops;
  return out;
}

// mbk bag's rows of a recording without a base (offline/base_track.h recording_rows): the kept
// rows' times and states, (rows,) and (rows, nq), and the drops, the reading's included.
py::dict recording_rows(const ModelPtr& model, const RecordedPtr& recorded,
                        const std::string& estimator, double max_gap, int threads) {
  check_same_model(*model, *recorded);
  mbk::DropLog log = recorded->log;
  const double origin = recorded->recording.origin;  // a wall clock's whole seconds, or 0
  std::vector<double> time, position, velocity, acceleration;
  {
    py::gil_scoped_release release;
    const auto keep = [&](const mbk::OfflineRow& row) {
      time.push_back(origin + row.stamp);
      const mbk::JointState<double>& s = row.state;
      position.insert(position.end(), s.position.data(), s.position.data() + s.position.size());
      velocity.insert(velocity.end(), s.velocity.data(), s.velocity.data() + s.velocity.size());
      acceleration.insert(acceleration.end(), s.acceleration.data(),
                          s.acceleration.data() + s.acceleration.size());
    };
    mbk::recording_rows(*model, recorded->recording, mbk::make_offline_estimator(estimator),
                        max_gap, nullptr, threads, log, keep);
  }
  const std::size_t n = time.size(), nq = model->nq;
  py::dict out;
  out["time"] = matrix(time, n, 1).attr("ravel")();
  out["position"] = matrix(position, n, nq);
  out["velocity"] = matrix(velocity, n, nq);
  out["acceleration"] = matrix(acceleration, n, nq);
  out["drops"] = log.drops;
  return out;
}

RecordedPtr recording_of_positions(const ModelPtr& model, const InputArray& time,
                                   const InputArray& position) {
  if (time.ndim() != 1 || position.ndim() != 2 || position.shape(0) != time.shape(0) ||
      position.shape(1) != model->nq)
    throw std::invalid_argument("times, positions: wrong shapes");
  auto out = std::make_shared<Recorded>();
  out->coordinates = model->coordinate_names;
  out->recording =
      mbk::recording_of_positions(model->nq, time.shape(0), time.data(), position.data());
  return out;
}

py::dict recording_states(const ModelPtr& model, const RecordedPtr& recorded,
                          const std::string& estimator, double max_gap) {
  check_same_model(*model, *recorded);
  mbk::RecordingStates s;
  {
    py::gil_scoped_release release;
    s = mbk::recording_states(*model, recorded->recording, estimator, max_gap);
  }
  const std::size_t rows = recorded->recording.rows(), nq = model->nq;
  py::dict out;
  out["position"] = matrix(s.position, rows, nq);
  out["velocity"] = matrix(s.velocity, rows, nq);
  out["acceleration"] = matrix(s.acceleration, rows, nq);
  if (!s.velocity_se.empty()) {
    out["velocity_se"] = matrix(s.velocity_se, rows, nq);
    out["acceleration_se"] = matrix(s.acceleration_se, rows, nq);
  }
  out["drop_reason"] = s.drop_reason;
  return out;
}

// The shape of an output for `samples` samples and `bodies` chosen bodies (batch_field_shape).
py::tuple field_shape(const ModelPtr& model, const std::string& name, std::size_t samples,
                      std::size_t bodies) {
  std::vector<std::size_t> shape =
      mbk::batch_field_shape(*model, mbk::batch_field_from_name(name), bodies);
  shape.insert(shape.begin(), samples);
  return py::tuple(py::cast(shape));
}

py::dict field_traits() {
  py::dict out;
  for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
    const mbk::BatchFieldTraits& t = mbk::batch_field_traits(static_cast<mbk::BatchField>(f));
    py::dict d;
    d["level"] = static_cast<int>(t.level);
    d["needs_velocity"] = t.needs_velocity;
    d["needs_acceleration"] = t.needs_acceleration;
    d["per_body"] = t.per_body;
    d["width"] = t.width;
    d["opt_in"] = t.opt_in;
    out[t.name] = d;
  }
  return out;
}

// The angles (samples, series, 3) of rotations (samples, series, 3, 3) in `orders` (one, or one
// per series), continuous along the samples (core/euler_angles.h).
py::array_t<double> euler_angles(const InputArray& rotations,
                                 const std::vector<std::string>& orders) {
  if (rotations.ndim() != 4 || rotations.shape(2) != 3 || rotations.shape(3) != 3)
    throw std::invalid_argument("rotations: wrong shape");
  std::vector<mbk::EulerOrder> o;
  for (const std::string& text : orders) o.push_back(mbk::euler_order_from_string(text));
  const std::size_t samples = rotations.shape(0), series = rotations.shape(1);
  py::array_t<double> out({samples, series, std::size_t{3}});
  double* x = out.mutable_data();
  py::gil_scoped_release release;
  mbk::euler_angle_series(rotations.data(), samples, series, o, x);
  return out;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "mb_kinematics' compiled part; use the package mb_kinematics (doc/python.md)";
  m.attr("__version__") = MBK_VERSION;  // package.xml's (CMakeLists.txt)
  m.def("is_model_text", &mbk::is_model_text);
  py::class_<mbk::Model, ModelPtr>(m, "Model")
      .def_readonly("frame", &mbk::Model::frame)
      .def_readonly("nq", &mbk::Model::nq)
      .def_readonly("nv", &mbk::Model::nv)
      .def_readonly("coordinate_names", &mbk::Model::coordinate_names)
      .def_readonly("speed_names", &mbk::Model::speed_names)
      .def_readonly("warnings", &mbk::Model::warnings)
      .def_property_readonly("body_count", &mbk::Model::body_count)
      .def_property_readonly("lower", &mbk::Model::lower_body_array)
      .def_property_readonly(
          "lower_table",
          [](const mbk::Model& m) { return mbk::lower_body_table(m.lower_body_array()); })
      .def_property_readonly("tables_text",
                             [](const mbk::Model& m) {
                               std::vector<std::string> names;
                               for (int k = 1; k <= m.body_count(); ++k)
                                 names.push_back(m.bodies[k].name);
                               return mbk::format_lower_body_table(m.lower_body_array(), names);
                             })
      .def_property_readonly("bodies",
                             [](const mbk::Model& m) {
                               py::list out;
                               for (int k = 0; k <= m.body_count(); ++k) {
                                 const mbk::Body& b = m.bodies[k];
                                 py::dict d;
                                 d["name"] = b.name;
                                 d["lower"] = b.lower;
                                 d["mass"] = b.mass;
                                 d["mass_center"] = std::vector<double>(b.mass_center.data(),
                                                                        b.mass_center.data() + 3);
                                 d["joint"] = joint(b);
                                 d["q_index"] = b.q_index;
                                 d["v_index"] = b.v_index;
                                 out.append(d);
                               }
                               return out;
                             })
      .def_property_readonly("mimics", &mimics)
      .def_property_readonly("neutral_position", &neutral_position);
  m.def("load", &load, py::arg("path_or_text"), py::arg("scale") = py::none(),
        py::arg("body_mass") = py::none(), py::arg("sex") = py::none(),
        py::arg("segments") = py::none(), py::arg("source") = "<text>",
        py::arg("anthropometry") = py::none());
  m.def("batch_kinematics", &batch_kinematics, py::arg("model"), py::arg("position"),
        py::arg("velocity"), py::arg("acceleration"), py::arg("outputs"), py::arg("bodies"),
        py::arg("threads"), py::arg("single"));
  m.def("empty", &empty, py::arg("shape"), py::arg("single"));
  m.def("kept_bytes", [] { return mbk::RetainedBlocks::shared().kept_bytes(); });
  m.def("release_memory", [] { return mbk::RetainedBlocks::shared().release(); });
  m.def("check_bvh_options", &check_bvh_options);
  m.def("check_column_options", &check_column_options);
  m.def("bag_options", &bag_options);
  m.def("field_traits", &field_traits);
  m.def("field_shape", &field_shape);
  m.def("euler_angles", &euler_angles);
  py::class_<Recorded, RecordedPtr>(m, "Recording")
      .def_property_readonly("times",
                             [](const Recorded& r) {
                               const mbk::Recording& rec = r.recording;
                               std::vector<double> t =
                                   rec.recorded_stamp.empty() ? rec.stamp : rec.recorded_stamp;
                               for (double& x : t) x += rec.origin;
                               return matrix(t, rec.rows(), 1).attr("ravel")();
                             })
      .def_property_readonly("grid",
                             [](const Recorded& r) {
                               const mbk::StampGrid& g = r.recording.grid;
                               py::dict d;
                               d["found"] = g.found;
                               d["moves"] = g.moves;
                               d["period"] = static_cast<double>(g.period);
                               d["worst"] = g.worst;
                               d["tolerance"] = g.tolerance;
                               return d;
                             })
      .def_property_readonly("positions",
                             [](const Recorded& r) {
                               return where_given(r.recording, r.recording.position,
                                                  mbk::Recording::kPosition);
                             })
      .def_property_readonly("velocities",
                             [](const Recorded& r) {
                               return where_given(r.recording, r.recording.velocity,
                                                  mbk::Recording::kVelocity);
                             })
      .def_property_readonly("accelerations",
                             [](const Recorded& r) {
                               return where_given(r.recording, r.recording.acceleration,
                                                  mbk::Recording::kAcceleration);
                             })
      .def_property_readonly("base", &base_arrays)
      .def_property_readonly("drops", [](const Recorded& r) { return r.log.drops; });
  m.def("read_recording", &read_recording);
  m.def("recording_of_positions", &recording_of_positions);
  m.def("recording_states", &recording_states);
  m.def("recording_rows", &recording_rows);
  m.def("floating_base_kinematics", &floating_base_kinematics);
}
