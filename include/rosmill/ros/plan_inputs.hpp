// What the planner node plans from: the latest mesh and the latest cloud it received (each accepted, or rejected
// with its reason), which of them came last, and a count of inputs that lets a plan on input notice that a newer
// input has superseded it. Shared between the subscriber threads, the services and the actions.
#pragma once
#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/ros/input_slot.hpp"
#include "rosmill/ros/namespaces.hpp"

namespace rosmill::edge {

struct PlanSource {
  std::shared_ptr<const Mesh> mesh;         // one of the two is set
  std::shared_ptr<const PointCloud> cloud;
};

class PlanInputs {
 public:
  // Records an accepted input of `source` ("mesh" or "cloud"); returns its generation.
  uint64_t accept_mesh(std::shared_ptr<const Mesh> mesh);
  uint64_t accept_cloud(std::shared_ptr<const PointCloud> cloud);
  // Records a rejected input: what a later plan of that source is answered with.
  void reject(const std::string& source, const std::string& why);

  // The input a plan names ("mesh", "cloud", or "" for the one accepted last); an Error says why there is none.
  PlanSource select(const std::string& source) const;
  // False once an input newer than `generation` has arrived.
  bool current(uint64_t generation) const { return inputs_.load() == generation; }

 private:
  uint64_t accepted(const char* source);

  InputSlot<Mesh> mesh_{"mesh"};
  InputSlot<PointCloud> cloud_{"cloud"};
  std::atomic<uint64_t> inputs_{0};  // inputs received (accepted or not)
  mutable std::mutex latest_mutex_;
  std::string latest_;  // the source last accepted
};

}  // namespace rosmill::edge
