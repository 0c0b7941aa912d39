// `asbuilt review` in a real browser (ctest review/browser): Playwright
// (playwright-core, pinned by package-lock.json) drives Debian's chromium on
// two surveys — a panorama of a box room with exact labels, and the demo
// classroom (stereo, exact labels) — loads the page, drags a corner, sees the
// plan's numbers change, undoes, drags again, saves with Ctrl-S and checks
// the written plan.json. Exit 77 (skip) without chromium.
//
// It also draws a window (w, drag a box) and checks plan.json has it, and on
// the panorama finds the box room's door with one click inside it (d, click).
//
//   node review_browser_test.mjs ASBUILT [SCREENSHOT.png]
import {spawnSync} from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import zlib from "node:zlib";

import {fail, setUp, startReview as start} from "./browser_setup.mjs";

const {chromium, browserPath, work} = await setUp("review-browser");
const asbuilt = process.argv[2];
const screenshot = process.argv[3];

function run(args) {
  const r = spawnSync(asbuilt, args, {encoding: "utf8"});
  if (r.status !== 0) fail(`asbuilt ${args.join(" ")} exited ${r.status}: ${r.stderr}`);
  return r;
}

// --- PNG writing (8-bit grey or RGB) with node's zlib.
const CRC = new Int32Array(256).map((_, n) => { let c = n; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; return c; });
function crc32(buf) { let c = -1; for (const b of buf) c = CRC[(c ^ b) & 255] ^ (c >>> 8); return (c ^ -1) >>> 0; }
function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, "ascii");
  data.copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}
function png(width, height, channels, pixel) {
  const raw = Buffer.alloc((width * channels + 1) * height);
  for (let y = 0; y < height; y++) {
    raw[y * (width * channels + 1)] = 0;
    for (let x = 0; x < width; x++) {
      const p = pixel(x, y);
      for (let c = 0; c < channels; c++) raw[y * (width * channels + 1) + 1 + x * channels + c] = p[c];
    }
  }
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0); header.writeUInt32BE(height, 4);
  header[8] = 8; header[9] = channels === 1 ? 0 : 2;
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk("IHDR", header),
                        chunk("IDAT", zlib.deflateSync(raw)), chunk("IEND", Buffer.alloc(0))]);
}

// --- The box room (as src/asbuilt/review/review_test_fixtures.cc): 4 × 3 m, 2.5 m high.
const X0 = -2, X1 = 2, Y0 = -1.5, Y1 = 1.5, H = 2.5, CAM = [0.4, -0.3, 1.4];
function labelOfRay(ray) {
  let best = Infinity, hit = null;
  for (const [axis, planes] of [[0, [X0, X1]], [1, [Y0, Y1]]]) {
    for (const plane of planes) {
      if (Math.abs(ray[axis]) < 1e-12) continue;
      const t = (plane - CAM[axis]) / ray[axis];
      if (t > 0 && t < best) { best = t; hit = [0, 1, 2].map(i => CAM[i] + t * ray[i]); }
    }
  }
  if (!hit || hit[2] < 0 || hit[2] > H) return 0;
  if (Math.abs(hit[1] - Y1) < 1e-9 && hit[0] > -0.6 && hit[0] < 0.3 && hit[2] < 2.0) return 2;
  return 1;
}
// The panorama pixel of a world point (docs/formats.md), as labelOfRay's rays.
function pixelOf(p) {
  const d = [0, 1, 2].map(i => p[i] - CAM[i]);
  const yaw = Math.atan2(-d[0], d[1]), elev = Math.atan2(d[2], Math.hypot(d[0], d[1]));
  const u = ((-yaw / (2 * Math.PI)) * 1024 - 0.5 + 1024) % 1024;
  return [u, (0.5 - elev / Math.PI) * 512 - 0.5];
}
function panoramaSurvey() {
  const dir = path.join(work, "pano");
  fs.mkdirSync(path.join(dir, "labels"), {recursive: true});
  const W = 1024, Hp = 512;
  fs.writeFileSync(path.join(dir, "pano.png"), png(W, Hp, 3, (u, v) => {
    const yaw = -2 * Math.PI * (u + 0.5) / W, elev = Math.PI * (0.5 - (v + 0.5) / Hp);
    const ray = [-Math.sin(yaw) * Math.cos(elev), Math.cos(yaw) * Math.cos(elev), Math.sin(elev)];
    const l = labelOfRay(ray);
    const shade = 170 + 40 * Math.abs(ray[0]) / Math.hypot(ray[0], ray[1]);
    return l === 2 ? [140, 90, 60] : l === 1 ? [shade, shade, shade - 10] : ray[2] > 0 ? [250, 250, 250] : [110, 100, 90];
  }));
  fs.writeFileSync(path.join(dir, "capture.json"), JSON.stringify(
      {version: 1, kind: "panorama", panorama: "pano.png", position_m: CAM}));
  const w = 128, h = 256, f = 64, cx = (w - 1) / 2, cy = (h - 1) / 2;
  for (let i = 0; i < 12; i++) {
    const psi = i * Math.PI / 6, right = [Math.cos(psi), Math.sin(psi), 0], fwd = [-Math.sin(psi), Math.cos(psi), 0];
    fs.writeFileSync(path.join(dir, "labels", String(i).padStart(3, "0") + ".png"), png(w, h, 1, (u, v) => {
      const x = (u - cx) / f, y = (v - cy) / f;
      return [labelOfRay([0, 1, 2].map(k => x * right[k] - y * (k === 2 ? 1 : 0) + fwd[k]))];
    }));
  }
  run(["survey", path.join(dir, "capture.json"), "-o", path.join(dir, "out"), "--labels", path.join(dir, "labels"),
       "--pano-size", "128x256", "--pano-fx", "64", "-q"]);
  return path.join(dir, "out");
}
function classroomSurvey() {
  run(["demo", "-o", path.join(work, "demo"), "--capture-labels", "--spp", "1", "-q"]);
  return path.join(work, "demo", "survey");
}

const startReview = out => start(asbuilt, out);

async function dragCorner(page, dx, dy) {
  const viewer = await page.locator("#rv-photo").boundingBox();
  const corners = page.locator("circle.corner");
  const n = await corners.count();
  for (let i = 0; i < n; i++) {
    const box = await corners.nth(i).boundingBox();
    if (!box) continue;
    const x = box.x + box.width / 2, y = box.y + box.height / 2;
    if (x < viewer.x + 40 || x > viewer.x + viewer.width - 40 || y < viewer.y + 40 || y > viewer.y + viewer.height - 40) continue;
    // Toward the middle of the view, so the point stays on the floor.
    const sx = x < viewer.x + viewer.width / 2 ? 1 : -1, sy = y < viewer.y + viewer.height / 2 ? 1 : -1;
    await page.mouse.move(x, y);
    await page.mouse.down();
    await page.mouse.move(x + sx * dx, y + sy * dy, {steps: 6});
    await page.mouse.up();
    return;
  }
  fail("no corner inside the view");
}

const area = page => page.locator("#rv-area").textContent();
const edits = page => page.locator("#rv-edits").textContent();

// The verdict is shown first, and the doubtful walls are listed first,
// haloed on the photo, and `n` jumps to them. Returns the banner's verdict,
// or with `count` the number of doubtful walls.
async function checkVerdict(page, name, count = false) {
  const verdict = await page.locator("#rv-verdict").getAttribute("class");
  if (!["good", "check", "unreliable"].includes(verdict)) fail(`${name}: no verdict banner (class ${verdict})`);
  const state = await page.evaluate(() => state);
  const doubtful = state.walls.filter(w => w.verdict !== "good").length;
  const rows = await page.locator("#rv-walls tr.doubt").count();
  if (rows !== doubtful) fail(`${name}: ${doubtful} doubtful walls in the state, ${rows} marked rows`);
  if (doubtful > 0) {
    const first = await page.locator("#rv-walls tr[data-wall]").first().getAttribute("class");
    if (!first.includes("doubt")) fail(`${name}: the first wall row is not a doubtful one`);
    const viewBefore = await page.locator("#rv-photo").getAttribute("viewBox");
    await page.keyboard.press("n");
    if ((await page.locator("#rv-photo").getAttribute("viewBox")) === viewBefore) fail(`${name}: n did not move the view`);
    await page.keyboard.press("0");
  }
  return count ? doubtful : verdict;
}

async function checkSurvey(browser, name, out) {
  const {child, url} = await startReview(out);
  const page = await browser.newPage({viewport: {width: 1400, height: 800}});
  const errors = [];
  page.on("pageerror", e => errors.push(e.message));
  page.on("console", m => { if (m.type() === "error") errors.push(m.text()); });
  try {
    await page.goto(url);
    await page.waitForSelector("body[data-ready='1']", {timeout: 30000});
    await page.waitForSelector("circle.corner");
    const verdict = await checkVerdict(page, name);
    const before = await area(page);
    await dragCorner(page, 60, 40);
    await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "1", null, {timeout: 20000});
    const dragged = await area(page);
    const doubtful = await checkVerdict(page, name + " after a drag", true);
    if (dragged === before) fail(`${name}: the area did not change after a drag (${before} m²)`);
    await page.keyboard.press("Control+z");
    await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "2", null, {timeout: 20000});
    if ((await area(page)) !== before) fail(`${name}: undo did not restore the area (${await area(page)} vs ${before})`);
    await dragCorner(page, 30, 20);
    await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "3", null, {timeout: 20000});
    // A window: a box across the middle of the view.
    const openings = async () => Number((await page.locator("#rv-summary").textContent()).match(/(\d+) openings/)[1]);
    const before_openings = await openings();
    const viewer = await page.locator("#rv-photo").boundingBox();
    const cx = viewer.x + viewer.width / 2, cy = viewer.y + viewer.height / 2;
    await page.keyboard.press("w");
    await page.mouse.move(cx - 30, cy - 25);
    await page.mouse.down();
    await page.mouse.move(cx + 30, cy + 15, {steps: 5});
    await page.mouse.up();
    await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "4", null, {timeout: 20000});
    if ((await openings()) !== before_openings + 1) fail(`${name}: drawing a window did not add an opening`);
    await page.keyboard.press("c");
    let expectedEdits = 4;
    if (name === "panorama") {
      // One click inside the door (d, click): asbuilt finds its jambs and head
      // in the photo. The survey found it: select it, Delete, then click.
      await page.keyboard.press("0");
      const doors = async () => (await page.evaluate(() => state.openings)).filter(o => o.kind === "door");
      const surveyed = await doors();
      if (surveyed.length !== 1) fail(`${name}: the survey found ${surveyed.length} doors, not the one`);
      await page.locator(`.opening[data-id="${surveyed[0].id}"]`).first().click();
      await page.keyboard.press("Delete");
      await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "5", null, {timeout: 20000});
      if ((await doors()).length !== 0) fail(`${name}: the survey's door was not deleted`);
      const [du, dv] = pixelOf([-0.15, Y1, 1.0]);
      const at = await page.evaluate(([u, v]) => {
        const svg = document.querySelector("#rv-photo"), layer = document.querySelector("#rv-layer");
        const pt = svg.createSVGPoint();
        pt.x = u; pt.y = v;
        const s = pt.matrixTransform(layer.getScreenCTM());
        return [s.x, s.y];
      }, [du, dv]);
      await page.keyboard.press("Escape");  // Nothing selected: a click adds, not redraws.
      await page.keyboard.press("d");
      await page.mouse.click(at[0], at[1]);
      await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "6", null, {timeout: 20000});
      const found = await doors();
      if (found.length !== 1) fail(`${name}: a click inside the door added no door`);
      const door = found[found.length - 1];
      const xs = [door.start_m[0], door.end_m[0]].sort((a, b) => a - b);
      if (Math.abs(xs[0] + 0.6) > 0.05 || Math.abs(xs[1] - 0.3) > 0.05) fail(`${name}: the clicked door spans x ${xs}, not -0.6..0.3`);
      await page.keyboard.press("c");
      // Straighten: select a corner, Ctrl-click the one two along, s: the corner between goes.
      const ids = await page.evaluate(() => state.corners.map(c => c.id));
      await page.locator(`circle.corner[data-id="${ids[0]}"]`).click();
      await page.locator(`circle.corner[data-id="${ids[2]}"]`).click({modifiers: ["Control"]});
      await page.keyboard.press("s");
      await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "7", null, {timeout: 20000});
      const left = await page.evaluate(() => state.corners.map(c => c.id));
      if (left.length !== ids.length - 1 || left.includes(ids[1])) fail(`${name}: straighten left corners ${left} of ${ids}`);
      // Trace: t, a click on each corner in turn, Enter: the same outline, every corner the person's.
      await page.keyboard.press("t");
      for (const id of left) {
        const box = await page.locator(`circle.corner[data-id="${id}"]`).boundingBox();
        await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
      }
      if ((await page.locator("circle.trace-point").count()) !== left.length) fail(`${name}: trace drew no points`);
      await page.keyboard.press("Enter");
      await page.waitForFunction(() => document.querySelector("#rv-edits").textContent === "8", null, {timeout: 20000});
      const traced = await page.evaluate(() => state.corners.map(c => c.by));
      if (traced.length !== left.length || traced.some(by => by !== "user")) fail(`${name}: trace gave corners ${traced}`);
      expectedEdits = 8;
    }
    const saved = await area(page);
    await page.keyboard.press("?");
    await page.waitForSelector("#rv-help", {state: "visible"});
    await page.keyboard.press("Escape");
    if (screenshot && name === "panorama") await page.screenshot({path: screenshot});
    await page.keyboard.press("Control+s");
    await page.waitForFunction(() => document.querySelector("#rv-status").textContent.startsWith("saved"), null, {timeout: 30000});
    const plan = JSON.parse(fs.readFileSync(path.join(out, "plan.json"), "utf8"));
    const written = plan.rooms[0].area_m2.toFixed(2);
    if (written !== saved) fail(`${name}: plan.json has ${written} m², the page showed ${saved} m²`);
    const corrections = JSON.parse(fs.readFileSync(path.join(out, "review", "corrections.json"), "utf8"));
    if (corrections.edits.length !== expectedEdits) fail(`${name}: corrections.json has ${corrections.edits.length} edits, not ${expectedEdits}`);
    if (!plan.openings.some(o => o.kind === "window")) fail(`${name}: plan.json has no window`);
    if (errors.length) fail(`${name}: console errors: ${errors.join("; ")}`);
    if (!plan.verdict || !["good", "check", "unreliable"].includes(plan.verdict.verdict)) fail(`${name}: plan.json has no verdict`);
    console.log(`${name}: verdict ${verdict}, ${doubtful} wall(s) to check after a drag; ${before} → ${dragged} m² after a drag, undo back to ${before}, saved ${saved} m²: ok`);
  } finally {
    await page.close();
    child.kill("SIGINT");
  }
}

const bad = spawnSync(asbuilt, ["review", work], {encoding: "utf8"});
if (bad.status === 0 || !/not a folder written by `asbuilt survey`/.test(bad.stderr)) {
  fail(`asbuilt review on a folder that is no survey: exit ${bad.status}, ${bad.stderr}`);
}
const t0 = Date.now();
const surveys = [["panorama", panoramaSurvey()]];
console.log(`panorama survey: ${(Date.now() - t0) / 1000} s`);
surveys.push(["stereo classroom", classroomSurvey()]);
console.log(`classroom demo survey: ${(Date.now() - t0) / 1000} s`);
const browser = await chromium.launch({executablePath: browserPath, args: ["--no-sandbox", "--disable-gpu"]});
try {
  for (const [name, out] of surveys) await checkSurvey(browser, name, out);
} finally {
  await browser.close();
}
console.log("review page: ok");
