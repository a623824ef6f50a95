// A message published by shared pointer: subscribers in the same process (nodelets) get it
// without a copy or serialization, remote ones get it serialized as before. It is reused for
// the next sample, so publishing allocates no message, unless a subscriber in the process
// still holds the last one: then the next sample goes into a copy of it.
#pragma once

#include <ros/publisher.h>

#include <boost/make_shared.hpp>
#include <boost/shared_ptr.hpp>

namespace mbk_ros {

template <typename M>
class ReusedMessage {
 public:
  ReusedMessage() : msg_(boost::make_shared<M>()) {}
  // The message to fill for the next sample (what the last sample left in it stays).
  M& next() {
    if (msg_.use_count() > 1) msg_ = boost::make_shared<M>(*msg_);
    return *msg_;
  }
  void publish(const ros::Publisher& publisher) const { publisher.publish(msg_); }
  const M& message() const { return *msg_; }
  const boost::shared_ptr<M>& shared() const { return msg_; }

 private:
  boost::shared_ptr<M> msg_;
};

}  // namespace mbk_ros
