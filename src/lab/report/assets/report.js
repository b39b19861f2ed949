// lightlab report viewer: two images, slider or flip, exposure, zoom with sharp pixels.
// Image data: window.LIGHTLAB_IMAGES[key] = {width, height, data: base64 float32 RGB};
// the list to show: window.LIGHTLAB_VIEWER = [{label, key}].
(function () {
  "use strict";
  var list = window.LIGHTLAB_VIEWER || [];
  var store = window.LIGHTLAB_IMAGES || {};
  var stage = document.getElementById("stage");
  if (!stage || list.length === 0) { return; }
  var frame = document.getElementById("frame");
  var canvases = [document.getElementById("canvas-a"), document.getElementById("canvas-b")];
  var picks = [document.getElementById("pick-a"), document.getElementById("pick-b")];
  var tags = [document.getElementById("label-a"), document.getElementById("label-b")];
  var divider = document.getElementById("divider");
  var split = document.getElementById("split");
  var exposure = document.getElementById("exposure");
  var exposureValue = document.getElementById("exposure-value");
  var zoomValue = document.getElementById("zoom-value");
  var decoded = {};
  var view = { scale: 1, x: 0, y: 0, mode: "slider", flipped: false };
  var size = { width: 1, height: 1 };

  function pixels(key) {
    if (decoded[key]) { return decoded[key]; }
    var item = store[key];
    if (!item) { return null; }
    var bin = atob(item.data);
    var bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) { bytes[i] = bin.charCodeAt(i); }
    decoded[key] = { width: item.width, height: item.height, rgb: new Float32Array(bytes.buffer) };
    return decoded[key];
  }

  function srgb(v) {
    v = v > 0 ? (v < 1 ? v : 1) : 0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  }

  function draw(side) {
    var entry = list[Number(picks[side].value)];
    var img = pixels(entry.key);
    var canvas = canvases[side];
    tags[side].textContent = entry.label;
    if (!img) {
      console.error("lightlab report: no pixel data for " + entry.key + " (img/" + entry.key + ".js)");
      return;
    }
    canvas.width = img.width;
    canvas.height = img.height;
    size = { width: img.width, height: img.height };
    var ctx = canvas.getContext("2d");
    var out = ctx.createImageData(img.width, img.height);
    var scale = Math.pow(2, Number(exposure.value));
    var n = img.width * img.height;
    for (var p = 0; p < n; p++) {
      for (var c = 0; c < 3; c++) {
        out.data[4 * p + c] = Math.round(255 * srgb(img.rgb[3 * p + c] * scale));
      }
      out.data[4 * p + 3] = 255;
    }
    ctx.putImageData(out, 0, 0);
  }

  function layout() {
    frame.style.width = size.width + "px";
    frame.style.height = size.height + "px";
    frame.style.transform = "translate(" + view.x + "px," + view.y + "px) scale(" + view.scale + ")";
    var t = Number(split.value) / 100;
    if (view.mode === "slider") {
      canvases[0].style.visibility = "visible";
      canvases[1].style.visibility = "visible";
      canvases[1].style.clipPath = "inset(0 0 0 " + (t * 100) + "%)";
      divider.style.display = "block";
      divider.style.left = (view.x + t * size.width * view.scale - 1) + "px";
      tags[0].style.display = "block";
      tags[1].style.display = "block";
    } else {
      canvases[1].style.clipPath = "none";
      canvases[0].style.visibility = view.flipped ? "hidden" : "visible";
      canvases[1].style.visibility = view.flipped ? "visible" : "hidden";
      divider.style.display = "none";
      tags[0].style.display = view.flipped ? "none" : "block";
      tags[1].style.display = view.flipped ? "block" : "none";
    }
    zoomValue.textContent = "zoom " + view.scale.toFixed(2) + "x";
  }

  function fit() {
    var w = stage.clientWidth, h = stage.clientHeight;
    view.scale = Math.min(w / size.width, h / size.height);
    if (view.scale >= 1) { view.scale = Math.floor(view.scale); }
    view.x = (w - size.width * view.scale) / 2;
    view.y = (h - size.height * view.scale) / 2;
    layout();
  }

  function zoomAt(factor, cx, cy) {
    var s = Math.min(64, Math.max(0.05, view.scale * factor));
    view.x = cx - (cx - view.x) * (s / view.scale);
    view.y = cy - (cy - view.y) * (s / view.scale);
    view.scale = s;
    layout();
  }

  stage.addEventListener("wheel", function (e) {
    e.preventDefault();
    var r = stage.getBoundingClientRect();
    zoomAt(e.deltaY < 0 ? 1.25 : 0.8, e.clientX - r.left, e.clientY - r.top);
  }, { passive: false });

  var drag = null;
  stage.addEventListener("mousedown", function (e) {
    drag = { x: e.clientX, y: e.clientY, vx: view.x, vy: view.y, moved: false };
    stage.classList.add("dragging");
  });
  window.addEventListener("mousemove", function (e) {
    if (!drag) { return; }
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 2) { drag.moved = true; }
    view.x = drag.vx + dx;
    view.y = drag.vy + dy;
    layout();
  });
  window.addEventListener("mouseup", function () {
    if (drag && !drag.moved && view.mode === "flip") { view.flipped = !view.flipped; layout(); }
    drag = null;
    stage.classList.remove("dragging");
  });
  window.addEventListener("keydown", function (e) {
    if (e.key === " " && view.mode === "flip") { e.preventDefault(); view.flipped = !view.flipped; layout(); }
    if (e.key === "+" || e.key === "=") { zoomAt(1.25, stage.clientWidth / 2, stage.clientHeight / 2); }
    if (e.key === "-") { zoomAt(0.8, stage.clientWidth / 2, stage.clientHeight / 2); }
  });
  document.querySelectorAll("input[name=mode]").forEach(function (radio) {
    radio.addEventListener("change", function () { view.mode = radio.value; layout(); });
  });
  picks.forEach(function (pick, side) {
    pick.addEventListener("change", function () { draw(side); layout(); });
  });
  exposure.addEventListener("input", function () {
    exposureValue.textContent = Number(exposure.value).toFixed(1);
    draw(0);
    draw(1);
  });
  split.addEventListener("input", layout);
  document.getElementById("zoom-fit").addEventListener("click", fit);
  document.getElementById("zoom-1").addEventListener("click", function () {
    zoomAt(1 / view.scale, stage.clientWidth / 2, stage.clientHeight / 2);
  });

  // The starting view can be set in the address: #a=0&b=2&mode=flip&exposure=1.5&split=30.
  var start = {};
  location.hash.replace(/^#/, "").split("&").forEach(function (pair) {
    var kv = pair.split("=");
    if (kv.length === 2) { start[kv[0]] = decodeURIComponent(kv[1]); }
  });
  function index(v, fallback) {
    var i = parseInt(v, 10);
    return i >= 0 && i < list.length ? String(i) : String(fallback);
  }
  picks[0].value = index(start.a, 0);
  picks[1].value = index(start.b, Math.min(1, list.length - 1));
  if (start.mode === "flip") {
    view.mode = "flip";
    document.querySelector("input[name=mode][value=flip]").checked = true;
  }
  if (start.exposure !== undefined && isFinite(Number(start.exposure))) {
    exposure.value = start.exposure;
    exposureValue.textContent = Number(exposure.value).toFixed(1);
  }
  if (start.split !== undefined && isFinite(Number(start.split))) { split.value = start.split; }
  draw(0);
  draw(1);
  fit();
})();
