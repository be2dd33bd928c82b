// Reads an MCAP recording with Foxglove's own libraries, not ours: @mcap/core through the summary
// and indexes (McapIndexedReader) and front to back with every chunk's CRC checked
// (McapStreamReader); each channel's OMG IDL schema parsed by @foxglove/omgidl-parser and every
// message decoded from CDR by @foxglove/omgidl-serialization (the scene's channels, JSON in
// Foxglove's schemas, parsed as JSON: tests/clients/scene_check.cjs checks them against the schemas). Prints one JSON object: per topic its
// schema, count and a SHA-256 over (log time, bytes) in order, so a test can hold it against the
// same run's SQLite recording, and one over every message in the file's order (channel, time,
// bytes); with --last TOPIC, that topic's last message decoded.
// Exit 1 (with the reason) on anything the libraries refuse.
"use strict";
const fs = require("fs");
const crypto = require("crypto");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("@foxglove/wasm-lz4");

async function main() {
  const args = process.argv.slice(2);
  const file = args[0];
  const last = args[1] === "--last" ? args[2] : undefined;
  // --window LIVE.json (live_check's output): per topic, the hash of only the messages between
  // its first and last receive time there, to hold a live client's stream against the recording.
  const window = args[1] === "--window" ? JSON.parse(fs.readFileSync(args[2], "utf8")).topics : undefined;
  await zstd.isLoaded;
  await lz4.isLoaded;
  const decompressHandlers = { zstd: (b, n) => zstd.decompress(b, Number(n)), lz4: (b, n) => lz4(b, Number(n)) };
  const buf = fs.readFileSync(file);

  // Front to back, CRCs checked.
  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(buf);
  let streamed = 0;
  const order = crypto.createHash("sha256"), head = Buffer.alloc(10);
  for (let rec; (rec = stream.nextRecord()); )
    if (rec.type === "Message") {
      streamed++;
      head.writeUInt16LE(rec.channelId, 0);
      head.writeBigUInt64LE(rec.logTime, 2);
      order.update(head).update(rec.data);
    }
  if (!stream.done()) throw new Error("the stream reader did not reach the end");

  // Through the summary and indexes.
  const readable = { size: async () => BigInt(buf.length), read: async (o, l) => buf.subarray(Number(o), Number(o + l)) };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const out = { messages: 0, streamed, order_sha256: order.digest("hex"), metadata: {}, topics: {} };
  for await (const m of reader.readMetadata()) out.metadata[m.name] = Object.fromEntries(m.metadata);
  const decoders = new Map(), hashes = new Map();
  for (const [id, ch] of reader.channelsById) {
    const schema = reader.schemasById.get(ch.schemaId);
    const scene = schema && schema.encoding === "jsonschema" && ch.messageEncoding === "json";  // the scene, in Foxglove's schemas
    if (!scene && (!schema || schema.encoding !== "omgidl" || ch.messageEncoding !== "cdr"))
      throw new Error(`channel ${ch.topic}: schema ${schema && schema.encoding}, messages ${ch.messageEncoding} (want omgidl, cdr; or the scene's jsonschema, json)`);
    if (scene) decoders.set(id, { readMessage: (d) => JSON.parse(new TextDecoder().decode(d)) });
    else decoders.set(id, new MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))));
    hashes.set(id, crypto.createHash("sha256"));
    out.topics[ch.topic] = { schema: schema.name, count: 0 };
  }
  const time = Buffer.alloc(8);
  for await (const m of reader.readMessages()) {
    const ch = reader.channelsById.get(m.channelId);
    if (window) {
      const w = window[ch.topic], t = Number(m.logTime);
      if (!w || w.first === null || t < w.first || t > w.last) continue;
    }
    const decoded = decoders.get(m.channelId).readMessage(m.data);  // throws on bytes that do not fit the schema
    time.writeBigUInt64LE(m.logTime);
    hashes.get(m.channelId).update(time).update(m.data);
    out.topics[ch.topic].count++;
    out.messages++;
    if (ch.topic === last) out.last = decoded;
  }
  for (const [id, ch] of reader.channelsById) out.topics[ch.topic].sha256 = hashes.get(id).digest("hex");
  if (!window && reader.statistics && Number(reader.statistics.messageCount) !== out.messages)
    throw new Error(`statistics say ${reader.statistics.messageCount} messages, the indexes gave ${out.messages}`);
  if (!window && streamed !== out.messages) throw new Error(`front to back ${streamed} messages, through the indexes ${out.messages}`);
  console.log(JSON.stringify(out, (k, v) => (typeof v === "bigint" ? Number(v) : ArrayBuffer.isView(v) ? Array.from(v) : v)));
}

main().catch((e) => {
  console.error(`mcap_check: ${process.argv[2]}: ${e && e.message ? e.message : e}`);
  process.exit(1);
});
