// A ROS 2 bag as a team's own stack would have written it, made by third-party libraries, not ours
// (docs/ros2.md, tests/cli/ros2_bag_play.sh): a Brickyard recording's LiDAR clouds, GNSS fixes and
// IMU read by @mcap/core and Foxglove's IDL decoder, written as rosbag2 MCAP (profile ros2) with
// ROS 2 Humble's own definitions (@foxglove/rosmsg-msgs-common) by @foxglove/rosmsg2-serialization
// and @mcap/core's writer: each cloud a sensor_msgs/msg/PointCloud2 (x, y, z, intensity, FLOAT32)
// on /NODE/points, each fix a sensor_msgs/msg/NavSatFix on /NODE/fix (its latitude, longitude and
// altitude from FIXES, a JSON of [topic, seq, lat, lon, alt, status]), the IMU a sensor_msgs/msg/Imu
// on /imu/data, the estimates a nav_msgs/msg/Odometry on /odom (a team's localization); also a cloud without z (/bad/points), a topic of a type bag play does not know
// (/rosout_text, std_msgs/msg/String), and the IMU's first 10 messages again on /imu/damaged, the
// fifth cut to 20 bytes.
// usage: node ros2_bag_write.cjs RECORDING.mcap FIXES.json OUT.mcap
"use strict";
const fs = require("fs");
const { McapWriter } = require("@mcap/core");
const { parseIDL } = require("@foxglove/omgidl-parser");
const omgidl = require("@foxglove/omgidl-serialization");
const { stringify } = require("@foxglove/rosmsg");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { definitions } = require("./ros2_humble.cjs");
const { openMcap } = require("./mcap_open.cjs");

class BagWriter {
  constructor(file) {
    this.fd = fs.openSync(file, "w");
    this.mcap = new McapWriter({ writable: { position: () => BigInt(this.at), write: async (b) => this.write(b) }, useChunks: true });
    this.at = 0;
    this.channels = new Map();
  }
  async write(buffer) {
    fs.writeSync(this.fd, buffer);
    this.at += buffer.length;
  }
  async channel(topic, type) {
    const defs = definitions(type);
    const name = type.replace("/", "/msg/");
    const schemaId = await this.mcap.registerSchema({ name, encoding: "ros2msg", data: new TextEncoder().encode(stringify(defs)) });
    const id = await this.mcap.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: new Map() });
    this.channels.set(topic, { id, writer: new MessageWriter(defs), seq: 0 });
  }
  async message(topic, stamp, msg, cut = 0) {
    const c = this.channels.get(topic);
    const data = c.writer.writeMessage(msg);
    await this.mcap.addMessage({ channelId: c.id, sequence: c.seq++, logTime: stamp, publishTime: stamp, data: cut ? data.subarray(0, cut) : data });
  }
}

const time = (ns) => ({ sec: Number(ns / 1000000000n), nanosec: Number(ns % 1000000000n) });
const header = (m) => ({ stamp: time(m.header.stamp_ns), frame_id: m.header.frame_id });

function pointCloud2(m, withZ = true) {
  const names = withZ ? ["x", "y", "z", "intensity"] : ["x", "y", "intensity"];
  const n = m.x.length, step = 4 * names.length, data = new Uint8Array(n * step), view = new DataView(data.buffer);
  const columns = { x: m.x, y: m.y, z: m.z, intensity: m.intensity.length === n ? m.intensity : new Float32Array(n) };
  for (let i = 0; i < n; i++) names.forEach((f, k) => view.setFloat32(i * step + 4 * k, columns[f][i], true));
  return {
    header: header(m), height: 1, width: n, is_bigendian: false, point_step: step, row_step: n * step, data, is_dense: true,
    fields: names.map((name, k) => ({ name, offset: 4 * k, datatype: 7, count: 1 })),
  };
}

// A localization's output as a team's stack publishes it: the car (base_link) in the map, its
// covariance over x, y and yaw in the 6 x 6's places, z, roll and pitch unknown.
function odometry(m) {
  const cov = new Float64Array(36), at = [0, 1, 5];
  for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) cov[at[r] * 6 + at[c]] = m.covariance[r * 3 + c];
  for (const k of [2, 3, 4]) cov[k * 6 + k] = 99999;
  return {
    header: header(m), child_frame_id: "base_link",
    pose: { pose: { position: { x: m.x, y: m.y, z: 0 }, orientation: { x: 0, y: 0, z: Math.sin(m.yaw / 2), w: Math.cos(m.yaw / 2) } }, covariance: cov },
    twist: { twist: { linear: { x: m.speed, y: 0, z: 0 }, angular: { x: 0, y: 0, z: m.yaw_rate } }, covariance: new Float64Array(36) },
  };
}

async function main() {
  const [input, fixesFile, output] = process.argv.slice(2);
  const fixes = new Map(JSON.parse(fs.readFileSync(fixesFile, "utf8")).map((f) => [`${f[0]}#${f[1]}`, f]));
  const reader = await openMcap(input);
  const bag = new BagWriter(output);
  await bag.mcap.start({ profile: "ros2", library: "ros2_bag_write.cjs (@mcap/core)" });
  const decoders = new Map(), counts = {};
  for (const [id, ch] of reader.channelsById) {
    const schema = reader.schemasById.get(ch.schemaId);
    if (ch.messageEncoding !== "cdr") continue;
    decoders.set(id, new omgidl.MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))));
    const node = ch.topic.split(".")[0];
    if (schema.name.endsWith("::PointCloud")) await bag.channel(`/${node}/points`, "sensor_msgs/PointCloud2");
    else if (schema.name.endsWith("::GnssFix")) await bag.channel(`/${node}/fix`, "sensor_msgs/NavSatFix");
    else if (schema.name.endsWith("::Imu")) await bag.channel("/imu/data", "sensor_msgs/Imu");
    else if (schema.name.endsWith("::LocalizationEstimate")) await bag.channel("/odom", "nav_msgs/Odometry");
  }
  await bag.channel("/bad/points", "sensor_msgs/PointCloud2");
  await bag.channel("/rosout_text", "std_msgs/String");
  await bag.channel("/imu/damaged", "sensor_msgs/Imu");
  let damagedWritten = 0;
  let badWritten = false;
  for await (const m of reader.readMessages()) {
    const ch = reader.channelsById.get(m.channelId), schema = reader.schemasById.get(ch.schemaId);
    if (!decoders.has(m.channelId)) continue;
    const msg = decoders.get(m.channelId).readMessage(m.data), node = ch.topic.split(".")[0];
    let topic = null, out = null;
    if (schema.name.endsWith("::PointCloud")) {
      topic = `/${node}/points`, out = pointCloud2(msg);
      if (!badWritten) await bag.message("/bad/points", m.logTime, pointCloud2(msg, false)), (badWritten = true);
    } else if (schema.name.endsWith("::GnssFix")) {
      const f = fixes.get(`${ch.topic}#${msg.header.seq}`);
      if (!f) throw new Error(`no latitude and longitude for ${ch.topic} seq ${msg.header.seq}`);
      const cov = [msg.sigma_x ** 2, 0, 0, 0, msg.sigma_y ** 2, 0, 0, 0, msg.sigma_z ** 2];
      topic = `/${node}/fix`;
      out = { header: header(msg), status: { status: f[5], service: 1 }, latitude: f[2], longitude: f[3], altitude: f[4], position_covariance: cov,
              position_covariance_type: 2 };
    } else if (schema.name.endsWith("::Imu")) {
      topic = "/imu/data";
      out = { header: header(msg), orientation: { x: 0, y: 0, z: 0, w: 1 }, orientation_covariance: new Float64Array(9).fill(0).map((v, i) => (i ? 0 : -1)),
              angular_velocity: { x: msg.gyro_x, y: msg.gyro_y, z: msg.gyro_z }, angular_velocity_covariance: new Float64Array(9),
              linear_acceleration: { x: msg.accel_x, y: msg.accel_y, z: msg.accel_z }, linear_acceleration_covariance: new Float64Array(9) };
    } else if (schema.name.endsWith("::LocalizationEstimate")) {
      topic = "/odom", out = odometry(msg);
    }
    if (!topic) continue;
    await bag.message(topic, m.logTime, out);
    if (topic === "/imu/data" && damagedWritten < 10) await bag.message("/imu/damaged", m.logTime, out, damagedWritten++ === 4 ? 20 : 0);
    counts[topic] = (counts[topic] || 0) + 1;
  }
  await bag.message("/rosout_text", 1n, { data: "a type bag play does not know" });
  await bag.mcap.end();
  fs.closeSync(bag.fd);
  console.log(JSON.stringify(counts));
}

main().catch((e) => {
  console.error(`ros2_bag_write: ${e.stack || e.message}`);
  process.exit(1);
});
