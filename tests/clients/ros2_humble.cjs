// ROS 2 Humble's own message definitions (@foxglove/rosmsg-msgs-common), as ROS 2's readers and
// writers take them: a type's definition first, then every type it uses.
"use strict";
const { ros2humble } = require("@foxglove/rosmsg-msgs-common");

// "nav_msgs/Odometry" (or "nav_msgs/msg/Odometry") -> [its definition, each type it uses once].
function definitions(type) {
  const order = [type.replace("/msg/", "/")], out = [];
  for (let i = 0; i < order.length; i++) {
    const d = ros2humble[order[i]];
    if (!d) throw new Error(`no ROS 2 definition of ${order[i]}`);
    out.push(d);
    for (const f of d.definitions) if (f.isComplex && !order.includes(f.type)) order.push(f.type);
  }
  return out;
}

module.exports = { definitions };
