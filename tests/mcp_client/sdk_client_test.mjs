// Drives `asbuilt mcp` with the official MCP TypeScript SDK client
// (@modelcontextprotocol/sdk, version pinned in package-lock.json): spawn the
// server on stdio, initialize, list tools, build a room with a door and two
// windows, validate, render a preview, export the plan and check it, and
// check that a bad argument comes back as an actionable isError result.
//
//   node tests/mcp_client/sdk_client_test.mjs path/to/asbuilt
//
// Exit 0 on success; a failed check prints what differed and exits 1.

import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

let Client, StdioClientTransport;
try {
  ({ Client } = await import("@modelcontextprotocol/sdk/client/index.js"));
  ({ StdioClientTransport } = await import("@modelcontextprotocol/sdk/client/stdio.js"));
} catch (e) {
  console.error("sdk_client_test: the MCP SDK is not installed; run " +
    "`bash tests/mcp_client/install.sh` (make deps does): " + e.message);
  process.exit(1);
}

const asbuilt = process.argv[2] ?? process.env.ASBUILT_CLI;
if (!asbuilt) {
  console.error("usage: node sdk_client_test.mjs path/to/asbuilt");
  process.exit(2);
}
const workspace = fs.mkdtempSync(path.join(os.tmpdir(), "asbuilt-mcp-sdk-"));
const timer = setTimeout(() => {
  console.error("sdk_client_test: timed out");
  process.exit(1);
}, 120_000);

function text(result) {
  return result.content.filter((c) => c.type === "text").map((c) => c.text).join("\n");
}

async function ok(client, name, args = {}) {
  const result = await client.callTool({ name, arguments: args });
  assert.equal(result.isError, false, `${name} failed: ${text(result)}`);
  return result;
}

const client = new Client({ name: "asbuilt-sdk-test", version: "1.0.0" });
const transport = new StdioClientTransport({
  command: asbuilt,
  args: ["mcp", "--workspace", workspace, "--quiet"],
  stderr: "inherit",
});

let step = "connect";
try {
  await client.connect(transport);
  const server = client.getServerVersion();
  assert.equal(server.name, "asbuilt");
  assert.ok(client.getServerCapabilities().tools, "server announces tools");

  step = "tools/list";
  const { tools } = await client.listTools();
  const names = new Set(tools.map((t) => t.name));
  for (const required of ["new_scene", "add_room", "add_door", "add_window", "add_furniture",
    "set_material", "set_lighting", "place_rig", "scene_from_text", "describe_scene",
    "validate_scene", "render_preview", "render_capture", "export_plan", "save_scene",
    "load_scene"]) {
    assert.ok(names.has(required), `tool ${required} listed`);
  }
  for (const t of tools) {
    assert.equal(t.inputSchema.type, "object", `${t.name} has an object schema`);
  }

  step = "build a room";
  await ok(client, "new_scene", { name: "classroom" });
  const room = await ok(client, "add_room", { width_m: 6, depth_m: 8, height_m: 3 });
  assert.match(text(room), /faces east/);
  await ok(client, "add_door", { side: "east", width_m: 1.0 });
  await ok(client, "add_window", { side: "north", width_m: 1.5, count: 2 });
  await ok(client, "place_rig", { step_deg: 45 });

  step = "validate_scene";
  const valid = await ok(client, "validate_scene");
  assert.match(text(valid), /valid/);
  if (valid.structuredContent) assert.equal(valid.structuredContent.valid, true);

  step = "render_preview";
  const preview = await ok(client, "render_preview", { width_px: 400 });
  const image = preview.content.find((c) => c.type === "image");
  assert.ok(image, "an image content block");
  assert.equal(image.mimeType, "image/png");
  const png = Buffer.from(image.data, "base64");
  assert.ok(png.length > 1000, "a PNG of some size");
  assert.deepEqual([...png.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);

  step = "export_plan";
  const exported = await ok(client, "export_plan", { path: "plans/truth.json" });
  const plan = JSON.parse(exported.content[0].text);
  assert.equal(plan.version, 1);
  assert.equal(plan.units, "m");
  assert.equal(plan.walls.length, 4);
  const length = (w) => Math.hypot(w.end[0] - w.start[0], w.end[1] - w.start[1]);
  assert.deepEqual(plan.walls.map(length).map((l) => l.toFixed(3)), ["6.000", "8.000", "6.000", "8.000"]);
  const doors = plan.openings.filter((o) => o.kind === "door");
  const windows = plan.openings.filter((o) => o.kind === "window");
  assert.equal(doors.length, 1);
  assert.equal(windows.length, 2);
  assert.ok(Math.abs(doors[0].width - 1.0) < 1e-9, `door width ${doors[0].width}`);
  for (const w of windows) assert.ok(Math.abs(w.width - 1.5) < 1e-9, `window width ${w.width}`);
  // The door is on the east wall (x = 6), the windows on the north wall (y = 8).
  assert.ok(Math.abs(doors[0].start[0] - 6) < 1e-9 && Math.abs(doors[0].end[0] - 6) < 1e-9);
  for (const w of windows) assert.ok(Math.abs(w.start[1] - 8) < 1e-9);
  assert.equal(plan.rooms.length, 1);
  assert.ok(Math.abs(plan.rooms[0].area_m2 - 48) < 1e-9);
  const written = JSON.parse(fs.readFileSync(path.join(workspace, "plans", "truth.json"), "utf8"));
  assert.equal(written.openings.length, 3);

  step = "bad argument";
  const bad = await client.callTool({ name: "add_door", arguments: { wall: 9 } });
  assert.equal(bad.isError, true);
  assert.match(text(bad), /arguments\.wall: room 0 has walls 0\.\.3, got 9/);
  const badType = await client.callTool({ name: "add_room", arguments: { width_m: "six", depth_m: 8 } });
  assert.equal(badType.isError, true);
  assert.match(text(badType), /arguments\.width_m: must be a finite number/);

  step = "path outside the workspace";
  const escape = await client.callTool({ name: "save_scene", arguments: { path: "../escape.json" } });
  assert.equal(escape.isError, true);
  assert.match(text(escape), /\.\./);
  assert.ok(!fs.existsSync(path.join(workspace, "..", "escape.json")));

  step = "unknown tool";
  await assert.rejects(client.callTool({ name: "make_coffee", arguments: {} }), (e) => {
    assert.equal(e.code, -32602);
    return true;
  });

  step = "render_capture with progress";
  await ok(client, "place_rig", { yaws_deg: [0, 90, 180, 270], width_px: 64, height_px: 48 });
  const updates = [];
  const capture = await client.callTool(
    { name: "render_capture", arguments: { output: "captures/classroom", samples_per_pixel: 1 } },
    undefined, { onprogress: (p) => updates.push(p) });
  assert.equal(capture.isError, false, text(capture));
  assert.ok(updates.length >= 1, "progress notifications arrive");
  assert.equal(updates.at(-1).progress, 4);
  assert.equal(updates.at(-1).total, 4);
  const captureJson = JSON.parse(
    fs.readFileSync(path.join(workspace, "captures", "classroom", "capture.json"), "utf8"));
  assert.equal(captureJson.frames.length, 4);
  assert.ok(!fs.readdirSync(workspace).some((n) => n.startsWith(".asbuilt-tmp-")), "no temp left");

  step = "save and load";
  await ok(client, "save_scene", { path: "scenes/classroom.json" });
  await ok(client, "new_scene");
  const loaded = await ok(client, "load_scene", { path: "scenes/classroom.json" });
  assert.match(text(loaded), /6\.00 × 8\.00 m room/);

  step = "close";
  await client.close();
  clearTimeout(timer);
  fs.rmSync(workspace, { recursive: true, force: true });
  console.log("sdk_client_test: all checks passed");
} catch (e) {
  console.error(`sdk_client_test: failed at step "${step}":`, e);
  try { await client.close(); } catch {}
  process.exit(1);
}
