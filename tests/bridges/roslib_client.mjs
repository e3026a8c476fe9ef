// A roslibjs client for tests/bridges: the npm `roslib` package (roslibjs 2, over `ws` in
// Node.js), as browser dashboards use it. Usage: node roslib_client.mjs URL PLAN_JSON.
// It prints one JSON line per result, in this order: the topics rosapi lists; the first message
// of plan.topic plain and with each of the compressions cbor, cbor-raw (the raw bytes' length)
// and png; a service call's response (plan.service); an action goal that roslibjs itself serves
// (advertise_action) and sends (send_action_goal), its feedback and result; and, once the client
// asked for fragments of plan.fragment_size, the topics again (a reply longer than that).
// It publishes plan.publish.data on plan.publish.topic every 200 ms until it is ended.
import path from "node:path";
import { pathToFileURL } from "node:url";

const modules = process.env.ROBOMODEL_NODE_MODULES;
const { Ros, Topic, Service, Action } = await import(
  pathToFileURL(path.join(modules, "roslib", "dist", "RosLib.js")).href
);

const [url, planText] = process.argv.slice(2);
const plan = JSON.parse(planText);
const say = (kind, value) => process.stdout.write(JSON.stringify({ kind, value }) + "\n");
const within = (promise, what) =>
  Promise.race([
    promise,
    new Promise((_, reject) => setTimeout(() => reject(new Error(`no ${what}`)), plan.wait_ms)),
  ]);

const ros = new Ros({ url });
await within(new Promise((resolve) => ros.on("connection", resolve)), "connection");
say("connected", true);
// count the fragment frames roslibjs joins (its transport's entry for every frame)
let fragmentFrames = 0;
const handleRaw = ros.transport.handleRawMessage.bind(ros.transport);
ros.transport.handleRawMessage = (data) => {
  if (typeof data === "string" && data.startsWith('{"op": "fragment"')) fragmentFrames += 1;
  handleRaw(data);
};

say("topics", await within(new Promise((resolve, reject) => ros.getTopics(resolve, reject)), "topics"));

const first = (compression) =>
  within(
    new Promise((resolve) => {
      const topic = new Topic({ ros, name: plan.topic, messageType: plan.type, compression });
      topic.subscribe((message) => {
        topic.unsubscribe();
        resolve(message);
      });
    }),
    `a ${compression} message`,
  );
say("none", await first("none"));
say("cbor", await first("cbor"));
const raw = await first("cbor-raw");
say("cbor-raw", { secs: raw.secs, length: raw.bytes.length });
say("png", await first("png"));

const talker = new Topic({ ros, name: plan.publish.topic, messageType: "std_msgs/msg/String" });
setInterval(() => talker.publish({ data: plan.publish.data }), 200);

const service = new Service({ ros, name: plan.service.name, serviceType: plan.service.type });
say(
  "service",
  await within(
    new Promise((resolve, reject) => service.callService(plan.service.request, resolve, reject, 10)),
    "service response",
  ),
);

const server = new Action({ ros, name: plan.action.name, actionType: plan.action.type });
server.advertise(
  (goal, id) => {
    server.sendFeedback(id, { position: goal.command.position / 2 });
    setTimeout(() => server.setSucceeded(id, { position: goal.command.position, reached_goal: true }), 300);
  },
  () => {},
);
const client = new Action({ ros, name: plan.action.name, actionType: plan.action.type });
const feedback = [];
const result = await within(
  new Promise((resolve, reject) => {
    const send = () =>
      client.sendGoal(
        plan.action.goal,
        resolve,
        (values) => feedback.push(values),
        (error) => (String(error).includes("send_goal") ? setTimeout(send, 300) : reject(error)),
      );
    setTimeout(send, 300); // the advertised action's services reach the graph first
  }),
  "action result",
);
say("action", { feedback, result });

ros.callOnConnection({ op: "set_level", level: "error", fragment_size: plan.fragment_size });
const joined = await within(
  new Promise((resolve, reject) => ros.getTopics(resolve, reject)),
  "topics in fragments",
);
say("fragmented", { topics: joined.topics, frames: fragmentFrames });
