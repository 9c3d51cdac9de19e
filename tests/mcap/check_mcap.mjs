// Checks an MCAP file written by ColAG-fw with the reference implementation: @mcap/core reads it
// twice (streamed, every CRC checked; then through its summary and indexes, as viewers seek),
// @foxglove/rosmsg2-serialization decodes every message with the schema stored in the file, and
// the content is checked against the mission (see `usage`). Exit 0: all good; 1: a check
// failed (each failure printed); 2: usage; 77: the packages are not installed (`npm ci` in
// tests/mcap; scripts/setup does it): CTest counts the test as skipped.
//
//   node check_mcap.mjs FILE [--ugvs N] [--arena-half M] [--require-plan] [--topics a,b,...]
import { readFile, open } from "node:fs/promises";

let McapStreamReader, McapIndexedReader, parse, MessageReader, crc32;
try {
  ({ McapStreamReader, McapIndexedReader } = await import("@mcap/core"));
  ({ parse } = await import("@foxglove/rosmsg"));
  ({ MessageReader } = await import("@foxglove/rosmsg2-serialization"));
  ({ crc32 } = await import("@foxglove/crc"));
} catch (e) {
  console.error(`check_mcap: SKIPPED: ${e.message}\n  install the test packages: (cd tests/mcap && npm ci)`);
  process.exit(77);
}

function usage(msg) {
  console.error(`check_mcap: ${msg}\n` +
    "usage: node check_mcap.mjs FILE [--ugvs N] [--arena-half M] [--require-plan] [--topics a,b]");
  process.exit(2);
}

const args = process.argv.slice(2);
const opt = { file: undefined, ugvs: 0, arenaHalf: 20, requirePlan: false, topics: [] };
for (let i = 0; i < args.length; ++i) {
  const a = args[i];
  const value = () => (i + 1 < args.length ? args[++i] : usage(`${a} needs a value`));
  if (a === "--ugvs") opt.ugvs = Number(value());
  else if (a === "--arena-half") opt.arenaHalf = Number(value());
  else if (a === "--require-plan") opt.requirePlan = true;
  else if (a === "--topics") opt.topics = value().split(",").filter((t) => t);
  else if (a.startsWith("--")) usage(`unknown option ${a}`);
  else if (opt.file === undefined) opt.file = a;
  else usage(`unexpected ${a}`);
}
if (opt.file === undefined) usage("no file");

const failures = [];
const fail = (m) => {
  if (failures.length < 50) console.error(`FAIL: ${m}`);
  failures.push(m);
};
const check = (ok, m) => ok || fail(m);

const bytes = new Uint8Array(await readFile(opt.file));

// 1. Streamed: every record, chunk CRCs checked; the data section's CRC recomputed here.
const stream = new McapStreamReader({ validateCrcs: true });
stream.append(bytes);
const schemas = new Map(), channels = new Map(), streamed = [];
let statistics, dataEnd, footer, header;
try {
  for (let r; (r = stream.nextRecord());) {
    if (r.type === "Header") header = r;
    else if (r.type === "Schema") schemas.set(r.id, r);
    else if (r.type === "Channel") channels.set(r.id, r);
    else if (r.type === "Message") streamed.push(r);
    else if (r.type === "Statistics") statistics = r;
    else if (r.type === "DataEnd") dataEnd = r;
    else if (r.type === "Footer") footer = r;
  }
  check(stream.done(), "the stream reader did not reach the end magic");
} catch (e) {
  fail(`stream read: ${e.message}`);
}
check(header?.profile === "ros2", `profile ${header?.profile}, expected ros2`);
check(dataEnd !== undefined, "no DataEnd record");
if (dataEnd !== undefined && footer !== undefined) {
  // DataEnd is 13 bytes (opcode, length, crc) just before the summary.
  const dataEndAt = Number(footer.summaryStart) - 13;
  check(dataEnd.dataSectionCrc === crc32(bytes.subarray(0, dataEndAt)),
        "data section CRC does not match");
}

// 2. Indexed, as a viewer seeks: the summary (its CRC checked by Initialize), the chunk
// indexes, the message indexes.
const fh = await open(opt.file, "r");
const readable = {
  size: async () => BigInt((await fh.stat()).size),
  read: async (offset, size) => {
    const buf = new Uint8Array(Number(size));
    await fh.read(buf, 0, Number(size), Number(offset));
    return buf;
  },
};
let indexed = 0;
try {
  const reader = await McapIndexedReader.Initialize({ readable });
  check(reader.chunkIndexes.length > 0, "no chunk indexes in the summary");
  check(reader.statistics !== undefined, "no statistics in the summary");
  let last = -1n;
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    check(m.logTime >= last, "indexed messages out of log-time order");
    last = m.logTime;
    ++indexed;
  }
} catch (e) {
  fail(`indexed read: ${e.message}`);
}
await fh.close();
check(indexed === streamed.length,
      `indexed read found ${indexed} messages, the stream ${streamed.length}`);
check(statistics !== undefined && Number(statistics.messageCount) === streamed.length,
      `statistics count ${statistics?.messageCount}, messages ${streamed.length}`);

// 3. Every message decodes with its channel's schema.
const readers = new Map();
const topicOf = new Map();
for (const [id, c] of channels) {
  topicOf.set(id, c.topic);
  const s = schemas.get(c.schemaId);
  check(c.messageEncoding === "cdr", `${c.topic}: encoding ${c.messageEncoding}`);
  if (!s || s.encoding !== "ros2msg") {
    fail(`${c.topic}: schema ${s?.name} encoded ${s?.encoding}`);
    continue;
  }
  try {
    readers.set(id, new MessageReader(parse(new TextDecoder().decode(s.data), { ros2: true })));
  } catch (e) {
    fail(`${c.topic}: schema ${s.name} does not parse: ${e.message}`);
  }
}
const byTopic = new Map();
for (const m of streamed) {
  const topic = topicOf.get(m.channelId);
  const reader = readers.get(m.channelId);
  if (!reader) continue;
  let msg;
  try {
    msg = reader.readMessage(m.data);
  } catch (e) {
    fail(`${topic}: message ${m.sequence} does not decode: ${e.message}`);
    continue;
  }
  if (!byTopic.has(topic)) byTopic.set(topic, []);
  byTopic.get(topic).push(msg);
}

// 4. The content.
const schemaOf = (topic) => {
  for (const c of channels.values()) if (c.topic === topic) return schemas.get(c.schemaId)?.name;
};
const expected = {
  "/tf": "tf2_msgs/msg/TFMessage",
  "/uav/odom": "nav_msgs/msg/Odometry",
  "/uav/map": "nav_msgs/msg/OccupancyGrid",
  "/uav/support_plan": "nav_msgs/msg/Path",
  "/uav/status": "colag_msgs/msg/UavStatus",
};
for (let i = 0; i < opt.ugvs; ++i) {
  expected[`/ugv${i}/odom`] = "nav_msgs/msg/Odometry";
  expected[`/ugv${i}/status`] = "colag_msgs/msg/UgvStatus";
  expected[`/ugv${i}/plan`] = "nav_msgs/msg/Path";
  expected[`/ugv${i}/map`] = "nav_msgs/msg/OccupancyGrid";
  expected[`/ugv${i}/prediction`] = "visualization_msgs/msg/MarkerArray";
}
for (const t of opt.topics) expected[t] ??= undefined;
for (const [topic, type] of Object.entries(expected)) {
  check(byTopic.get(topic)?.length > 0, `no messages on ${topic}`);
  if (type !== undefined) check(schemaOf(topic) === type, `${topic}: ${schemaOf(topic)}, expected ${type}`);
}
const inside = (p) => Math.abs(p.x) <= opt.arenaHalf && Math.abs(p.y) <= opt.arenaHalf &&
  Number.isFinite(p.z);
for (const [topic, msgs] of byTopic) {
  if (topic.endsWith("/odom")) {
    for (const m of msgs) {
      check(m.header.frame_id === "map", `${topic}: frame ${m.header.frame_id}`);
      check(inside(m.pose.pose.position), `${topic}: pose ${JSON.stringify(m.pose.pose.position)} outside the arena`);
      const q = m.pose.pose.orientation;
      check(Math.abs(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w - 1) < 1e-6, `${topic}: quaternion not unit`);
    }
  } else if (topic.endsWith("/map")) {
    for (const m of msgs) {
      check(m.info.width > 0 && m.info.height > 0 && m.info.resolution > 0, `${topic}: empty geometry`);
      check(m.data.length === m.info.width * m.info.height,
            `${topic}: ${m.data.length} cells for ${m.info.width} x ${m.info.height}`);
    }
    const lastMap = msgs[msgs.length - 1];
    const known = lastMap.data.filter((v) => v !== -1).length;
    check(known > 0, `${topic}: nothing known at the end of the mission`);
    check(lastMap.data.every((v) => v === -1 || v === 0 || v === 100), `${topic}: cell values other than -1/0/100`);
  } else if (topic === "/tf") {
    const frames = new Set(msgs.flatMap((m) => m.transforms.map((t) => t.child_frame_id)));
    for (let i = 0; i < opt.ugvs; ++i) check(frames.has(`ugv${i}/base_link`), `/tf: no ugv${i}/base_link`);
    check(frames.has("uav/base_link"), "/tf: no uav/base_link");
  } else if (topic.startsWith("/truth/") && topic.endsWith("/pose")) {
    for (const m of msgs) check(inside(m.pose.position), `${topic}: outside the arena`);
  }
}
const plans = byTopic.get("/uav/support_plan") ?? [];
if (opt.requirePlan) {
  check(plans.some((p) => p.poses.length > 0), "/uav/support_plan: never a stop");
}

const counts = [...byTopic].map(([t, m]) => `${t} ${m.length}`).sort().join(", ");
if (failures.length > 0) {
  console.error(`check_mcap: ${failures.length} failure(s) in ${opt.file}`);
  process.exit(1);
}
console.log(`check_mcap: ${opt.file}: ${streamed.length} messages on ${channels.size} channels, ` +
  `all CRCs and indexes good, every message decoded\n  ${counts}`);
