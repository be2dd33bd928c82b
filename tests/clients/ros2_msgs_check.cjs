// A ROS 2 message package written by `brickyard ros2 msgs` (docs/ros2.md) held against a
// recording's samples with third-party libraries, not ours: each msg/*.msg parsed as ROS 2
// message definitions by @foxglove/rosmsg (the MSG-separated form a ROS 2 bag's ros2msg schema
// has), and every message of an MCAP recording (omgidl schemas, CDR) decoded twice, by
// @foxglove/rosmsg2-serialization with the package's definition of its type and by
// @foxglove/omgidl-serialization with the recording's own IDL: the two must be equal, field for
// field, every message of every channel. Prints a JSON object of counts per topic; exit 1 with
// the first difference or anything the libraries refuse.
// usage: node ros2_msgs_check.cjs PACKAGE_DIR RECORDING.mcap
"use strict";
const fs = require("fs");
const path = require("path");
const { McapIndexedReader } = require("@mcap/core");
const { parseIDL } = require("@foxglove/omgidl-parser");
const omgidl = require("@foxglove/omgidl-serialization");
const { parse } = require("@foxglove/rosmsg");
const ros2 = require("@foxglove/rosmsg2-serialization");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("@foxglove/wasm-lz4");

// The package's messages: name -> .msg text; the package's name from package.xml.
function readPackage(dir) {
  const name = /<name>([^<]+)<\/name>/.exec(fs.readFileSync(path.join(dir, "package.xml"), "utf8"))[1];
  const msgs = new Map();
  for (const f of fs.readdirSync(path.join(dir, "msg")))
    if (f.endsWith(".msg")) msgs.set(f.slice(0, -4), fs.readFileSync(path.join(dir, "msg", f), "utf8"));
  return { name, msgs };
}

// TYPE's definition with every type it uses after it, as a ros2msg schema holds them.
function schemaText(pkg, type) {
  const order = [type], seen = new Set(order);
  for (let i = 0; i < order.length; i++) {
    const text = pkg.msgs.get(order[i]);
    if (text === undefined) throw new Error(`the package has no ${order[i]}.msg`);
    for (const m of text.matchAll(new RegExp(`^${pkg.name}/(\\w+)`, "gm")))
      if (!seen.has(m[1])) seen.add(m[1]), order.push(m[1]);
  }
  let out = pkg.msgs.get(type);
  for (const t of order.slice(1)) out += `\n${"=".repeat(80)}\nMSG: ${pkg.name}/${t}\n${pkg.msgs.get(t)}`;
  return out;
}

// A decoded value made comparable: typed arrays as arrays, 64-bit integers as strings.
const plain = (v) => JSON.stringify(v, (k, x) => (typeof x === "bigint" ? x.toString() : ArrayBuffer.isView(x) ? Array.from(x) : x));

function firstDifference(a, b, where = "") {
  if (typeof a !== "object" || a === null || typeof b !== "object" || b === null)
    return plain(a) === plain(b) ? null : `${where || "/"}: ${plain(a)} against ${plain(b)}`;
  const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
  for (const k of keys) {
    const d = firstDifference(a[k], b[k], `${where}/${k}`);
    if (d) return d;
  }
  return null;
}

async function main() {
  const [dir, file] = process.argv.slice(2);
  await zstd.isLoaded;
  await lz4.isLoaded;
  const pkg = readPackage(dir);
  for (const t of pkg.msgs.keys()) parse(schemaText(pkg, t), { ros2: true });  // every message parses
  const buf = fs.readFileSync(file);
  const readable = { size: async () => BigInt(buf.length), read: async (o, l) => buf.subarray(Number(o), Number(o + l)) };
  const decompressHandlers = { zstd: (b, n) => zstd.decompress(b, Number(n)), lz4: (b, n) => lz4(b, Number(n)) };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const readers = new Map(), out = { package: pkg.name, messages: pkg.msgs.size, topics: {} };
  for (const [id, ch] of reader.channelsById) {
    if (ch.messageEncoding !== "cdr") continue;  // the scene's channels (JSON, Foxglove's schemas): no message of ours
    const schema = reader.schemasById.get(ch.schemaId);
    const type = schema.name.split("::").pop();
    readers.set(id, {
      ours: new omgidl.MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))),
      theirs: new ros2.MessageReader(parse(schemaText(pkg, type), { ros2: true })),
    });
    out.topics[ch.topic] = { type: `${pkg.name}/${type}`, count: 0 };
  }
  for await (const m of reader.readMessages()) {
    if (!readers.has(m.channelId)) continue;
    const ch = reader.channelsById.get(m.channelId), r = readers.get(m.channelId);
    const d = firstDifference(r.theirs.readMessage(m.data), r.ours.readMessage(m.data));
    if (d) throw new Error(`${ch.topic}, message ${out.topics[ch.topic].count}: the ROS 2 definition reads ${d.replace(" against ", " where the IDL reads ")}`);
    out.topics[ch.topic].count++;
  }
  console.log(JSON.stringify(out));
}

main().catch((e) => {
  console.error(`ros2_msgs_check: ${e.message}`);
  process.exit(1);
});
