// Connects to ugv-foxglove with Foxglove's own client (@foxglove/ws-protocol over `ws`) and
// checks what it serves against the MCAP ugv-mcap wrote from the same log:
//   node check_live.mjs ws://HOST:PORT FILE.mcap EXPECTED.json
// EXPECTED.json: {"optional": [topic, ...], "grid": {"topic", "nx", "ny"}, "grids": N, "timeout_s": T}.
// Every topic of the MCAP must be advertised with encoding json and the same schema name and
// schema text; other topics only when "optional"; every schema compiles (ajv). Then the grid
// topic is subscribed and N grids decoded (cell count, strides, heights along the map's
// slope), each valid against its schema; messages come for that subscription only. Exit 0
// when all holds, 1 otherwise. (Latency: watch_live.mjs; here the client is busy compiling
// the schemas when the first grids come.)
import { readFile } from "node:fs/promises";
import { McapIndexedReader } from "@mcap/core";
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";
import Ajv from "ajv";
import { checkGridLayout } from "./grid.mjs";

const { FoxgloveClient } = wsProtocol;  // a CommonJS package
const [url, mcapFile, expectedFile] = process.argv.slice(2);
const expected = JSON.parse(await readFile(expectedFile, "utf8"));
const failures = [];
const fail = (text) => failures.push(text);

// The MCAP's topics and schemas.
const bytes = new Uint8Array(await readFile(mcapFile));
const reader = await McapIndexedReader.Initialize({
  readable: {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  },
});
const want = new Map();
for (const channel of reader.channelsById.values()) {
  const schema = reader.schemasById.get(channel.schemaId);
  want.set(channel.topic, { schemaName: schema.name, schema: new TextDecoder().decode(schema.data) });
}
const optional = new Set(expected.optional ?? []);
const gridWant = expected.grid;
const gridsWanted = expected.grids ?? 2;

const ajv = new Ajv({ strict: false });
const advertised = new Map();  // topic -> channel
const validators = new Map();  // channel id -> validate
let serverInfo = null, gridSub = -1, grids = 0;

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
const finish = () => {
  for (const topic of want.keys()) if (!advertised.has(topic)) fail(`topic ${topic} of the MCAP not advertised`);
  if (!serverInfo) fail("no serverInfo");
  if (grids < gridsWanted) fail(`${grids} grids decoded, ${gridsWanted} wanted`);
  console.log(`check_live: ${url}: ${advertised.size} topics advertised, ${want.size} in the MCAP, ${grids} grids decoded`);
  for (const f of failures) console.log(`check_live: FAIL ${f}`);
  client.close();
  process.exit(failures.length === 0 ? 0 : 1);
};
const timer = setTimeout(() => {
  fail(`timed out after ${expected.timeout_s ?? 30} s`);
  finish();
}, 1000 * (expected.timeout_s ?? 30));

client.on("error", (e) => fail(`client error: ${e?.message ?? e}`));
client.on("close", () => {
  if (grids < gridsWanted) {
    fail("the server closed the connection");
    clearTimeout(timer);
    finish();
  }
});
client.on("serverInfo", (info) => {
  serverInfo = info;
  if (!(info.supportedEncodings ?? []).includes("json")) fail(`serverInfo: supportedEncodings ${info.supportedEncodings}`);
});
client.on("advertise", (channels) => {
  for (const c of channels) {
    if (advertised.has(c.topic)) fail(`${c.topic} advertised twice`);
    advertised.set(c.topic, c);
    if (c.encoding !== "json") fail(`${c.topic}: encoding ${c.encoding}`);
    if (c.schemaEncoding !== "jsonschema") fail(`${c.topic}: schemaEncoding ${c.schemaEncoding}`);
    try {
      validators.set(c.id, ajv.compile(JSON.parse(c.schema)));
    } catch (e) {
      fail(`${c.topic}: schema ${c.schemaName} is not a valid JSON Schema: ${e.message}`);
    }
    const m = want.get(c.topic);
    if (!m) {
      if (!optional.has(c.topic)) fail(`${c.topic} advertised, not in the MCAP`);
    } else {
      if (m.schemaName !== c.schemaName) fail(`${c.topic}: schema name ${c.schemaName}, the MCAP's ${m.schemaName}`);
      if (m.schema !== c.schema) fail(`${c.topic}: schema text differs from the MCAP's`);
    }
    if (c.topic === gridWant.topic) gridSub = client.subscribe(c.id);
  }
});
client.on("message", ({ subscriptionId, data }) => {
  if (subscriptionId !== gridSub) {
    fail(`a message for subscription ${subscriptionId}, not ours`);
    return;
  }
  const channel = advertised.get(gridWant.topic);
  let g;
  try {
    g = JSON.parse(new TextDecoder().decode(data));
  } catch (e) {
    fail(`${gridWant.topic}: not JSON: ${e.message}`);
    return;
  }
  const validate = validators.get(channel.id);
  if (validate && !validate(g)) fail(`${gridWant.topic}: does not match its schema: ${ajv.errorsText(validate.errors)}`);
  checkGrid(gridWant.topic, g, gridWant);
  if (++grids === gridsWanted) {
    client.unsubscribe(gridSub);
    clearTimeout(timer);
    finish();
  }
});

function checkGrid(topic, g, want) {
  const at = checkGridLayout(topic, g, want, fail);
  if (!at) return;
  // The sample maps are planes: 0.01 m per column i, -0.02 m per row j, plus the map's index.
  const base = at(1, 0);  // (0, 0) is one of the sample's NaN cells
  for (const [i, j] of [[1, 2], [want.nx - 1, 0], [5, want.ny - 1]]) {
    const z = base + 0.01 * (i - 1) - 0.02 * j;
    if (Math.abs(at(i, j) - z) > 1e-4) fail(`${topic}: cell (${i}, ${j}) height ${at(i, j)}, the plane ${z}`);
  }
}
