// Owns: the polar plots read without sight. Each plot canvas gets role="img" and a
// description (describe.js) once a change settles, a "table" toggle with its sampled values
// (CSV download) and a keyboard cursor that walks the curve and says its value. It reads the
// page's state (brdfLab.state) and attaches by DOM; lab.js knows nothing of it.
import { csvText, cursor, describe, summarise, table } from "./describe.js";

const SETTLE_MS = 400;
// Page settings by the registry's names (lab.settings); a page from before the registry kept
// them as fields of its state under these names.
const OLD_NAMES = { polar_cos: "cosWeighted", polar_log: "polarLog", phi_o: "phiO", lobe_yaw: "lobeYaw",
  lobe_pitch: "lobePitch", lobe_zoom: "lobeZoom" };
/** The name `setSettings` takes for setting `name` on this page. */
export const settingName = (lab, name) => (lab.settings && name in lab.settings ? name : OLD_NAMES[name] ?? name);
/** A page setting's value. */
export const setting = (lab, name) => (lab.settings && name in lab.settings ? lab.settings[name] : lab[settingName(lab, name)]);

/** The lobes a plot shows, as describe.js takes them. */
function lobesOf(lab, C, panels) {
  const names = panels.map((p) => p.name);
  return panels.filter((p) => p.lobe && p.model).map((p) => {
    const values = [];
    const thetaO = [];
    for (let i = 0; i < 181; i++) {
      let f = C.LUMA[0] * p.lobe[4 * i] + C.LUMA[1] * p.lobe[4 * i + 1] + C.LUMA[2] * p.lobe[4 * i + 2];
      if (setting(lab, "polar_cos")) f *= Math.cos(((i - 90) * Math.PI) / 180);
      values.push(Number.isFinite(f) ? Math.max(f, 0) : 0);
      thetaO.push(i - 90);
    }
    const k = lab.panels.indexOf(p);
    const name = names.filter((n) => n === p.name).length > 1 ? `${p.name} (model ${k + 1})` : p.name;
    const spike = p.spike ? C.LUMA[0] * p.spike[0] + C.LUMA[1] * p.spike[1] + C.LUMA[2] * p.spike[2] : null;
    return { name, thetaO, values, spike };
  });
}

const what = (lab) => (setting(lab, "polar_cos") ? "f_r cos θo" : "f_r");

/** Reading aids under one plot canvas: table toggle, CSV, cursor readout. */
class PlotReader {
  constructor(canvas, panels, lab, C, el) {
    Object.assign(this, { canvas, panels, lab, C, el });
    this.theta = null; // the cursor's θo (null: not placed yet)
    canvas.setAttribute("role", "img");
    canvas.tabIndex = 0;
    const id = `plot-${PlotReader.count = (PlotReader.count || 0) + 1}`;
    this.readout = el("p", { class: "plot-cursor", id: `${id}-cursor`, "aria-live": "polite" });
    this.tableBox = el("div", { class: "plot-table", id: `${id}-table`, hidden: "" });
    this.toggle = el("button", { type: "button", class: "plot-table-toggle", "aria-expanded": "false",
      "aria-controls": this.tableBox.id }, "table");
    this.toggle.addEventListener("click", () => this.showTable(this.tableBox.hidden));
    this.csv = el("button", { type: "button", class: "plot-csv" }, "CSV");
    this.csv.addEventListener("click", () => this.download());
    this.listen = el("button", { type: "button", class: "plot-listen",
      title: "hear the lobe: a 3 s sweep from θo −90° to 90°, pitch follows f_r, left–right follows θo as drawn, ticks at L, N and R" }, "listen");
    this.listen.addEventListener("click", () => sonify(this.lobes(), this.lab.lights[0].theta));
    this.tools = el("div", { class: "plot-read" }, this.toggle, this.csv, this.listen, this.readout);
    canvas.closest(".view").append(this.tools, this.tableBox); // under the plot, in its box
    canvas.setAttribute("aria-describedby", this.readout.id);
    canvas.addEventListener("keydown", (e) => this.key(e));
    this.marker = el("canvas", { class: "plot-marker", "aria-hidden": "true" });
    canvas.after(this.marker);
  }

  lobes() {
    return lobesOf(this.lab, this.C, this.panels());
  }

  /** The description as the canvas's name; the table again if it is open. */
  refresh() {
    const lobes = this.lobes();
    const lab = this.lab;
    if (!lobes.length) return;
    const phiO = setting(lab, "phi_o");
    const plane = phiO ? `In the plane turned φo ${phiO}° from the plane of incidence: ` : "";
    const text = describe(lobes, lab.lights[0].theta, what(lab), this.C.GRAZING_DEG);
    this.canvas.setAttribute("aria-label", `Polar plot. ${plane}${text}`);
    this.canvas.dataset.description = text;
    this.csv.setAttribute("aria-label", `download the values of this plot (${lobes.map((l) => l.name).join(", ")}) as CSV`);
    if (!this.tableBox.hidden) this.showTable(true);
    this.drawMarker();
  }

  rows() {
    return table(this.lobes(), this.lab.lights[0].theta, this.C.GRAZING_DEG);
  }

  showTable(open) {
    this.tableBox.hidden = !open;
    this.toggle.setAttribute("aria-expanded", String(open));
    if (!open) return;
    const { el } = this;
    const [header, ...rows] = this.rows();
    this.tableBox.replaceChildren(el("table", {},
      el("caption", {}, `${what(this.lab)} (sr⁻¹, luminance) every 5° of θo; θi ${this.lab.lights[0].theta}°`),
      el("thead", {}, el("tr", {}, ...header.map((h) => el("th", { scope: "col" }, h)))),
      el("tbody", {}, ...rows.map((r) => el("tr", r[r.length - 1] ? { class: "marked" } : {},
        el("th", { scope: "row" }, `${r[0]}°`.replace("-", "−")), ...r.slice(1).map((c) => el("td", {}, c)))))));
  }

  download() {
    const blob = new Blob([csvText(this.rows())], { type: "text/csv" });
    const a = this.el("a", { href: URL.createObjectURL(blob), download: `${this.lobes().map((l) => l.name).join("_")}_polar.csv` });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  /** Arrows walk θo as drawn (negative angles, toward the light, on the right). */
  key(e) {
    const lobes = this.lobes();
    if (!lobes.length) return;
    const steps = { ArrowLeft: 1, ArrowRight: -1, ArrowUp: 1, ArrowDown: -1, PageUp: 10, PageDown: -10 };
    const thetaI = this.lab.lights[0].theta;
    let theta = this.theta ?? Math.round(thetaI);
    if (e.key in steps) theta += steps[e.key];
    else if (e.key === "Home") theta = -90;
    else if (e.key === "End") theta = 90;
    else if (e.key === "m") theta = Math.round(thetaI);
    else return;
    e.preventDefault();
    e.stopPropagation(); // in a slide the arrows move the cursor, not the deck
    this.theta = Math.min(Math.max(theta, -90), 90);
    this.say(lobes);
  }

  say(lobes) {
    const parts = lobes.map((l) => (lobes.length > 1 ? `${l.name}: ` : "") +
      cursor(l, this.theta, what(this.lab), this.C.GRAZING_DEG).replace(/^θo [^,]*, /, ""));
    const at = `${this.theta}°`.replace("-", "−");
    this.readout.textContent = lobes.length > 1 ? `θo ${at}; ${parts.join("; ")}` : `θo ${at}, ${parts[0]}`;
    this.drawMarker();
  }

  /** Over lab.js's plot: with several models a marker shape per model along its curve and
   * its name at its peak (colour is not the only cue); the cursor's ray. */
  drawMarker() {
    const c = this.canvas;
    const m = this.marker;
    m.width = c.width;
    m.height = c.height;
    Object.assign(m.style, { left: `${c.offsetLeft}px`, top: `${c.offsetTop}px`, width: `${c.offsetWidth}px`,
      height: `${c.offsetHeight}px` });
    const ctx = m.getContext("2d");
    ctx.clearRect(0, 0, m.width, m.height);
    const overlay = !c.classList.contains("polar");
    const geometry = overlay ? this.lab.overlayGeometry : this.panels()[0]?.polarGeometry;
    if (!geometry?.centre || this.lab.plot === "theta" || !geometry.scale) return;
    const [cx, cy] = geometry.centre;
    const at = (theta, r) => {
      const a = (theta * Math.PI) / 180;
      return [cx - r * Math.sin(a), cy - r * Math.cos(a)];
    };
    const radiusOf = (f) => {
      const floor = geometry.scale * Math.pow(10, -this.C.PLOT_DECADES);
      const r = setting(this.lab, "polar_log") ? Math.log10(Math.max(f, floor) / floor) / this.C.PLOT_DECADES : f / geometry.scale;
      return geometry.radius * Math.min(Math.max(r, 0), 1);
    };
    const panels = this.panels().filter((p) => p.lobe && p.model);
    const lobes = this.lobes();
    if (overlay && lobes.length > 1) {
      const font = Math.max(11, Math.round(c.width / 30));
      ctx.font = `${font}px system-ui, sans-serif`;
      ctx.lineWidth = 1.5;
      const taken = []; // label boxes placed so far
      lobes.forEach((lobe, k) => {
        const color = panels[k]?.color || "#ffffff";
        for (let t = -80; t <= 80; t += 20) {
          const r = radiusOf(lobe.values[t + k * 3 + 90]);
          if (r > 0.2 * geometry.radius) shape(ctx, k, ...at(t + k * 3, r), color); // not in the crowd at the centre
        }
        const s = summarise(lobe, this.C.GRAZING_DEG);
        const peak = (s.halfWidth === null ? -45 : s.peakTheta) + 90; // a constant: its name at −45°
        const [x, y] = at(peak - 90, radiusOf(lobe.values[peak]));
        shape(ctx, k, x, y, color, 7);
        // The name in the text colour on a dark box, clear of the other names and the titles,
        // joined to its peak by a line of the curve's colour.
        const w = ctx.measureText(lobe.name).width + 6;
        const h = font + 4;
        const box = placeLabel(taken, x, y, w, h, m.width, 2.7 * font, cy);
        taken.push(box);
        ctx.strokeStyle = color;
        ctx.setLineDash([]);
        ctx.beginPath();
        ctx.moveTo(x, y);
        ctx.lineTo(box[0] + (box[0] > x ? 0 : w), box[1] + h / 2);
        ctx.stroke();
        ctx.fillStyle = "#15171cdd";
        ctx.fillRect(box[0], box[1], w, h);
        ctx.strokeRect(box[0], box[1], w, h);
        ctx.fillStyle = "#e6e6e6";
        ctx.fillText(lobe.name, box[0] + 3, box[1] + font);
      });
    }
    if (this.theta === null) return;
    ctx.strokeStyle = "#ffffff";
    ctx.lineWidth = 2;
    ctx.setLineDash([6, 3]);
    ctx.beginPath();
    ctx.moveTo(cx, cy);
    ctx.lineTo(...at(this.theta, geometry.radius));
    ctx.stroke();
    ctx.setLineDash([]);
  }
}

const SWEEP_S = 3;
let audio = null;

/** The lobes as sound (Web Audio): one sweep of θo from −90° to 90° in SWEEP_S seconds, one
 * voice per lobe, pitch from 220 Hz (0) to 880 Hz (the highest peak), panned as drawn (the
 * light's side on the right); short ticks at the light (L), the normal (N) and the mirror (R).
 * `context`: an (Offline)AudioContext to play into instead of the speakers. */
export function sonify(lobes, thetaI, context = null) {
  if (!context && !window.AudioContext) return;
  audio = context || audio || new AudioContext();
  const t0 = audio.currentTime + 0.05;
  const top = Math.max(1e-12, ...lobes.map((l) => Math.max(...l.values)));
  const pan = audio.createStereoPanner();
  pan.connect(audio.destination);
  pan.pan.setValueAtTime(1, t0);
  pan.pan.linearRampToValueAtTime(-1, t0 + SWEEP_S); // θo −90° (right, as drawn) to 90° (left)
  lobes.forEach((lobe, k) => {
    const osc = audio.createOscillator();
    const gain = audio.createGain();
    osc.type = ["sine", "triangle", "square", "sawtooth"][k % 4];
    const freqs = new Float32Array(lobe.values.map((v) => 220 * Math.pow(4, Math.min(v / top, 1))));
    osc.frequency.setValueCurveAtTime(freqs, t0, SWEEP_S);
    gain.gain.value = 0.15 / lobes.length;
    osc.connect(gain).connect(pan);
    osc.start(t0);
    osc.stop(t0 + SWEEP_S);
  });
  for (const theta of [-thetaI, 0, thetaI]) {
    const tick = audio.createOscillator();
    const gain = audio.createGain();
    const at = t0 + ((theta + 90) / 180) * SWEEP_S;
    tick.frequency.value = 1760;
    gain.gain.setValueAtTime(0.2, at);
    gain.gain.exponentialRampToValueAtTime(0.001, at + 0.05);
    tick.connect(gain).connect(pan);
    tick.start(at);
    tick.stop(at + 0.06);
  }
}

/** A free spot [left, top] for a w × h label near (x, y): right of it, else left, stepping
 * away up and down; inside the canvas, below `top` and above `bottom`. */
function placeLabel(taken, x, y, w, h, width, top, bottom) {
  const free = (l, t) => l >= 2 && l + w <= width - 2 && t >= top && t + h <= bottom &&
    taken.every(([a, b]) => l + w <= a || a + w <= l || t + h <= b || b + h <= t);
  for (let step = 0; step < 40; step++) {
    const dy = (step % 2 ? -1 : 1) * Math.ceil(step / 2) * (h + 2);
    for (const l of [x + 10, x - 10 - w]) {
      const t = y - h / 2 + dy;
      if (free(l, t)) return [l, t];
    }
  }
  return [Math.min(Math.max(x + 10, 2), width - w - 2), Math.max(top, Math.min(y, bottom - h))];
}

/** Marker k (circle, square, triangle, diamond, cross, star) at (x, y), outlined dark. */
function shape(ctx, k, x, y, color, size = 4.5) {
  ctx.beginPath();
  const s = size;
  switch (k % 6) {
    case 0: ctx.arc(x, y, s, 0, 2 * Math.PI); break;
    case 1: ctx.rect(x - s, y - s, 2 * s, 2 * s); break;
    case 2: ctx.moveTo(x, y - s * 1.2); ctx.lineTo(x + s, y + s); ctx.lineTo(x - s, y + s); ctx.closePath(); break;
    case 3: ctx.moveTo(x, y - s * 1.3); ctx.lineTo(x + s, y); ctx.lineTo(x, y + s * 1.3); ctx.lineTo(x - s, y); ctx.closePath(); break;
    case 4: ctx.rect(x - s, y - s / 3, 2 * s, (2 * s) / 3); ctx.rect(x - s / 3, y - s, (2 * s) / 3, 2 * s); break;
    default: for (let i = 0; i < 10; i++) {
      const r = i % 2 ? s / 2 : s * 1.2;
      const a = (i * Math.PI) / 5;
      ctx[i ? "lineTo" : "moveTo"](x + r * Math.sin(a), y - r * Math.cos(a));
    }
    ctx.closePath();
  }
  ctx.fillStyle = color;
  ctx.strokeStyle = "#15171c";
  ctx.fill();
  ctx.stroke();
}

/** Attaches readers to every polar plot (again as panels come and go); refreshes them once
 * a change settles. Returns { refresh } for tests. */
export function readPlots(lab, C, el) {
  const readers = new Map(); // canvas -> PlotReader
  const attach = () => {
    for (const panel of lab.panels) {
      if (panel.polar && !readers.has(panel.polar) && panel.polar.closest(".view")) {
        readers.set(panel.polar, new PlotReader(panel.polar, () => [panel], lab, C, el));
      }
    }
    const overlay = document.querySelector("#overlay canvas");
    if (overlay && !readers.has(overlay)) readers.set(overlay, new PlotReader(overlay, () => lab.panels, lab, C, el));
    for (const canvas of readers.keys()) if (!canvas.isConnected && canvas !== overlay) readers.delete(canvas);
  };
  const refresh = () => {
    attach();
    for (const reader of readers.values()) reader.refresh();
  };
  let timer = 0;
  const soon = () => {
    clearTimeout(timer);
    timer = setTimeout(refresh, SETTLE_MS);
  };
  for (const type of ["input", "change", "pointerup", "keyup", "hashchange", "click"]) addEventListener(type, soon, true);
  refresh();
  return { refresh, readers };
}
