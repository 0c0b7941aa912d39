// What the review's browser tests share: Playwright and Debian's chromium
// (exit 77, skip, without them), a scratch folder removed at exit, and
// `asbuilt review OUT --no-open` started with its address read from the
// first stdout line.
import {spawn} from "node:child_process";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

export async function setUp(name) {
  let chromium;
  try {
    ({chromium} = await import("playwright-core"));
  } catch {
    console.log("playwright-core not installed (make deps runs tests/review_browser/install.sh)");
    process.exit(77);
  }
  const browserPath = ["/usr/bin/chromium", "/usr/bin/chromium-browser"].find(p => fs.existsSync(p));
  if (!browserPath) { console.log("chromium not installed"); process.exit(77); }
  const work = fs.mkdtempSync(path.join(os.tmpdir(), `asbuilt-${name}-`));
  process.on("exit", () => fs.rmSync(work, {recursive: true, force: true}));
  return {chromium, browserPath, work};
}

export function fail(message) { console.error("FAIL: " + message); process.exit(1); }

// Starts `asbuilt review OUT --no-open`; resolves with {child, url} (the first stdout line).
export function startReview(asbuilt, out) {
  const child = spawn(asbuilt, ["review", out, "--no-open", "-q"], {stdio: ["ignore", "pipe", "inherit"]});
  // A failed check exits at once: the server goes too (else ctest waits on its pipe).
  process.on("exit", () => child.kill());
  return new Promise((resolve, reject) => {
    let text = "";
    const timer = setTimeout(() => reject(new Error("no address within 60 s")), 60000);
    child.stdout.on("data", d => {
      text += d;
      if (!text.includes("\n")) return;
      const line = text.split("\n")[0];
      const m = line.match(/^asbuilt review: (http:\/\/127\.0\.0\.1:\d+\/\?token=[0-9a-f]{32})$/);
      clearTimeout(timer);
      if (!m) reject(new Error("first stdout line: " + line)); else resolve({child, url: m[1]});
    });
    child.on("exit", code => { clearTimeout(timer); reject(new Error("asbuilt review exited " + code)); });
  });
}
