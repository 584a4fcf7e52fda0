// The day's daylight as a plain 2-D canvas chart: global illuminance and melanopic EDI (lux) on
// a log axis at the left, CCT (K) on a log axis at the right, against the UTC time of day, with
// a marker at one time. The values are drawn as given (sky-wasm's DaylightDay); `plotGeometry`
// is the mapping from values to pixels, which the browser test uses to find the curves.

/** Margins, axis ranges and colours of the chart on a canvas of `width` × `height`. */
export function plotGeometry(width, height) {
  return {
    left: 64, right: width - 64, top: 16, bottom: height - 36,
    hours: [0, 24],
    lux: [1e-5, 1e6],
    kelvin: [1e3, 1e5],
    colours: { global: "#ffd25a", edi: "#5ac8ff", cct: "#ff7a59", marker: "#ffffff" },
  };
}

/** Pixel x of `seconds` after 0:00 UTC. */
export function xOf(g, seconds) {
  return g.left + ((seconds / 3600 - g.hours[0]) / (g.hours[1] - g.hours[0])) * (g.right - g.left);
}

/** Pixel y of `value` on the log axis `[lo, hi]` (clamped to the plot). */
export function yOfLog(g, [lo, hi], value) {
  const f = (Math.log10(value) - Math.log10(lo)) / (Math.log10(hi) - Math.log10(lo));
  return g.bottom - Math.min(1, Math.max(0, f)) * (g.bottom - g.top);
}

function curve(ctx, g, times, values, range, colour) {
  ctx.strokeStyle = colour;
  ctx.lineWidth = 2;
  ctx.beginPath();
  let drawing = false;
  times.forEach((t, k) => {
    const v = values[k];
    // NaN (CCT off the locus) and non-positive values leave a gap.
    if (!(v > 0)) {
      drawing = false;
      return;
    }
    const [x, y] = [xOf(g, t), yOfLog(g, range, v)];
    if (drawing) ctx.lineTo(x, y);
    else ctx.moveTo(x, y);
    drawing = true;
  });
  ctx.stroke();
}

/** Draws `day` ({ times, globalLux, melanopicEdiLux, cctK }: arrays of one day) and a marker
 * at `markerSeconds` on `ctx`'s canvas; returns the geometry used. */
export function drawDaylightPlot(ctx, day, markerSeconds) {
  const { width, height } = ctx.canvas;
  const g = plotGeometry(width, height);
  ctx.fillStyle = "#000";
  ctx.fillRect(0, 0, width, height);
  ctx.font = "12px system-ui, sans-serif";
  ctx.lineWidth = 1;
  // Grid and axes: every 3 hours, every decade of lux, and the CCT decades' labels.
  ctx.strokeStyle = "#2a3142";
  ctx.fillStyle = "#9aa6b8";
  ctx.textAlign = "center";
  for (let h = 0; h <= 24; h += 3) {
    const x = xOf(g, h * 3600);
    ctx.beginPath(); ctx.moveTo(x, g.top); ctx.lineTo(x, g.bottom); ctx.stroke();
    ctx.fillText(`${String(h).padStart(2, "0")}:00`, x, g.bottom + 16);
  }
  ctx.fillText("time (UTC)", (g.left + g.right) / 2, height - 4);
  ctx.textAlign = "right";
  for (let e = Math.log10(g.lux[0]); e <= Math.log10(g.lux[1]); e++) {
    const y = yOfLog(g, g.lux, 10 ** e);
    ctx.beginPath(); ctx.moveTo(g.left, y); ctx.lineTo(g.right, y); ctx.stroke();
    ctx.fillText(`1e${e} lx`, g.left - 6, y + 4);
  }
  ctx.textAlign = "left";
  for (let e = Math.log10(g.kelvin[0]); e <= Math.log10(g.kelvin[1]); e++) {
    ctx.fillText(`${10 ** e} K`, g.right + 6, yOfLog(g, g.kelvin, 10 ** e) + 4);
  }
  curve(ctx, g, day.times, day.globalLux, g.lux, g.colours.global);
  curve(ctx, g, day.times, day.melanopicEdiLux, g.lux, g.colours.edi);
  curve(ctx, g, day.times, day.cctK, g.kelvin, g.colours.cct);
  // Legend.
  [["global illuminance (lx)", g.colours.global], ["melanopic EDI (lx)", g.colours.edi],
    ["CCT (K)", g.colours.cct]].forEach(([label, colour], k) => {
    const x = g.left + 12 + k * 190;
    ctx.fillStyle = colour;
    ctx.fillRect(x, g.top + 6, 18, 3);
    ctx.fillStyle = "#dde3ee";
    ctx.fillText(label, x + 24, g.top + 12);
  });
  // The marker: the time the sky shows, one pixel column wide (at a pixel's centre).
  const x = Math.round(xOf(g, markerSeconds)) + 0.5;
  ctx.strokeStyle = g.colours.marker;
  ctx.setLineDash([4, 3]);
  ctx.beginPath(); ctx.moveTo(x, g.top); ctx.lineTo(x, g.bottom); ctx.stroke();
  ctx.setLineDash([]);
  return g;
}
