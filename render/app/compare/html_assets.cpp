#include "render/app/compare/html_assets.h"

namespace spume::compare {

const char* const kReportCss = R"CSS(
:root { --pass: #1b7f3b; --fail: #c0262d; --ink: #1d1f22; --muted: #5f6670; --line: #d9dde2; --bg: #f6f7f9; }
* { box-sizing: border-box; }
body { margin: 0; font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif;
       color: var(--ink); background: var(--bg); }
h1 { margin: 0; font-size: 22px; font-weight: 600; }
h2 { font-size: 17px; margin: 14px 0 8px; font-weight: 600; }
code { font-size: 13px; word-break: break-all; }
.banner { padding: 14px 24px; color: #fff; }
.banner.pass { background: var(--pass); }
.banner.fail { background: var(--fail); }
.banner p { margin: 4px 0 0; }
.overall { margin-left: 8px; padding: 1px 10px; border: 2px solid #fff; border-radius: 4px; }
#script-error { margin: 10px 24px; padding: 10px; background: #fff3cd; border: 1px solid #e0b000; }
section { padding: 4px 24px; }
.meta table { border-collapse: collapse; }
.meta th { text-align: left; color: var(--muted); font-weight: normal; padding: 2px 16px 2px 0; vertical-align: top; }
.meta td { padding: 2px 0; }
#error-plot { width: 100%; max-width: 1100px; height: auto; background: #fff; border: 1px solid var(--line); }
#error-plot .panel { fill: none; stroke: #aab; }
#error-plot .grid { stroke: #e4e7eb; }
#error-plot .tick { font-size: 10px; text-anchor: end; fill: var(--muted); }
#error-plot .xtick, #error-plot .xtitle { font-size: 10px; text-anchor: middle; fill: var(--muted); }
#error-plot .title { font-size: 12px; fill: var(--ink); }
#error-plot .threshold { stroke: var(--fail); stroke-dasharray: 5 4; }
#error-plot .threshold-label { font-size: 10px; text-anchor: end; fill: var(--fail); }
#error-plot .series { fill: none; stroke: #4a6fa5; stroke-width: 1.2; }
#error-plot .marker { cursor: pointer; }
#error-plot circle.pass { fill: #4a6fa5; }
#error-plot circle.fail, #error-plot .problem { fill: var(--fail); }
#error-plot #plot-cursor { stroke: #000; stroke-width: 1; stroke-dasharray: 2 2; }
#error-plot .empty { font-size: 16px; text-anchor: middle; fill: var(--muted); }
.hint { color: var(--muted); font-size: 12px; margin: 4px 0; }
#viewer { background: #fff; border-top: 1px solid var(--line); border-bottom: 1px solid var(--line); padding-bottom: 12px; }
.viewer-head { display: flex; align-items: center; justify-content: space-between; flex-wrap: wrap; gap: 8px; }
.v-modes { display: flex; flex-wrap: wrap; gap: 6px; align-items: center; margin-bottom: 8px; }
.v-modes label { margin-left: 10px; color: var(--muted); }
button { font: inherit; padding: 3px 10px; border: 1px solid #b8bec6; background: #fff; border-radius: 4px; cursor: pointer; }
button:hover { background: #eef1f5; }
button.active { background: var(--ink); color: #fff; border-color: var(--ink); }
button:disabled { opacity: 0.4; cursor: default; }
.stage { max-width: 100%; overflow: auto; background: #222; padding: 0; }
.frame { position: relative; width: 100%; margin: 0 auto; user-select: none; cursor: ew-resize; }
.frame img { position: absolute; left: 0; top: 0; width: 100%; height: 100%; display: block; }
.stage.actual .frame img, .stage.upscaled .frame img { image-rendering: pixelated; }
#v-divider { position: absolute; top: 0; bottom: 0; width: 2px; margin-left: -1px; background: #fff;
             box-shadow: 0 0 3px #000; pointer-events: none; }
#v-tag { position: absolute; left: 6px; top: 6px; padding: 1px 6px; background: rgba(0,0,0,.65); color: #fff;
         font-size: 12px; border-radius: 3px; pointer-events: none; }
#v-slider { width: 100%; max-width: 100%; }
#v-reason { color: var(--fail); margin: 6px 0; }
#v-numbers td { padding: 1px 14px 1px 0; }
#v-numbers td:first-child { color: var(--muted); }
.controls { display: flex; flex-wrap: wrap; gap: 16px; align-items: center; margin-bottom: 8px; }
.legend { color: var(--muted); font-size: 12px; }
.swatch { display: inline-block; width: 12px; height: 12px; margin: 0 3px 0 6px; vertical-align: -2px; border-radius: 2px; }
#frame-table { border-collapse: collapse; background: #fff; }
#frame-table th { position: sticky; top: 0; background: #eceff3; text-align: left; padding: 5px 8px; font-weight: 600;
                  border-bottom: 1px solid var(--line); z-index: 1; }
#frame-table td { padding: 4px 8px; border-bottom: 1px solid var(--line); vertical-align: top; }
#frame-table tr { cursor: pointer; }
#frame-table tr.fail td { background: #fdeeee; }
#frame-table tr.current td { background: #dde7f5; }
#frame-table td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
#frame-table td.thumb img { width: 160px; height: auto; display: block; background: #ddd; }
#frame-table td.none { color: var(--muted); text-align: center; width: 160px; }
.reason { font-size: 12px; color: var(--fail); max-width: 340px; }
.badge { display: inline-block; padding: 0 7px; border-radius: 3px; font-size: 12px; font-weight: 600; color: #fff; }
.badge.pass { background: var(--pass); }
.badge.fail { background: var(--fail); }
footer { padding: 10px 24px 30px; color: var(--muted); font-size: 12px; max-width: 1100px; }
)CSS";

const char* const kReportJs = R"JS(
(function () {
  'use strict';
  var body = document.body;
  function fail(message) {
    body.setAttribute('data-status', 'error');
    var box = document.getElementById('script-error');
    if (box) {
      box.hidden = false;
      box.textContent = 'The report script failed: ' + message +
        '. The header, plot and table above and below are complete without it.';
    }
  }
  window.addEventListener('error', function (e) { fail(e.message || 'unknown error'); });

  function byId(id) {
    var el = document.getElementById(id);
    if (!el) throw new Error('element #' + id + ' is missing');
    return el;
  }

  try {
    var data = JSON.parse(byId('compare-data').textContent);
    var frames = data.frames;
    var tbody = document.querySelector('#frame-table tbody');
    var rows = Array.prototype.slice.call(tbody.rows);
    var rowOf = {};
    rows.forEach(function (row) { rowOf[row.getAttribute('data-index')] = row; });
    var worstOrder = rows.slice();
    var viewer = byId('viewer'), stage = byId('v-stage'), frameBox = byId('v-frame');
    var imgRef = byId('v-ref'), imgNew = byId('v-new'), imgExtra = byId('v-extra');
    var divider = byId('v-divider'), tag = byId('v-tag'), slider = byId('v-slider');
    var modeButtons = Array.prototype.slice.call(viewer.querySelectorAll('[data-mode]'));
    var state = { index: -1, mode: 'slider', showNew: false, timer: null };

    function available(f, mode) {
      // Overlaying images of two sizes would stretch one: those frames show each image alone.
      if (mode === 'slider' || mode === 'flip') return !!(f.ref && f.new) && f.w === f.nw && f.h === f.nh;
      if (mode === 'reference') return !!f.ref;
      if (mode === 'new') return !!f.new;
      if (mode === 'diff') return !!f.diff;
      if (mode === 'heat') return !!f.heat;
      return false;
    }

    // Every image of the frame is requested when it opens, so switching modes is instant; the viewer
    // records whether they all loaded (data-images) for people and tests alike.
    function watch(img, url) {
      img.onload = img.onerror = null;
      if (!url) { img.removeAttribute('src'); img.setAttribute('data-state', 'none'); return; }
      img.setAttribute('data-state', 'loading');
      img.onload = function () { img.setAttribute('data-state', 'loaded'); imagesSettled(); };
      img.onerror = function () { img.setAttribute('data-state', 'broken'); imagesSettled(); };
      if (img.getAttribute('src') !== url) img.setAttribute('src', url);
      else if (img.complete && img.naturalWidth > 0) img.setAttribute('data-state', 'loaded');
    }
    function imagesSettled() {
      var states = [imgRef, imgNew, imgExtra].map(function (i) { return i.getAttribute('data-state'); });
      if (states.indexOf('loading') >= 0) return;
      var broken = states.indexOf('broken') >= 0;
      viewer.setAttribute('data-images', broken ? 'broken' : 'loaded');
      if (broken) byId('v-reason').textContent += ' (an image could not be loaded: moved or deleted?)';
    }

    function extraUrl(f) { return state.mode === 'heat' ? f.heat : state.mode === 'diff' ? f.diff : null; }

    // The frame box takes the shown image's size. Fit: as wide as the page allows, small frames
    // enlarged to 960 px with visible pixels; actual: one image pixel per CSS pixel.
    function sizeFrame(w, h) {
      var actual = byId('v-actual').checked;
      frameBox.style.aspectRatio = w + ' / ' + h;
      frameBox.style.width = actual ? w + 'px' : '';
      frameBox.style.maxWidth = actual ? 'none' : Math.max(w, 960) + 'px';
      stage.classList.toggle('actual', actual);
      stage.classList.toggle('upscaled', !actual && w < 960);
    }

    function render() {
      var f = frames[state.index];
      if (state.mode === 'new' && f.nw) sizeFrame(f.nw, f.nh);
      else sizeFrame(f.w || f.nw || 16, f.h || f.nh || 9);
      modeButtons.forEach(function (b) {
        var m = b.getAttribute('data-mode');
        b.disabled = !available(f, m);
        b.classList.toggle('active', m === state.mode);
      });
      var pos = slider.value / 10;
      var m = state.mode;
      imgRef.style.visibility = (m === 'slider' || m === 'reference' || (m === 'flip' && !state.showNew)) ? 'visible' : 'hidden';
      imgNew.style.visibility = (m === 'slider' || m === 'new' || (m === 'flip' && state.showNew)) ? 'visible' : 'hidden';
      imgNew.style.clipPath = m === 'slider' ? 'inset(0 0 0 ' + pos + '%)' : 'none';
      imgExtra.style.visibility = (m === 'diff' || m === 'heat') ? 'visible' : 'hidden';
      if (m === 'diff' || m === 'heat') imgExtra.setAttribute('src', extraUrl(f));
      divider.style.display = m === 'slider' ? 'block' : 'none';
      divider.style.left = pos + '%';
      slider.style.display = m === 'slider' ? 'block' : 'none';
      tag.textContent = m === 'slider' ? 'reference | new' : m === 'flip' ? (state.showNew ? 'new' : 'reference')
        : m === 'diff' ? 'difference \u00d7' + data.scale : m === 'heat' ? 'heat map' : m;
    }

    function setMode(mode) {
      var f = frames[state.index];
      if (!available(f, mode)) return;
      state.mode = mode;
      render();
    }

    function open(index, scroll) {
      var f = frames[index];
      if (!f) return;
      state.index = index;
      viewer.hidden = false;
      viewer.setAttribute('data-frame', f.label);
      byId('v-label').textContent = f.label;
      var badge = byId('v-verdict');
      badge.textContent = f.verdict;
      badge.className = 'badge ' + (f.pass ? 'pass' : 'fail');
      byId('v-reason').textContent = f.reason;
      var numbers = byId('v-numbers');
      numbers.textContent = '';
      f.numbers.forEach(function (pair) {
        var tr = numbers.insertRow();
        tr.insertCell().textContent = pair[0];
        tr.insertCell().textContent = pair[1];
      });
      if (!available(f, state.mode)) {
        state.mode = ['slider', 'reference', 'new', 'heat'].filter(function (m) { return available(f, m); })[0] || 'slider';
      }
      viewer.setAttribute('data-images', 'loading');
      watch(imgRef, f.ref);
      watch(imgNew, f.new);
      watch(imgExtra, extraUrl(f) || f.heat || f.diff);
      imagesSettled();
      rows.forEach(function (r) { r.classList.remove('current'); });
      var row = rowOf[index];
      if (row) row.classList.add('current');
      var cursor = document.getElementById('plot-cursor');
      var svg = document.getElementById('error-plot');
      if (cursor && svg) {
        var left = parseFloat(svg.getAttribute('data-left')), width = parseFloat(svg.getAttribute('data-width'));
        var x = left + (index + 0.5) * width / Math.max(frames.length, 1);
        cursor.setAttribute('x1', x);
        cursor.setAttribute('x2', x);
        cursor.setAttribute('visibility', 'visible');
      }
      render();
      if (scroll) viewer.scrollIntoView({ block: 'start' });
    }

    function visibleRows() { return Array.prototype.slice.call(tbody.rows).filter(function (r) { return !r.hidden; }); }
    function step(delta) {
      var list = visibleRows();
      if (!list.length) return;
      var at = list.indexOf(rowOf[state.index]);
      var next = list[Math.min(list.length - 1, Math.max(0, at + delta))];
      open(parseInt(next.getAttribute('data-index'), 10), false);
    }

    modeButtons.forEach(function (b) {
      b.addEventListener('click', function () { setMode(b.getAttribute('data-mode')); });
    });
    byId('v-prev').addEventListener('click', function () { step(-1); });
    byId('v-next').addEventListener('click', function () { step(1); });
    slider.addEventListener('input', render);
    byId('v-actual').addEventListener('change', function () { open(state.index, false); });
    byId('v-autoflip').addEventListener('change', function (e) {
      clearInterval(state.timer);
      state.timer = null;
      if (e.target.checked) {
        setMode('flip');
        state.timer = setInterval(function () { state.showNew = !state.showNew; render(); }, 500);
      }
    });
    // Dragging on the image moves the slider; a click in flip mode flips.
    var dragging = false;
    function dragTo(e) {
      var r = frameBox.getBoundingClientRect();
      if (r.width > 0) slider.value = Math.round(1000 * Math.min(1, Math.max(0, (e.clientX - r.left) / r.width)));
      render();
    }
    frameBox.addEventListener('pointerdown', function (e) {
      if (state.mode === 'flip') { state.showNew = !state.showNew; render(); return; }
      if (state.mode !== 'slider') return;
      dragging = true;
      try { frameBox.setPointerCapture(e.pointerId); } catch (err) { /* a synthetic pointer: no capture needed */ }
      dragTo(e);
    });
    frameBox.addEventListener('pointermove', function (e) { if (dragging) dragTo(e); });
    frameBox.addEventListener('pointerup', function () { dragging = false; });

    tbody.addEventListener('click', function (e) {
      if (e.target.closest('a[href]') && !e.target.closest('td.name')) return;  // thumbnails open the full image
      var row = e.target.closest('tr');
      if (!row) return;
      e.preventDefault();
      history.replaceState(null, '', '#' + row.id);
      open(parseInt(row.getAttribute('data-index'), 10), true);
    });
    Array.prototype.forEach.call(document.querySelectorAll('#error-plot .marker'), function (m) {
      m.addEventListener('click', function () { open(parseInt(m.getAttribute('data-index'), 10), true); });
    });

    byId('order').addEventListener('change', function (e) {
      var list = e.target.value === 'sequence'
        ? rows.slice().sort(function (a, b) { return a.getAttribute('data-index') - b.getAttribute('data-index'); })
        : worstOrder;
      list.forEach(function (r) { tbody.appendChild(r); });
    });
    byId('only-failing').addEventListener('change', function (e) {
      rows.forEach(function (r) { r.hidden = e.target.checked && r.getAttribute('data-pass') === '1'; });
    });
    document.addEventListener('keydown', function (e) {
      if (e.target.closest && e.target.closest('input, select, textarea')) return;
      if (e.altKey || e.ctrlKey || e.metaKey || state.index < 0) return;
      var modes = ['slider', 'flip', 'reference', 'new', 'diff', 'heat'];
      if (e.key === 'j') step(1);
      else if (e.key === 'k') step(-1);
      else if (e.key === 'f') { setMode('flip'); state.showNew = !state.showNew; render(); }
      else if (e.key >= '1' && e.key <= '6') setMode(modes[parseInt(e.key, 10) - 1]);
    });

    // The frame named in the address (#f-STEM), else the worst.
    var start = rows.length ? rows[0] : null, named = null;
    if (location.hash.length > 1) {
      named = document.getElementById(decodeURIComponent(location.hash.slice(1)));
      if (named && rowOf[named.getAttribute('data-index')] === named) start = named;
      else named = null;
    }
    if (start) open(parseInt(start.getAttribute('data-index'), 10), !!named);
    if (body.getAttribute('data-status') !== 'error') body.setAttribute('data-status', 'ready');
  } catch (e) {
    fail(e && e.message ? e.message : String(e));
  }
})();
)JS";

}  // namespace spume::compare
