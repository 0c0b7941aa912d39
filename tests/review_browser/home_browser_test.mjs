// `asbuilt review` of a home in a real browser (ctest review/home_browser):
// Playwright (playwright-core) drives Debian's chromium on a home of two
// rooms joined by a door (OUT/review/home.json as `asbuilt survey home.json`
// writes it): the page draws both rooms placed; dragging a room holds it
// where it was dropped; Ctrl+Z lets the door place it again; Shift+click on
// the two doors says they are not one (that pair then places nothing);
// Ctrl+S writes the home's plan.json. Exit 77 (skip) without chromium.
//
//   node home_browser_test.mjs ASBUILT [SCREENSHOT.png]
import fs from "node:fs";
import path from "node:path";

import {fail, setUp, startReview} from "./browser_setup.mjs";

const {chromium, browserPath, work} = await setUp("home-browser");
const asbuilt = process.argv[2];
const screenshot = process.argv[3];

// A rectangular room's plan, counter-clockwise, with a 0.8 m door on wall
// `doorWall` at `offset` m from its start; in the room's own frame.
function roomPlan(w, h, doorWall, offset) {
  const c = [[0, 0], [w, 0], [w, h], [0, h]];
  const walls = c.map((p, k) => ({start: p, end: c[(k + 1) % 4], height: 2.5}));
  const s = walls[doorWall].start, e = walls[doorWall].end;
  const len = Math.hypot(e[0] - s[0], e[1] - s[1]), d = [(e[0] - s[0]) / len, (e[1] - s[1]) / len];
  const at = t => [s[0] + t * d[0], s[1] + t * d[1]];
  return {version: 1, units: "m", walls,
          openings: [{kind: "door", wall: doorWall, start: at(offset), end: at(offset + 0.8), width: 0.8, height: 2.0}],
          rooms: [{polygon: c, area_m2: w * h}]};
}
// Living 4 × 3 m, its east wall's door at y 1.0–1.8; the study 3 × 3 m east
// of it across 0.12 m, its west wall (from (0,3) down) with the door 1.2 m
// from its start, i.e. at y 1.8–1.0.
const out = path.join(work, "home");
fs.mkdirSync(path.join(out, "review"), {recursive: true});
fs.writeFileSync(path.join(out, "review", "home.json"), JSON.stringify({
  version: 1, kind: "home",
  rooms: [{name: "living", plan: roomPlan(4, 3, 1, 1.0)}, {name: "study", plan: roomPlan(3, 3, 3, 1.2)}]}));

const {child, url} = await startReview(asbuilt, out);
const browser = await chromium.launch({executablePath: browserPath, args: ["--no-sandbox"]});
try {
  const page = await browser.newPage({viewport: {width: 1400, height: 800}});
  await page.goto(url);
  await page.waitForFunction(() => typeof state !== "undefined" && state !== null);
  let s = await page.evaluate(() => state);
  if (s.kind !== "home" || s.rooms.length !== 2) fail("the page's state is not the two-room home");
  if (s.placed !== 2) fail(`${s.placed} rooms placed at first, expected 2`);
  const studyAt = s.rooms[1].pose.position_m;
  // The study's frame is its south-west corner: across the 0.12 m partition from the living room.
  if (Math.abs(studyAt[0] - 4.12) > 0.02 || Math.abs(studyAt[1]) > 0.02) fail(`the study placed at ${studyAt}`);

  // Drag the study by its floor: it is held where it was dropped.
  const study = page.locator('polygon.room[data-room="1"]');
  const box = await study.boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 80, box.y + box.height / 2 + 30, {steps: 8});
  await page.mouse.up();
  await page.waitForFunction(() => state.rooms[1].held === true);
  s = await page.evaluate(() => state);
  if (s.rooms[1].placed_by !== "moved by hand") fail(`after the drag the study is placed by "${s.rooms[1].placed_by}"`);
  const rows = await page.locator("#hv-rooms").textContent();
  if (!rows.includes("moved by hand")) fail("the rooms table does not say the study was moved by hand");

  // Undo: the door places it again.
  await page.keyboard.press("Control+z");
  await page.waitForFunction(() => state.rooms[1].held === false && state.edits === 0);

  // Shift+click the two doors: not one door; the study has no other door.
  await page.locator('polygon.door[data-room="0"]').click();
  await page.locator('polygon.door[data-room="1"]').click({modifiers: ["Shift"]});
  await page.waitForFunction(() => state.different.length === 1);
  s = await page.evaluate(() => state);
  // Placed no more by that pair (a one-sided guess may place it elsewhere).
  if (s.rooms[1].placed_by.includes("living#0 = study#0") || s.links.some(l => l.a.opening === 0 && l.b.opening === 0)) {
    fail("the study is still placed by the doors that were unlinked: " + s.rooms[1].placed_by);
  }

  // Link them again by clicking (one door), then save with Ctrl+S.
  await page.locator('polygon.door[data-room="0"]').click();
  await page.locator('polygon.door[data-room="1"]').click();
  await page.waitForFunction(() => state.same.length === 1 && state.placed === 2);
  await page.keyboard.press("Control+s");
  await page.waitForFunction(() => document.getElementById("hv-status").textContent.startsWith("saved"));
  const plan = JSON.parse(fs.readFileSync(path.join(out, "plan.json"), "utf8"));
  if (plan.rooms.length !== 2 || plan.rooms[1].name !== "study") fail("plan.json does not hold the two named rooms");
  if (!plan.openings.some(o => Array.isArray(o.rooms))) fail("plan.json has no door joining the rooms");
  if (screenshot) await page.screenshot({path: screenshot});
  console.log("home review in chromium: placed, dragged, undone, unlinked, linked, saved");
} finally {
  await browser.close();
  child.kill("SIGINT");
}
