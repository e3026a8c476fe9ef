// The Foxglove client of bench/bench_bridges.py: @foxglove/ws-protocol's FoxgloveClient (what
// Foxglove Studio uses) over `ws`, subscribed to the bench's topics. Each message's latency is
// CLOCK_MONOTONIC (process.hrtime, Python's time.monotonic_ns) now minus the header.stamp at
// the CDR payload's offset 4. Prints one JSON object {topic: [latency ms, ...]} when it ends.
// Usage: node bench_bridges_client.js URL SECONDS TOPIC...
"use strict";
const path = require("path");
const modules = process.env.ROBOMODEL_NODE_MODULES;
const { FoxgloveClient } = require(path.join(modules, "@foxglove/ws-protocol"));
const WebSocket = require(path.join(modules, "ws"));

const [url, seconds, ...topics] = process.argv.slice(2);
const latencies = Object.fromEntries(topics.map((t) => [t, []]));
const bySubscription = new Map();
const client = new FoxgloveClient({ ws: new WebSocket(url, ["foxglove.sdk.v1"]) });
client.on("advertise", (channels) => {
  for (const channel of channels) {
    if (channel.topic in latencies) bySubscription.set(client.subscribe(channel.id), channel.topic);
  }
});
client.on("message", ({ subscriptionId, data }) => {
  const now = process.hrtime.bigint();
  const stampNs = BigInt(data.getInt32(4, true)) * 1000000000n + BigInt(data.getUint32(8, true));
  latencies[bySubscription.get(subscriptionId)].push(Number(now - stampNs) / 1e6);
});
setTimeout(() => {
  client.close();
  // a pipe's write completes later: exit once it has, or the output is cut at 64 KiB
  process.stdout.write(JSON.stringify(latencies) + "\n", () => process.exit(0));
}, Number(seconds) * 1000);
