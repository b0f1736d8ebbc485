// The page's API for tests, slides and benchmarks (window.brdfLab): read what the page
// drew as floats, set models, settings and lights, and time frames.
import { addLight, buildLights, setLight, showAmbient } from "./lights.js";
import { addPanel, fitEmbed } from "./panels.js";
import { addModelText } from "./files.js";
import { currentEditor, currentExercises, openEditor, openExercise } from "./editing.js";
import { presetHash } from "./hash.js";
import { applyPreset, reset } from "./address.js";
import { showToolbar } from "./toolbar.js";
import { renderAll, renderNow, settleNow, stopSettling, writeHash } from "./scheduler.js";

const toBase64 = (floats) => {
  const bytes = new Uint8Array(floats.buffer);
  let text = "";
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
};

/** window.brdfLab: the page's API for tests, slides and benchmarks (`ready` resolves once
 * the page has drawn). */
export function installTestApi(lab, ready) {
  window.brdfLab = {
    ready,
    state: lab,
    panel: (i = 0) => lab.panels[i],
    renderNow,
    setLight: (theta, phi, index = 0) => {
      setLight(lab, theta, phi, index);
      return renderNow();
    },
    /** Replaces the lights: [{theta, phi, rgb}], and the ambient radiance [r, g, b]. */
    setLights(lights, ambient = [0, 0, 0]) {
      lab.lights = lights.map((l) => ({ theta: l.theta, phi: l.phi, rgb: l.rgb || [1, 1, 1] }));
      lab.ambient = ambient;
      showAmbient(lab);
      lab.active = 0;
      buildLights(lab);
      fitEmbed(lab);
      return renderNow();
    },
    addLight: () => {
      addLight(lab);
      return renderNow();
    },
    /** Where the page's controls are (for layout tests): every range input's box. */
    sliderBoxes: () => [...document.querySelectorAll("input[type=range]")].map((s) => {
      const r = s.getBoundingClientRect();
      return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
    }),
    setModel(i, name, values = {}) {
      lab.panels[i].setModel(name, values);
      return renderNow();
    },
    values: (i = 0) => ({ ...lab.panels[i].values }),
    errors: (i = 0) => lab.panels[i].error,
    /** The loop guard's warning on panel i ('' when no loop was stopped). */
    loopWarning: (i = 0) => (lab.panels[i].loopBox.hidden ? "" : lab.panels[i].loopBox.textContent),
    notes: () => lab.notes.slice(),
    applyPreset: (i) => applyPreset(lab, i),
    /** Opens the editor on panel i; returns its API (text, setText, errors, check). */
    async edit(i = 0) {
      await openEditor(lab.panels[i]);
      return true;
    },
    get editor() {
      return currentEditor();
    },
    /** Opens an exercise (folder name) in practice mode; resolves when its checks ran. */
    openExercise: (name) => openExercise(lab, name),
    get exercises() {
      return currentExercises();
    },
    presetHash: (preset) => {
      const skipped = [];
      return { hash: presetHash(lab, preset, skipped), skipped };
    },
    reset: () => reset(lab),
    moveSlider(i, name, position) {
      const value = lab.panels[i].moveSlider(name, position);
      renderNow();
      writeHash();
      return value;
    },
    /** The float sphere of panel i, base64 float32 RGBA, row 0 at the top. */
    readSphere(i = 0) {
      settleNow();
      const { width, height, data } = lab.panels[i].readSphere();
      return { width, height, data: toBase64(data) };
    },
    /** Polar probe values of panel i (181 x RGBA, theta_o = -90..90). */
    readLobe: (i = 0) => Array.from(lab.panels[i].lobe || []),
    /** Another view of panel i: images as {width, height, data} (base64 float32 RGBA, row 0
     * at the top); the albedo as {thetas, rgb, gain}. */
    readView(i, name) {
      settleNow();
      const view = lab.panels[i].extra[name];
      if (view.stale) view.render(); // off screen: drawn for the reader
      view.stale = false;
      const out = view.read();
      return out.data ? { ...out, data: toBase64(out.data) } : out;
    },
    /** Shows these views (names of the registry's page views) and renders. */
    setViews(names) {
      lab.views = lab.pageViews.filter((n) => names.includes(n));
      showToolbar(lab);
      writeHash();
      return renderNow();
    },
    /** Sets registry settings by their names ({phi_d: 45, shape: 2, polar_log: true}) and
     * renders; a name that is no setting throws. */
    setSettings(values) {
      for (const [name, value] of Object.entries(values)) lab.set(name, value);
      showToolbar(lab);
      writeHash();
      return renderNow();
    },
    overlay: () => lab.overlayGeometry,
    /** The delta spike of panel i: its RGB reflectance (null for other models) and its
     * drawn length as a fraction of the polar plot's radius. */
    spike: (i = 0) => {
      const panel = lab.panels[i];
      const g = panel.polarGeometry;
      return { rgb: panel.spike, length: g ? g.spikeLength / g.radius : 0 };
    },
    loadModel(label, code) {
      const name = addModelText(lab, label, code);
      lab.panels.forEach((p) => p.fillPicker());
      const panel = addPanel(lab, name);
      renderNow();
      return panel ? panel.error : lab.modelErrors[name];
    },
    /** Frame times (ms) while a slider of panel i moves through `steps` positions. */
    sliderFrames(i, name, steps = 60) {
      const times = [];
      stopSettling();
      lab.fast = true;
      for (let k = 0; k < steps; k++) {
        const start = performance.now();
        lab.panels[i].moveSlider(name, Math.round((lab.constants.SLIDER_STEPS * ((k * 37) % steps)) / steps));
        renderAll();
        lab.panels[i].gl.finish();
        times.push(performance.now() - start);
      }
      lab.fast = false;
      renderNow();
      return times;
    },
  };
}
