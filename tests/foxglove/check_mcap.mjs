// Reads an MCAP written by ugv-mcap with Foxglove's own MCAP library (@mcap/core) and checks
// it against what the log held:
//   node check_mcap.mjs FILE.mcap EXPECTED.json
// EXPECTED.json: {"counts": {topic: messages}, "optional": [topic, ...],
//                 "grids": {topic: {"nx", "ny", "cells": [[[i, j, height], ...] of message 0, ...]}}}.
// Every topic of "counts" must be present with exactly that many messages (statistics and a
// full read agree), every schema must compile as a JSON Schema (ajv) and every message must
// parse as JSON and validate against its channel's schema; each grid of "grids" is decoded
// (cell count, strides, the named cells' heights). Exit 0 when all holds, 1 otherwise.
import { readFile } from "node:fs/promises";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { decompress as zstdDecompress } from "fzstd";
import lz4 from "lz4js";
import Ajv from "ajv";
import { checkGridLayout } from "./grid.mjs";

const [file, expectedFile] = process.argv.slice(2);
const bytes = new Uint8Array(await readFile(file));
const expected = JSON.parse(await readFile(expectedFile, "utf8"));
const failures = [];
const fail = (text) => failures.push(text);

const decompressHandlers = {
  zstd: (buffer) => zstdDecompress(buffer),
  lz4: (buffer, size) => lz4.decompress(buffer, Number(size)),
};
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};

// 1. The indexed reader: footer, summary (with its CRC), chunk indexes, statistics.
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
const topicOf = new Map();
for (const [id, channel] of reader.channelsById) topicOf.set(id, channel);
const topics = new Map([...topicOf.values()].map((c) => [c.topic, c]));
for (const topic of Object.keys(expected.counts)) if (!topics.has(topic)) fail(`topic ${topic} missing`);
const optional = new Set(expected.optional ?? []);
for (const topic of topics.keys())
  if (!(topic in expected.counts) && !optional.has(topic)) fail(`topic ${topic} not expected`);

const ajv = new Ajv({ strict: false, allErrors: false });
const validators = new Map();
for (const [id, schema] of reader.schemasById) {
  if (schema.encoding !== "jsonschema") fail(`schema ${schema.name}: encoding ${schema.encoding}`);
  try {
    validators.set(id, ajv.compile(JSON.parse(new TextDecoder().decode(schema.data))));
  } catch (e) {
    fail(`schema ${schema.name} is not a valid JSON Schema: ${e.message}`);
  }
}
const statsCounts = reader.statistics?.channelMessageCounts ?? new Map();
for (const [id, channel] of topicOf) {
  if (channel.messageEncoding !== "json") fail(`${channel.topic}: message encoding ${channel.messageEncoding}`);
  const want = expected.counts[channel.topic];
  const got = Number(statsCounts.get(id) ?? 0);
  if (want !== undefined && got !== want) fail(`${channel.topic}: statistics say ${got} messages, the log ${want}`);
}
if (reader.chunkIndexes.length === 0 && Object.keys(expected.counts).length > 0) fail("no chunk indexes");

// 2. Every message through the index, in log-time order: JSON, valid against its schema.
const counts = new Map();
const text = new TextDecoder();
let lastTime = -1n, invalid = 0;
const grids = expected.grids ?? {};
for await (const message of reader.readMessages()) {
  const channel = topicOf.get(message.channelId);
  counts.set(channel.topic, (counts.get(channel.topic) ?? 0) + 1);
  if (message.logTime < lastTime) fail(`${channel.topic}: log times out of order`);
  lastTime = message.logTime;
  let value;
  try {
    value = JSON.parse(text.decode(message.data));
  } catch (e) {
    fail(`${channel.topic}: message ${message.sequence} is not JSON: ${e.message}`);
    continue;
  }
  const validate = validators.get(channel.schemaId);
  if (validate && !validate(value) && invalid++ < 5)
    fail(`${channel.topic}: message ${message.sequence} does not match its schema: ${ajv.errorsText(validate.errors)}`);
  const grid = grids[channel.topic];
  if (grid) checkGrid(channel.topic, value, grid, counts.get(channel.topic) - 1);
}
for (const [topic, want] of Object.entries(expected.counts)) {
  const got = counts.get(topic) ?? 0;
  if (got !== want) fail(`${topic}: ${got} messages read, the log has ${want}`);
}

// 3. The stream reader over the whole file: every record parses, chunk CRCs hold.
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
stream.append(bytes);
let records = 0, footer = false;
for (let r; (r = stream.nextRecord()); ) {
  ++records;
  if (r.type === "Footer") footer = true;
}
if (!footer || !stream.done()) fail("the stream reader did not reach the footer");

function checkGrid(topic, g, want, n) {
  const heightAt = checkGridLayout(topic, g, want, fail);
  if (!heightAt) return;
  for (const [i, j, z] of want.cells?.[n] ?? []) {
    const got = heightAt(i, j);
    if (Math.fround(z) !== got) fail(`${topic}: cell (${i}, ${j}) height ${got}, the map ${z}`);
  }
}

const total = [...counts.values()].reduce((a, b) => a + b, 0);
console.log(`check_mcap: ${file}: ${topics.size} topics, ${reader.schemasById.size} schemas, ${total} messages, ` +
  `${reader.chunkIndexes.length} chunks, ${records} records streamed`);
for (const f of failures) console.log(`check_mcap: FAIL ${f}`);
process.exit(failures.length === 0 ? 0 : 1);
