// The latest accepted input of one kind (a mesh, a cloud), or why the latest one was rejected. A rejected input
// replaces the one before: planning on an older scan of a part that has since moved would be wrong. Shared between
// the subscriber threads and the services, under its own lock.
#pragma once
#include <memory>
#include <mutex>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/ros/namespaces.hpp"

namespace rosmill::edge {

template <typename T>
class InputSlot {
 public:
  explicit InputSlot(std::string name) : name_(std::move(name)) {}

  void accept(std::shared_ptr<const T> value) {
    std::lock_guard<std::mutex> lock(mutex_);
    value_ = std::move(value);
    refused_.clear();
  }
  void reject(const std::string& why) {
    std::lock_guard<std::mutex> lock(mutex_);
    value_.reset();
    refused_ = why;
  }
  // The input, or an Error saying why there is none.
  std::shared_ptr<const T> require() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (value_) return value_;
    if (!refused_.empty())
      throw Error("source " + name_, "no usable " + name_ + ": the last one was rejected: " + refused_);
    throw Error("source " + name_, "no " + name_ + " has been received");
  }

 private:
  const std::string name_;
  mutable std::mutex mutex_;
  std::shared_ptr<const T> value_;
  std::string refused_;
};

}  // namespace rosmill::edge
