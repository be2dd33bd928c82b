// Watches a live run as Foxglove does, with Foxglove's own client (@foxglove/ws-protocol over the
// `ws` package): connects to URL (retrying while the run starts), takes the server info and the
// advertised channels, subscribes to every channel but those of the types given with --skip,
// decodes every message with the channel's OMG IDL schema (@foxglove/omgidl-serialization; the
// scene's channels are JSON, each message validated against Foxglove's schema), and
// stops when the server closes the connection (the run ended). Writes OUT as JSON: the server
// info, the channels, per topic the messages' count, first and last receive time and a SHA-256
// over (time, bytes) in order, how many time messages came, and each topic's last message decoded.
// Exit 1 on anything the client or the decoder refuses.
// usage: node live_check.cjs URL OUT [--skip SCHEMA]... [--keep TOPIC]...
"use strict";
const fs = require("fs");
const crypto = require("crypto");
const WebSocket = require("ws");
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const foxgloveSchemas = require("@foxglove/schemas/jsonschema");
const Ajv = require("ajv");
const ajv = new Ajv({ strict: false });

const [url, outFile, ...rest] = process.argv.slice(2);
const skip = new Set(), keep = new Set();
for (let i = 0; i < rest.length; i += 2) (rest[i] === "--keep" ? keep : skip).add(rest[i + 1]);

function fail(why) {
  console.error(`live_check: ${url}: ${why}`);
  process.exit(1);
}

const deadline = Date.now() + 30000;
// The client and its handlers exist before the socket opens: the server's first messages can
// arrive in the same read as the handshake's answer.
function attempt() {
  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  let opened = false;
  ws.on("open", () => (opened = true));
  ws.on("error", (e) => {
    if (opened) fail(e && e.message ? e.message : String(e));
    if (Date.now() > deadline) fail("no server came up");
    setTimeout(attempt, 200);
  });
  watch(new FoxgloveClient({ ws }));
}

function watch(client) {
  const out = { serverInfo: null, channels: [], topics: {}, time_messages: 0, last_time: 0, last: {}, status: [] };
  const bySub = new Map();
  const time = Buffer.alloc(8);
  client.on("serverInfo", (info) => (out.serverInfo = info));
  client.on("status", (s) => out.status.push(s));
  client.on("time", (t) => {
    out.time_messages++;
    out.last_time = Number(t.timestamp);
  });
  client.on("advertise", (channels) => {
    for (const ch of channels) {
      out.channels.push({ id: ch.id, topic: ch.topic, encoding: ch.encoding, schemaName: ch.schemaName, schemaEncoding: ch.schemaEncoding });
      if (skip.has(ch.schemaName) && !keep.has(ch.topic)) continue;
      // The wires: CDR with their OMG IDL; the scene: JSON in Foxglove's own schemas.
      let reader;
      if (ch.encoding === "cdr" && ch.schemaEncoding === "omgidl" && ch.schemaName.startsWith("foxglove::")) {
        // A Foxglove schema in CDR (the clouds): decoded, then checked against the same JSON
        // schema with its bytes as base64, as the JSON encoding carries them.
        const cdr = new MessageReader(ch.schemaName, parseIDL(ch.schema));
        const valid = ajv.compile(foxgloveSchemas[ch.schemaName.replace(/^foxglove::/, "")]);
        reader = {
          readMessage: (b) => {
            const m = cdr.readMessage(b);
            const asJson = { ...m, data: Buffer.from(m.data).toString("base64") };
            if (!valid(asJson)) fail(`${ch.topic}: not a ${ch.schemaName}: ${JSON.stringify(valid.errors).slice(0, 300)}`);
            return { ...m, data: { bytes: m.data.length } };
          },
        };
      } else if (ch.encoding === "cdr" && ch.schemaEncoding === "omgidl") reader = new MessageReader(ch.schemaName, parseIDL(ch.schema));
      else if (ch.encoding === "json" && foxgloveSchemas[ch.schemaName.replace(/^foxglove\./, "")]) {
        // Checked against Foxglove's published JSON schema (@foxglove/schemas), as its 3D panel reads it.
        const valid = ajv.compile(foxgloveSchemas[ch.schemaName.replace(/^foxglove\./, "")]);
        reader = {
          readMessage: (b) => {
            const m = JSON.parse(Buffer.from(b).toString("utf8"));
            if (!valid(m)) fail(`${ch.topic}: not a ${ch.schemaName}: ${JSON.stringify(valid.errors).slice(0, 300)}`);
            return m;
          },
        };
      }
      else fail(`channel ${ch.topic}: ${ch.encoding} / ${ch.schemaEncoding} ${ch.schemaName}`);
      const id = client.subscribe(ch.id);
      bySub.set(id, { topic: ch.topic, reader, hash: crypto.createHash("sha256"), count: 0, first: null, last: null });
    }
  });
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const s = bySub.get(subscriptionId);
    if (!s) fail(`a message for subscription ${subscriptionId}, which was never made`);
    const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
    const decoded = s.reader.readMessage(bytes);
    time.writeBigUInt64LE(BigInt(timestamp));
    s.hash.update(time).update(bytes);
    if (s.first === null) s.first = Number(timestamp);
    s.last = Number(timestamp);
    s.count++;
    out.last[s.topic] = decoded;
  });
  client.on("close", () => {
    for (const s of bySub.values()) out.topics[s.topic] = { count: s.count, first: s.first, last: s.last, sha256: s.hash.digest("hex") };
    fs.writeFileSync(outFile, JSON.stringify(out, (k, v) => (typeof v === "bigint" ? Number(v) : ArrayBuffer.isView(v) ? Array.from(v) : v)));
    process.exit(0);
  });
}

attempt();
