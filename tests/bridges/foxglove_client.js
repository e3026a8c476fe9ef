// A Foxglove client for tests/bridges: @foxglove/ws-protocol's FoxgloveClient over `ws`, with
// @foxglove/rosmsg2-serialization (cdr) or @foxglove/rosmsg-serialization (ros1) for messages.
// Usage: node foxglove_client.js URL PLAN_JSON. It prints one JSON line per result:
// serverInfo, the topics of advertised channels, the first message of plan.subscribe (each one with plan.every), a service response of plan.service,
// plan.param's value, plan.assets' fetch results, a connection graph update; and it publishes
// plan.publish.data on plan.publish.topic every 200 ms until it is ended.
"use strict";
const path = require("path");
const modules = process.env.ROBOMODEL_NODE_MODULES;
const need = (name) => require(path.join(modules, name));
const { FoxgloveClient } = need("@foxglove/ws-protocol");
const WebSocket = need("ws");
const { parse } = need("@foxglove/rosmsg");
const ros2 = need("@foxglove/rosmsg2-serialization");
const ros1 = need("@foxglove/rosmsg-serialization");

const [url, planText] = process.argv.slice(2);
const plan = JSON.parse(planText);
const say = (kind, value) =>
  process.stdout.write(
    JSON.stringify({ kind, value }, (_, v) => (typeof v === "bigint" ? Number(v) : v)) + "\n",
  );
const codec = (encoding, schema) => {
  const cdr = encoding === "cdr";
  const definitions = parse(schema, { ros2: cdr });
  const lib = cdr ? ros2 : ros1;
  return { reader: new lib.MessageReader(definitions), writer: new lib.MessageWriter(definitions) };
};

// the SDK-based servers (foxglove_bridge 3, robomodel) speak foxglove.sdk.v1
const client = new FoxgloveClient({ ws: new WebSocket(url, ["foxglove.sdk.v1"]) });
const readers = new Map();
let encoding = "cdr";
let serviceCalled = false;
const responses = new Map();

client.on("serverInfo", (info) => {
  encoding = info.supportedEncodings[0];
  say("serverInfo", { capabilities: info.capabilities, encodings: info.supportedEncodings });
  if (plan.param) client.getParameters([plan.param], "get");
  client.subscribeConnectionGraph();
  (plan.assets || []).forEach((uri, i) => client.fetchAsset(uri, i + 1));
  if (plan.publish) {
    const p = plan.publish;
    const id = client.advertise({ topic: p.topic, encoding, schemaName: p.type,
                                  schema: p.schema, schemaEncoding: encoding === "cdr" ? "ros2msg" : "ros1msg" });
    const { writer } = codec(encoding, p.schema);
    setInterval(() => client.sendMessage(id, writer.writeMessage({ data: p.data })), 200);
  }
});
client.on("advertise", (channels) => {
  say("channels", channels.map((c) => c.topic));
  for (const channel of channels) {
    if (channel.topic !== plan.subscribe || readers.size) continue;
    const subscription = client.subscribe(channel.id);
    readers.set(subscription, { reader: codec(channel.encoding, channel.schema).reader, channel });
  }
});
// A channel the server takes back (its topic left the graph) is said, and its subscription
// dropped: the topic's next channel is subscribed to when it is advertised, as Foxglove does.
client.on("unadvertise", (channelIds) => {
  say("unadvertised", channelIds);
  for (const [subscription, found] of readers) {
    if (channelIds.includes(found.channel.id)) readers.delete(subscription);
  }
});
// A subscription the server refused is said, and not sent again, as Foxglove does not: the
// Foxglove SDK (0.30.3) refuses one that comes between a new channel's advertisement and its
// registration, and the bridge then advertises the topic again (tests/bridges/
// test_foxglove_inprocess.py), which the "advertise" handler above subscribes to.
client.on("status", ({ message }) => {
  const unknown = /Unknown channel ID: (\d+)/.exec(message);
  if (unknown) say("refused", Number(unknown[1]));
});
client.on("message", ({ subscriptionId, data }) => {
  const found = readers.get(subscriptionId);
  if (!found) return;
  readers.set(subscriptionId, { ...found, done: true });
  if (found.done && !plan.every) return; // plan.every: say each message, not the first only
  say("message", { topic: found.channel.topic, schemaName: found.channel.schemaName,
                   encoding: found.channel.encoding, msg: found.reader.readMessage(data) });
});
client.on("advertiseServices", (services) => {
  for (const service of services) {
    if (serviceCalled || !plan.service || service.name !== plan.service.name) continue;
    serviceCalled = true;
    const request = codec(encoding, service.request.schema).writer.writeMessage(plan.service.request);
    responses.set(1, codec(encoding, service.response.schema).reader);
    client.sendServiceCallRequest({ serviceId: service.id, callId: 1, encoding, data: new DataView(request.buffer, request.byteOffset, request.byteLength) });
  }
});
client.on("serviceCallResponse", (response) => {
  say("serviceResponse", responses.get(response.callId).readMessage(response.data));
});
client.on("serviceCallFailure", (failure) => say("serviceFailure", failure.message));
client.on("parameterValues", (event) => say("parameters", event.parameters));
client.on("fetchAssetResponse", (event) =>
  say("asset", { requestId: event.requestId, status: event.status,
                 bytes: event.status === 0 ? event.data.byteLength : 0, error: event.error }),
);
let graphSaid = false;
client.on("connectionGraphUpdate", (event) => {
  if (graphSaid || !event.publishedTopics.length) return;
  graphSaid = true;
  say("graph", { publishedTopics: event.publishedTopics.map((t) => t.name) });
});
client.on("error", (error) => say("error", String(error)));
