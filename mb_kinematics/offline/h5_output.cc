#include "mb_kinematics/offline/h5_output.h"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/number_format.h"
#include "mb_kinematics/offline/batch_kinematics.h"

#ifndef MBK_VERSION
#define MBK_VERSION "unknown"
#endif

namespace mbk_offline {
namespace {

using mbk::BatchField;

// The datasets, in the file's order. A new output of Model.kinematics (offline/batch_kinematics.h)
// is one line of kBatchQuantities; one from the rows (the states, their error bars) one line of
// kRowQuantities.
enum class Need { kAlways, kMass, kErrors };
struct BatchQuantity {
  BatchField field;
  const char* unit;
  Need need;
};
const BatchQuantity kBatchQuantities[] = {
    {BatchField::kRotation, "1", Need::kAlways},
    {BatchField::kOrigin, "m", Need::kAlways},
    {BatchField::kMassCenter, "m", Need::kAlways},
    {BatchField::kOmega, "rad/s", Need::kAlways},
    {BatchField::kAlpha, "rad/s^2", Need::kAlways},
    {BatchField::kVelocity, "m/s", Need::kAlways},
    {BatchField::kAcceleration, "m/s^2", Need::kAlways},
    {BatchField::kSystemMass, "kg", Need::kMass},
    {BatchField::kSystemMassCenter, "m", Need::kMass},
    {BatchField::kSystemVelocity, "m/s", Need::kMass},
    {BatchField::kSystemAcceleration, "m/s^2", Need::kMass},
    {BatchField::kLinearMomentum, "kg m/s", Need::kMass},
    {BatchField::kAngularMomentum, "kg m^2/s", Need::kMass},
};

// What a row quantity holds per row: one number, one per coordinate, three per body.
enum class Extent { kOne, kCoordinates, kBodyVectors };
using RowFill = void (*)(const mbk::OfflineRow& row, double* out, std::size_t width);
struct RowQuantity {
  const char* name;
  const char* unit;
  Need need;
  Extent extent;
  RowFill fill;
};

void copy_or_nan(const double* values, bool given, double* out, std::size_t width) {
  if (given)
    std::copy(values, values + width, out);
  else
    std::fill(out, out + width, std::numeric_limits<double>::quiet_NaN());
}
// Bodies 1..B of per-body vectors (index 0 is R).
void bodies_or_nan(const std::vector<mbk::Vec3<double>>& v, double* out, std::size_t width) {
  copy_or_nan(v.empty() ? nullptr : v[1].data(), !v.empty(), out, width);
}

const char kCoordinateUnit[] = "each coordinate's: rad (angles), m (translations), 1 (e1..e4)";
const RowQuantity kRowQuantities[] = {
    {"time", "s", Need::kAlways, Extent::kOne, nullptr},  // H5Output::write: the stamp as written
    {"joint_position", kCoordinateUnit, Need::kAlways, Extent::kCoordinates,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) {
       std::copy_n(r.state.position.data(), n, x);
     }},
    {"joint_velocity", "the coordinates' per s", Need::kAlways, Extent::kCoordinates,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) {
       std::copy_n(r.state.velocity.data(), n, x);
     }},
    {"joint_acceleration", "the coordinates' per s^2", Need::kAlways, Extent::kCoordinates,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) {
       std::copy_n(r.state.acceleration.data(), n, x);
     }},
    {"alpha_se", "rad/s^2", Need::kErrors, Extent::kBodyVectors,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) { bodies_or_nan(r.alpha_se, x, n); }},
    {"acceleration_se", "m/s^2", Need::kErrors, Extent::kBodyVectors,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) {
       bodies_or_nan(r.acceleration_se, x, n);
     }},
    {"joint_velocity_se", "the coordinates' per s", Need::kErrors, Extent::kCoordinates,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) {
       copy_or_nan(r.joint_velocity_se.data(), !r.joint_velocity_se.empty(), x, n);
     }},
    {"joint_acceleration_se", "the coordinates' per s^2", Need::kErrors, Extent::kCoordinates,
     [](const mbk::OfflineRow& r, double* x, std::size_t n) {
       copy_or_nan(r.joint_acceleration_se.data(), !r.joint_acceleration_se.empty(), x, n);
     }},
};

constexpr std::size_t kChunkBytes = 1 << 20;  // the largest dataset's chunk, at most
constexpr std::size_t kMostChunkRows = 4096;

// What the library said went wrong: the system's message (errno's text, as the sec2 driver
// writes it) when there is one, else its innermost description.
std::string h5_reason() {
  std::string system, innermost;
  struct Found {
    std::string *system, *innermost;
  } found{&system, &innermost};
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        auto* f = static_cast<Found*>(data);
        const std::string desc = e->desc ? e->desc : "";
        if (f->innermost->empty()) *f->innermost = desc;
        const std::string tag = "error message = '";
        const std::size_t at = desc.find(tag);
        if (f->system->empty() && at != std::string::npos) {
          const std::size_t end = desc.find('\'', at + tag.size());
          *f->system = desc.substr(at + tag.size(), end - at - tag.size());
        }
        return 0;
      },
      &found);
  H5Eclear2(H5E_DEFAULT);
  if (!system.empty()) return system;
  if (!innermost.empty()) return "HDF5: " + innermost;
  return errno ? std::strerror(errno) : "HDF5 error";
}

}  // namespace

// An identifier of the C API closed by its own function (outside the anonymous namespace: File's
// members hold them).
class H5Id {
 public:
  H5Id() = default;
  H5Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  H5Id(H5Id&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  H5Id& operator=(H5Id&& o) noexcept {
    reset();
    id_ = std::exchange(o.id_, -1), close_ = o.close_;
    return *this;
  }
  ~H5Id() { reset(); }
  hid_t get() const { return id_; }
  void reset() {
    if (id_ >= 0) close_(id_);
    id_ = -1;
  }
  herr_t close() {  // reset, saying whether the library could
    const herr_t status = id_ >= 0 ? close_(id_) : 0;
    id_ = -1;
    return status;
  }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

namespace {

H5Id utf8_string_type() { return H5Id(H5Tcopy(H5T_C_S1), H5Tclose); }

}  // namespace

struct H5Output::File {
  struct Dataset {
    std::string name;
    std::vector<hsize_t> shape;  // per row
    std::size_t width = 1;       // numbers per row
    RowFill fill = nullptr;      // a row quantity's; null: a batch field's
    H5Id id;
    std::vector<double> buffer;  // chunk_rows x width
  };

  std::string shown;
  const mbk::Model& model;
  std::size_t nq, bodies, chunk_rows = 1, rows = 0;  // rows: buffered
  double origin = 0;                                  // the stamps' (set_time_origin)
  std::size_t time = 0;                               // the `time` dataset's index
  hsize_t written = 0;
  H5Id file;
  std::vector<Dataset> datasets;
  mbk::BatchOutput<double> batch;  // the batch fields' buffers
  mbk::SystemKinematics<double> system;
  bool closed = false;
  bool raw_chunks = false;  // whole chunks written as they are: uncompressed, doubles as stored

  File(const std::string& s, const mbk::Model& m, std::size_t coordinates)
      : shown(s), model(m), nq(coordinates), bodies(m.body_count()) {}

  [[noreturn]] void fail(const char* what) const {
    throw std::runtime_error(shown + ": " + what + " (" + h5_reason() + ")");
  }
  void check(herr_t status, const char* what) const {
    if (status < 0) fail(what);
  }
  H5Id made(hid_t id, herr_t (*close)(hid_t), const char* what) const {
    if (id < 0) fail(what);
    return H5Id(id, close);
  }

  // False, adding nothing, for a dataset of no number per row (a model without coordinates).
  bool add(std::string name, std::vector<hsize_t> shape, RowFill fill) {
    if (std::find(shape.begin(), shape.end(), 0) != shape.end()) return false;
    Dataset d;
    d.name = std::move(name), d.shape = std::move(shape), d.fill = fill;
    for (hsize_t n : d.shape) d.width *= n;
    datasets.push_back(std::move(d));
    return true;
  }
  std::vector<hsize_t> batch_shape(BatchField field) const {
    const mbk::BatchFieldTraits& t = mbk::batch_field_traits(field);
    std::vector<hsize_t> shape;
    if (t.per_body) shape.push_back(bodies);
    if (t.width == 9) shape.insert(shape.end(), {3, 3});
    if (t.width == 3) shape.push_back(3);
    return shape;
  }
  std::vector<hsize_t> row_shape(Extent e) const {
    switch (e) {
      case Extent::kOne:
        return {};
      case Extent::kCoordinates:
        return {nq};
      case Extent::kBodyVectors:
        return {bodies, 3};
    }
    return {};
  }

  void create(const Dataset& d, Dataset& out, const char* unit, int compression) {
    std::vector<hsize_t> dims{0}, most{H5S_UNLIMITED}, chunk{chunk_rows};
    dims.insert(dims.end(), d.shape.begin(), d.shape.end());
    most.insert(most.end(), d.shape.begin(), d.shape.end());
    chunk.insert(chunk.end(), d.shape.begin(), d.shape.end());
    for (hsize_t& n : chunk) n = std::max<hsize_t>(n, 1);
    const int rank = static_cast<int>(dims.size());
    H5Id space = made(H5Screate_simple(rank, dims.data(), most.data()), H5Sclose, "cannot create");
    H5Id properties = made(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create");
    check(H5Pset_chunk(properties.get(), rank, chunk.data()), "cannot create");
    check(H5Pset_fill_time(properties.get(), H5D_FILL_TIME_NEVER), "cannot create");
    // No times in the file: the same run writes the same bytes.
    check(H5Pset_obj_track_times(properties.get(), false), "cannot create");
    if (compression > 0) {
      check(H5Pset_shuffle(properties.get()), "cannot create");
      check(H5Pset_deflate(properties.get(), static_cast<unsigned>(compression)), "cannot create");
    }
    out.id = made(H5Dcreate2(file.get(), d.name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                             properties.get(), H5P_DEFAULT),
                  H5Dclose, "cannot create");
    attribute(out.id.get(), "unit", unit);
  }

  void attribute(hid_t object, const char* name, const std::string& value) {
    H5Id type = utf8_string_type();
    check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot create");
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot create");
    H5Id space = made(H5Screate(H5S_SCALAR), H5Sclose, "cannot create");
    H5Id a = made(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                  H5Aclose, "cannot create");
    const char* text = value.c_str();
    check(H5Awrite(a.get(), type.get(), &text), "cannot write");
  }

  void names(const char* name, const std::vector<std::string>& values) {
    H5Id type = utf8_string_type();
    check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot create");
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot create");
    const hsize_t n = values.size();
    H5Id space = made(H5Screate_simple(1, &n, nullptr), H5Sclose, "cannot create");
    H5Id properties = made(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create");
    check(H5Pset_obj_track_times(properties.get(), false), "cannot create");
    H5Id d = made(H5Dcreate2(file.get(), name, type.get(), space.get(), H5P_DEFAULT,
                             properties.get(), H5P_DEFAULT),
                  H5Dclose, "cannot create");
    std::vector<const char*> texts;
    for (const std::string& v : values) texts.push_back(v.c_str());
    if (n > 0)
      check(H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()),
            "write failed");
  }

  // The rows buffered appended to every dataset: a whole chunk, when it is stored as it is in
  // memory, straight into the file (H5Dwrite_chunk), else through the library's chunk cache
  // (which zeroes a chunk, then copies the rows into it).
  void flush() {
    if (rows == 0) return;
    for (Dataset& d : datasets) {
      std::vector<hsize_t> size{written + rows}, start{written}, count{rows};
      size.insert(size.end(), d.shape.begin(), d.shape.end());
      for (hsize_t n : d.shape) start.push_back(0), count.push_back(n);
      const int rank = static_cast<int>(size.size());
      check(H5Dset_extent(d.id.get(), size.data()), "write failed");
      if (raw_chunks && rows == chunk_rows) {
        check(H5Dwrite_chunk(d.id.get(), H5P_DEFAULT, 0, start.data(),
                             rows * d.width * sizeof(double), d.buffer.data()),
              "write failed");
        continue;
      }
      H5Id space = made(H5Dget_space(d.id.get()), H5Sclose, "write failed");
      check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                                nullptr),
            "write failed");
      H5Id memory = made(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, "write failed");
      check(H5Dwrite(d.id.get(), H5T_NATIVE_DOUBLE, memory.get(), space.get(), H5P_DEFAULT,
                     d.buffer.data()),
            "write failed");
    }
    written += rows;
    rows = 0;
  }
};

H5Output::H5Output(const std::string& path, const std::string& shown, const mbk::Model& model,
                   const std::vector<std::string>& coordinates, const H5Attributes& attributes,
                   bool errors, int compression)
    : file_(std::make_unique<File>(shown, model, coordinates.size())) {
  File& f = *file_;
  // A file whose writing failed (a full disk) stays half-closed in the library, and its
  // termination at exit would crash on it: the process's end frees what is left instead.
  H5dont_atexit();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are thrown, one line, not printed
  if (compression < 0 || compression > 9)
    throw std::invalid_argument("--h5-compression needs a level from 0 to 9");
  if (compression > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
    throw std::invalid_argument("--h5-compression: this HDF5 library has no deflate filter");
  double mass = 0;
  for (const mbk::Body& b : model.bodies) mass += b.mass;
  const auto needed = [&](Need n) {
    return n == Need::kAlways || (n == Need::kMass && mass > 0) || (n == Need::kErrors && errors);
  };
  std::vector<const char*> units;
  for (const RowQuantity& q : kRowQuantities)
    if (needed(q.need) && f.add(q.name, f.row_shape(q.extent), q.fill)) units.push_back(q.unit);
  std::vector<BatchField> fields;
  for (const BatchQuantity& q : kBatchQuantities)
    if (needed(q.need) &&
        f.add(mbk::batch_field_traits(q.field).name, f.batch_shape(q.field), nullptr))
      units.push_back(q.unit), fields.push_back(q.field);
  std::size_t widest = 1;
  for (const File::Dataset& d : f.datasets) widest = std::max(widest, d.width);
  f.chunk_rows =
      std::clamp<std::size_t>(kChunkBytes / (widest * sizeof(double)), 1, kMostChunkRows);
  f.raw_chunks = compression == 0 && H5Tequal(H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE) > 0;
  try {
    H5Id creation = f.made(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "cannot write");
    f.check(H5Pset_obj_track_times(creation.get(), false), "cannot write");
    f.file = f.made(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation.get(), H5P_DEFAULT), H5Fclose,
                    "cannot write");
    for (std::size_t i = 0; i < f.datasets.size(); ++i) {
      File::Dataset& d = f.datasets[i];
      f.create(d, d, units[i], compression);
      d.buffer.resize(f.chunk_rows * d.width);
    }
    f.names("body_names", [&] {
      std::vector<std::string> v;
      for (std::size_t k = 1; k <= f.bodies; ++k) v.push_back(model.bodies[k].name);
      return v;
    }());
    f.names("coordinate_names", coordinates);
    const hid_t root = f.file.get();
    f.attribute(root, "frame", attributes.frame);
    f.attribute(root, "model_file", attributes.model_file);
    f.attribute(root, "input", attributes.input);
    f.attribute(root, "estimator", attributes.estimator);
    f.attribute(root, "system", attributes.system);
    f.attribute(root, "mbk_version", MBK_VERSION);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  for (int k = 1; k <= model.body_count(); ++k) f.batch.bodies.push_back(k);
  std::size_t first_batch = f.datasets.size() - fields.size();
  for (std::size_t i = 0; i < fields.size(); ++i)
    f.batch[fields[i]] = f.datasets[first_batch + i].buffer.data();
}

H5Output::~H5Output() = default;

void H5Output::write(const mbk::OfflineRow& row, const mbk::Data<double>& data) {
  File& f = *file_;
  if (static_cast<std::size_t>(row.state.position.size()) != f.nq ||
      static_cast<std::size_t>(row.state.velocity.size()) != f.nq)
    throw std::logic_error("H5Output: a row of another model");
  for (File::Dataset& d : f.datasets)
    if (d.fill) d.fill(row, d.buffer.data() + f.rows * d.width, d.width);
  f.datasets[f.time].buffer[f.rows] = mbk::written_stamp(f.origin, row.stamp);
  mbk::write_batch_fields(f.model, data, f.rows, mbk::Level::kAcceleration, f.batch, f.system);
  if (++f.rows == f.chunk_rows) f.flush();
}

void H5Output::set_time_origin(double seconds) {
  File& f = *file_;
  f.origin = seconds;
  for (std::size_t i = 0; i < f.datasets.size(); ++i)
    if (f.datasets[i].name == "time") f.time = i;
}

void H5Output::close() {
  File& f = *file_;
  if (f.closed) return;
  f.flush();
  for (File::Dataset& d : f.datasets)
    if (d.id.close() < 0) f.fail("write failed");
  f.check(H5Fflush(f.file.get(), H5F_SCOPE_LOCAL), "write failed");
  if (f.file.close() < 0) f.fail("write failed");
  f.closed = true;
}

}  // namespace mbk_offline
