// rockhatch's web map: the rock drawing's vector tiles over a hillshade, both served by
// `rockhatch serve` (tiles.json lists them). Each zoom level of the rock tiles was drawn at
// its own map scale, the one where a pixel of a `tile_px`-pixel tile is `pixel_mm` on paper
// (rockhatch's writer: 256 and OGC's 0.28 mm). MapLibre shows a level-z tile 512 CSS pixels
// wide at map zoom z, so the drawing is on screen magnified 512 / tile_px times, and its
// lines with it: width_mm / pixel_mm * 512 / tile_px CSS pixels at an integer zoom, and
// 2^(zoom - floor(zoom)) times that between two levels and past the last one.
"use strict";

const MM_PER_CSS_PX = 0.2646;            // 96 CSS pixels to the inch: the scale on screen
const EARTH_CIRCUMFERENCE = 40075016.686;  // metres, web mercator
const DEFAULT_WIDTH_MM = 0.1;

// Read by the browser test (web/test/shoot.mjs): the map, its rock layers, timings in ms
// since the page's navigation started, and the errors met.
const rockhatch = (window.rockhatch = {
  map: null, rockLayers: [], baseLayers: [], drawnAt: null, firstRockDrawnMs: null, firstIdleMs: null, errors: [],
});

// line-width in CSS pixels: the saw-tooth above from the first level to the last, then
// growing with the map past the last level (over-zoom).
function lineWidth(minMapZoom, maxMapZoom, pixelMm, tilePx) {
  const base = ["*", ["/", ["coalesce", ["get", "width_mm"], DEFAULT_WIDTH_MM], pixelMm], 512 / tilePx];
  const stops = [];
  for (let z = minMapZoom; z < maxMapZoom; z++) {
    stops.push(z, base, z + 0.999, ["*", base, Math.pow(2, 0.999)]);
  }
  stops.push(maxMapZoom, base, maxMapZoom + 8, ["*", base, 256]);
  return ["interpolate", ["exponential", 2], ["zoom"], ...stops];
}

const LINES = ["match", ["geometry-type"], ["LineString", "MultiLineString"], true, false];
const POLYGONS = ["match", ["geometry-type"], ["Polygon", "MultiPolygon"], true, false];

function buildStyle(sets) {
  const style = {
    version: 8,
    sources: {},
    layers: [{ id: "background", type: "background", paint: { "background-color": "#ffffff" } }],
  };
  const base = sets.raster[0];
  if (base) {
    style.sources.base = {
      type: "raster", tiles: base.tiles, tileSize: base.tile_size, bounds: base.bounds,
      minzoom: base.minzoom, maxzoom: base.maxzoom, attribution: base.attribution || undefined,
    };
    style.layers.push({
      id: "hillshade", type: "raster", source: "base",
      paint: { "raster-opacity": 0.45, "raster-resampling": "linear" },
    });
    rockhatch.baseLayers.push("hillshade");
  }
  let minZoom = Infinity, maxZoom = -Infinity;
  sets.vector.forEach((ts, i) => {
    const id = `rock${i}`;
    // A vector tile spans 512 CSS pixels: a level-z tile is at its own size at map zoom z.
    const z0 = ts.minzoom, z1 = ts.maxzoom;
    minZoom = Math.min(minZoom, z0);
    maxZoom = Math.max(maxZoom, z1);
    style.sources[id] = {
      type: "vector", tiles: ts.tiles, bounds: ts.bounds,
      minzoom: ts.minzoom, maxzoom: ts.maxzoom, attribution: ts.attribution || "rock drawing: rockhatch",
    };
    const width = lineWidth(z0, z1, ts.pixel_mm || 0.28, ts.tile_px || 256);
    rockhatch.drawnAt = { pixelMm: ts.pixel_mm || 0.28, tilePx: ts.tile_px || 256, minzoom: z0, maxzoom: z1 };
    for (const layer of ts.vector_layers || []) {
      // Every layer is drawn as lines and as filled polygons, each for its own geometries:
      // the line families (fill, ridge, ...) stroke, the polygon ones (stone, hachure,
      // crest) fill black, whatever a writer names them.
      style.layers.push({
        id: `${id}-${layer.id}-fill`, type: "fill", source: id, "source-layer": layer.id,
        filter: POLYGONS, paint: { "fill-color": "#000000" },
      });
      style.layers.push({
        id: `${id}-${layer.id}-line`, type: "line", source: id, "source-layer": layer.id,
        filter: LINES, layout: { "line-cap": "round", "line-join": "round" },
        paint: { "line-color": "#000000", "line-width": width },
      });
      rockhatch.rockLayers.push(`${id}-${layer.id}-fill`, `${id}-${layer.id}-line`);
    }
  });
  return { style, minZoom, maxZoom };
}

function unionBounds(sets) {
  const b = [Infinity, Infinity, -Infinity, -Infinity];
  for (const ts of sets) {
    b[0] = Math.min(b[0], ts.bounds[0]); b[1] = Math.min(b[1], ts.bounds[1]);
    b[2] = Math.max(b[2], ts.bounds[2]); b[3] = Math.max(b[3], ts.bounds[3]);
  }
  return [[b[0], b[1]], [b[2], b[3]]];
}

function scaleNumber(denominator) {
  const rounded = Math.round(denominator / 100) * 100;
  return `1:${rounded.toLocaleString("en").replace(/,/g, "\u202f")}`;
}

// The map scale on screen at the centre (metres per CSS pixel over 0.2646 mm), and the scale
// the level shown was drawn at (metres per pixel of a tile_px tile over pixel_mm).
function scaleText(map) {
  const zoom = map.getZoom();
  const ground = EARTH_CIRCUMFERENCE * Math.cos(map.getCenter().lat * Math.PI / 180);
  let text = `zoom ${zoom.toFixed(1)} \u00b7 screen ${scaleNumber(ground / (512 * Math.pow(2, zoom)) / (MM_PER_CSS_PX / 1000))}`;
  const d = rockhatch.drawnAt;
  if (d) {
    const level = Math.min(Math.max(Math.floor(zoom), d.minzoom), d.maxzoom);
    text += ` \u00b7 drawn for ${scaleNumber(ground / (d.tilePx * Math.pow(2, level)) / (d.pixelMm / 1000))}`;
  }
  return text;
}

function showMessage(text) {
  const el = document.getElementById("message");
  el.textContent = text;
  el.hidden = false;
}

function toggle(checkbox, layers) {
  checkbox.addEventListener("change", () => {
    for (const id of layers) {
      rockhatch.map.setLayoutProperty(id, "visibility", checkbox.checked ? "visible" : "none");
    }
  });
}

async function main() {
  let sets;
  try {
    const response = await fetch("tiles.json");
    if (!response.ok) throw new Error(`tiles.json: HTTP ${response.status}`);
    sets = await response.json();
  } catch (e) {
    rockhatch.errors.push(String(e));
    showMessage(`cannot read the tilesets: ${e.message}`);
    return;
  }
  const { style, minZoom, maxZoom } = buildStyle(sets);
  const map = new maplibregl.Map({
    container: "map",
    bounds: unionBounds(sets.vector),
    fitBoundsOptions: { padding: 24 },
    maxZoom: maxZoom + 4,
    hash: true,
    attributionControl: { compact: false },
  });
  rockhatch.map = map;
  // Listened to before the style is set, so an error in it is kept too.
  map.on("error", (e) => { rockhatch.errors.push(String(e.error && e.error.message || e.error || e)); });
  let styleLoaded = false;
  map.once("style.load", () => { styleLoaded = true; });
  map.setStyle(style);
  map.addControl(new maplibregl.NavigationControl({ showCompass: false }), "top-right");

  const scale = document.getElementById("scale");
  const note = () => {
    const z = map.getZoom();
    scale.textContent = scaleText(map) + (z < minZoom ? " (zoom in: no rock tiles at this level)" : "");
  };
  map.on("move", note);
  map.on("load", note);

  // The first frame that shows a rock feature: queryRenderedFeatures answers from the tiles
  // drawn, so it is asked on each frame until it finds one.
  const onRender = () => {
    if (!styleLoaded || rockhatch.firstRockDrawnMs !== null) return;
    if (map.queryRenderedFeatures({ layers: rockhatch.rockLayers }).length > 0) {
      rockhatch.firstRockDrawnMs = performance.now();
      map.off("render", onRender);
    }
  };
  map.on("render", onRender);
  map.once("idle", () => { rockhatch.firstIdleMs = performance.now(); });

  toggle(document.getElementById("rock-toggle"), rockhatch.rockLayers);
  toggle(document.getElementById("base-toggle"), rockhatch.baseLayers);
  if (!rockhatch.baseLayers.length) document.getElementById("base-toggle").parentElement.hidden = true;
}

main();
