#pragma once
// Roles: what a node of the car stack is for, as a contract of ports and promises. A plugin says
// which roles it plays (Manifest::plays); the host refuses a library whose plugin claims a role
// its ports do not fit, and a graph node that names a role ("role": "planner") refuses a plugin
// that does not play it, naming the missing or mistyped port. Swapping a planner is then one edit
// that cannot wire the wrong thing. docs/roles.md gives each role's promises in full.
#include <brickyard/manifest.hpp>
#include <brickyard/message_traits.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace brickyard {

namespace roles {
inline constexpr char planner[] = "planner";
inline constexpr char path_tracker[] = "path_tracker";
inline constexpr char estimator[] = "estimator";
inline constexpr char fallback_controller[] = "fallback_controller";
inline constexpr char system_manager[] = "system_manager";
inline constexpr char gnss_driver[] = "gnss_driver";
inline constexpr char imu_driver[] = "imu_driver";
inline constexpr char lidar_driver[] = "lidar_driver";
inline constexpr char wheel_speed_driver[] = "wheel_speed_driver";
inline constexpr char vehicle_interface[] = "vehicle_interface";
}  // namespace roles

// One port of a role: a plugin playing the role has it with this direction and type (`needed`),
// or, when it has a port of that name at all, has it with this direction and type.
struct RolePort {
  std::string name;
  PortDirection direction;
  std::string type_name;
  bool needed = true;
};

struct RoleContract {
  std::string name;
  std::string promise;  // what a plugin playing it promises, beyond its ports
  std::vector<RolePort> ports;
};

namespace detail {
template <class T> RolePort needs_input(std::string n) { return {std::move(n), PortDirection::input, message_traits<T>::name, true}; }
template <class T> RolePort needs_output(std::string n) { return {std::move(n), PortDirection::output, message_traits<T>::name, true}; }
template <class T> RolePort may_input(std::string n) { return {std::move(n), PortDirection::input, message_traits<T>::name, false}; }
}  // namespace detail

// Every role the SDK defines, by name.
inline const std::vector<RoleContract>& role_contracts() {
  using namespace detail;
  static const std::vector<RoleContract> all = {
      {roles::planner,
       "publishes a path in the map frame from the car's estimate, inside the track, at its own rate",
       {needs_input<msgs::LocalizationEstimate>("estimate"), may_input<msgs::TrackMap>("map"),
        may_input<msgs::ObstacleList>("obstacles"), needs_output<msgs::Path>("path")}},
      {roles::path_tracker,
       "steers and pedals the car along the newest path, a command for each estimate, within the car's limits",
       {needs_input<msgs::Path>("path"), needs_input<msgs::LocalizationEstimate>("estimate"),
        needs_output<msgs::ControlCommand>("command")}},
      {roles::estimator,
       "publishes the car's pose, velocity and covariance on the map, and how far it may be trusted (mode)",
       {may_input<msgs::Imu>("imu"), may_input<msgs::WheelSpeeds>("wheels"), may_input<msgs::GnssFix>("gnss0"),
        may_input<msgs::GnssFix>("gnss1"), needs_output<msgs::LocalizationEstimate>("estimate"),
        needs_output<msgs::ModeStatus>("mode")}},
      {roles::fallback_controller,
       "drives the car without the estimate (LiDAR and speed alone) when the system manager hands it the car",
       {may_input<msgs::WallEstimate>("wall"), may_input<msgs::WheelSpeeds>("wheels"), may_input<msgs::ModeStatus>("mode"),
        needs_output<msgs::ControlCommand>("command")}},
      {roles::system_manager,
       "chooses which controller drives from the estimator's mode, and publishes the choice; never a stale command",
       {needs_input<msgs::ModeStatus>("localization"), needs_input<msgs::ControlCommand>("path_command"),
        needs_input<msgs::ControlCommand>("wall_command"), needs_output<msgs::ControlCommand>("command"),
        needs_output<msgs::ModeStatus>("mode")}},
      {roles::gnss_driver, "publishes each receiver's fix, stamped at its measurement, with its reported sigma",
       {needs_output<msgs::GnssFix>("fix")}},
      {roles::imu_driver, "publishes each IMU sample, stamped at its measurement, in the vehicle frame",
       {needs_output<msgs::Imu>("imu")}},
      {roles::lidar_driver, "publishes each LiDAR frame in the sensor's frame, its mount pose in the message",
       {needs_output<msgs::PointCloud>("cloud")}},
      {roles::wheel_speed_driver, "publishes the four wheel speeds, stamped at their measurement",
       {needs_output<msgs::WheelSpeeds>("speeds")}},
      {roles::vehicle_interface, "takes the control command to the car's actuators, and stops the car when commands stop",
       {needs_input<msgs::ControlCommand>("command")}},
  };
  return all;
}

inline const RoleContract* find_role(std::string_view name) {
  for (const auto& r : role_contracts())
    if (r.name == name) return &r;
  return nullptr;
}

// Why a manifest does not fit a role: one line per missing or mistyped port; empty when it fits.
inline std::vector<std::string> role_mismatches(const Manifest& m, const RoleContract& role) {
  std::vector<std::string> out;
  for (const auto& rp : role.ports) {
    const char* dir = rp.direction == PortDirection::input ? "input" : "output";
    const PortSpec* p = m.port(rp.name);
    if (!p) {
      if (rp.needed) out.push_back("no " + std::string(dir) + " '" + rp.name + "' (" + rp.type_name + ")");
      continue;
    }
    if (p->direction != rp.direction)
      out.push_back("'" + rp.name + "' is an " + (p->direction == PortDirection::input ? "input" : "output") + ", the role's is an " + dir);
    else if (p->type_name != rp.type_name)
      out.push_back(std::string(dir) + " '" + rp.name + "' carries " + p->type_name + ", the role's carries " + rp.type_name);
  }
  return out;
}

inline bool plays(const Manifest& m, std::string_view role) {
  for (const auto& r : m.roles)
    if (r == role) return true;
  return false;
}

}  // namespace brickyard
