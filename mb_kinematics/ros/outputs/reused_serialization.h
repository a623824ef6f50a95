// A ReusedMessage whose serialized bytes are kept as well: a sample that changes only the
// message's numbers (next()) writes them into the bytes of the last one (serialized_numbers.h)
// instead of serializing every field, string and length again; a change of its strings or
// array lengths (reshape()) serializes it whole with ros::serialization, once. The bytes sent are
// ros::serialization's of the message. Published as ros::Publisher::publish publishes a shared
// pointer (not for latched publishers): subscribers in the same process get the message itself,
// and the bytes are written only when a subscriber is remote. Bytes still queued for sending
// are not written over: the next sample goes into a copy of them.
#pragma once

#include <ros/publisher.h>
#include <ros/serialization.h>
#include <ros/topic_manager.h>

#include <boost/shared_array.hpp>
#include <cstring>
#include <string>
#include <typeinfo>

#include "mb_kinematics/ros/outputs/reused_message.h"
#include "mb_kinematics/ros/outputs/serialized_numbers.h"

namespace mbk_ros {

template <typename M>
class ReusedSerialization {
 public:
  // The message to write the next sample's numbers in: its strings and array lengths stay.
  M& next() { return msg_.next(); }
  // The message to change in any way (strings, array lengths): serialized whole when published.
  M& reshape() {
    whole_ = true;
    return msg_.next();
  }
  void publish(const ros::Publisher& publisher) {
    if (!publisher) return;
    if (publisher != publisher_) {  // its topic's name, once (getTopic copies it)
      publisher_ = publisher;
      topic_ = publisher.getTopic();
    }
    ros::SerializedMessage m;
    m.type_info = &typeid(M);
    m.message = msg_.shared();
    ros::TopicManager::instance()->publish(
        topic_, [this] { return serialize(); }, m);
  }
  // The message's bytes as ros::serialization::serializeMessage gives them (publish asks for
  // them when a subscriber is remote).
  ros::SerializedMessage serialize() {
    if (!whole_ && image_) {
      if (image_.use_count() > 1) {  // still queued for a subscriber
        boost::shared_array<uint8_t> copy(new uint8_t[bytes_]);
        std::memcpy(copy.get(), image_.get(), bytes_);
        image_ = copy;
      }
      if (write_numbers(msg_.message(), image_.get() + 4, bytes_ - 4)) return serialized();
    }
    const ros::SerializedMessage m = ros::serialization::serializeMessage(msg_.message());
    image_ = m.buf;
    bytes_ = m.num_bytes;
    whole_ = false;
    return m;
  }

 private:
  // The image as serializeMessage gives it: the length (uint32), then the message.
  ros::SerializedMessage serialized() const {
    ros::SerializedMessage m(image_, bytes_);
    m.message_start = image_.get() + 4;
    return m;
  }

  ReusedMessage<M> msg_;
  boost::shared_array<uint8_t> image_;  // the last sample's serialized bytes
  size_t bytes_ = 0;
  bool whole_ = true;  // strings or lengths changed since image_ was made
  ros::Publisher publisher_;
  std::string topic_;  // publisher_'s
};

}  // namespace mbk_ros
