// A 2D-canvas strip chart of the last few seconds of force: |force| of each
// tool as a solid line and its z component (fz) dashed, against the frames'
// simulation time (time_s).

import { TOOL_LINE_COLORS } from './colors.js';

const WINDOW_S = 5;
const MARGIN = { left: 44, right: 8, top: 8, bottom: 18 };
const AXIS_COLOR = '#8a929c';
const FONT = '11px system-ui, sans-serif';

export class StripChart {
  constructor(canvas) {
    this.canvas = canvas;
    this.samples = [];   // {t, forces: Map(tool -> {magnitude, fz})}, oldest first
    this.toolOrder = []; // tools in first-seen order: their colour index
    this.dirty = true;
  }

  /** Records a "frame" message. */
  add(frame) {
    const t = frame.time_s;
    if (!Number.isFinite(t)) return;
    const last = this.samples.at(-1);
    if (last && t < last.t) this.samples = []; // the scene restarted
    const forces = new Map();
    for (const tool of Array.isArray(frame.tools) ? frame.tools : []) {
      const f = Array.isArray(tool.force_n) && tool.force_n.every(Number.isFinite)
        ? tool.force_n : [0, 0, 0];
      forces.set(tool.name, { magnitude: Math.hypot(f[0], f[1], f[2]), fz: f[2] });
      if (!this.toolOrder.includes(tool.name)) this.toolOrder.push(tool.name);
    }
    this.samples.push({ t, forces });
    while (this.samples[0].t < t - WINDOW_S) this.samples.shift();
    this.dirty = true;
  }

  /** Redraws if something changed (new samples or a new canvas size). */
  draw() {
    if (!this.fitCanvas() && !this.dirty) return;
    this.dirty = false;
    const ctx = this.canvas.getContext('2d');
    const ratio = window.devicePixelRatio || 1;
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    const width = this.canvas.width / ratio;
    const height = this.canvas.height / ratio;
    ctx.clearRect(0, 0, width, height);
    ctx.font = FONT;

    const plot = {
      x0: MARGIN.left, x1: width - MARGIN.right,
      y0: MARGIN.top, y1: height - MARGIN.bottom,
    };
    const tEnd = this.samples.at(-1)?.t ?? 0;
    const { low, high } = this.valueRange();
    const x = (t) => plot.x1 - ((tEnd - t) / WINDOW_S) * (plot.x1 - plot.x0);
    const y = (v) => plot.y1 - ((v - low) / (high - low)) * (plot.y1 - plot.y0);

    drawAxes(ctx, plot, low, high, y);
    this.toolOrder.forEach((tool, i) => {
      const color = TOOL_LINE_COLORS[i % TOOL_LINE_COLORS.length];
      this.drawLine(ctx, tool, 'magnitude', color, [], x, y);
      this.drawLine(ctx, tool, 'fz', color, [4, 3], x, y);
    });
    this.drawKey(ctx, plot);
  }

  /** Matches the canvas's pixel size to its CSS size; true if it changed. */
  fitCanvas() {
    const ratio = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(this.canvas.clientWidth * ratio));
    const height = Math.max(1, Math.round(this.canvas.clientHeight * ratio));
    if (this.canvas.width === width && this.canvas.height === height) return false;
    this.canvas.width = width;
    this.canvas.height = height;
    return true;
  }

  /** The value axis: from 0 (or below, for a negative fz) to a round maximum, at least 1 N. */
  valueRange() {
    let max = 1;
    let min = 0;
    for (const sample of this.samples) {
      for (const f of sample.forces.values()) {
        max = Math.max(max, f.magnitude);
        min = Math.min(min, f.fz);
      }
    }
    const high = niceCeil(max);
    return { low: min < 0 ? -niceCeil(-min) : 0, high };
  }

  drawLine(ctx, tool, field, color, dash, x, y) {
    ctx.strokeStyle = color;
    ctx.lineWidth = 1.5;
    ctx.setLineDash(dash);
    ctx.beginPath();
    let drawing = false;
    for (const sample of this.samples) {
      const f = sample.forces.get(tool);
      if (!f) {
        drawing = false; // the tool was absent: leave a gap
        continue;
      }
      if (drawing) ctx.lineTo(x(sample.t), y(f[field]));
      else ctx.moveTo(x(sample.t), y(f[field]));
      drawing = true;
    }
    ctx.stroke();
    ctx.setLineDash([]);
  }

  /** Tool names in their colours, top left inside the plot. */
  drawKey(ctx, plot) {
    ctx.textAlign = 'left';
    ctx.textBaseline = 'top';
    this.toolOrder.forEach((tool, i) => {
      ctx.fillStyle = TOOL_LINE_COLORS[i % TOOL_LINE_COLORS.length];
      ctx.fillText(tool, plot.x0 + 6, plot.y0 + 2 + 13 * i);
    });
    ctx.fillStyle = AXIS_COLOR;
    ctx.textAlign = 'right';
    ctx.fillText('solid |F|, dashed fz', plot.x1 - 2, plot.y0 + 2);
  }
}

/** Frame, zero line, value labels (N) and time labels (s before the latest frame). */
function drawAxes(ctx, plot, low, high, y) {
  ctx.strokeStyle = AXIS_COLOR;
  ctx.lineWidth = 1;
  ctx.strokeRect(plot.x0, plot.y0, plot.x1 - plot.x0, plot.y1 - plot.y0);
  ctx.beginPath();
  ctx.moveTo(plot.x0, y(0));
  ctx.lineTo(plot.x1, y(0));
  ctx.stroke();

  ctx.fillStyle = AXIS_COLOR;
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  for (const v of new Set([high, 0, low])) {
    ctx.fillText(`${+v.toPrecision(3)} N`, plot.x0 - 4, y(v));
  }
  ctx.textBaseline = 'top';
  ctx.textAlign = 'left';
  ctx.fillText(`-${WINDOW_S} s`, plot.x0, plot.y1 + 3);
  ctx.textAlign = 'right';
  ctx.fillText('now', plot.x1, plot.y1 + 3);
}

/** The smallest 1, 2 or 5 x 10^k that is >= v (v > 0). */
function niceCeil(v) {
  const power = 10 ** Math.floor(Math.log10(v));
  for (const m of [1, 2, 5, 10]) {
    if (m * power >= v) return m * power;
  }
  return 10 * power;
}
