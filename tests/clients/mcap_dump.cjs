// The messages of some channels of an MCAP recording, as JSON lines ({"topic", "msg"}), decoded by
// third-party libraries (@mcap/core, @foxglove/omgidl-serialization with the recording's own IDL):
// what a recording says was published, for a test to hold another reader's samples against.
// 64-bit integers are written as numbers' digits (JSON has no 64-bit integer).
// --first: only each topic's first message.
// usage: node mcap_dump.cjs RECORDING.mcap [--first] TOPIC...
"use strict";
const { parseIDL } = require("@foxglove/omgidl-parser");
const omgidl = require("@foxglove/omgidl-serialization");
const { openMcap } = require("./mcap_open.cjs");

async function main() {
  const [file, ...rest] = process.argv.slice(2);
  const first = rest.includes("--first"), topics = rest.filter((t) => t !== "--first"), seen = new Set();
  const reader = await openMcap(file);
  const readers = new Map();
  for (const [id, ch] of reader.channelsById) {
    if (!topics.includes(ch.topic)) continue;
    const schema = reader.schemasById.get(ch.schemaId);
    readers.set(id, new omgidl.MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))));
  }
  for (const t of topics)
    if (![...readers.keys()].some((id) => reader.channelsById.get(id).topic === t)) throw new Error(`${file}: no channel ${t}`);
  const out = [];
  for await (const m of reader.readMessages({ topics })) {
    if (first && seen.has(m.channelId)) continue;
    seen.add(m.channelId);
    const msg = readers.get(m.channelId).readMessage(m.data);
    const text = JSON.stringify(msg, (k, x) => (typeof x === "bigint" ? `@@${x}@@` : ArrayBuffer.isView(x) ? Array.from(x) : x));
    out.push(`{"topic":${JSON.stringify(reader.channelsById.get(m.channelId).topic)},"msg":${text.replace(/"@@(-?\d+)@@"/g, "$1")}}`);
  }
  process.stdout.write(out.join("\n") + "\n");
}

main().catch((e) => {
  console.error(`mcap_dump: ${e.message}`);
  process.exit(1);
});
