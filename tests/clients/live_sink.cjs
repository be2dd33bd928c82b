// A light live client for bench_live: subscribes to every advertised channel (but those of the
// schema names given with --skip, unless their topic is given with --keep) and counts what
// arrives, decoding nothing, until the server closes. Prints {"messages": N, "bytes": B}.
// Retries while the run starts.
// usage: node live_sink.cjs URL [--skip SCHEMA]... [--keep TOPIC]...
"use strict";
const WebSocket = require("ws");
const [url, ...rest] = process.argv.slice(2);
const skip = new Set(), keep = new Set();
for (let i = 0; i < rest.length; i += 2) (rest[i] === "--keep" ? keep : skip).add(rest[i + 1]);
const deadline = Date.now() + 60000;
let messages = 0, bytes = 0;
function attempt() {
  const ws = new WebSocket(url, ["foxglove.websocket.v1"]);
  let opened = false;
  ws.on("open", () => (opened = true));
  ws.on("message", (data, binary) => {
    if (binary) return void (messages++, (bytes += data.length));
    const j = JSON.parse(data.toString());
    if (j.op !== "advertise") return;
    const subscriptions = j.channels.filter((c) => keep.has(c.topic) || !skip.has(c.schemaName)).map((c) => ({ id: c.id, channelId: c.id }));
    ws.send(JSON.stringify({ op: "subscribe", subscriptions }));
  });
  ws.on("close", () => opened && (console.log(JSON.stringify({ messages, bytes })), process.exit(0)));
  ws.on("error", () => {
    if (opened || Date.now() > deadline) process.exit(1);
    setTimeout(attempt, 100);
  });
}
attempt();
