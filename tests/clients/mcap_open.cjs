// An MCAP file opened through its summary and indexes by @mcap/core, its chunks' zstd and lz4
// decompressed by Foxglove's WebAssembly builds: what the test clients share.
"use strict";
const fs = require("fs");
const { McapIndexedReader } = require("@mcap/core");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("@foxglove/wasm-lz4");

async function openMcap(file) {
  await zstd.isLoaded;
  await lz4.isLoaded;
  const buf = fs.readFileSync(file);
  const readable = { size: async () => BigInt(buf.length), read: async (o, l) => buf.subarray(Number(o), Number(o + l)) };
  const decompressHandlers = { zstd: (b, n) => zstd.decompress(b, Number(n)), lz4: (b, n) => lz4(b, Number(n)) };
  return McapIndexedReader.Initialize({ readable, decompressHandlers });
}

module.exports = { openMcap };
