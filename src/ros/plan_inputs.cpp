#include "rosmill/ros/plan_inputs.hpp"

#include "rosmill/error.hpp"

namespace rosmill::edge {

uint64_t PlanInputs::accept_mesh(std::shared_ptr<const Mesh> mesh) {
  mesh_.accept(std::move(mesh));
  return accepted("mesh");
}

uint64_t PlanInputs::accept_cloud(std::shared_ptr<const PointCloud> cloud) {
  cloud_.accept(std::move(cloud));
  return accepted("cloud");
}

uint64_t PlanInputs::accepted(const char* source) {
  const uint64_t generation = ++inputs_;
  std::lock_guard<std::mutex> lock(latest_mutex_);
  latest_ = source;
  return generation;
}

void PlanInputs::reject(const std::string& source, const std::string& why) {
  if (source == "mesh") mesh_.reject(why);
  else cloud_.reject(why);
  ++inputs_;
}

PlanSource PlanInputs::select(const std::string& requested) const {
  std::string source = requested;
  if (source.empty()) {
    std::lock_guard<std::mutex> lock(latest_mutex_);
    source = latest_;
  }
  if (source.empty()) throw Error("plan", "no input yet: publish a mesh or a cloud first");
  PlanSource out;
  if (source == "mesh")
    out.mesh = mesh_.require();
  else if (source == "cloud")
    out.cloud = cloud_.require();
  else
    throw Error("source", "must be \"mesh\", \"cloud\" or empty, got \"" + source + "\"");
  return out;
}

}  // namespace rosmill::edge
