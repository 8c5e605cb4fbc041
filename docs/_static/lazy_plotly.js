/* Draw plotly figures only near the viewport (the site of lbo_notebooks; loaded by docs/conf.py).
 *
 * Each 3D scene of a plotly figure holds a WebGL context, and a browser keeps only so many per page
 * (Chromium: 16); past that it drops the oldest, whose scene then shows a broken image. A notebook
 * page can hold more scenes than that (11_regularized_pca has 21). So:
 *
 * - a figure is drawn when it comes near the viewport (within half a viewport height);
 * - a 3D figure that moves farther away is replaced by a picture of its current view, and its WebGL
 *   contexts are released (Plotly.purge, then WEBGL_lose_context: purge alone leaves them alive);
 * - when it comes back it is drawn again from its current data, layout and frames, so the camera the
 *   reader chose and the slider's position are kept;
 * - at most MAX_SCENES scenes are live: to draw another, the live figure farthest from view goes first.
 *
 * This file runs after plotly.min.js and before the page's body: each figure's inline script calls
 * Plotly.newPlot, which it wraps. Figures without 3D scenes hold no WebGL context here; they are drawn
 * when first near and then stay.
 */
(function () {
  "use strict";
  if (!window.Plotly || !window.IntersectionObserver) return;   // plotly draws every figure at once

  const MAX_SCENES = 12;        // live WebGL contexts we allow ourselves (Chromium's limit is 16)
  const NEAR = "50% 0px";       // "near the viewport": within half its height above or below
  const SCENE_TYPES = new Set(["mesh3d", "scatter3d", "surface", "cone", "streamtube", "isosurface", "volume"]);
  const newPlot = Plotly.newPlot, addFrames = Plotly.addFrames, animate = Plotly.animate;
  const figures = new Map();    // graph div -> {gd, figure: {data, layout, config, frames}, scenes, live, near, visible, drawing, standIn, afterDraw}
  let liveScenes = 0;

  function graphDiv(div) {
    return typeof div === "string" ? document.getElementById(div) : div;
  }

  /* The number of 3D scenes (WebGL contexts) a figure draws. */
  function sceneCount(data) {
    return new Set((data || []).filter(t => SCENE_TYPES.has(t.type)).map(t => t.scene || "scene")).size;
  }

  /* How far the figure is from the viewport, in pixels (0: at least partly on screen). */
  function distance(rec) {
    const r = rec.gd.getBoundingClientRect();
    return Math.max(0, -r.bottom, r.top - window.innerHeight);
  }

  /* Release live 3D figures that are not on screen, farthest first, until `need` more scenes fit. */
  function makeRoom(need, except) {
    while (liveScenes + need > MAX_SCENES) {
      const victims = [...figures.values()].filter(r => r.live && r.scenes && !r.drawing && r !== except && !r.visible);
      if (!victims.length) return false;
      hide(victims.reduce((a, b) => (distance(a) >= distance(b) ? a : b)));
    }
    return true;
  }

  function show(rec, mustDraw) {
    if (rec.live) return;
    if (!makeRoom(rec.scenes, rec) && !mustDraw) return;   // drawn when it scrolls into view
    rec.live = true;
    liveScenes += rec.scenes;
    const f = rec.figure;
    // Drawing is asynchronous: a figure is released only once drawn (plotly would draw on into a
    // purged div), so one that went away meanwhile is released here.
    rec.drawing = newPlot(rec.gd, {data: f.data, layout: f.layout, config: f.config, frames: f.frames})
      .catch(err => console.error(err))
      .then(() => {
        rec.drawing = null;
        if (rec.standIn) rec.standIn.remove();
        rec.standIn = null;
        rec.afterDraw.splice(0).forEach(call => call());
        if (!rec.near && !rec.visible && rec.scenes) hide(rec);
      });
  }

  /* A static copy of the drawn figure (titles, colour bars, slider), each scene's canvas replaced by
     a picture of it: Scene.toImage, plotly's own export of one scene, reads its live context
     (Plotly.toImage would draw a copy of the figure, needing as many new contexts). These are
     plotly internals (_fullLayout.sceneN._scene); should they change, the scenes' pictures stay
     blank and nothing else is lost. */
  function picture(gd) {
    const container = gd.querySelector(".plot-container");
    if (!container) return null;
    const shots = new Map();   // canvas -> PNG data URL
    for (const [key, value] of Object.entries(gd._fullLayout || {})) {
      const scene = /^scene\d*$/.test(key) && value && value._scene;
      try {
        if (scene && scene.glplot) shots.set(scene.glplot.canvas, scene.toImage("png"));
      } catch (err) { /* that scene stays blank in the picture */ }
    }
    const copy = container.cloneNode(true);
    const canvases = container.querySelectorAll("canvas");
    copy.querySelectorAll("canvas").forEach((canvas, i) => {
      if (!shots.has(canvases[i])) return;
      const img = document.createElement("img");
      img.src = shots.get(canvases[i]);
      img.alt = "";
      img.style.cssText = canvas.style.cssText;
      canvas.replaceWith(img);
    });
    copy.querySelectorAll(".modebar-container").forEach(e => e.remove());
    const standIn = document.createElement("div");
    standIn.className = "lbo-plot-standin";
    // Beside the graph div (Plotly.newPlot empties it), over its place and over the figure being
    // drawn again (whose white paper would hide the picture) until that is drawn.
    gd.parentNode.style.position = "relative";
    standIn.style.cssText = `position: absolute; left: ${gd.offsetLeft}px; top: ${gd.offsetTop}px; ` +
      `width: ${gd.offsetWidth}px; height: ${gd.offsetHeight}px; z-index: 1; pointer-events: none;`;
    standIn.appendChild(copy);
    return standIn;
  }

  function hide(rec) {
    if (!rec.live || rec.drawing) return;
    const gd = rec.gd;
    // The figure as it is now: a slider step or a camera the reader moved changed data and layout.
    rec.figure = {
      data: gd.data || rec.figure.data,
      layout: gd.layout || rec.figure.layout,
      config: rec.figure.config,
      frames: (gd._transitionData && gd._transitionData._frames) || rec.figure.frames,
    };
    const standIn = picture(gd);
    const canvases = [...gd.querySelectorAll("canvas")];
    Plotly.purge(gd);
    for (const canvas of canvases) {
      const gl = canvas.getContext("webgl");   // the scene's own context (plotly asks for "webgl")
      const lose = gl && gl.getExtension("WEBGL_lose_context");
      if (lose) lose.loseContext();
    }
    if (rec.standIn) rec.standIn.remove();
    rec.standIn = standIn;
    if (standIn) gd.after(standIn);
    rec.live = false;
    liveScenes -= rec.scenes;
  }

  const nearby = new IntersectionObserver(entries => {
    const changed = entries.map(e => {
      const rec = figures.get(e.target);
      rec.near = e.isIntersecting;
      return rec;
    });
    changed.filter(r => !r.near && r.scenes).forEach(hide);   // free contexts before drawing others
    changed.filter(r => r.near).forEach(r => show(r, false));
  }, {rootMargin: NEAR});
  // A figure on screen is always drawn (a near one may have waited for room). One that only touches
  // the viewport's edge (no area on screen) is not on screen.
  const onScreen = new IntersectionObserver(entries => {
    for (const e of entries) {
      const rec = figures.get(e.target);
      rec.visible = e.isIntersecting && e.intersectionRatio > 0;
      if (rec.visible) show(rec, true);
    }
  });

  Plotly.newPlot = function (div, data, layout, config) {
    const gd = graphDiv(div);
    if (!gd) return newPlot.apply(this, arguments);
    // Plotly.newPlot(div, data, layout, config) or Plotly.newPlot(div, {data, layout, config, frames}).
    const figure = Array.isArray(data) || data === undefined
      ? {data: data || [], layout: layout || {}, config: config || {}, frames: []}
      : {data: data.data || [], layout: data.layout || {}, config: data.config || {}, frames: data.frames || []};
    const known = figures.get(gd);
    if (known) {   // drawn again by the page: start over with the new figure
      if (known.live) hide(known);
      known.figure = figure;
      known.scenes = sceneCount(figure.data);
      if (known.near || known.visible) show(known, known.visible);
      return Promise.resolve(gd);
    }
    figures.set(gd, {gd, figure, scenes: sceneCount(figure.data), live: false, near: false, visible: false, drawing: null, standIn: null, afterDraw: []});
    nearby.observe(gd);
    onScreen.observe(gd);
    return Promise.resolve(gd);
  };

  // plotly's HTML export adds animation frames after newPlot, then plays them (Plotly.animate): for
  // a figure not drawn yet, the frames are kept with it and the animation is played once it is drawn.
  Plotly.addFrames = function (div, frames, indices) {
    const rec = figures.get(graphDiv(div));
    if (rec && !rec.live) {
      rec.figure.frames = (rec.figure.frames || []).concat(frames || []);
      return Promise.resolve();
    }
    return addFrames.apply(this, arguments);
  };
  Plotly.animate = function (div) {
    const rec = figures.get(graphDiv(div));
    if (rec && !rec.live) {
      const args = arguments;
      rec.afterDraw.push(() => animate.apply(Plotly, args));
      return Promise.resolve();
    }
    return animate.apply(this, arguments);
  };
})();
