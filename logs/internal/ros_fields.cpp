#include "logs/internal/ros_fields.hpp"

#include <algorithm>

namespace retrace::logs::internal {
namespace {

// The types `name` depends on, depth first in order of first use.
void CollectDependencies(const MessageDefinitions& definitions, std::string_view name,
                         std::vector<std::string_view>& out) {
  for (std::string_view dep : definitions.at(name).depends) {
    if (std::find(out.begin(), out.end(), dep) != out.end()) continue;
    out.push_back(dep);
    CollectDependencies(definitions, dep, out);
  }
}

}  // namespace

MessageDefinitions WithSharedGeometry(MessageDefinitions own) {
  // geometry_msgs/Quaternion is not among them: ROS 2 gives its fields defaults.
  static const MessageDefinitions kShared{
      {"geometry_msgs/Point", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Vector3", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Pose",
       {"geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
        {"geometry_msgs/Point", "geometry_msgs/Quaternion"}}},
      {"geometry_msgs/PoseWithCovariance",
       {"geometry_msgs/Pose pose\nfloat64[36] covariance\n", {"geometry_msgs/Pose"}}},
      {"geometry_msgs/Twist",
       {"geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
        {"geometry_msgs/Vector3"}}},
      {"geometry_msgs/TwistWithCovariance",
       {"geometry_msgs/Twist twist\nfloat64[36] covariance\n", {"geometry_msgs/Twist"}}},
      {"geometry_msgs/Transform",
       {"geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
        {"geometry_msgs/Vector3", "geometry_msgs/Quaternion"}}},
  };
  own.insert(kShared.begin(), kShared.end());
  return own;
}

std::string FullDefinition(const MessageDefinitions& definitions, std::string_view name) {
  std::string text(definitions.at(name).fields);
  std::vector<std::string_view> deps;
  CollectDependencies(definitions, name, deps);
  for (std::string_view dep : deps) {
    text += std::string(80, '=');
    text += "\nMSG: ";
    text += dep;
    text += '\n';
    text += definitions.at(dep).fields;
  }
  return text;
}

}  // namespace retrace::logs::internal
