// The demo: every control redraws on `input`, so the image follows a slider while it is dragged.
// Each view is one call into WebAssembly that fills a canvas's ImageData.
import init, { Sky, Renderer, SunPosition, DaylightDay, aoasPresets } from "./pkg/sky_wasm.js";
import { drawDaylightPlot } from "./daylight-plot.js";

await init();

const $ = (id) => document.getElementById(id);
const DEG = Math.PI / 180;

/** A canvas with a renderer of its size and an ImageData to fill. */
function view(id, make) {
  const canvas = $(id);
  const { width, height } = canvas;
  return {
    canvas,
    ctx: canvas.getContext("2d"),
    renderer: make(width, height),
    image: new ImageData(width, height),
    other: new ImageData(width, height),
  };
}

const dome = view("dome", Renderer.fisheye);
const panorama = view("panorama", Renderer.panorama);
const sphere = view("sphere", (size) => Renderer.sphere(size));
/** Bands of the SH sky: 5 is where its irradiance is within 1 % (sky-core's docs). */
const SH_BANDS = 5;
/** The turbidities the SH tables were fitted for. */
const SH_TURBIDITY = [2.5, 6];

for (const name of aoasPresets()) $("preset").add(new Option(name, name));

const TURBIDITY_RANGE = { "neural-hosek": [1, 10], aoas: null, sh: SH_TURBIDITY, daylight: null };

/** The largest sun zenith angle (degrees) the sliders reach: the horizon, and for the daylight
 * sky the end of astronomical twilight (the sun 18° down), the last sun its networks know. */
const MAX_SUN_ZENITH_DEG = { daylight: 108 };
const maxSunZenithDeg = (model) => MAX_SUN_ZENITH_DEG[model] ?? 90;

/** The sun from the date, time and place controls, by sky-core's SPA. */
function sunFromTime() {
  const [year, month, day] = $("date").value.split("-").map(Number);
  const t = Number($("time").value);
  const [lat, lon] = [Number($("latitude").value), Number($("longitude").value)];
  if (!year) throw new Error("date: enter a date (years 1 to 2999)");
  const at = SunPosition.at(year, month, day, Math.floor(t / 3600), Math.floor(t / 60) % 60, t % 60,
    lat, lon, placeElevation);
  try {
    return { zenith: at.zenith, azimuth: at.azimuth, elevationDeg: at.elevationDeg,
      compassDeg: at.compassAzimuthDeg };
  } finally {
    at.free();
  }
}

/** Metres above sea level of the chosen place (0 for a place typed in). */
let placeElevation = 190;

/** Seconds between the daylight plot's samples. */
const DAYLIGHT_STEP_S = 120;
/** The plotted day: its inputs, as a key, and its series (sky-wasm's DaylightDay, one call). */
let daylight = { key: "", day: null };

/** The daylight of the date and place controls' day, recomputed when they or the aerosol
 * optical depth change. */
function daylightDay() {
  const [year, month, day] = $("date").value.split("-").map(Number);
  const [lat, lon] = [Number($("latitude").value), Number($("longitude").value)];
  const aod = Number($("aod").value);
  const key = [year, month, day, lat, lon, placeElevation, aod].join(",");
  if (key !== daylight.key) {
    daylight = { key, day: null };
    if (!year) throw new Error("date: enter a date (years 2000 to 2110 for the daylight plot)");
    const series = DaylightDay.at(year, month, day, 0, 86399, DAYLIGHT_STEP_S, lat, lon,
      placeElevation, aod);
    try {
      daylight.day = {
        times: series.times, elevationDeg: series.elevationDeg, globalLux: series.globalLux,
        diffuseLux: series.diffuseLux, directLux: series.directLux, x: series.x, y: series.y,
        cctK: series.cctK, melanopicEdiLux: series.melanopicEdiLux,
      };
    } finally {
      series.free();
    }
  }
  return daylight.day;
}

/** The plot of the day's daylight with the marker at the time control's value, and the values
 * there (the sample at or before it). */
function drawDaylight() {
  const canvas = $("daylight-plot");
  const ctx = canvas.getContext("2d");
  try {
    const day = daylightDay();
    const t = Number($("time").value);
    const geometry = drawDaylightPlot(ctx, day, t);
    const k = Math.min(day.times.length - 1, Math.floor(t / DAYLIGHT_STEP_S));
    const cct = Number.isNaN(day.cctK[k]) ? "no CCT (|Duv| > 0.05)" : `${Math.round(day.cctK[k])} K`;
    $("daylight-error").textContent = "";
    window.skyDemo.daylight = { key: daylight.key, day, geometry, marker: t };
    $("daylight-readout").textContent = `${new Date(day.times[k] * 1000).toISOString().slice(11, 16)} UTC: sun ${day.elevationDeg[k].toFixed(1)}°, ` +
      `${day.globalLux[k].toPrecision(3)} lx, ${cct}, melanopic EDI ${day.melanopicEdiLux[k].toPrecision(3)} lx`;
  } catch (e) {
    ctx.fillStyle = "#000";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    window.skyDemo.daylight = null;
    $("daylight-readout").textContent = "";
    $("daylight-error").textContent = e.message;
  }
}

/** The zenith slider's range follows the model, as soon as it is chosen (a lower maximum moves
 * the thumb up to it). */
function syncZenithRange() {
  $("sun-zenith").max = String(maxSunZenithDeg($("model").value));
}

function readControls() {
  const p = {
    model: $("model").value,
    view: $("view").value,
    sunFrom: $("sun-from").value,
    sunZenith: Number($("sun-zenith").value) * DEG,
    sunAzimuth: Number($("sun-azimuth").value) * DEG,
    turbidity: Number($("turbidity").value),
    aod: Number($("aod").value),
    preset: $("preset").value,
    ev: Number($("exposure").value),
  };
  if (p.sunFrom === "time") {
    p.sun = sunFromTime();
    [p.sunZenith, p.sunAzimuth] = [p.sun.zenith, p.sun.azimuth];
  }
  return p;
}

/** The date, time and place controls, and the sun they put in the sky. */
function syncSunControls(p) {
  const byTime = p.sunFrom === "time";
  $("when-where").disabled = !byTime;
  $("sun-zenith").disabled = byTime;
  $("sun-azimuth").disabled = byTime;
  const t = Number($("time").value);
  const two = (n) => String(n).padStart(2, "0");
  $("time-value").value = `${two(Math.floor(t / 3600))}:${two(Math.floor(t / 60) % 60)}:${two(t % 60)}`;
  const readout = $("sun-readout");
  if (!byTime) {
    readout.textContent = "";
    delete readout.dataset.elevationDeg;
    delete readout.dataset.compassDeg;
    return;
  }
  const { elevationDeg, compassDeg } = p.sun;
  readout.dataset.elevationDeg = elevationDeg.toFixed(6);
  readout.dataset.compassDeg = compassDeg.toFixed(6);
  readout.textContent = `sun ${elevationDeg.toFixed(2)}° high, compass azimuth ` +
    `${compassDeg.toFixed(2)}° (geometric, NREL SPA)`;
  const lowestDeg = 90 - maxSunZenithDeg(p.model);
  if (elevationDeg < lowestDeg) {
    const why = lowestDeg < 0
      ? `the daylight sky ends at ${-lowestDeg}° below, with astronomical twilight`
      : "the sky models need it above (the daylight sky goes to −18°)";
    throw new Error(`the sun is ${(-elevationDeg).toFixed(2)}° below the horizon at this time ` +
      `and place: ${why} (try a later time)`);
  }
  // The angle sliders follow, so that switching back keeps this sun.
  $("sun-zenith").value = (p.sunZenith / DEG).toFixed(1);
  $("sun-azimuth").value = (((p.sunAzimuth / DEG) % 360 + 360) % 360).toFixed(0);
}

function makeSky(model, p) {
  switch (model) {
    case "preetham": return Sky.preetham(p.sunZenith, p.sunAzimuth, p.turbidity);
    case "neural-preetham": return Sky.neural("preetham", p.sunZenith, p.sunAzimuth, p.turbidity);
    case "neural-hosek": return Sky.neural("hosek", p.sunZenith, p.sunAzimuth, p.turbidity);
    case "aoas": return Sky.aoasWithSun(p.preset, p.sunZenith, p.sunAzimuth);
    case "sh": return Sky.sh(p.sunZenith, p.sunAzimuth, p.turbidity, SH_BANDS);
    case "daylight": return Sky.daylight(p.sunZenith, p.sunAzimuth, p.aod);
    default: throw new Error(`unknown model ${model}`);
  }
}

/** The skies a frame shows: one, or the neural sky and its reference for the split and
 * difference views. The exposure is the shown (or reference) sky's automatic one. */
function makeFrame(p) {
  if (p.view === "single") {
    const sky = makeSky(p.model, p);
    return { skies: [sky], exposure: sky.autoExposure() * 2 ** p.ev };
  }
  const neural = makeSky("neural-preetham", p);
  const reference = makeSky("preetham", p);
  return { skies: [neural, reference], exposure: reference.autoExposure() * 2 ** p.ev };
}

function drawView(v, frame, mode) {
  const [a, b] = frame.skies;
  if (mode === "difference") {
    v.renderer.renderDifferenceSrgb(a, b, v.image.data, frame.exposure * 8);
    v.ctx.putImageData(v.image, 0, 0);
  } else if (mode === "split") {
    v.renderer.renderSrgb(a, v.image.data, frame.exposure);
    v.renderer.renderSrgb(b, v.other.data, frame.exposure);
    const half = v.image.width >> 1;
    v.ctx.putImageData(v.image, 0, 0, 0, 0, half, v.image.height);
    v.ctx.putImageData(v.other, 0, 0, half, 0, v.image.width - half, v.image.height);
  } else {
    v.renderer.renderSrgb(a, v.image.data, frame.exposure);
    v.ctx.putImageData(v.image, 0, 0);
  }
}

/** One frame as a person sees it while dragging: build the sky, expose it, draw the dome.
 * Returns the milliseconds this took. */
function drawDome(p) {
  const t0 = performance.now();
  const frame = makeFrame(p);
  try {
    drawView(dome, frame, p.view);
  } catch (e) {
    frame.skies.forEach((s) => s.free());
    throw e;
  }
  const ms = performance.now() - t0;
  return { ms, frame };
}

function syncControls(p) {
  const range = p.model in TURBIDITY_RANGE ? TURBIDITY_RANGE[p.model] : [2, 6];
  const t = $("turbidity");
  t.disabled = range === null;
  if (range) [t.min, t.max] = range;
  $("preset").disabled = p.model !== "aoas";
  $("sun-zenith-value").value = $("sun-zenith").value;
  $("sun-azimuth-value").value = $("sun-azimuth").value;
  $("turbidity-value").value = range === null ? "n/a" : t.value;
  $("exposure-value").value = $("exposure").value;
}

/** The sphere, lit by the SH sky of the same sun (the tables' turbidity range, 2.5-6); none
 * for a sun below the horizon (the daylight sky's twilight), where the SH tables end. */
function drawSphere(p) {
  if (p.sunZenith > Math.PI / 2) {
    sphere.ctx.clearRect(0, 0, sphere.canvas.width, sphere.canvas.height);
    $("sphere-caption").textContent = "no sphere: the SH lighting needs the sun above the horizon";
    return;
  }
  const [lo, hi] = SH_TURBIDITY;
  const turbidity = Math.min(hi, Math.max(lo, p.turbidity));
  const sh = Sky.sh(p.sunZenith, p.sunAzimuth, turbidity, SH_BANDS);
  try {
    sphere.renderer.renderSrgb(sh, sphere.image.data, sh.autoExposure() * 2 ** p.ev);
    sphere.ctx.putImageData(sphere.image, 0, 0);
  } finally {
    sh.free();
  }
  $("sphere-caption").textContent =
    `a white sphere lit by the Preetham sky's spherical harmonics (${SH_BANDS} bands, turbidity ${turbidity}), seen from the south`;
}

function draw() {
  $("aod-value").value = Number($("aod").value).toFixed(2);
  drawDaylight();
  try {
    const p = readControls();
    syncSunControls(p);
    syncControls(p);
    const { ms, frame } = drawDome(p);
    drawView(panorama, frame, p.view);
    frame.skies.forEach((s) => s.free());
    drawSphere(p);
    $("frame-ms").textContent = ms.toFixed(2);
    $("error").textContent = "";
  } catch (e) {
    $("error").textContent = e.message;
  }
}

let pending = false;
function requestDraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => {
    pending = false;
    draw();
  });
}

/** The readout the browser test records: the median over 60 dome frames, the sun's azimuth
 * stepping by 1° per frame as if a person were dragging its slider. */
async function measure() {
  const p = readControls();
  const times = [];
  for (let i = 0; i < 60; i++) {
    const { ms, frame } = drawDome({ ...p, sunAzimuth: p.sunAzimuth + i * DEG });
    frame.skies.forEach((s) => s.free());
    times.push(ms);
    await new Promise((resolve) => requestAnimationFrame(resolve));
  }
  times.sort((x, y) => x - y);
  const median = (times[29] + times[30]) / 2;
  const out = $("measured");
  out.dataset.model = p.view === "single" ? p.model : p.view;
  out.dataset.medianMs = median.toFixed(3);
  out.textContent = `${out.dataset.model}: median ${median.toFixed(2)} ms/frame ` +
    `(min ${times[0].toFixed(2)}, max ${times[59].toFixed(2)}; 60 frames, 512×512 dome)`;
  draw();
}

$("preset").addEventListener("input", () => {
  // A preset brings its own sun (sunrise, sunset): move the sliders there.
  try {
    const sky = Sky.aoas($("preset").value);
    $("sun-zenith").value = (sky.sunZenith / DEG).toFixed(1);
    $("sun-azimuth").value = (((sky.sunAzimuth / DEG) % 360 + 360) % 360).toFixed(0);
    sky.free();
  } catch (e) {
    $("error").textContent = e.message;
  }
  requestDraw();
});
$("place").addEventListener("input", () => {
  if ($("place").value === "") return; // "other": the fields as they are
  const [lat, lon, elevation] = $("place").value.split(",").map(Number);
  [$("latitude").value, $("longitude").value, placeElevation] = [lat, lon, elevation];
  requestDraw();
});
for (const id of ["latitude", "longitude"]) {
  $(id).addEventListener("input", () => {
    $("place").value = "";
    placeElevation = 0;
  });
}
for (const id of ["model", "view", "sun-zenith", "sun-azimuth", "turbidity", "exposure",
  "sun-from", "latitude", "longitude", "date", "time", "aod"]) {
  $(id).addEventListener("input", requestDraw);
}
$("model").addEventListener("input", syncZenithRange);
$("measure").addEventListener("click", measure);
/** What the browser tests read: the plotted day and its geometry. */
window.skyDemo = { daylight: null };
document.body.dataset.ready = "true";
syncZenithRange();
draw();
