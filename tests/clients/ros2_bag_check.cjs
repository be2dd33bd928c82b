// A recording in MCAP's ros2 profile (`brickyard run --record FILE --record-profile ros2`,
// docs/recording.md) read as a ROS 2 bag by third-party libraries, not ours: @mcap/core opens it
// (its header's profile "ros2"), each channel's schema is ros2msg (parsed by @foxglove/rosmsg as a
// ROS 2 bag's definitions), every CDR message decoded by @foxglove/rosmsg2-serialization; held against
// a recording of the same run in our own profile (omgidl schemas, decoded by
// @foxglove/omgidl-serialization): the same topics (/brickyard/NODE/PORT for NODE.PORT), the same
// count of each, every message equal field for field. Prints a JSON object of counts per topic;
// exit 1 with the first difference.
// usage: node ros2_bag_check.cjs ROS2.mcap OURS.mcap
"use strict";
const { parseIDL } = require("@foxglove/omgidl-parser");
const omgidl = require("@foxglove/omgidl-serialization");
const { parse } = require("@foxglove/rosmsg");
const ros2 = require("@foxglove/rosmsg2-serialization");
const { openMcap } = require("./mcap_open.cjs");

// topic -> decoded messages, in log-time order; `reader(schema)` makes a decoder.
async function messages(mcap, decoder) {
  const readers = new Map(), out = new Map();
  for (const [id, ch] of mcap.channelsById) {
    if (ch.messageEncoding !== "cdr") continue;  // the scene's (JSON, Foxglove's schemas): scene_check.cjs
    readers.set(id, decoder(mcap.schemasById.get(ch.schemaId)));
    out.set(ch.topic, []);
  }
  for await (const m of mcap.readMessages())
    if (readers.has(m.channelId)) out.get(mcap.channelsById.get(m.channelId).topic).push(readers.get(m.channelId).readMessage(m.data));
  return out;
}

const plain = (v) => JSON.stringify(v, (k, x) => (typeof x === "bigint" ? x.toString() : ArrayBuffer.isView(x) ? Array.from(x) : x));

async function main() {
  const [bagFile, oursFile] = process.argv.slice(2);
  const bag = await openMcap(bagFile), ours = await openMcap(oursFile);
  if (bag.header.profile !== "ros2") throw new Error(`${bagFile}: profile "${bag.header.profile}", not ros2`);
  const theirs = await messages(bag, (schema) => {
    if (schema.encoding !== "ros2msg") throw new Error(`schema ${schema.name}: encoding ${schema.encoding}, not ros2msg`);
    if (!/^\w+\/msg\/\w+$/.test(schema.name)) throw new Error(`schema ${schema.name}: not a ROS 2 type name`);
    return new ros2.MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true }));
  });
  const mine = await messages(ours, (schema) => new omgidl.MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))));
  const out = { topics: {} };
  for (const [topic, list] of mine) {
    const name = "/brickyard/" + topic.replace(/\.([^.]*)$/, "/$1");
    const other = theirs.get(name);
    if (!other) throw new Error(`${bagFile}: no topic ${name} (${topic} in ${oursFile})`);
    if (other.length !== list.length) throw new Error(`${name}: ${other.length} messages, ${list.length} in ${oursFile}`);
    for (let i = 0; i < list.length; i++)
      if (plain(other[i]) !== plain(list[i])) throw new Error(`${name}, message ${i}: ${plain(other[i])} against ${plain(list[i])}`);
    out.topics[name] = list.length;
  }
  if (theirs.size !== mine.size) throw new Error(`${bagFile}: ${theirs.size} topics, ${mine.size} in ${oursFile}`);
  console.log(JSON.stringify(out));
}

main().catch((e) => {
  console.error(`ros2_bag_check: ${e.message}`);
  process.exit(1);
});
