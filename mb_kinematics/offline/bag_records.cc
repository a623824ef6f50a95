#include "mb_kinematics/offline/bag_records.h"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <vector>

namespace mbk_offline {
namespace {

// The bag format 2.0 (wiki.ros.org/Bags/Format/2.0): every record is a header length, the
// header's fields (each a length and "name=value"), a data length and the data.
constexpr char kChunk = 0x05;
constexpr char kIndexData = 0x04;
constexpr std::uint32_t kLargestChunk = 1u << 30;  // a larger size is left to librosbag

std::uint32_t u32(const char* at) {
  std::uint32_t v = 0;
  std::memcpy(&v, at, 4);
  return v;
}

// A header's fields, name -> value; a field past the header's end ends them.
std::map<std::string, std::string> fields_of(const std::string& header) {
  std::map<std::string, std::string> fields;
  for (std::size_t at = 0; at + 4 <= header.size();) {
    const std::size_t length = u32(header.data() + at);
    if (length > header.size() - at - 4) break;
    const std::string field = header.substr(at + 4, length);
    const std::size_t eq = field.find('=');
    if (eq != std::string::npos) fields[field.substr(0, eq)] = field.substr(eq + 1);
    at += 4 + length;
  }
  return fields;
}

std::uint32_t u32_field(const std::map<std::string, std::string>& fields, const char* name) {
  const auto f = fields.find(name);
  return f != fields.end() && f->second.size() == 4 ? u32(f->second.data()) : 0;
}

// The chunk's records as librosbag will read them: the data itself, or decompressed into
// `uncompressed`. False when it does not decompress (librosbag then refuses its messages).
bool chunk_records(const std::map<std::string, std::string>& fields, std::string& data,
                   std::string& uncompressed) {
  const auto compression = fields.find("compression");
  if (compression == fields.end() || compression->second == "none") return true;
  unsigned int size = u32_field(fields, "size");
  if (size > kLargestChunk) return false;
  uncompressed.resize(size);
  if (compression->second == "bz2") {
    if (BZ2_bzBuffToBuffDecompress(uncompressed.data(), &size, data.data(),
                                   static_cast<unsigned int>(data.size()), 0, 0) != BZ_OK)
      return false;
  } else if (compression->second == "lz4") {
    if (roslz4_buffToBuffDecompress(data.data(), static_cast<unsigned int>(data.size()),
                                    uncompressed.data(), &size) != ROSLZ4_OK)
      return false;
  } else {
    return false;  // an unknown compression: librosbag's error to give
  }
  uncompressed.resize(size);
  data.swap(uncompressed);
  return true;
}

class RecordCheck {
 public:
  explicit RecordCheck(const std::string& path) : path_(path) {}

  void run() {
    std::ifstream in(path_, std::ios::binary | std::ios::ate);
    const std::uint64_t size = in ? static_cast<std::uint64_t>(in.tellg()) : 0;
    char magic[13] = {};
    in.seekg(0);
    if (!in.read(magic, sizeof magic) || std::string(magic, sizeof magic) != "#ROSBAG V2.0\n")
      return;  // not a bag: rosbag's error to give
    for (std::uint64_t at = 13; in && at < size;) {
      const std::uint32_t header_length = length_at(in, at, size, "header");
      std::string header(header_length, '\0');
      in.read(header.data(), header_length);
      const std::uint64_t data_at = at + 4 + header_length;
      const std::uint32_t data_length = length_at(in, data_at, size, "data");
      const std::map<std::string, std::string> fields = fields_of(header);
      const auto op = fields.find("op");
      if (op != fields.end() && op->second.size() == 1 &&
          (op->second[0] == kChunk || op->second[0] == kIndexData)) {
        data_.resize(data_length);
        in.read(data_.data(), data_length);
        if (op->second[0] == kChunk)
          chunk(fields, at);
        else
          index(fields, at);
      }
      at = data_at + 4 + data_length;
    }
  }

 private:
  // The length at byte `at`, the record's part after it within the file.
  std::uint32_t length_at(std::ifstream& in, std::uint64_t at, std::uint64_t size,
                          const char* part) {
    std::uint32_t length = 0;
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(&length), 4) || at + 4 + length > size)
      throw std::invalid_argument(path_ + ": damaged or truncated bag: the record " + part +
                                  " at byte " + std::to_string(at) +
                                  " goes beyond the end of the file; `rosbag reindex " + path_ +
                                  "` may recover it");
    return length;
  }

  // Each record inside the chunk within its data; their starts kept for the index after it.
  void chunk(const std::map<std::string, std::string>& fields, std::uint64_t chunk_at) {
    starts_.clear();
    chunk_at_ = chunk_at;
    if (!(chunk_readable_ = chunk_records(fields, data_, uncompressed_))) return;
    const std::uint64_t size = data_.size();
    for (std::uint64_t at = 0; at < size;) {
      std::uint64_t end = at + 4;
      if (end <= size) end += u32(data_.data() + at) + std::uint64_t{4};
      if (end <= size) end += u32(data_.data() + end - 4);
      if (end > size)
        throw std::invalid_argument(path_ + ": damaged bag: the record at byte " +
                                    std::to_string(at) + " of the chunk at byte " +
                                    std::to_string(chunk_at) + " goes beyond the chunk's " +
                                    std::to_string(size) + " bytes");
      starts_.push_back(static_cast<std::uint32_t>(at));
      at = end;
    }
  }

  // An index record (version 1): each entry's offset a record of the chunk before it.
  void index(const std::map<std::string, std::string>& fields, std::uint64_t index_at) {
    if (!chunk_readable_ || u32_field(fields, "ver") != 1) return;
    const std::uint64_t count = u32_field(fields, "count");
    if (count > data_.size() / 12)
      throw std::invalid_argument(path_ + ": damaged bag: the index at byte " +
                                  std::to_string(index_at) + " counts " + std::to_string(count) +
                                  " messages in " + std::to_string(data_.size()) + " bytes");
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::uint32_t offset = u32(data_.data() + 12 * i + 8);  // after the time
      if (!std::binary_search(starts_.begin(), starts_.end(), offset))
        throw std::invalid_argument(path_ + ": damaged bag: the index at byte " +
                                    std::to_string(index_at) + " points at byte " +
                                    std::to_string(offset) + " of the chunk at byte " +
                                    std::to_string(chunk_at_) + ", where no record starts");
    }
  }

  const std::string& path_;
  std::string data_, uncompressed_;
  std::vector<std::uint32_t> starts_;  // the last chunk's records, in order
  std::uint64_t chunk_at_ = 0;
  bool chunk_readable_ = false;
};

}  // namespace

void check_bag_records(const std::string& path) { RecordCheck(path).run(); }

}  // namespace mbk_offline
