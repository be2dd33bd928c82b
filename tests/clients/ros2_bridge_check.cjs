// The bridge's ROS 2 messages (ros2.bridge, docs/ros2.md) read as a ROS 2 node would read them, by
// third-party libraries and ROS 2 Humble's own definitions (@foxglove/rosmsg-msgs-common), not ours:
// a recording in MCAP's ros2 profile of configs/race_ros2.json (@mcap/core), each bridge channel's
// schema ROS 2's type name, every message decoded by @foxglove/rosmsg2-serialization with Humble's
// definitions and, the same, with the recording's own schema; each held against what it was made
// from in the same recording (the estimate, the three LiDARs' clouds, the path, the obstacles, the
// IMU, the fixes: their latitude, longitude and height from FIXES, made without GeographicLib by
// tests/cli/enu_to_geodetic.py): counts, frames, stamps and values. Prints a JSON object of counts;
// exit 1 with the first difference.
// usage: node ros2_bridge_check.cjs RECORDING.mcap FIXES.json
"use strict";
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { definitions } = require("./ros2_humble.cjs");
const { openMcap } = require("./mcap_open.cjs");

const kBridge = {
  odom: "nav_msgs/msg/Odometry", pose: "geometry_msgs/msg/PoseStamped", tf: "tf2_msgs/msg/TFMessage",
  points: "sensor_msgs/msg/PointCloud2", path_markers: "visualization_msgs/msg/MarkerArray",
  obstacle_markers: "visualization_msgs/msg/MarkerArray", imu_data: "sensor_msgs/msg/Imu", fix: "sensor_msgs/msg/NavSatFix",
};
const plain = (v) => JSON.stringify(v, (k, x) => (typeof x === "bigint" ? x.toString() : ArrayBuffer.isView(x) ? Array.from(x) : x));
const ns = (stamp) => BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nanosec);
function expect(ok, what) {
  if (!ok) throw new Error(what);
}
function near(a, b, tol, what) {
  expect(Math.abs(a - b) <= tol, `${what}: ${a} against ${b}`);
}

// topic -> decoded messages in log-time order: the bridge's by Humble's definitions (and the same
// by the recording's schema), the others by the recording's schema.
async function read(file) {
  const mcap = await openMcap(file);
  expect(mcap.header.profile === "ros2", `${file}: profile "${mcap.header.profile}", not ros2`);
  const readers = new Map(), out = new Map();
  for (const [id, ch] of mcap.channelsById) {
    if (ch.messageEncoding !== "cdr") continue;
    const schema = mcap.schemasById.get(ch.schemaId);
    const own = new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true }));
    const port = ch.topic.startsWith("/brickyard/bridge/") ? ch.topic.slice(18) : null;
    let humble = null;
    if (port !== null) {
      expect(kBridge[port] === schema.name, `${ch.topic}: schema ${schema.name}, not ${kBridge[port]}`);
      humble = new MessageReader(definitions(schema.name));
    }
    readers.set(id, { own, humble, topic: ch.topic });
    out.set(ch.topic, []);
  }
  for await (const m of mcap.readMessages()) {
    const r = readers.get(m.channelId);
    if (!r) continue;
    const msg = r.own.readMessage(m.data);
    if (r.humble) {
      const h = r.humble.readMessage(m.data);
      expect(plain(h) === plain(msg), `${r.topic}: ROS 2 Humble's definition reads ${plain(h).slice(0, 200)}, the recording's schema ${plain(msg).slice(0, 200)}`);
    }
    out.get(r.topic).push(msg);
  }
  return out;
}

function yaw(q) {
  return Math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
}

function checkEstimates(t, out) {
  const est = t.get("/brickyard/estimator/estimate"), odom = t.get("/brickyard/bridge/odom"), pose = t.get("/brickyard/bridge/pose");
  expect(est && est.length > 0, "no estimates recorded");
  expect(odom.length === est.length && pose.length === est.length, `${odom.length} odometry and ${pose.length} poses for ${est.length} estimates`);
  const tfs = t.get("/brickyard/bridge/tf").flatMap((m) => m.transforms).filter((x) => x.child_frame_id === "base_link");
  expect(tfs.length === est.length, `${tfs.length} map-to-base transforms for ${est.length} estimates`);
  est.forEach((e, i) => {
    const o = odom[i], p = pose[i].pose, tr = tfs[i];
    expect(ns(o.header.stamp) === BigInt(e.header.stamp_ns), `odom ${i}: stamp ${ns(o.header.stamp)}, the estimate's ${e.header.stamp_ns}`);
    expect(o.header.frame_id === "map" && o.child_frame_id === "base_link", `odom ${i}: frames ${o.header.frame_id} / ${o.child_frame_id}`);
    for (const [what, got] of [["odom", o.pose.pose], ["pose", p], ["tf", { position: tr.transform.translation, orientation: tr.transform.rotation }]]) {
      expect(got.position.x === e.x && got.position.y === e.y, `${what} ${i}: (${got.position.x}, ${got.position.y}), the estimate's (${e.x}, ${e.y})`);
      near(Math.atan2(Math.sin(yaw(got.orientation) - e.yaw), Math.cos(yaw(got.orientation) - e.yaw)), 0, 1e-12, `${what} ${i}: yaw against the estimate's`);
    }
    const c = o.pose.covariance;
    expect(c[0] === e.covariance[0] && c[1] === e.covariance[1] && c[5] === e.covariance[2] && c[35] === e.covariance[8],
           `odom ${i}: covariance not the estimate's over x, y, yaw`);
    expect(o.twist.twist.linear.x === e.speed && o.twist.twist.angular.z === e.yaw_rate, `odom ${i}: twist not the estimate's speed and yaw rate`);
  });
  out.estimates = est.length;
}

function checkClouds(t, out) {
  const clouds = ["lidar_front", "lidar_left", "lidar_right"].flatMap((n) => t.get(`/brickyard/${n}/cloud`) || []);
  const points = t.get("/brickyard/bridge/points");
  expect(clouds.length > 0 && points.length === clouds.length, `${points.length} PointCloud2 for ${clouds.length} clouds`);
  const key = (frame, stamp) => `${frame}@${stamp}`;
  const byKey = new Map(points.map((p) => [key(p.header.frame_id, ns(p.header.stamp)), p]));
  const mounts = t.get("/brickyard/bridge/tf").flatMap((m) => m.transforms).filter((x) => x.header.frame_id === "base_link");
  expect(mounts.length === clouds.length, `${mounts.length} base-to-sensor transforms for ${clouds.length} clouds`);
  for (const c of clouds) {
    const p = byKey.get(key(c.header.frame_id, BigInt(c.header.stamp_ns)));
    expect(p, `no PointCloud2 in ${c.header.frame_id} stamped ${c.header.stamp_ns}`);
    expect(p.width === c.x.length && p.height === 1, `${c.header.frame_id} @${c.header.stamp_ns}: ${p.width} points, the cloud's ${c.x.length}`);
    const view = new DataView(p.data.buffer, p.data.byteOffset, p.data.byteLength);
    const field = (name) => p.fields.find((f) => f.name === name).offset;
    for (const i of [0, c.x.length - 1].filter((k) => k >= 0))
      for (const [axis, col] of [["x", c.x], ["y", c.y], ["z", c.z]])
        expect(view.getFloat32(i * p.point_step + field(axis), !p.is_bigendian) === Math.fround(col[i]), `${c.header.frame_id} point ${i} ${axis}`);
  }
  const first = (t.get("/brickyard/lidar_front/cloud") || [])[0];
  const front = mounts.find((m) => m.child_frame_id === first.header.frame_id);
  expect(front && front.transform.translation.x === first.sensor_x && front.transform.translation.z === first.sensor_z,
         `base_link to ${first.header.frame_id} (the front LiDAR): not the cloud's sensor pose`);
  out.clouds = clouds.length;
}

function checkMarkersAndImu(t, out) {
  const paths = t.get("/brickyard/planner/path"), pm = t.get("/brickyard/bridge/path_markers");
  expect(paths.length > 0 && pm.length === paths.length, `${pm.length} path marker arrays for ${paths.length} paths`);
  paths.forEach((p, i) => {
    const m = pm[i].markers[0];
    expect(m.type === 4 && m.points.length === p.poses.length, `path ${i}: marker type ${m.type}, ${m.points.length} points for ${p.poses.length} poses`);
    p.poses.forEach((q, k) => expect(m.points[k].x === q.x && m.points[k].y === q.y, `path ${i}, point ${k}`));
  });
  const obs = t.get("/brickyard/obstacles/obstacles"), om = t.get("/brickyard/bridge/obstacle_markers");
  expect(om.length === obs.length, `${om.length} obstacle marker arrays for ${obs.length} obstacle lists`);
  let boxes = 0;
  obs.forEach((o, i) => {
    const m = om[i].markers;
    expect(m.length === o.obstacles.length + 1 && m[0].action === 3, `obstacles ${i}: ${m.length} markers for ${o.obstacles.length} obstacles`);
    o.obstacles.forEach((b, k) => expect(m[k + 1].pose.position.x === b.x && m[k + 1].scale.y === b.size_y, `obstacles ${i}, box ${k}`));
    boxes += o.obstacles.length;
  });
  const imu = t.get("/brickyard/imu/imu"), im = t.get("/brickyard/bridge/imu_data");
  expect(imu.length > 0 && im.length === imu.length, `${im.length} ROS 2 IMU samples for ${imu.length}`);
  imu.forEach((s, i) => {
    const r = im[i];
    expect(r.angular_velocity.z === s.gyro_z && r.linear_acceleration.x === s.accel_x && r.orientation_covariance[0] === -1,
           `imu ${i}: not the IMU's sample`);
  });
  Object.assign(out, { paths: paths.length, obstacle_lists: obs.length, boxes, imu: imu.length });
}

// Each receiver's fixes as NavSatFix in its antenna's frame (gnss_N), about the datum.
function checkFixes(t, fixesFile, out) {
  const expected = new Map(JSON.parse(require("fs").readFileSync(fixesFile, "utf8")).map((f) => [`${f[0]}#${f[1]}`, f]));
  const nav = new Map(t.get("/brickyard/bridge/fix").map((m) => [`${m.header.frame_id}@${ns(m.header.stamp)}`, m]));
  let n = 0, worst = 0;
  for (const topic of ["gnss_left.fix", "gnss_right.fix"])
    for (const f of t.get(`/brickyard/${topic.replace(".", "/")}`)) {
      const want = expected.get(`${topic}#${f.header.seq}`), got = nav.get(`gnss_${f.receiver_id}@${f.header.stamp_ns}`);
      expect(want && got, `${topic} seq ${f.header.seq}: no NavSatFix in gnss_${f.receiver_id} stamped ${f.header.stamp_ns}`);
      const m = 111320;  // metres in a degree of latitude, about: the errors below in metres
      const err = Math.max(Math.abs(got.latitude - want[2]) * m, Math.abs(got.longitude - want[3]) * m * Math.cos((want[2] * Math.PI) / 180),
                           Math.abs(got.altitude - want[4]));
      expect(err <= 1e-6, `${topic} seq ${f.header.seq}: ${err} m from the position`);
      expect(got.status.status === want[5], `${topic} seq ${f.header.seq}: status ${got.status.status}, expected ${want[5]}`);
      expect(got.position_covariance[0] === f.sigma_x * f.sigma_x && got.position_covariance_type === 2, `${topic} seq ${f.header.seq}: covariance`);
      worst = Math.max(worst, err), n++;
    }
  expect(n > 0 && nav.size === n, `${nav.size} NavSatFix for ${n} fixes`);
  Object.assign(out, { fixes: n, fix_error_m: worst });
}

async function main() {
  const t = await read(process.argv[2]);
  for (const port of Object.keys(kBridge)) expect(t.has(`/brickyard/bridge/${port}`), `no topic /brickyard/bridge/${port}`);
  const out = {};
  checkEstimates(t, out);
  checkClouds(t, out);
  checkMarkersAndImu(t, out);
  checkFixes(t, process.argv[3], out);
  console.log(JSON.stringify(out));
}

main().catch((e) => {
  console.error(`ros2_bridge_check: ${e.message}`);
  process.exit(1);
});
