// Watches topics of ugv-foxglove with Foxglove's own client for a while and prints, per topic,
// the messages received and the latency from each message's log time (the bridge's LCM
// receive time) to its arrival here (same host clock):
//   node watch_live.mjs ws://HOST:PORT SECONDS TOPIC...
// docs/foxglove.md's latency figure comes from it. Exit 1 when a topic got no message.
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;  // a CommonJS package
const [url, seconds, ...topics] = process.argv.slice(2);
const byTopic = new Map(topics.map((t) => [t, { latencies: [], bytes: 0 }]));
const topicOfSub = new Map();
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => console.error(`watch_live: ${e?.message ?? e}`));
client.on("advertise", (channels) => {
  for (const c of channels) if (byTopic.has(c.topic)) topicOfSub.set(client.subscribe(c.id), c.topic);
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const arrivedNs = process.hrtime.bigint() - hrtimeOffsetNs;
  const t = byTopic.get(topicOfSub.get(subscriptionId));
  t.latencies.push(Number(arrivedNs - timestamp) / 1e6);
  t.bytes += data.byteLength;
});
// The wall clock in ns with hrtime's resolution: hrtime minus its offset from Date.now().
const hrtimeOffsetNs = process.hrtime.bigint() - BigInt(Date.now()) * 1000000n;

setTimeout(() => {
  let missing = 0;
  for (const [topic, t] of byTopic) {
    const l = t.latencies.sort((a, b) => a - b);
    const q = (p) => (l.length ? l[Math.min(l.length - 1, Math.floor(p * l.length))].toFixed(1) : "-");
    console.log(`watch_live: ${topic}: ${l.length} messages, ${(t.bytes / 1e6).toFixed(1)} MB; latency ms median ${q(0.5)}, ` +
      `p95 ${q(0.95)}, max ${l.length ? l.at(-1).toFixed(1) : "-"}`);
    if (l.length === 0) ++missing;
  }
  client.close();
  process.exit(missing === 0 ? 0 : 1);
}, 1000 * Number(seconds));
