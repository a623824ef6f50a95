#include "mb_kinematics/offline/bag_input.h"

#include <mb_kinematics_msgs/JointAccelerations.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/quaternion_scale.h"
#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/offline/bag_records.h"

namespace mbk_offline {
namespace {

// topic -> types of its connections in the bag (a topic may have several, of other types).
using Topics = std::map<std::string, std::set<std::string>>;

Topics bag_topics(const rosbag::Bag& bag) {
  Topics topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) topics[c->topic].insert(c->datatype);
  return topics;
}

std::string join(const std::set<std::string>& types) {
  std::string out;
  for (const std::string& t : types) out += (out.empty() ? "" : " and ") + t;
  return out;
}

std::string list(const Topics& topics) {
  if (topics.empty()) return "the bag has no topics";
  std::string out = "the bag has ";
  bool first = true;
  for (const auto& t : topics)
    out += (first ? "" : ", ") + t.first + " (" + join(t.second) + ")", first = false;
  return out;
}

std::string without_slash(const std::string& topic) {
  return topic.rfind('/', 0) == 0 ? topic.substr(1) : topic;
}

// The bag's names of `topic`: itself and its form with or without the leading '/' (`rosbag
// record joint_states` stores `joint_states`), as rosbag's tools match them. One of their
// connections must be of `type`.
std::vector<std::string> require(const Topics& topics, const std::string& path,
                                 const std::string& topic, const std::string& type) {
  std::vector<std::string> names;
  std::set<std::string> types;
  for (const auto& t : topics)
    if (without_slash(t.first) == without_slash(topic))
      names.push_back(t.first), types.insert(t.second.begin(), t.second.end());
  if (names.empty())
    throw std::invalid_argument(
        mbk::printable(path + ": no topic '" + topic + "'; " + list(topics)));
  if (!types.count(type))
    throw std::invalid_argument(
        mbk::printable(path + ": topic '" + topic + "' is " + join(types) + ", not " + type));
  return names;
}

double stamp_of(const std_msgs::Header& header, const rosbag::MessageInstance& m) {
  return header.stamp.isZero() ? m.getTime().toSec() : header.stamp.toSec();  // as the node
}

void add_odometry(const nav_msgs::Odometry& o, double t, const std::string& where,
                  BaseOdometry& base, mbk::DropLog& log) {
  mbk::BaseSample s;
  s.t = t;
  const auto& p = o.pose.pose;
  s.position << p.position.x, p.position.y, p.position.z;
  s.orientation =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  mbk::scale_large_quaternion(s.orientation);  // components of 1e154 and more: a finite norm
  s.linear << o.twist.twist.linear.x, o.twist.twist.linear.y, o.twist.twist.linear.z;
  s.angular << o.twist.twist.angular.x, o.twist.twist.angular.y, o.twist.twist.angular.z;
  const double norm = s.orientation.norm();
  if (!std::isfinite(t) || !s.position.allFinite() || !s.linear.allFinite() ||
      !s.angular.allFinite() || !std::isfinite(norm) || norm < 1e-6)
    return log.note("base odometry ignored", where + ": NaN/Inf or a zero quaternion");
  if (!base.samples.empty() && t <= base.samples.back().t)
    return log.note("base odometry ignored", where + ": stamp not after the previous one");
  s.orientation.normalize();
  if (base.frame.empty()) base.frame = o.header.frame_id;
  base.samples.push_back(s);
}

enum class Kind { kJointStates, kAccelerations, kOdometry };
const std::string kJointState = "sensor_msgs/JointState";
const std::string kJointAccelerations = "mb_kinematics_msgs/JointAccelerations";
const std::string kOdometry = "nav_msgs/Odometry";

// The variable-length fields of a message, in order (the fixed ones after them need no check:
// deserializing refuses a message too short for them).
enum class Field { kHeader, kString, kStrings, kDoubles };
const std::vector<Field> kJointStateFields = {Field::kHeader, Field::kStrings, Field::kDoubles,
                                              Field::kDoubles, Field::kDoubles};
const std::vector<Field> kAccelerationFields = {Field::kHeader, Field::kStrings, Field::kDoubles};
const std::vector<Field> kOdometryFields = {Field::kHeader, Field::kString};

// Walks serialized bytes: every length and array count within the bytes left.
class ByteWalk {
 public:
  ByteWalk(const std::uint8_t* data, size_t size) : data_(data), left_(size) {}
  // "" if the fields fit, else which count does not.
  std::string check(const std::vector<Field>& fields) {
    for (size_t f = 0; f < fields.size(); ++f)
      if (!field(fields[f]))
        return "field " + std::to_string(f + 1) + " counts " + std::to_string(count_) +
               " elements with " + std::to_string(left_) + " bytes left: damaged";
    return "";
  }

 private:
  bool skip(size_t n) {
    if (n > left_) return false;
    data_ += n, left_ -= n;
    return true;
  }
  bool next_count() {
    if (left_ < 4) return false;
    std::memcpy(&count_, data_, 4);
    return skip(4);
  }
  bool string() { return next_count() && skip(count_); }
  bool field(Field f) {
    switch (f) {
      case Field::kHeader:  // seq, stamp, frame_id
        return skip(12) && string();
      case Field::kString:
        return string();
      case Field::kStrings: {
        if (!next_count() || count_ > left_ / 4)
          return false;  // each string takes 4 bytes at least
        for (std::uint32_t n = count_, i = 0; i < n; ++i)
          if (!string()) return false;
        return true;
      }
      case Field::kDoubles:
        return next_count() && count_ <= left_ / 8 && skip(8 * size_t{count_});
    }
    return false;
  }

  const std::uint8_t* data_;
  size_t left_;
  std::uint32_t count_ = 0;
};

// A message's serialized bytes into `bytes`, its record read once (MessageInstance::size() would
// read the record's header a second time).
void copy_bytes(const rosbag::MessageInstance& m, std::vector<std::uint8_t>& bytes) {
  struct Sink {  // rosbag's stream: advance(n) gives room for the n bytes it copies
    std::vector<std::uint8_t>& bytes;
    std::uint8_t* advance(std::uint32_t n) {
      bytes.resize(n);
      return bytes.data();
    }
  } sink{bytes};
  bytes.clear();
  m.write(sink);
}

// Reads messages from their bytes, checked before they are deserialized (a count of 2^32 names
// in a damaged message would otherwise be allocated), into the recording or the odometry.
class MessageReader {
 public:
  // The reason message m could not be read (of another type, damaged), or "".
  std::string read(const rosbag::MessageInstance& m, Kind kind, const std::string& where,
                   mbk::RecordingBuilder& builder, BaseOdometry& base) {
    try {
      std::string error;
      if (kind == Kind::kJointStates) {
        if ((error = load(m, kJointStateFields, js_)).empty())
          builder.add(stamp_of(js_.header, m), js_.name, js_.position, js_.velocity, where);
      } else if (kind == Kind::kAccelerations) {
        if ((error = load(m, kAccelerationFields, accelerations_)).empty())
          builder.add_accelerations(stamp_of(accelerations_.header, m), accelerations_.name,
                                    accelerations_.acceleration, where);
      } else if ((error = load(m, kOdometryFields, odometry_)).empty()) {
        add_odometry(odometry_, stamp_of(odometry_.header, m), where, base, builder.log());
      }
      return error;
    } catch (const std::exception& e) {  // rosbag's and roscpp's (a message cut short)
      return e.what();
    }
  }
  // A joint state message into `js` (read's first step): why it could not be read, or "".
  std::string load_joint_state(const rosbag::MessageInstance& m, sensor_msgs::JointState& js) {
    try {
      return load(m, kJointStateFields, js);
    } catch (const std::exception& e) {
      return e.what();
    }
  }

 private:
  template <typename M>
  std::string load(const rosbag::MessageInstance& m, const std::vector<Field>& fields, M& out) {
    const char* type = ros::message_traits::datatype<M>();
    if (m.getDataType() != type || m.getMD5Sum() != ros::message_traits::md5sum<M>())
      return "a " + m.getDataType() + " message (md5 " + m.getMD5Sum() + "), not " + type;
    copy_bytes(m, bytes_);
    const std::string error = ByteWalk(bytes_.data(), bytes_.size()).check(fields);
    if (!error.empty()) return error;
    ros::serialization::IStream in(bytes_.data(), static_cast<uint32_t>(bytes_.size()));
    ros::serialization::deserialize(in, out);
    return "";
  }

  std::vector<std::uint8_t> bytes_;
  sensor_msgs::JointState js_;
  mb_kinematics_msgs::JointAccelerations accelerations_;
  nav_msgs::Odometry odometry_;
};

// Reads the whole bag as read_bag will (its index, every chunk, every message's bytes) in a
// child process: librosbag itself crashes on some damaged headers (a flipped byte in a chunk or
// index record), and a crash there must be an error, not the end of mbk. Exceptions are left to
// the real reading, which counts them. `bag`: constructed, not open (the child opens its copy:
// rosbag's plugin loader, in Bag's constructor, runs once for both).
void survive_or_refuse(const std::string& path, rosbag::Bag& bag) {
  const pid_t child = fork();
  if (child < 0) return;  // cannot isolate: read it anyway
  if (child == 0) {
    try {
      bag.open(path, rosbag::bagmode::Read);
      std::vector<std::uint8_t> bytes;
      for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
        try {  // as the real reading: past a message that throws, on to the next
          copy_bytes(m, bytes);
        } catch (const std::exception&) {
        }
      }
    } catch (...) {
    }
    _exit(0);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0))  // a sanitizer's
    throw std::invalid_argument(path + ": damaged bag: reading it crashes librosbag (" +
                                (WIFSIGNALED(status)
                                     ? "signal " + std::to_string(WTERMSIG(status))
                                     : "exit " + std::to_string(WEXITSTATUS(status))) +
                                "); `rosbag reindex " + path + "` may recover it");
}

// The messages of a view of joint states alone, read ahead: rosbag's iteration, each message's
// bytes checked and deserialized (MessageReader) on a second thread, a batch at a time, while the
// caller's thread adds the batch before to the recording. In the messages' order: the same
// samples, drops and messages as read on one thread.
class ReadAhead {
 public:
  struct Message {
    sensor_msgs::JointState js;  // its buffers reused from one batch to the next
    double stamp = 0;
    std::string where, error;  // error: why it could not be read, or ""
  };
  // Reads `view` on a second thread; false (nothing read) when none can start.
  bool start(rosbag::View& view) {
    try {
      reader_ = std::thread([this, &view] { produce(view); });
    } catch (const std::exception&) {  // std::system_error, std::bad_alloc: read on one thread
      return false;
    }
    return true;
  }
  ~ReadAhead() {  // also when the caller's thread throws: the reading stops first
    if (!reader_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    reader_.join();
  }
  // Each message in order to take(message); then, when rosbag failed part way (its index or a
  // chunk), the messages iterated before and its error (else -1 and "").
  template <typename Take>
  void consume(const Take& take, long& read_before_failure, std::string& failure) {
    for (int b = 0;; b = 1 - b) {
      Batch& batch = batches_[b];
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return batch.ready; });
      }
      for (int i = 0; i < batch.count; ++i) take(batch.messages[i]);
      const bool last = batch.last;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        batch.ready = false;
      }
      changed_.notify_all();
      if (last) break;
    }
    reader_.join();
    read_before_failure = failed_after_, failure = failure_;
  }

 private:
  static constexpr int kBatch = 256;
  struct Batch {
    std::vector<Message> messages = std::vector<Message>(kBatch);
    int count = 0;
    bool ready = false, last = false;  // ready: filled, not yet taken
  };

  void produce(rosbag::View& view) {
    MessageReader reader;
    long done = 0;
    int b = 0;
    if (!wait_free(b)) return;
    try {
      for (const rosbag::MessageInstance& m : view) {
        if (batches_[b].count == kBatch) {
          hand_over(b, false);
          b = 1 - b;
          if (!wait_free(b)) return;
        }
        Message& message = batches_[b].messages[batches_[b].count++];
        message.where.assign(m.getTopic()).append(" message ").append(std::to_string(++done));
        message.error = reader.load_joint_state(m, message.js);
        if (message.error.empty()) message.stamp = stamp_of(message.js.header, m);
      }
    } catch (const std::exception& e) {  // rosbag's own exceptions: the index or a chunk
      failed_after_ = done, failure_ = e.what();
    }
    hand_over(b, true);
  }
  // Waits until batch b is taken (false: stop reading).
  bool wait_free(int b) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return stop_ || !batches_[b].ready; });
    batches_[b].count = 0;
    return !stop_;
  }
  void hand_over(int b, bool last) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      batches_[b].ready = true, batches_[b].last = last;
    }
    changed_.notify_all();
  }

  Batch batches_[2];
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stop_ = false;
  long failed_after_ = -1;  // the reader's, read after join
  std::string failure_;
  std::thread reader_;
};

}  // namespace

void read_bag(const std::string& path, const BagTopics& topics, mbk::RecordingBuilder& builder,
              BaseOdometry& base, Unreadable& unreadable,
              const std::function<void(long, long)>& progress, bool checked) {
  mbk::check_regular_file(path, "the recording");  // a pipe or /dev/zero: read without end
  rosbag::Bag bag;
  if (!checked) check_bag_records(path), survive_or_refuse(path, bag);
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw std::invalid_argument(path +
                                ": the bag has no index (truncated, or its recording was "
                                "cut short): run `rosbag reindex " +
                                path + "` first");
  } catch (const rosbag::BagException& e) {
    std::ifstream in(path, std::ios::binary);
    char magic[13] = {};
    in.read(magic, sizeof magic);
    if (std::string(magic, sizeof magic) == "#ROSBAG V2.0\n")  // a bag, damaged or cut short
      throw std::invalid_argument(mbk::printable(path + ": not a readable bag (" + e.what() +
                                                 "): truncated or corrupt; `rosbag reindex " +
                                                 path + "` may recover it"));
    throw std::invalid_argument(mbk::printable(path + ": not a readable bag (" + e.what() + ")"));
  }
  const Topics present = bag_topics(bag);
  std::map<std::string, Kind> kinds;
  for (const std::string& t : require(present, path, topics.joint_states, kJointState))
    kinds[t] = Kind::kJointStates;
  if (!topics.joint_accelerations.empty())
    for (const std::string& t :
         require(present, path, topics.joint_accelerations, kJointAccelerations))
      kinds[t] = Kind::kAccelerations;
  if (!topics.base_odometry.empty())
    for (const std::string& t : require(present, path, topics.base_odometry, kOdometry))
      kinds[t] = Kind::kOdometry;
  std::vector<std::string> wanted;
  for (const auto& k : kinds) wanted.push_back(k.first);
  rosbag::View view(bag, rosbag::TopicQuery(wanted));
  const long total = view.size();
  long done = 0;
  ReadAhead ahead;  // joint states alone: read ahead on a second thread
  if (topics.joint_accelerations.empty() && topics.base_odometry.empty() && ahead.start(view)) {
    long failed_after = -1;
    std::string failure;
    ahead.consume(
        [&](const ReadAhead::Message& m) {
          if (++done % 1024 == 0) progress(done, total);
          if (m.error.empty())
            builder.add(m.stamp, m.js.name, m.js.position, m.js.velocity, m.where);
          else
            unreadable.add(1, m.where + ": " + m.error);
        },
        failed_after, failure);
    if (failed_after >= 0)
      unreadable.add(std::max(1L, total - failed_after),
                     path + ": after message " + std::to_string(failed_after) + " of " +
                         std::to_string(total) + ": " + failure);
    return progress(total, total);
  }
  MessageReader reader;
  std::string where;  // reused: no allocation per message
  try {
    for (const rosbag::MessageInstance& m : view) {
      if (++done % 1024 == 0) progress(done, total);
      where.assign(m.getTopic()).append(" message ").append(std::to_string(done));
      const std::string error = reader.read(m, kinds.at(m.getTopic()), where, builder, base);
      if (!error.empty()) unreadable.add(1, where + ": " + error);
    }
  } catch (const std::exception& e) {  // rosbag's own exceptions: the index or a chunk
    unreadable.add(std::max(1L, total - done), path + ": after message " + std::to_string(done) +
                                                   " of " + std::to_string(total) + ": " +
                                                   e.what());
  }
  progress(total, total);
}

}  // namespace mbk_offline
