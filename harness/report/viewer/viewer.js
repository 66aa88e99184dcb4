// xshade image-diff viewer: one interactive block per group of bit-identical lanes on a scene page.
//
// The page (harness/report/report_html.cpp) inlines this file after <div id="xshade-viewer">, the
// scene JSON in <script id="xshade-viewer-data"> and, optionally, pixels/SCENE.js, which fills
// window.XSHADE_PIXELS with deflated float32 RGBA images. Reports are opened from file://, where
// fetch, XHR and canvas readback of <img> are forbidden: the PNGs are shown as <img> layers and
// every number in the readout comes from the float data, never from the PNGs.
//
// Geometry: each view is a fixed-size viewport; inside it, "stages" the size of the image get
// translate(tx, ty) scale(zoom) with image-rendering: pixelated, so pixels stay crisp squares.
// Screen position in a viewport = t + zoom * image position. Markers sit outside the stages, in
// viewport pixels, so that their outlines keep one width at every zoom.
//
// Test hooks (kept stable for tests/report/viewer_driver.py): section.xv-group[data-lanes][data-mode],
// button[data-xv-mode], button[data-xv-action], [data-xv-field], .xv-readout[data-pinned],
// .xv-worst, window.xshadeViewer.{ready, pixelToClient}.
//
// Under `xshade watch` the page's live script (harness/live/live.js) puts a new state of the page
// in place and calls window.xshadeViewer.rebuild(version): the viewer is built again from the new
// data, each group keeping its zoom, pan, mode, mask and pinned pixel, and every image it shows is
// asked for as IMAGE?v=VERSION, so that the browser shows the new file under the same name.
(function () {
  "use strict";

  const ZOOM_STEPS = [0.5, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32];
  const SMALL_IMAGE = 256;  // images up to half this are shown enlarged by a whole factor, to about this size
  const GOTO_ZOOM = 8;      // "go to worst": single pixels and their neighbours both visible
  const BLINK_MS = 500;     // one image change every 500 ms: ~2 Hz
  const MARK_PAD = 3;       // a marker's outline stands this far off its pixel and never hides it
  const CLICK_SLOP = 4;     // a press that moves less than this (px) is a click, not a pan
  const WHEEL_STEP = 60;    // wheel delta per zoom step: a mouse notch is ~100, trackpads send many small ones
  const MASK_RGBA = [0, 229, 255, 255];  // cyan: not in the heat map's inferno palette, rare in renders
  const ENCODING = "deflate-f32le-rgba";
  const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;
  const MODES = [["side", "Side by side"], ["flip", "Flip"], ["swipe", "Swipe"], ["onion", "Onion skin"]];
  const UNAVAILABLE = "float values not available";
  let version = "";  // the report's state under `xshade watch`: image addresses carry it
  const versioned = (url) => (url && version ? `${url}?v=${version}` : url);

  // ---------------------------------------------------------------- small helpers

  // document.createElement with attributes ("class", "text" and "style" are special) and children.
  function h(tag, attrs, ...children) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attrs || {})) {
      if (value === null || value === undefined || value === false) continue;
      if (key === "class") node.className = value;
      else if (key === "text") node.textContent = value;
      else if (key === "style") Object.assign(node.style, value);
      else node.setAttribute(key, value === true ? "" : String(value));
    }
    for (const child of children) if (child !== null && child !== undefined && child !== false) node.append(child);
    return node;
  }

  const plural = (n, one, many) => `${n} ${n === 1 ? one : many}`;
  const samePixel = (a, b) => !!a && !!b && a.x === b.x && a.y === b.y;
  const clamp = (v, lo, hi) => Math.min(Math.max(v, lo), hi);

  // The shortest decimal that reads back as the same float32 (at most 9 significant digits), so
  // that a value can be typed into a test or a shader exactly; String() drops the "e+2" of
  // toPrecision and any trailing zeros.
  function formatFloat(v) {
    if (Number.isNaN(v)) return "NaN";
    if (v === Infinity) return "Infinity";
    if (v === -Infinity) return "-Infinity";
    if (v === 0) return Object.is(v, -0) ? "-0" : "0";
    for (let digits = 1; digits < 9; ++digits) {
      const text = v.toPrecision(digits);
      if (Math.fround(Number(text)) === v) return String(Number(text));
    }
    return String(Number(v.toPrecision(9)));
  }

  function formatZoom(z) {
    if (z >= 1) return `${z}×`;
    return z === 0.5 ? "1/2×" : `${z.toFixed(2)}×`;
  }

  // The 8-bit code write_png stores for a colour channel: the largest k with v >= starts[k]
  // (harness/image/srgb8_encoder.h); NaN and v <= 0 encode as 0.
  function makeEncoder(starts) {
    if (!Array.isArray(starts) || starts.length !== 256 || starts.some((s) => typeof s !== "number")) return null;
    // fround: a start printed with 9 significant digits parses to a double a hair off the float it names.
    const table = Float64Array.from(starts, Math.fround);
    return (v) => {
      if (!(v > 0)) return 0;
      if (v >= table[255]) return 255;
      let lo = 0, hi = 255;  // table[lo] <= v < table[hi]
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (v >= table[mid]) lo = mid; else hi = mid;
      }
      return lo;
    };
  }

  // Alpha as write_png stores it: lround(min(a, 1) * 255) in float arithmetic; NaN and a <= 0 as 0.
  const alpha8 = (a) => (a > 0 ? Math.round(Math.fround(Math.min(a, 1) * 255)) : 0);

  // Where a difference of `steps` sits on the heat map's colour ramp: heat_position in
  // harness/image/image_compare.cpp. Only the legend's layout uses it; colours come from the palette.
  function heatPosition(steps, tolerance) {
    if (steps === 0) return 0;
    if (steps <= tolerance) return 0.05 + 0.25 * steps / tolerance;
    const span = 255 - tolerance;
    if (span < 2) return 0.5;
    return 0.5 + 0.5 * Math.log(steps - tolerance) / Math.log(span);
  }

  const validPalette = (p) => (Array.isArray(p) && p.length === 256 ? p : null);

  function hexToRgb(hex) {
    const n = parseInt(String(hex).replace("#", ""), 16);
    return [(n >> 16) & 255, (n >> 8) & 255, n & 255];
  }

  // ---------------------------------------------------------------- float data

  // An error the viewer explains in its readout; `quiet` ones are expected states (no pixel file,
  // no key), the others are also reported with console.warn.
  class Unavailable extends Error {
    constructor(message, quiet) { super(message); this.quiet = quiet; }
  }

  const decoded = new Map();  // key -> Promise<Float32Array>: groups often share one golden

  function pixels(key, width, height) {
    if (!decoded.has(key)) decoded.set(key, decodePixels(key, width, height));
    return decoded.get(key);
  }

  async function decodePixels(key, width, height) {
    const all = window.XSHADE_PIXELS;
    if (!all || typeof all !== "object") throw new Unavailable("the page has no pixel data file", true);
    const entry = Object.prototype.hasOwnProperty.call(all, key) ? all[key] : null;
    if (!entry) throw new Unavailable(`no pixel data for "${key}"`, false);
    if (entry.encoding !== ENCODING) throw new Unavailable(`"${key}" has encoding "${entry.encoding}"`, false);
    if (entry.width !== width || entry.height !== height)
      throw new Unavailable(`"${key}" is ${entry.width}x${entry.height}, the scene ${width}x${height}`, false);
    if (typeof DecompressionStream !== "function") throw new Unavailable("this browser has no DecompressionStream", false);
    const binary = atob(entry.data);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
    const buffer = await new Response(stream).arrayBuffer();
    if (buffer.byteLength !== width * height * 16)
      throw new Unavailable(`"${key}" holds ${buffer.byteLength} bytes, not ${width * height * 16}`, false);
    if (LITTLE_ENDIAN) return new Float32Array(buffer);
    const view = new DataView(buffer), floats = new Float32Array(width * height * 4);
    for (let i = 0; i < floats.length; ++i) floats[i] = view.getFloat32(i * 4, true);
    return floats;
  }

  // Paints width x height pixels (fill(rgbaBytes) writes them) into an image an <img> can show.
  function paintToUrl(width, height, fill) {
    const canvas = h("canvas", {width, height});
    const context = canvas.getContext("2d");
    const image = context.createImageData(width, height);
    fill(image.data);
    context.putImageData(image, 0, 0);
    return new Promise((resolve) => canvas.toBlob((blob) => resolve(blob ? URL.createObjectURL(blob) : null)));
  }

  // ---------------------------------------------------------------- the heat-map legend

  function buildLegend(palette, tolerance) {
    const width = 320;
    const bar = h("canvas", {class: "xv-legend-bar", width, height: 1, "aria-hidden": "true"});
    const context = bar.getContext("2d");
    // Step s covers [pos(s), pos(s + 1)): the bar has the heat map's log layout, ticks line up.
    for (let s = 0; s < 256; ++s) {
      const x0 = Math.round(heatPosition(s, tolerance) * width);
      const x1 = s < 255 ? Math.round(heatPosition(s + 1, tolerance) * width) : width;
      context.fillStyle = palette[s];
      context.fillRect(Math.min(x0, width - 1), 0, Math.max(1, x1 - x0), 1);
    }
    const tick = (steps, label, align) =>
      h("span", {class: `xv-tick xv-tick-${align}`, style: {left: `${heatPosition(steps, tolerance) * 100}%`}}, label);
    const ticks = h("div", {class: "xv-ticks"}, tick(0, "0", "start"));
    if (tolerance >= 1) {
      const band = h("span", {class: "xv-tick xv-band", style: {
        left: `${heatPosition(1, tolerance) * 100}%`,
        width: `${(heatPosition(tolerance + 1, tolerance) - heatPosition(1, tolerance)) * 100}%`}},
      tolerance === 1 ? "1" : `1–${tolerance}`);
      ticks.append(band);
    }
    if (tolerance < 254) ticks.append(tick(tolerance + 1, String(tolerance + 1), "mid"));
    ticks.append(tick(255, "255", "end"));
    const within = tolerance >= 1 ? `, dark purple = within tolerance (${tolerance === 1 ? "1 step" : `1–${tolerance} steps`})` : "";
    return h("div", {class: "xv-legend"},
      h("div", {class: "xv-legend-title"}, "Heat map: largest channel difference (8-bit sRGB steps)"),
      h("div", {class: "xv-legend-scale"}, bar, ticks),
      h("div", {class: "xv-legend-text"},
        `Log scale. Black = identical${within}, red → yellow = beyond tolerance (${tolerance + 1}+ steps).`));
  }

  // ---------------------------------------------------------------- the metric's legend

  // Each metric's heat map (metric_heat_map in harness/image/metric_layers.cpp): what 0 and 1 mean,
  // and where to put ticks on its even scale.
  const METRIC_SCALES = {
    flip: {name: "FLIP", title: "Heat map: FLIP per pixel",
      text: "0 = cannot be told apart as the two images alternate, 1 = the largest difference (green against blue).",
      ticks: [[0, "0"], [0.25, "0.25"], [0.5, "0.5"], [0.75, "0.75"], [1, "1"]]},
    ssim: {name: "SSIM", title: "Heat map: 1 − SSIM of the 11×11 window centred on each pixel",
      text: "0 = the same structure; the 5-pixel border no window is centred on is black.",
      ticks: [[0, "0"], [0.5, "0.5"], [1, "1"]]},
    deltae: {name: "ΔE00", title: "Heat map: CIEDE2000 per pixel",
      text: "1 is the smallest difference noticed side by side; the scale ends at 10, a difference seen at a glance.",
      ticks: [[0, "0"], [0.1, "1"], [0.5, "5"], [1, "10+"]]},
  };

  function buildMetricLegend(palette, metric) {
    const scale = METRIC_SCALES[metric.name];
    if (!scale) return null;
    const width = 320;
    const bar = h("canvas", {class: "xv-legend-bar", width, height: 1, "aria-hidden": "true"});
    const context = bar.getContext("2d");
    for (let i = 0; i < 256; ++i) {
      context.fillStyle = palette[i];
      context.fillRect(Math.floor((i / 256) * width), 0, Math.ceil(width / 256), 1);
    }
    const ticks = h("div", {class: "xv-ticks"});
    for (const [at, label] of scale.ticks)
      ticks.append(h("span", {class: `xv-tick xv-tick-${at === 0 ? "start" : at === 1 ? "end" : "mid"}`,
        style: {left: `${at * 100}%`}}, label));
    return h("div", {class: "xv-legend xv-metric-legend", "data-metric": metric.name},
      h("div", {class: "xv-legend-title"}, scale.title),
      h("div", {class: "xv-legend-scale"}, bar, ticks),
      h("div", {class: "xv-legend-text"}, scale.text));
  }

  function metricCaption(metric) {
    const scale = METRIC_SCALES[metric.name] || {name: metric.name};
    const bound = metric.name === "ssim" ? "≥" : "≤";
    return `${scale.name}: ${formatMetric(metric.value)} (${bound} ${metric.threshold})`;
  }

  function formatMetric(value) {
    return typeof value === "number" ? value.toPrecision(4) : "–";
  }

  // ---------------------------------------------------------------- one group's viewer

  class Group {
    constructor(scene, spec, encode) {
      this.spec = spec;
      this.W = scene.width;
      this.H = scene.height;
      this.encode = encode;
      this.hasGolden = !!spec.golden;
      this.tolerance = Number(spec.channel_tolerance) || 0;
      this.palette = validPalette(spec.heat_palette) || validPalette(scene.heat_palette);
      this.metric = spec.metric && spec.metric.map ? spec.metric : null;
      this.metricPalette = validPalette(scene.metric_palette);
      this.mode = this.hasGolden ? "side" : "output-only";
      // View state, shared by every view of the group so that they stay synchronised.
      this.zoom = 1; this.baseZoom = 1; this.tx = 0; this.ty = 0; this.vw = this.W; this.vh = this.H;
      this.userZoomed = false;  // until the user zooms or pans, a resize refits the image
      this.hover = null; this.pin = null;
      this.pointer = null;      // {x, y} in viewport px while the pointer is over a view: +/- zoom around it
      this.drag = null; this.wheel = 0;
      this.showOutput = true; this.blink = 0; this.swipe = 0.5; this.onion = 0.5; this.maskOn = false;
      this.golden = null; this.output = null; this.steps = null;  // Float32Array, Float32Array, Uint8Array
      this.floatStatus = "decoding float values…";
      this.layers = {golden: [], output: [], difference: [], metric: [], mask: []};
      this.views = [];
      this.fields = {};
      this.build();
    }

    // -------------------------------------------------------------- construction

    build() {
      const spec = this.spec, lanes = (spec.lanes || []).join(" = ");
      this.root = h("section", {class: "xv-group", "data-lanes": (spec.lanes || []).join(","),
        "data-mode": this.mode, "data-verdict": spec.verdict, "aria-label": `Images of ${lanes}`});
      const verdict = String(spec.verdict || "");
      const facts = [];
      if (this.hasGolden) {
        facts.push(`${plural(spec.failing_pixels || 0, "failing pixel", "failing pixels")} (tolerance ${plural(this.tolerance, "step", "steps")})`);
        if (spec.worst) facts.push(`worst ${plural(spec.worst.steps, "step", "steps")} at (${spec.worst.x}, ${spec.worst.y})`);
      } else {
        facts.push("no golden image: the output alone");
      }
      this.root.append(h("div", {class: "xv-head"},
        h("span", {class: "xv-lanes"}, lanes),
        h("span", {class: `xv-badge xv-v-${verdict}`}, verdict.toUpperCase()),
        h("span", {class: "xv-facts"}, facts.join(" · "))));
      this.root.append(this.buildToolbar());
      this.viewsEl = h("div", {class: "xv-views"});
      if (this.hasGolden) {
        this.makeSideView("golden", "Golden", "golden");
        this.makeSideView("output", `Output (${lanes})`, "output");
        this.makeSideView("difference", "Difference: heat map", "difference");
        if (this.metric) this.makeSideView("metric", metricCaption(this.metric), "metric");
        this.makeSingleView(lanes);
      } else {
        this.makeSideView("output", `Output (${lanes})`, "output");
      }
      this.root.append(this.viewsEl);
      const bottom = h("div", {class: "xv-bottom"}, this.buildReadout());
      if (this.hasGolden && this.palette) bottom.append(buildLegend(this.palette, this.tolerance));
      if (this.metric && this.metricPalette) {
        const legend = buildMetricLegend(this.metricPalette, this.metric);
        if (legend) bottom.append(legend);
      }
      this.root.append(bottom);
      this.setSources();
      this.setMode(this.mode);
    }

    button(label, attrs, onClick, key) {
      const b = h("button", Object.assign({type: "button", class: "xv-btn"}, attrs), label,
        key ? h("kbd", {class: "xv-key", "aria-hidden": "true"}, key) : null);
      if (key) b.setAttribute("aria-keyshortcuts", key);
      // Mouse clicks leave focus on the page, so Space keeps flipping instead of re-pressing the
      // button; keyboard users still Tab to buttons and press them as usual.
      b.addEventListener("mousedown", (e) => e.preventDefault());
      b.addEventListener("click", onClick);
      return b;
    }

    buildToolbar() {
      const bar = h("div", {class: "xv-toolbar"});
      if (this.hasGolden) {
        this.modeButtons = MODES.map(([mode, label], i) =>
          this.button(label, {"data-xv-mode": mode, "aria-pressed": "false"}, () => this.setMode(mode), String(i + 1)));
        bar.append(h("div", {class: "xv-seg", role: "group", "aria-label": "Comparison mode"}, ...this.modeButtons));
      }
      this.fields.zoom = h("span", {class: "xv-zoom", "data-xv-field": "zoom", "aria-live": "polite"}, "1×");
      bar.append(h("div", {class: "xv-seg", role: "group", "aria-label": "Zoom"},
        this.button("−", {"data-xv-action": "zoom-out", "aria-label": "Zoom out", title: "Zoom out (-)"}, () => this.zoomStep(-1)),
        this.fields.zoom,
        this.button("+", {"data-xv-action": "zoom-in", "aria-label": "Zoom in", title: "Zoom in (+)"}, () => this.zoomStep(1)),
        this.button("Reset", {"data-xv-action": "reset", title: "The first zoom: 1:1, or fit to width"}, () => this.resetView(), "0")));
      const spec = this.spec;
      if (this.hasGolden && spec.worst)
        bar.append(this.button("Go to worst", {"data-xv-action": "worst"}, () => this.goTo(spec.worst), "W"));
      if (this.hasGolden && spec.first_failing)
        bar.append(this.button("Go to first failing", {"data-xv-action": "first"}, () => this.goTo(spec.first_failing)));
      if (this.hasGolden) {
        this.fields["mask-count"] = h("span", {"data-xv-field": "mask-count"}, "…");
        this.maskButton = this.button("Mask", {"data-xv-action": "mask", "aria-pressed": "false",
          title: "Failing pixels as an overlay"}, () => this.setMask(!this.maskOn), "M");
        bar.append(h("span", {class: "xv-mask-info"}, this.maskButton, " ", this.fields["mask-count"], " failing"));
        // Controls of the one-view modes; setMode shows those of the current mode.
        this.fields.showing = h("b", {"data-xv-field": "showing"}, "output");
        this.blinkButton = this.button("Blink", {"data-xv-action": "blink", "aria-pressed": "false",
          title: "Alternate automatically at 2 Hz"}, () => this.setBlink(!this.blink), "B");
        this.flipControls = h("span", {class: "xv-modectl"},
          this.button("Flip", {"data-xv-action": "flip", title: "Show the other image"}, () => this.flip(), "F"),
          this.blinkButton, h("span", {class: "xv-showing"}, "Showing: ", this.fields.showing));
        this.swipeInput = h("input", {type: "range", min: 0, max: 1000, value: 500, "data-xv-control": "swipe",
          "aria-label": "Divider position"});
        this.swipeInput.addEventListener("input", () => this.setSwipe(this.swipeInput.value / 1000));
        this.swipeControls = h("label", {class: "xv-modectl"}, "Golden ", this.swipeInput, " output");
        this.onionInput = h("input", {type: "range", min: 0, max: 100, value: 50, "data-xv-control": "onion",
          "aria-label": "Output opacity"});
        this.onionText = h("span", {"data-xv-field": "onion"}, "50%");
        this.onionInput.addEventListener("input", () => { this.onion = this.onionInput.value / 100; this.updateSingle(); });
        this.onionControls = h("label", {class: "xv-modectl"}, "Output opacity ", this.onionInput, " ", this.onionText);
        bar.append(this.flipControls, this.swipeControls, this.onionControls);
      }
      return bar;
    }

    // A view: caption, then a viewport holding the stages and the markers.
    makeView(name, caption) {
      const viewport = h("div", {class: "xv-viewport"});
      const marks = {};
      for (const kind of ["hover", "first", "worst", "pin"]) marks[kind] = h("div", {class: `xv-mark xv-${kind}`, hidden: true});
      const captionEl = h("div", {class: "xv-caption"}, caption);
      const view = {name, viewport, marks, caption: captionEl, stages: [],
        root: h("div", {class: "xv-view", "data-xv-view": name}, captionEl, viewport)};
      view.marksEl = h("div", {class: "xv-marks"}, ...Object.values(marks));
      this.attachPointer(view);
      this.views.push(view);
      this.viewsEl.append(view.root);
      return view;
    }

    layer(kind, checker) {
      const img = h("img", {class: `xv-layer xv-layer-${kind}${checker ? " xv-checker" : ""}`, alt: "", draggable: "false",
        style: {width: `${this.W}px`, height: `${this.H}px`}});
      img.addEventListener("error", () => this.imageFailed(kind, img));
      this.layers[kind].push(img);
      return img;
    }

    stage(view, parent, ...layers) {
      const stage = h("div", {class: "xv-stage", style: {width: `${this.W}px`, height: `${this.H}px`}}, ...layers);
      parent.append(stage);
      view.stages.push(stage);
      return stage;
    }

    makeSideView(name, caption, kind) {
      const view = this.makeView(name, caption);
      this.stage(view, view.viewport, this.layer(kind, true), this.layer("mask"));
      view.viewport.append(view.marksEl);
    }

    // The one view of flip, swipe and onion: output in a clipping box over golden, the mask over both.
    makeSingleView(lanes) {
      const view = this.makeView("single", "");
      this.single = view;
      this.stage(view, view.viewport, this.layer("golden", true));
      view.clip = h("div", {class: "xv-clip"});
      view.viewport.append(view.clip);
      this.stage(view, view.clip, this.layer("output"));
      this.stage(view, view.viewport, this.layer("mask"));
      view.tagLeft = h("span", {class: "xv-tag xv-tag-left"});
      view.tagRight = h("span", {class: "xv-tag xv-tag-right"});
      view.divider = h("div", {class: "xv-divider", role: "presentation"}, h("span", {class: "xv-handle"}, "⇔"));
      view.lanes = lanes;
      view.viewport.append(view.marksEl, view.divider, view.tagLeft, view.tagRight);
      // The divider captures its pointer, so its moves come here and never pan the view.
      view.divider.addEventListener("pointerdown", (e) => {
        e.stopPropagation();
        e.preventDefault();
        view.divider.setPointerCapture(e.pointerId);
      });
      view.divider.addEventListener("pointermove", (e) => {
        if (view.divider.hasPointerCapture(e.pointerId)) this.setSwipe(this.local(view, e).x / this.vw);
      });
    }

    buildReadout() {
      const field = (name) => (this.fields[name] = h("span", {class: "xv-val", "data-xv-field": name}, "–"));
      this.readout = h("div", {class: "xv-readout", "data-pinned": "false", "aria-label": "Pixel values"});
      this.fields.unpin = this.button("Unpin", {"data-xv-action": "unpin", hidden: true}, () => this.setPin(null), "Esc");
      this.fields.state = h("span", {class: "xv-state", "data-xv-field": "state"}, "under the pointer");
      this.readout.append(h("div", {class: "xv-readout-head"},
        "Pixel x ", field("x"), ", y ", field("y"), " ", this.fields.state, " ", this.fields.unpin));
      const grid = h("div", {class: "xv-grid"}, h("span", {class: "xv-label"}, "channels"),
        h("span", {class: "xv-val xv-channels"}, "R, G, B, A"));
      const rows = [["golden", "golden"], ["output", "output"], ["difference", "output − golden"],
        ["golden-srgb", "golden sRGB"], ["output-srgb", "output sRGB"], ["steps", "steps (out − gold)"]];
      for (const [name, label] of rows) grid.append(h("span", {class: "xv-label"}, label), field(name));
      this.readout.append(grid, h("div", {class: "xv-readout-foot"}, field("pixel-verdict"), " ",
        this.fields.status = h("span", {class: "xv-status", "data-xv-field": "data-status"}, this.floatStatus)),
      h("div", {class: "xv-hint"}, "Wheel or +/− zooms, drag pans, click pins a pixel (click again or Esc unpins, arrows move it)."));
      return this.readout;
    }

    // -------------------------------------------------------------- images and data

    setSources() {
      const spec = this.spec;
      const sources = {golden: spec.golden && spec.golden.png, output: spec.output && spec.output.png,
        difference: spec.heat_map, metric: this.metric && this.metric.map};
      for (const [kind, url] of Object.entries(sources))
        for (const img of this.layers[kind]) if (url) img.src = versioned(url);
    }

    imageFailed(kind, img) {
      if (img.dataset.generated) return;
      img.dataset.failed = "true";
      this.generateMissing();  // draws it from the float data, if that is or becomes available
    }

    // Layers whose PNG is absent (null in the JSON, or it failed to load) are drawn from the floats.
    async generateMissing() {
      if (!this.output) return;
      const {W, H} = this;
      for (const kind of ["golden", "output", "difference"]) {
        const imgs = this.layers[kind].filter((img) => (!img.getAttribute("src") || img.dataset.failed) && !img.dataset.generated);
        if (!imgs.length) continue;
        let fill = null;
        if (kind !== "difference" && this.encode && this[kind]) {
          const floats = this[kind];
          fill = (bytes) => {
            for (let i = 0; i < floats.length; i += 4) {
              for (let c = 0; c < 3; ++c) bytes[i + c] = this.encode(floats[i + c]);
              bytes[i + 3] = alpha8(floats[i + 3]);
            }
          };
        } else if (kind === "difference" && this.steps && this.palette) {
          const colours = this.palette.map(hexToRgb);
          fill = (bytes) => this.steps.forEach((s, p) => bytes.set([...colours[s], 255], p * 4));
        }
        if (!fill) continue;
        const url = await paintToUrl(W, H, fill);
        for (const img of imgs) { img.dataset.generated = "true"; img.src = url; }
      }
    }

    async load() {
      const spec = this.spec;
      try {
        const outputKey = spec.output && spec.output.pixels;
        if (!outputKey) throw new Unavailable("the report has no float data for this output", true);
        this.output = await pixels(outputKey, this.W, this.H);
        if (this.hasGolden) {
          if (!spec.golden.pixels) throw new Unavailable("the report has no float data for the golden", true);
          this.golden = await pixels(spec.golden.pixels, this.W, this.H);
          if (this.encode) await this.computeFailing();
        }
        this.floatStatus = this.encode ? "float values decoded" : "float values decoded (no sRGB code table)";
      } catch (err) {
        const reason = err instanceof Unavailable ? err.message : String(err && err.message || err);
        this.floatStatus = `${UNAVAILABLE}: ${reason}`;
        if (!(err instanceof Unavailable && err.quiet)) console.warn(`xshade viewer (${spec.lanes}): ${this.floatStatus}`);
      }
      if (!this.steps && this.fields["mask-count"]) {
        this.fields["mask-count"].textContent = String(spec.failing_pixels ?? "?");
        this.fields["mask-count"].title = "from the report: no float data to draw the mask from";
        this.maskButton.disabled = true;
      }
      this.fields.status.textContent = this.floatStatus;
      await this.generateMissing();
      this.updateReadout();
    }

    // Per pixel the largest channel difference in 8-bit steps, as image_compare.cpp's
    // compare_pixels: the mask, the readout's verdict and a missing heat map are drawn from it.
    async computeFailing() {
      const {W, H, golden, output, encode, tolerance, spec} = this;
      const steps = new Uint8Array(W * H);
      let failing = 0, worst = 0, worstPixel = 0;
      for (let p = 0, i = 0; p < W * H; ++p, i += 4) {
        let s = Math.abs(alpha8(output[i + 3]) - alpha8(golden[i + 3]));
        for (let c = 0; c < 3; ++c) s = Math.max(s, Math.abs(encode(output[i + c]) - encode(golden[i + c])));
        steps[p] = s;
        if (s > tolerance) ++failing;
        if (s > worst) { worst = s; worstPixel = p; }
      }
      this.steps = steps;
      this.fields["mask-count"].textContent = String(failing);
      // The report may forgive pixels by position radius, so a different count is a note, not an error.
      if (spec.failing_pixels !== undefined && failing !== spec.failing_pixels)
        console.warn(`xshade viewer (${spec.lanes}): ${failing} pixels differ by more than ${tolerance} steps; ` +
          `the report counts ${spec.failing_pixels} failing (position radius?)`);
      if (spec.worst && (spec.worst.steps !== worst || spec.worst.x !== worstPixel % W || spec.worst.y !== Math.floor(worstPixel / W)))
        console.warn(`xshade viewer (${spec.lanes}): worst ${worst} steps at (${worstPixel % W}, ${Math.floor(worstPixel / W)}), ` +
          `the report says ${spec.worst.steps} at (${spec.worst.x}, ${spec.worst.y})`);
      const url = await paintToUrl(W, H, (bytes) => {
        for (let p = 0; p < W * H; ++p) if (steps[p] > tolerance) bytes.set(MASK_RGBA, p * 4);
      });
      for (const img of this.layers.mask) img.src = url;
    }

    // -------------------------------------------------------------- modes

    setMode(mode) {
      if (this.hasGolden) {
        if (!MODES.some(([m]) => m === mode)) return;
        this.mode = mode;
        for (const b of this.modeButtons) b.setAttribute("aria-pressed", String(b.dataset.xvMode === mode));
        for (const view of this.views) view.root.hidden = (view.name === "single") === (mode === "side");
        this.flipControls.hidden = mode !== "flip";
        this.swipeControls.hidden = mode !== "swipe";
        this.onionControls.hidden = mode !== "onion";
        if (mode !== "flip") this.setBlink(false);
      }
      this.root.dataset.mode = this.mode;
      this.layout();
      this.updateSingle();
    }

    flip() {
      if (this.mode !== "flip") this.setMode("flip");
      else { this.showOutput = !this.showOutput; this.updateSingle(); }
    }

    setBlink(on) {
      if (!this.hasGolden || !!this.blink === on) return;
      if (on) {
        if (this.mode !== "flip") this.setMode("flip");
        this.blink = setInterval(() => { this.showOutput = !this.showOutput; this.updateSingle(); }, BLINK_MS);
      } else {
        clearInterval(this.blink);
        this.blink = 0;
      }
      this.blinkButton.setAttribute("aria-pressed", String(on));
    }

    setSwipe(fraction) {
      this.swipe = clamp(fraction, 0, 1);
      this.swipeInput.value = String(Math.round(this.swipe * 1000));
      this.updateSingle();
    }

    setMask(on) {
      if (!this.hasGolden || (this.maskButton.disabled && on)) return;
      this.maskOn = on;
      this.root.classList.toggle("xv-mask-on", on);
      this.maskButton.setAttribute("aria-pressed", String(on));
    }

    // The single view's layers, tags and caption for flip, swipe or onion.
    updateSingle() {
      const view = this.single;
      if (!view || this.mode === "side") return;
      const clip = view.clip.style, split = Math.round(this.swipe * this.vw);
      clip.visibility = this.mode !== "flip" || this.showOutput ? "visible" : "hidden";
      clip.clipPath = this.mode === "swipe" ? `inset(0 0 0 ${split}px)` : "none";
      clip.opacity = this.mode === "onion" ? String(this.onion) : "1";
      view.divider.hidden = this.mode !== "swipe";
      view.divider.style.left = `${split}px`;
      view.tagRight.hidden = this.mode !== "swipe";
      const showing = this.showOutput ? "output" : "golden";
      this.fields.showing.textContent = showing;
      this.onionText.textContent = `${Math.round(this.onion * 100)}%`;
      if (this.mode === "flip") {
        view.tagLeft.textContent = showing;
        view.caption.textContent = `Flip: showing ${showing === "output" ? `output (${view.lanes})` : "golden"}`;
      } else if (this.mode === "swipe") {
        view.tagLeft.textContent = "golden";
        view.tagRight.textContent = "output";
        view.caption.textContent = `Swipe: golden left of the divider, output (${view.lanes}) right`;
      } else {
        view.tagLeft.textContent = `output ${Math.round(this.onion * 100)}% over golden`;
        view.caption.textContent = `Onion skin: output (${view.lanes}) at ${Math.round(this.onion * 100)}% over golden`;
      }
    }

    // -------------------------------------------------------------- zoom and pan

    // Views are 1:1 unless the image is wider than the space, then fit to its width; a tiny image
    // (a test scene) is enlarged by a whole factor so that it can be seen. Every mode uses the same
    // viewport size, so switching modes keeps the zoom and pan.
    layout() {
      const style = getComputedStyle(this.viewsEl);
      let avail = this.viewsEl.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight) - 2;
      if (!(avail > 0)) avail = Infinity;  // not laid out (yet): no width to fit
      let base = Math.min(1, avail / this.W);
      const enlarge = Math.floor(SMALL_IMAGE / Math.max(this.W, this.H));
      if (enlarge >= 2) base = Math.max(1, Math.min(enlarge, Math.floor(avail / this.W)));
      const centre = [(this.vw / 2 - this.tx) / this.zoom, (this.vh / 2 - this.ty) / this.zoom];
      this.baseZoom = base;
      this.vw = Math.max(1, Math.round(this.W * base));
      this.vh = Math.max(1, Math.round(this.H * base));
      for (const view of this.views) {
        Object.assign(view.viewport.style, {width: `${this.vw}px`, height: `${this.vh}px`});
        view.caption.style.maxWidth = `${Math.max(this.vw + 2, 160)}px`;
      }
      if (!this.userZoomed) { this.zoom = base; this.tx = 0; this.ty = 0; }
      else this.centreOn(centre[0], centre[1]);  // keep what was in the middle there
      this.applyTransform();
    }

    levels() {
      return [...new Set([...ZOOM_STEPS, this.baseZoom])].filter((z) => z >= Math.min(0.5, this.baseZoom)).sort((a, b) => a - b);
    }

    // Zooms to `zoom` keeping the image point under viewport point (cx, cy) where it is.
    zoomTo(zoom, cx = this.vw / 2, cy = this.vh / 2) {
      const k = zoom / this.zoom;
      this.tx = cx - (cx - this.tx) * k;
      this.ty = cy - (cy - this.ty) * k;
      this.zoom = zoom;
      this.userZoomed = true;
      this.applyTransform();
    }

    zoomStep(direction, cx, cy) {
      const levels = this.levels(), z = this.zoom;
      const next = direction > 0 ? levels.find((l) => l > z + 1e-9) : levels.reverse().find((l) => l < z - 1e-9);
      if (next === undefined) return;
      if (cx === undefined && this.pointer) ({x: cx, y: cy} = this.pointer);
      this.zoomTo(next, cx, cy);
    }

    resetView() {
      this.userZoomed = false;
      this.layout();
    }

    // Puts image point (ix, iy) in the middle of the viewports.
    centreOn(ix, iy) {
      this.tx = this.vw / 2 - ix * this.zoom;
      this.ty = this.vh / 2 - iy * this.zoom;
    }

    goTo(pixel) {
      if (!pixel) return;
      this.zoom = Math.max(this.zoom, GOTO_ZOOM);
      this.userZoomed = true;
      this.centreOn(pixel.x + 0.5, pixel.y + 0.5);
      this.setPin({x: pixel.x, y: pixel.y});
      this.applyTransform();
    }

    // Translations are whole pixels (crisp at integer zooms); the image may be panned until its
    // edge reaches the middle of the view, so that every pixel, even a corner one, can be centred.
    applyTransform() {
      const sw = this.W * this.zoom, sh = this.H * this.zoom;
      this.tx = Math.round(clamp(this.tx, this.vw / 2 - sw, this.vw / 2));
      this.ty = Math.round(clamp(this.ty, this.vh / 2 - sh, this.vh / 2));
      const transform = `translate(${this.tx}px, ${this.ty}px) scale(${this.zoom})`;
      for (const view of this.views) for (const stage of view.stages) stage.style.transform = transform;
      this.fields.zoom.textContent = formatZoom(this.zoom);
      this.updateMarks();
      this.updateSingle();  // the swipe split is in viewport pixels
    }

    updateMarks() {
      const spec = this.spec;
      const place = (mark, p) => {
        mark.hidden = !p;
        if (!p) return;
        const size = this.zoom + 2 * MARK_PAD;
        Object.assign(mark.style, {left: `${this.tx + p.x * this.zoom - MARK_PAD}px`,
          top: `${this.ty + p.y * this.zoom - MARK_PAD}px`, width: `${size}px`, height: `${size}px`});
      };
      const first = this.hasGolden && spec.first_failing && !samePixel(spec.first_failing, spec.worst) ? spec.first_failing : null;
      for (const view of this.views) {
        place(view.marks.worst, this.hasGolden ? spec.worst : null);
        place(view.marks.first, first);
        place(view.marks.pin, this.pin);
        place(view.marks.hover, samePixel(this.hover, this.pin) ? null : this.hover);
      }
    }

    // -------------------------------------------------------------- pointer

    // Viewport coordinates (inside its border) of a pointer event.
    local(view, e) {
      const rect = view.viewport.getBoundingClientRect();
      return {x: e.clientX - rect.left - view.viewport.clientLeft, y: e.clientY - rect.top - view.viewport.clientTop};
    }

    pixelAt(point) {
      const x = Math.floor((point.x - this.tx) / this.zoom), y = Math.floor((point.y - this.ty) / this.zoom);
      return x >= 0 && y >= 0 && x < this.W && y < this.H ? {x, y} : null;
    }

    attachPointer(view) {
      const vp = view.viewport;
      vp.addEventListener("pointerdown", (e) => {
        if (e.button !== 0) return;
        activate(this);
        // preventDefault below keeps focus where it was: take it off a slider, so keys work again.
        if (this.root.contains(document.activeElement)) document.activeElement.blur();
        e.preventDefault();  // no text selection, no image drag
        vp.setPointerCapture(e.pointerId);
        this.drag = {id: e.pointerId, x: e.clientX, y: e.clientY, tx: this.tx, ty: this.ty, moved: false};
      });
      vp.addEventListener("pointermove", (e) => {
        const drag = this.drag;
        if (drag && drag.id === e.pointerId) {
          const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
          if (!drag.moved && Math.hypot(dx, dy) >= CLICK_SLOP) { drag.moved = true; vp.classList.add("xv-dragging"); }
          if (drag.moved) {
            this.tx = drag.tx + dx; this.ty = drag.ty + dy;
            this.userZoomed = true;
            this.applyTransform();
          }
        }
        this.pointer = this.local(view, e);
        this.setHover(this.pixelAt(this.pointer));
      });
      const release = (e, cancelled) => {
        const drag = this.drag;
        if (!drag || drag.id !== e.pointerId) return;
        this.drag = null;
        vp.classList.remove("xv-dragging");
        if (cancelled || drag.moved) return;
        const pixel = this.pixelAt(this.local(view, e));
        if (pixel) this.setPin(samePixel(pixel, this.pin) ? null : pixel);  // clicking the pinned pixel unpins
      };
      vp.addEventListener("pointerup", (e) => release(e, false));
      vp.addEventListener("pointercancel", (e) => release(e, true));
      vp.addEventListener("pointerleave", () => {
        if (this.drag) return;
        this.pointer = null;
        this.setHover(null);
      });
      vp.addEventListener("wheel", (e) => {
        e.preventDefault();
        activate(this);
        this.wheel += e.deltaY * (e.deltaMode === 1 ? 40 : e.deltaMode === 2 ? 400 : 1);
        if (Math.abs(this.wheel) < WHEEL_STEP) return;
        const direction = this.wheel < 0 ? 1 : -1;
        this.wheel = 0;
        this.pointer = this.local(view, e);
        this.zoomStep(direction, this.pointer.x, this.pointer.y);
        this.setHover(this.pixelAt(this.pointer));
      }, {passive: false});
    }

    setHover(pixel) {
      if (samePixel(pixel, this.hover) || (!pixel && !this.hover)) return;
      this.hover = pixel;
      this.updateMarks();
      this.updateReadout();
    }

    setPin(pixel) {
      this.pin = pixel;
      this.readout.dataset.pinned = String(!!pixel);
      this.fields.unpin.hidden = !pixel;
      this.updateMarks();
      this.updateReadout();
    }

    // -------------------------------------------------------------- readout

    updateReadout() {
      const f = this.fields, p = this.pin || this.hover;
      const set = (name, text, title) => { f[name].textContent = text; f[name].title = title || ""; };
      f.state.textContent = this.pin ? "pinned" : "under the pointer";
      f["pixel-verdict"].className = "xv-val";
      if (!p) {
        for (const name of ["x", "y", "golden", "output", "difference", "golden-srgb", "output-srgb", "steps", "pixel-verdict"]) set(name, "–");
        f["pixel-verdict"].textContent = "Point at an image to read its pixel; click to pin it.";
        return;
      }
      set("x", String(p.x));
      set("y", String(p.y));
      const i = (p.y * this.W + p.x) * 4;
      const out = this.output ? Array.from(this.output.subarray(i, i + 4)) : null;
      const gold = this.golden ? Array.from(this.golden.subarray(i, i + 4)) : null;
      const noGolden = this.hasGolden ? null : "no golden image";
      const codes = (v) => (this.encode ? [0, 1, 2].map((c) => this.encode(v[c])).concat(alpha8(v[3])) : null);
      set("output", out ? out.map(formatFloat).join(", ") : UNAVAILABLE, out ? "" : this.floatStatus);
      const outCodes = out && codes(out);
      set("output-srgb", outCodes ? outCodes.join(", ") : UNAVAILABLE);
      if (noGolden) {
        for (const name of ["golden", "difference", "golden-srgb", "steps"]) set(name, noGolden);
        f["pixel-verdict"].textContent = "";
        return;
      }
      set("golden", gold ? gold.map(formatFloat).join(", ") : UNAVAILABLE, gold ? "" : this.floatStatus);
      // float32 subtraction, as a shader would compute it
      set("difference", gold && out ? out.map((v, c) => formatFloat(Math.fround(v - gold[c]))).join(", ") : UNAVAILABLE);
      const goldCodes = gold && codes(gold);
      set("golden-srgb", goldCodes ? goldCodes.join(", ") : UNAVAILABLE);
      f.steps.textContent = "";
      f["pixel-verdict"].textContent = "";
      if (!goldCodes || !outCodes) { f.steps.textContent = UNAVAILABLE; return; }
      // Signed (output − golden), each channel beyond the tolerance emphasised; text stays "a, b, c, d".
      const steps = outCodes.map((o, c) => o - goldCodes[c]);
      steps.forEach((s, c) => {
        if (c) f.steps.append(", ");
        f.steps.append(h("span", {class: Math.abs(s) > this.tolerance ? "xv-over" : null}, String(s)));
      });
      const worst = Math.max(...steps.map(Math.abs));
      f["pixel-verdict"].textContent = worst === 0 ? "identical in 8 bits"
        : `largest difference ${plural(worst, "step", "steps")}: ${worst > this.tolerance ? "beyond" : "within"} the tolerance of ${this.tolerance}`;
      f["pixel-verdict"].classList.toggle("xv-fails", worst > this.tolerance);
    }

    // -------------------------------------------------------------- keyboard

    // Returns whether the key was the viewer's, so that the page does not also scroll.
    handleKey(e) {
      const key = e.key;
      const modeIndex = "1234".indexOf(key);
      if (modeIndex >= 0 && key.length === 1 && this.hasGolden) this.setMode(MODES[modeIndex][0]);
      else if ((key === " " || key === "f" || key === "F") && this.hasGolden) this.flip();
      else if ((key === "b" || key === "B") && this.hasGolden) this.setBlink(!this.blink);
      else if ((key === "m" || key === "M") && this.hasGolden) this.setMask(!this.maskOn);
      else if ((key === "w" || key === "W") && this.hasGolden && this.spec.worst) this.goTo(this.spec.worst);
      else if (key === "+" || key === "=") this.zoomStep(1);
      else if (key === "-" || key === "_") this.zoomStep(-1);
      else if (key === "0") this.resetView();
      else if (key === "Escape" && this.pin) this.setPin(null);
      else if (key.startsWith("Arrow") && this.pin) {
        const d = e.shiftKey ? 10 : 1, dx = {ArrowLeft: -d, ArrowRight: d}[key] || 0, dy = {ArrowUp: -d, ArrowDown: d}[key] || 0;
        this.setPin({x: clamp(this.pin.x + dx, 0, this.W - 1), y: clamp(this.pin.y + dy, 0, this.H - 1)});
      } else return false;
      return true;
    }

    // What the user chose to look at, to be kept when the viewer is built again with new images.
    viewState() {
      const {mode, zoom, tx, ty, userZoomed, pin, maskOn, swipe, onion, showOutput} = this;
      return {mode, zoom, tx, ty, userZoomed, pin, maskOn, swipe, onion, showOutput};
    }

    restoreView(state) {
      if (!state) return;
      if (this.hasGolden && state.mode !== "output-only") {
        this.swipe = state.swipe; this.onion = state.onion; this.showOutput = state.showOutput;
        this.swipeInput.value = String(Math.round(state.swipe * 1000));
        this.onionInput.value = String(Math.round(state.onion * 100));
        this.onionText.textContent = `${Math.round(state.onion * 100)}%`;
        this.setMode(state.mode);
        if (state.maskOn) this.setMask(true);
      }
      if (state.userZoomed) {
        Object.assign(this, {zoom: state.zoom, tx: state.tx, ty: state.ty, userZoomed: true});
        this.applyTransform();
      }
      if (state.pin && state.pin.x < this.W && state.pin.y < this.H) this.setPin(state.pin);
    }

    viewNamed(name) {
      if (!this.hasGolden && (name === "single" || name === "output")) return this.views[0];
      return this.views.find((v) => v.name === name) || null;
    }
  }

  // ---------------------------------------------------------------- cross-lane pairs

  function buildCrossLane(scene, tolerance) {
    const pairs = Array.isArray(scene.cross_lane) ? scene.cross_lane : [];
    if (!pairs.length) return null;
    // Small, but never by dropping pixels: whole-number enlargement, smooth reduction.
    const scale = scene.width > 192 ? 192 / scene.width : Math.max(1, Math.floor(192 / scene.width));
    const list = h("div", {class: "xv-pairs"});
    for (const pair of pairs) {
      const verdict = String(pair.verdict || "");
      const img = pair.heat_map
        ? h("img", {class: `xv-thumb${scale >= 1 ? " xv-crisp" : ""}`, src: versioned(pair.heat_map), alt: `heat map of ${pair.first} against ${pair.second}`,
          style: {width: `${Math.round(scene.width * scale)}px`, height: `${Math.round(scene.height * scale)}px`}})
        : h("div", {class: "xv-nothumb"}, "no heat map");
      const worst = pair.worst ? `worst ${plural(pair.worst.steps, "step", "steps")} at (${pair.worst.x}, ${pair.worst.y})` : "";
      list.append(h("div", {class: "xv-pair", "data-pair": `${pair.first},${pair.second}`},
        pair.heat_map ? h("a", {href: pair.heat_map, title: "full size"}, img) : img,
        h("div", {class: "xv-pair-caption"}, h("b", {}, `${pair.first} vs ${pair.second}`), " ",
          h("span", {class: `xv-badge xv-v-${verdict}`}, verdict.toUpperCase()), h("br"), worst)));
    }
    const palette = validPalette(scene.heat_palette);
    return h("section", {class: "xv-cross", "aria-label": "Lanes compared with each other"},
      h("div", {class: "xv-head"}, h("span", {class: "xv-lanes"}, "Lanes compared with each other"),
        h("span", {class: "xv-facts"}, "only pairs whose images differ")),
      h("div", {class: "xv-cross-body"}, list, palette ? buildLegend(palette, tolerance) : null));
  }

  // ---------------------------------------------------------------- page

  const groups = [];
  let active = null;
  let listening = false;  // the page's keyboard and resize handlers, added once
  let resolveReady;
  const ready = new Promise((resolve) => { resolveReady = resolve; });

  // The group the keyboard drives: the last one pointed at or focused.
  function activate(group) {
    if (active === group) return;
    if (active) active.root.classList.remove("xv-active");
    active = group;
    if (groups.length > 1) group.root.classList.add("xv-active");
  }

  function onKey(e) {
    if (!active || e.ctrlKey || e.metaKey || e.altKey || e.defaultPrevented) return;
    const target = e.target instanceof Element ? e.target : null;
    if (target && (target.isContentEditable || target.closest("input, textarea, select"))) return;
    // A focused control keeps Space and Enter: keyboard users press buttons with them.
    if ((e.key === " " || e.key === "Enter") && target && target.closest("button, a, summary")) return;
    if (active.handleKey(e)) e.preventDefault();
  }

  function init() {
    const mount = document.getElementById("xshade-viewer");
    const dataEl = document.getElementById("xshade-viewer-data");
    if (!mount || !dataEl) { resolveReady(); return Promise.resolve(); }
    let scene;
    try {
      scene = JSON.parse(dataEl.textContent);
    } catch (err) {
      console.error("xshade viewer: the scene data is not JSON:", err);
      mount.textContent = "The image viewer could not read its data.";
      resolveReady();
      return Promise.resolve();
    }
    const encode = makeEncoder(scene.srgb_code_starts);
    if (!encode) console.warn("xshade viewer: srgb_code_starts is not 256 numbers; no 8-bit codes");
    const root = h("div", {class: "xv-root"});
    mount.append(root);  // in the document before layout() measures it
    for (const spec of scene.groups || []) {
      const group = new Group(scene, spec, encode);
      groups.push(group);
      root.append(group.root);
      group.layout();
      group.root.addEventListener("pointerenter", () => activate(group));
      group.root.addEventListener("focusin", () => activate(group));
    }
    if (groups.length) activate(groups[0]);
    const tolerance = Number(scene.channel_tolerance ?? (scene.groups && scene.groups[0] && scene.groups[0].channel_tolerance)) || 0;
    const cross = buildCrossLane(scene, tolerance);
    if (cross) root.append(cross);
    if (!listening) {
      listening = true;
      document.addEventListener("keydown", onKey);
      let pending = 0;
      window.addEventListener("resize", () => {
        cancelAnimationFrame(pending);
        pending = requestAnimationFrame(() => groups.forEach((g) => g.layout()));
      });
    }
    return Promise.all(groups.map((g) => g.load())).then(() => resolveReady(), (err) => {
      console.warn("xshade viewer:", err);
      resolveReady();
    });
  }

  // The view state of each group, by its lanes ("gl,vk"): what rebuild keeps.
  function viewStates() {
    return Object.fromEntries(groups.map((g) => [(g.spec.lanes || []).join(","), g.viewState()]));
  }

  // The viewer built again from the page's data as it is now (live.js has put a new state of the
  // page in place), its images asked for at `newVersion`. Each group takes the view state of the
  // group with its lanes in `states` (default: the groups' own, before), else of the first group
  // (lanes that agreed may part after an edit). Resolves once the float data is decoded.
  function rebuild(newVersion, states) {
    const kept = states || viewStates();
    version = String(newVersion);
    groups.length = 0;
    active = null;
    decoded.clear();
    const mount = document.getElementById("xshade-viewer");
    if (mount) mount.replaceChildren();
    const loaded = init();
    const fallback = Object.values(kept)[0];
    for (const g of groups) g.restoreView(kept[(g.spec.lanes || []).join(",")] || fallback);
    return loaded;
  }

  // For tests: where pixel (x, y) of a view is on screen, to move the real mouse there.
  function pixelToClient(groupIndex, viewName, x, y) {
    const group = groups[groupIndex];
    const view = group && group.viewNamed(viewName);
    if (!view) throw new Error(`no view "${viewName}" in group ${groupIndex}`);
    const vp = view.viewport, rect = vp.getBoundingClientRect(), z = group.zoom;
    const left = rect.left + vp.clientLeft + group.tx + x * z, top = rect.top + vp.clientTop + group.ty + y * z;
    const visible = !view.root.hidden && left >= rect.left && top >= rect.top &&
      left + z <= rect.left + vp.clientLeft + group.vw && top + z <= rect.top + vp.clientTop + group.vh;
    return {clientX: left + z / 2, clientY: top + z / 2, left, top, size: z, visible};
  }

  window.xshadeViewer = {ready, pixelToClient, groups, viewStates, rebuild};
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init);
  else init();
})();
