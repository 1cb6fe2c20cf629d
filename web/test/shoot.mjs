// Drives headless Chromium over the page served by `rockhatch serve`, for
// tests/python/test_web.py: loads it, waits until the rock tiles are drawn, takes
// screenshots with and without the rock layers at the asked zoom levels, and prints one JSON
// object of measures on stdout.
//
//   node web/test/shoot.mjs URL OUTDIR [zoom ...]
//
// Chromium: /usr/bin/chromium (Debian's), or $RH_CHROMIUM. WebGL runs on SwiftShader, the
// CPU renderer Chromium ships, so no GPU or display is needed.
import { chromium } from "playwright-core";

const [url, outDir, ...zoomArgs] = process.argv.slice(2);
if (!url || !outDir) {
  console.error("usage: node web/test/shoot.mjs URL OUTDIR [zoom ...]");
  process.exit(2);
}
const zooms = zoomArgs.map(Number);
const executablePath = process.env.RH_CHROMIUM || "/usr/bin/chromium";
const TIMEOUT = Number(process.env.RH_WEB_TIMEOUT_MS || 60000);

const browser = await chromium.launch({
  executablePath,
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--no-sandbox"],
});
const out = { console: [], requests: { tiles: 0, failed: [] } };
try {
  const page = await browser.newPage({ viewport: { width: 1024, height: 768 }, deviceScaleFactor: 1 });
  page.on("console", (m) => out.console.push(`${m.type()}: ${m.text()}`));
  page.on("pageerror", (e) => out.console.push(`pageerror: ${e.message}`));
  page.on("requestfinished", (r) => { if (r.url().includes("/tiles/")) out.requests.tiles++; });
  // A request MapLibre cancels itself (a tile no longer needed) is not a failure.
  page.on("requestfailed", (r) => {
    const why = (r.failure() || {}).errorText || "";
    if (!why.includes("ERR_ABORTED")) out.requests.failed.push(`${r.url()}: ${why}`);
  });

  const t0 = Date.now();
  await page.goto(url, { waitUntil: "load" });
  // Until the first frame with a rock feature in it, then the first idle map.
  await page.waitForFunction(() => window.rockhatch && window.rockhatch.firstRockDrawnMs !== null,
                             null, { timeout: TIMEOUT, polling: 50 });
  out.wallFirstRockMs = Date.now() - t0;
  await page.waitForFunction(() => window.rockhatch.firstIdleMs !== null, null, { timeout: TIMEOUT, polling: 50 });
  Object.assign(out, await page.evaluate(() => ({
    firstRockDrawnMs: window.rockhatch.firstRockDrawnMs,
    firstIdleMs: window.rockhatch.firstIdleMs,
    pageLoadMs: performance.getEntriesByType("navigation")[0].loadEventEnd,
    errors: window.rockhatch.errors,
    rockLayers: window.rockhatch.rockLayers,
    fittedZoom: window.rockhatch.map.getZoom(),
    renderer: (() => {
      const gl = window.rockhatch.map.painter.context.gl;
      const info = gl.getExtension("WEBGL_debug_renderer_info");
      return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    })(),
  })));

  // Resolves on the map's next 'idle' after fn ran in the page (fn may change the view).
  const settle = (fn, arg) => page.evaluate(([src, a]) => new Promise((resolve) => {
    const map = window.rockhatch.map;
    map.once("idle", () => resolve());
    (0, eval)(src)(map, a);
    map.triggerRepaint();
  }), [fn.toString(), arg]);
  const setRock = (visible) => settle((map, v) => {
    for (const id of window.rockhatch.rockLayers) map.setLayoutProperty(id, "visibility", v ? "visible" : "none");
  }, visible);
  const count = () => page.evaluate(() => {
    const map = window.rockhatch.map;
    const features = map.queryRenderedFeatures({ layers: window.rockhatch.rockLayers });
    // The stroke width MapLibre evaluated for one feature of each line layer, with its width_mm.
    const widths = {};
    for (const f of features) {
      if (f.layer.type === "line" && !(f.layer.id in widths)) {
        widths[f.layer.id] = [f.properties.width_mm, f.layer.paint["line-width"]];
      }
    }
    return { features: features.length, widths, zoom: map.getZoom(),
             scale: document.getElementById("scale").textContent };
  });

  const shot = async (name) => {
    await setRock(true);
    const withRock = await count();
    await page.screenshot({ path: `${outDir}/${name}.png` });
    await setRock(false);
    await page.screenshot({ path: `${outDir}/${name}-base.png` });
    await setRock(true);
    return withRock;
  };
  out.views = { fitted: await shot("fitted") };
  for (const z of zooms) {
    await settle((map, zoom) => map.jumpTo({ zoom }), z);
    out.views[`z${z}`] = await shot(`z${z}`);
  }
} catch (e) {
  out.failure = String(e && e.message || e).split("\n")[0];
  process.exitCode = 1;
} finally {
  await browser.close();
}
process.stdout.write(JSON.stringify(out) + "\n");
