#include "mb_kinematics/offline/error_bar_files.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "mb_kinematics/io/number_format.h"

namespace mbk_offline {
namespace {

constexpr int kStampChars = 400;  // %.9f of the largest double fits

}  // namespace

bool has_side_files(const std::string& csv) {
  if (csv.empty()) return false;
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(csv, ec);
  return !std::filesystem::exists(st) || std::filesystem::is_regular_file(st);
}

std::string errors_path(const std::string& csv, const char* suffix) {
  const bool csv_end = csv.size() >= 4 && csv.compare(csv.size() - 4, 4, ".csv") == 0;
  return (csv_end ? csv.substr(0, csv.size() - 4) : csv) + suffix;
}

SampleErrorsFile::SampleErrorsFile(std::string path, const mbk::Model& model)
    : path_(std::move(path)), model_(model), v_(model.nq, 0.0), a_(model.nq, 0.0) {}

void SampleErrorsFile::write(const mbk::Recording& rec, const mbk::OfflineStates& states, int begin,
                             int end) {
  if (begin >= end || !states.coordinate_errors(begin, v_.data(), a_.data())) return;
  if (!file_) open();
  for (int r = begin; r < end; ++r) {
    states.coordinate_errors(r, v_.data(), a_.data());
    char* at = mbk::write_stamp(row_.data(), rec.origin, rec.recorded(r));
    for (int c = 0; c < model_.nq; ++c) {
      *at++ = ',';
      at = mbk::write_general(at, v_[c], 6);
      *at++ = ',';
      at = mbk::write_general(at, a_[c], 6);
    }
    *at++ = '\n';
    block_->write(row_.data(), static_cast<std::size_t>(at - row_.data()));
  }
}

void SampleErrorsFile::commit() {
  if (!file_) return;
  try {
    block_->close();
  } catch (const std::runtime_error&) {
    throw std::invalid_argument(path_ + ": cannot write the error bars");
  }
  file_->commit();
}

void SampleErrorsFile::open() {
  file_ = std::make_unique<OutputFile>(path_, false);
  block_ = std::make_unique<mbk::BlockFile>(file_->writing());
  std::string header = "stamp";
  for (const std::string& name : model_.coordinate_names)
    header += "," + name + "_velocity_se," + name + "_acceleration_se";
  block_->write(header + "\n");
  row_.resize(kStampChars + 2 * static_cast<std::size_t>(model_.nq) * (1 + mbk::kMaxDoubleChars) +
              1);
}

void write_errors(const std::string& path, const std::vector<mbk::CoordinateError>& errors) {
  OutputFile file(path, false);
  std::ofstream f(file.writing());
  f << "coordinate,noise,velocity_se,acceleration_se\n";
  f.precision(6);
  for (const mbk::CoordinateError& e : errors)
    f << e.name << "," << e.noise << "," << e.velocity_se << "," << e.acceleration_se << "\n";
  f.close();
  if (!f) throw std::invalid_argument(path + ": cannot write the error bars");
  file.commit();
}

}  // namespace mbk_offline
