// Clients that misbehave against a live run (docs/live.md), all at once: garbage text, a binary
// message, subscriptions to channels that do not exist and of the wrong shape, a flood of
// requests, a client that subscribes to everything and never reads, and one that leaves in the
// middle of a frame. Each must get a status message or be disconnected; none may stop or slow
// the run (the test checks the run). Prints what each saw as JSON.
// usage: node live_abuse.cjs HOST PORT
"use strict";
const net = require("net");
const WebSocket = require("ws");

const [host, port] = process.argv.slice(2);
const url = `ws://${host}:${port}`;
const seen = {};

function open(name, onOpen) {
  return new Promise((resolve) => {
    const tryOnce = (left) => {
      const ws = new WebSocket(url, ["foxglove.websocket.v1"]);
      const s = (seen[name] = { statuses: 0, closed: false, close_code: 0, advertised: 0 });
      ws.on("message", (data, binary) => {
        if (binary) return;
        const j = JSON.parse(data.toString());
        if (j.op === "status") s.statuses++;
        if (j.op === "advertise") s.advertised += j.channels.length;
      });
      ws.on("close", (code) => Object.assign(s, { closed: true, close_code: code }));
      ws.once("open", () => resolve(onOpen(ws, s)));
      ws.once("error", () => (left > 0 ? setTimeout(() => tryOnce(left - 1), 200) : resolve()));
    };
    tryOnce(100);
  });
}

const wait = (ms) => new Promise((r) => setTimeout(r, ms));

(async () => {
  await Promise.all([
    open("garbage", async (ws) => {
      ws.send("this is not json");
      ws.send("[1, 2, 3]");
      ws.send(JSON.stringify({ op: "getParameters", parameterNames: [] }));
      ws.send(Buffer.from([1, 0, 0, 0, 0, 9, 9, 9]));
      await wait(500);
    }),
    open("bad_subscriptions", async (ws) => {
      ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: 1, channelId: 99999 }] }));
      ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: -1, channelId: "x" }, "nope", null] }));
      ws.send(JSON.stringify({ op: "subscribe", subscriptions: "all" }));
      ws.send(JSON.stringify({ op: "unsubscribe", subscriptionIds: [42, "x"] }));
      ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: 7, channelId: 1 }, { id: 7, channelId: 2 }] }));
      await wait(500);
    }),
    open("flood", async (ws) => {
      for (let i = 0; i < 5000 && ws.readyState === WebSocket.OPEN; i++)
        ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: i, channelId: 1 }] }));
      await wait(1000);
    }),
    open("never_reads", async (ws, s) => {
      // Everything, the clouds too, then the socket is paused: the server's queue for it fills.
      const sub = [];
      for (let id = 1; id <= 64; id++) sub.push({ id, channelId: id });
      ws.send(JSON.stringify({ op: "subscribe", subscriptions: sub }));
      await wait(200);
      ws._socket.pause();
      s.paused = true;
      await wait(3000);
      ws._socket.resume();
      ws.terminate();
    }),
    // Half a WebSocket frame after a proper handshake, then gone (retried while the run starts).
    new Promise((resolve) => {
      const tryOnce = (left) => {
      const sock = net.connect(Number(port), host, () => {
        sock.write(
          `GET / HTTP/1.1\r\nHost: ${host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n` +
            "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n",
        );
        setTimeout(() => {
          sock.write(Buffer.from([0x81, 0xfe, 0x01, 0x00, 1, 2, 3, 4, 5, 6])); // a masked 256-byte text frame, cut short
          sock.destroy();
          seen.half_frame = { sent: true };
          resolve();
        }, 300);
      });
      sock.on("error", () => (left > 0 ? setTimeout(() => tryOnce(left - 1), 200) : resolve()));
      };
      tryOnce(100);
    }),
  ]);
  console.log(JSON.stringify(seen));
})();
