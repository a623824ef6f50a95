// The queue of the node's input subscriptions (doc/speed.md "The node's load"): each callback runs
// at once in the thread that queues it (roscpp's network thread for a remote publisher, the
// publisher's own thread for one in the same process), one at a time under mutex(). The
// default queue would hand every message from the network thread to the spinner thread, and
// the spinner would wake the network thread again to send what it publishes: two thread
// switches per sample that this one saves. The node's other callbacks (~reload, the services,
// the diagnostics timer) stay on its handle's queue and lock mutex() as well.
#pragma once

#include <ros/callback_queue_interface.h>

#include <cstdint>
#include <mutex>

namespace mbk_ros {

class ImmediateCallbackQueue : public ros::CallbackQueueInterface {
 public:
  void addCallback(const ros::CallbackInterfacePtr& callback, uint64_t) override {
    std::lock_guard<std::mutex> lock(mutex_);
    callback->call();
  }
  // A subscription removes its callbacks after the one it is running (if any) has returned.
  void removeByID(uint64_t) override {}
  std::mutex& mutex() { return mutex_; }

 private:
  std::mutex mutex_;
};

}  // namespace mbk_ros
