// The scene in a recording (docs/recording.md): every channel whose schema is Foxglove's
// ("foxglove.FrameTransform", "foxglove.SceneUpdate", JSON) read by @mcap/core and each message
// checked against Foxglove's published JSON schema (@foxglove/schemas, by ajv), as its 3D panel
// reads it. The recording must hold /tf with the map -> vehicle transform, and the track's scene.
// Prints a JSON object of counts per scene channel; exit 1 with the first message that fails.
// usage: node scene_check.cjs RECORDING.mcap
"use strict";
const foxgloveSchemas = require("@foxglove/schemas/jsonschema");
const Ajv = require("ajv");
const { openMcap } = require("./mcap_open.cjs");

async function main() {
  const [file] = process.argv.slice(2);
  const reader = await openMcap(file);
  const ajv = new Ajv({ strict: false });
  const checks = new Map(), counts = {}, frames = new Set();
  for (const [id, ch] of reader.channelsById) {
    const schema = reader.schemasById.get(ch.schemaId);
    if (!schema.name.startsWith("foxglove.")) continue;
    if (ch.messageEncoding !== "json") throw new Error(`${ch.topic}: encoding ${ch.messageEncoding}, not json`);
    const published = foxgloveSchemas[schema.name.replace(/^foxglove\./, "")];
    if (!published) throw new Error(`${ch.topic}: no Foxglove schema named ${schema.name}`);
    checks.set(id, { topic: ch.topic, valid: ajv.compile(published) });
    counts[ch.topic] = 0;
  }
  for await (const m of reader.readMessages()) {
    const c = checks.get(m.channelId);
    if (!c) continue;
    const msg = JSON.parse(new TextDecoder().decode(m.data));
    if (!c.valid(msg)) throw new Error(`${c.topic}, message ${counts[c.topic]}: ${ajv.errorsText(c.valid.errors)}`);
    if (c.topic === "/tf") frames.add(`${msg.parent_frame_id} -> ${msg.child_frame_id}`);
    counts[c.topic]++;
  }
  if (!counts["/tf"]) throw new Error(`${file}: no /tf`);
  if (!frames.has("map -> vehicle")) throw new Error(`${file}: /tf has no map -> vehicle (${[...frames].join(", ")})`);
  if (!counts["/scene/track"]) throw new Error(`${file}: no /scene/track`);
  console.log(JSON.stringify({ channels: counts, frames: [...frames] }));
}

main().catch((e) => {
  console.error(`scene_check: ${e.message}`);
  process.exit(1);
});
